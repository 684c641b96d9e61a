"""The Gradescope autograder: exported as the zip Gradescope takes, unpacked into a
temporary root laid out like Gradescope's ``/autograder``, run on the solution and on the
student version, its ``results.json`` checked against Gradescope's documented format."""

import json
import os
import shutil
import stat
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest
from grading_helpers import ROOT

try:
    import tomllib
except ModuleNotFoundError:  # Python 3.10
    import tomli as tomllib

from kinlib.grade.gradescope import export

NAME = "02_forward_kinematics"
# Gradescope's autograder specification (gradescope-autograders.readthedocs.io, "specs")
TOP = {"score", "execution_time", "output", "output_format", "test_output_format",
       "test_name_format", "visibility", "stdout_visibility", "extra_data", "tests",
       "leaderboard"}
TEST = {"score", "max_score", "status", "name", "name_format", "number", "output",
        "output_format", "tags", "visibility", "extra_data"}
SEEN = {"hidden", "after_due_date", "after_published", "visible"}


def check_results(data: dict) -> None:
    """results.json as Gradescope documents it (raises AssertionError otherwise)."""
    assert set(data) <= TOP, set(data) - TOP
    assert isinstance(data["score"], float | int) and data["score"] >= 0
    assert data.get("visibility", "visible") in SEEN
    assert data.get("stdout_visibility", "hidden") in SEEN
    assert isinstance(data.get("output", ""), str)
    for t in data["tests"]:
        assert set(t) <= TEST, set(t) - TEST
        assert isinstance(t["name"], str) and t["name"]
        assert isinstance(t["score"], float | int) and isinstance(t["max_score"], float | int)
        assert 0 <= t["score"] <= t["max_score"]
        assert t.get("status", "passed") in ("passed", "failed")
        assert t.get("visibility", "visible") in SEEN and isinstance(t.get("output", ""), str)
    assert abs(sum(t["score"] for t in data["tests"]) - data["score"]) < 0.05


@pytest.fixture(scope="module")
def autograder(tmp_path_factory):
    base = tmp_path_factory.mktemp("gradescope")
    zip_path = export(NAME, base / "autograder.zip", visibility="after_due_date")
    return base, zip_path


def unpack(zip_path: Path, root: Path) -> Path:
    """Gradescope's layout: the zip's contents in root/source, the submission, results."""
    source = root / "source"
    with zipfile.ZipFile(zip_path) as z:
        z.extractall(source)
        for info in z.infolist():  # (extractall drops the permission bits)
            mode = info.external_attr >> 16
            if mode:
                os.chmod(source / info.filename, mode)
    (root / "submission").mkdir()
    (root / "results").mkdir()
    return source


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
        # requirements.txt: kinlib's dependencies and the grade extra, as pyproject says
        pyproject = tomllib.loads((ROOT.parent / "pyproject.toml").read_text())["project"]
        want = pyproject["dependencies"] + pyproject["optional-dependencies"]["grade"]
        got = z.read("requirements.txt").decode().split("\n")
        norm = [r.replace('"', "'").replace(" ", "") for r in got if r]
        assert norm == [r.replace('"', "'").replace(" ", "") for r in want]
        config = json.loads(z.read("config.json"))
        assert config["assignment"] == NAME and config["visibility"] == "after_due_date"
        assert len(z.read("secret")) >= 32


@pytest.fixture(scope="module")
def unpacked(autograder):
    """One /autograder root for the runs below (each clears the submission and results)."""
    base, zip_path = autograder
    root = base / "autograder"
    unpack(zip_path, root)
    return root


def hand_in(root: Path, notebook: Path, name: str = "homework.ipynb") -> None:
    for d in ("submission", "results"):
        shutil.rmtree(root / d)
        (root / d).mkdir()
    shutil.copy(notebook, root / "submission" / name)


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
    assert {t["visibility"] for t in data["tests"]} == {"after_due_date"}
    assert data["stdout_visibility"] == "hidden"
    max_score = sum(t["max_score"] for t in data["tests"])
    assert max_score == 34 and len(data["tests"]) == 4
    if edition == "source":
        assert data["score"] == max_score
        assert {t["status"] for t in data["tests"]} == {"passed"}
    else:
        assert data["score"] == 0 and {t["status"] for t in data["tests"]} == {"failed"}
        assert all("NotImplementedError" in t["output"] for t in data["tests"])
    assert "total:" in out.stdout  # the instructor's view in Gradescope's stdout


def test_no_sandbox_in_the_container_refuses_unless_allowed(autograder, unpacked):
    base, _ = autograder
    root = unpacked
    hand_in(root, ROOT / "source" / f"{NAME}.ipynb", f"{NAME}.ipynb")
    out = run_autograder(root, KINLIB_BWRAP="/nonexistent/bwrap")
    assert out.returncode == 2 and "--allow-unsandboxed" in out.stderr
    assert not (root / "results" / "results.json").exists()
    allowed = export(NAME, base / "allowed.zip", allow_unsandboxed=True)
    with zipfile.ZipFile(allowed) as z:  # the same root, this zip's configuration
        (root / "source" / "config.json").write_bytes(z.read("config.json"))
    try:
        out = run_autograder(root, KINLIB_BWRAP="/nonexistent/bwrap")
        assert out.returncode == 0, out.stderr
        data = json.loads((root / "results" / "results.json").read_text())
    finally:
        with zipfile.ZipFile(autograder[1]) as z:
            (root / "source" / "config.json").write_bytes(z.read("config.json"))
    check_results(data)
    assert data["output"].startswith("WARNING: graded WITHOUT the sandbox")
    assert data["extra_data"]["kinlib"]["sandbox"] is None


def test_a_submission_without_a_notebook_gets_a_result_saying_so(unpacked, tmp_path):
    root = unpacked
    (tmp_path / "answers.py").write_text("print('hi')\n")
    hand_in(root, tmp_path / "answers.py", "answers.py")
    out = run_autograder(root)
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
