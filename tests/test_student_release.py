"""What students receive: ``python -m kinlib.assign --student-repo DIR``.

One release is built (once for the module: it builds kinlib's wheel) from a copy of the
course repository, with a grading secret planted beside it and in the environment. It must
hold the student editions, byte for byte the committed ones (which the JupyterLab test runs
cell by cell), and no solution: no block of either source, whole or a line of it, in any
file or in any file of the shipped wheel (``tests/solution_text.py`` says how the search
stays strong and deterministic). Its environment installs the shipped wheel; installed so
into a fresh virtual environment by the release's own ``binder/postBuild``, a release
notebook runs from the release's folder and a released assignment is graded there. A second
release into a clone of it updates it; folders that would leak or that are not a release
are refused."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import sysconfig
import zipfile
from importlib import metadata
from pathlib import Path

import pytest
from packaging.requirements import Requirement
from solution_text import (
    BEGIN,
    Block,
    absent_in_context,
    blocks,
    found_in,
    is_generic,
    library_text,
    tree_text,
)
from test_binder_env import check_postbuild, check_requirements, check_runtime, requirement_lines

from kinlib import KinlibError
from kinlib.assign import main
from kinlib.student import MANIFEST, check_destination, write_files

ROOT = Path(__file__).resolve().parents[1]
SECRET = "d41c8a7f0e9b-planted-grading-secret-5b2e"
URL = "https://github.com/our-course/kinematics"
COPIED = ("pyproject.toml", "README.md", "kinlib", "instructor", "notebooks", "assignments")


def _copy_course(to: Path, parts=COPIED) -> Path:
    to.mkdir()
    for name in parts:
        if (ROOT / name).is_dir():
            shutil.copytree(ROOT / name, to / name, ignore=shutil.ignore_patterns(
                "__pycache__", "*.pyc", ".ipynb_checkpoints"))
        else:
            shutil.copy2(ROOT / name, to / name)
    return to


def _assign(*args, cwd: Path, **env) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "kinlib.assign", *map(str, args)], cwd=cwd,
                          capture_output=True, text=True, timeout=600,
                          env={**os.environ, **env})


@pytest.fixture(scope="module")
def course(tmp_path_factory) -> Path:
    """A copy of the course repository, a grading secret lying in it as instructors keep
    one (it is not under version control, but it is in the folder)."""
    course = _copy_course(tmp_path_factory.mktemp("course") / "course")
    (course / "course-secret").write_text(SECRET + "\n")
    return course


@pytest.fixture(scope="module")
def release(course) -> Path:
    dest = course.parent / "student"
    out = _assign("--root", course, "--student-repo", dest, "--repo-url", URL, cwd=course.parent,
                  KINLIB_GRADE_SECRET=SECRET)
    assert out.returncode == 0, out.stdout + out.stderr
    return dest


def _files(folder: Path) -> set[str]:
    return {p.relative_to(folder).as_posix() for p in folder.rglob("*")
            if p.is_file() and p.relative_to(folder).parts[0] != ".git"}


def test_the_release_holds_the_student_editions_and_nothing_an_instructor_keeps(release):
    (wheel,) = (release / "wheels").glob("kinlib-*-py3-none-any.whl")
    notebooks = {f"notebooks/{p.name}" for p in (ROOT / "instructor").glob("*.ipynb")}
    assignments = {f"assignments/{p.name}" for p in (ROOT / "assignments/source").glob("*.ipynb")}
    assert len(notebooks) >= 15 and len(assignments) >= 6
    expected = notebooks | assignments | {
        "README.md", ".gitignore", MANIFEST, f"wheels/{wheel.name}", "binder/requirements.txt",
        "binder/runtime.txt", "binder/postBuild"}
    assert _files(release) == expected  # no instructor/, tests/, bench/, DEVELOPERS.md, ...
    # byte for byte what the suite runs: notebooks/ in JupyterLab (tests/test_lab.py), the
    # assignments' student versions graded by the grader tests
    for rel in sorted(notebooks):
        assert (release / rel).read_bytes() == (ROOT / rel).read_bytes(), rel
    for rel in sorted(assignments):
        committed = ROOT / "assignments/release" / Path(rel).name
        assert (release / rel).read_bytes() == committed.read_bytes(), rel
    manifest = json.loads((release / MANIFEST).read_text())
    assert manifest["files"] == sorted(expected - {MANIFEST}) and manifest["repo_url"] == URL


def test_no_solution_is_in_any_file_of_the_release_or_its_wheel(release):
    found, legit = blocks(ROOT)
    texts = tree_text(release)
    assert any("!kinlib/" in name for name in texts), "the wheel's files were not read"
    legit += library_text(ROOT)
    legit_lines = {line for doc in legit for line in doc.split("\n")}
    generic = [b for b in found if is_generic(b, legit)]
    searched = [b for b in found if b not in generic]
    # every solution block of both sources, 132 today (10 of them tagged cells)
    assert len(found) >= 120 and sum(b.tagged for b in found) >= 5
    # Generic blocks (none today) are not searched for everywhere; each is checked in its
    # cell below. Should most blocks turn generic, the search has stopped being a search:
    assert len(searched) >= 0.9 * len(found), [b.text for b in generic]
    leaks = {f"{b.source}, cell {b.cell_id}": hits for b in searched
             if (hits := found_in(b, texts, legit_lines))}
    assert not leaks, f"solution text in the student release: {leaks}"
    released = {}
    for b in found:  # every block, generic or not, is gone from its own cell
        if b.released not in released:
            released[b.released] = json.loads((release / b.released).read_text())
        problem = absent_in_context(b, released[b.released])
        assert problem is None, f"{b.released} ({b.source}): {problem}: {b.text!r}"


def test_a_generic_block_is_checked_in_its_own_cell():
    """The control of the fallback for blocks too generic to search for everywhere (none
    today): such a block must be gone from its released cell, unless the source cell has it
    outside its solution too; a tagged cell must be gone."""
    block = Block("instructor/x.ipynb", "notebooks/x.ipynb", "c1", "k = 2", "k = ...", False)
    assert is_generic(block, []) and is_generic(
        Block("s", "r", "c1", "R = np.eye(3)", "", False), ["x = 0\nR = np.eye(3)"])
    blank = {"cells": [{"id": "c1", "source": ["k = ...  # your answer\n"]}]}
    solved = {"cells": [{"id": "c1", "source": ["k = ...  # your answer\n", "  k = 2\n"]}]}
    assert absent_in_context(block, blank) is None
    assert absent_in_context(block, solved) == "cell c1 holds it"
    given = Block("s", "r", "c1", "k = 2", "k = 2\nprint(k)", False)  # a given, in both
    assert absent_in_context(given, solved) is None
    tagged = Block("s", "r", "c1", "discussion", "", True)
    assert absent_in_context(tagged, blank) == "cell c1 is there"
    assert absent_in_context(tagged, {"cells": []}) is None


def test_no_instructor_folder_marker_or_secret_is_in_the_release(release, course):
    texts = tree_text(release)
    wheel = [name for name in texts if "!" in name]
    members = {name.split("!", 1)[1] for name in wheel}
    assert {m.split("/")[0] for m in members} == {"kinlib", "kinlib-0.1.0.dist-info"}, members
    assert "kinlib/student/templates/README.md" in members  # package data made it
    for name in texts:
        parts = name.replace("!", "/").split("/")
        assert "instructor" not in parts and "source" not in parts and "tests" not in parts, name
        assert SECRET not in texts[name], f"the grading secret is in {name}"
        if "!" not in name:  # (kinlib.assign in the wheel names the marker, as it must)
            assert BEGIN not in texts[name], name
    assert (course / "course-secret").exists()  # it was there to be picked up


def test_the_environment_installs_the_shipped_wheel(release):
    (wheel,) = (release / "wheels").glob("*.whl")
    check_requirements((release / "binder/requirements.txt").read_text())
    check_runtime((release / "binder/runtime.txt").read_text())
    postbuild = release / "binder/postBuild"
    check_postbuild(postbuild.read_text(), wheel.name)
    assert postbuild.stat().st_mode & 0o111 == 0o111, oct(postbuild.stat().st_mode)
    # installable: each line a requirement that this environment satisfies, so a resolver can
    wanted = {}
    for line in requirement_lines((release / "binder/requirements.txt").read_text()):
        req = Requirement(line)
        assert req.specifier.contains(metadata.version(req.name), prereleases=True), line
        wanted[req.name.lower()] = req
    # and it covers every dependency the shipped wheel declares, with the same specifiers
    with zipfile.ZipFile(wheel) as whl:
        meta = whl.read("kinlib-0.1.0.dist-info/METADATA").decode()
    declared = [Requirement(line.split(":", 1)[1]) for line in meta.splitlines()
                if line.startswith("Requires-Dist:")]
    for req in (r for r in declared if r.marker is None):
        assert req.name.lower() in wanted and wanted[req.name.lower()].specifier \
            == req.specifier, f"{req} of the wheel is not in binder/requirements.txt"
    readme = (release / "README.md").read_text()
    assert f"pip install --no-deps wheels/{wheel.name}" in readme


def test_the_student_readme_speaks_to_students(release):
    readme = (release / "README.md").read_text()
    assert "https://mybinder.org/v2/gh/our-course/kinematics/HEAD?urlpath=lab/tree/notebooks" \
        in readme and f"git clone {URL}" in readme
    assert "python -m kinlib.grade --self-check assignments/01_rotations.ipynb" in readme
    assert 'check("01.3", answer)' in readme
    for notes in ("AutoRob", "Dorst", "Craig", "Lie groups"):
        assert notes in readme, notes
    lowered = readme.lower()
    for word in ("seed 0", "pytest", "test suite", "nbval", "instructor/", "make "):
        assert word not in lowered, word
    links = [line.split("](", 1)[1].split(")")[0] for line in readme.splitlines()
             if line.startswith("- [")]
    assert sorted(links) == sorted(f for f in _files(release) if f.endswith(".ipynb"))


# --- the release, installed by its own postBuild, runs from its folder ----------------

RUN = """\
import sys
from pathlib import Path
import nbformat
from nbclient import NotebookClient
from kinlib.student import template
venv, path = Path(sys.argv[1]).resolve(), Path(sys.argv[2])
template("README.md"), template("postBuild")   # the wheel's package data
nb = nbformat.read(path, as_version=4)
nb.cells.append(nbformat.v4.new_code_cell("import kinlib; print(kinlib.__file__)"))
NotebookClient(nb, timeout=300, kernel_name="python3",
               resources={"metadata": {"path": str(path.parent)}}).execute()
where = Path(nb.cells[-1].outputs[0]["text"].strip()).resolve()
assert venv in where.parents, f"the kernel imported kinlib from {where}"
print("ran", path)
"""


def _clean_env(tmp: Path, **extra) -> dict:
    env = {k: v for k, v in os.environ.items()
           if k not in ("PYTHONPATH", "PYTHONHOME", "PYTHONSTARTUP", "VIRTUAL_ENV")}
    return {**env, "PYTHONNOUSERSITE": "1", "PIP_DISABLE_PIP_VERSION_CHECK": "1",
            "JUPYTER_DATA_DIR": str(tmp / "jupyter"), "JUPYTER_CONFIG_DIR": str(tmp / "jcfg"),
            "IPYTHONDIR": str(tmp / "ipython"), "KINLIB_NUMBA": "0", **extra}


def test_the_release_installed_by_its_postbuild_runs_from_its_folder(release, tmp_path):
    """A fresh venv (no packages) gets kinlib from the release's own binder/postBuild, run
    in the release's folder with pip lent to it alone; then the checkout's packages stand in
    for binder/requirements.txt, and a release notebook (08: a URDF from the package data,
    the 3-D viewer) runs and a released assignment is self-checked as the README says,
    both from the release."""
    venv = tmp_path / "venv"
    base = getattr(sys, "_base_executable", None) or sys.executable
    subprocess.run([base, "-m", "venv", "--without-pip", str(venv)], check=True)
    python = venv / "bin" / "python"
    purelib = Path(subprocess.run([str(python), "-c", "import sysconfig; print(sysconfig."
                                   "get_paths()['purelib'])"], check=True, text=True,
                                  capture_output=True).stdout.strip())
    lent = tmp_path / "pip-only"
    lent.mkdir()
    (lent / "pip").symlink_to(Path(sysconfig.get_paths()["purelib"]) / "pip")
    (purelib / "_lent.pth").write_text(f"{lent}\n")
    env = _clean_env(tmp_path, PATH=f"{venv / 'bin'}{os.pathsep}{os.environ['PATH']}")
    built = subprocess.run(["bash", "binder/postBuild"], cwd=release, capture_output=True,
                           text=True, env=env, timeout=300)
    assert built.returncode == 0, built.stdout + built.stderr
    assert (purelib / "kinlib" / "__init__.py").is_file(), "postBuild did not install kinlib"
    (purelib / "_lent.pth").write_text(sysconfig.get_paths()["purelib"] + "\n")

    (tmp_path / "run.py").write_text(RUN)
    ran = subprocess.run([str(python), str(tmp_path / "run.py"), str(venv),
                          "notebooks/08_urdf_and_matrix_stack.ipynb"], cwd=release,
                         capture_output=True, text=True, env=env, timeout=600)
    assert ran.returncode == 0, ran.stdout + ran.stderr[-3000:]
    # the self-check as the README tells a student to run it, from the release's folder
    (command,) = [line for line in (release / "README.md").read_text().splitlines()
                  if line.startswith("python -m kinlib.grade --self-check ")]
    graded = subprocess.run([str(python), *command.split()[1:]], cwd=release,
                            capture_output=True, text=True, env=env, timeout=600)
    assert graded.returncode == 0, graded.stdout + graded.stderr
    assert graded.stdout.startswith("PRACTICE: "), graded.stdout[:500]
    assert "(01_rotations: Rotations)" in graded.stdout
    assert "\n  total: 0 / " in graded.stdout  # blank: every function still unwritten
    assert _files(release) == set(json.loads((release / MANIFEST).read_text())["files"]) \
        | {MANIFEST}, "running the release left files in it"


# --- a second release updates a clone of the first -----------------------------------

def test_a_second_release_updates_a_clone_and_removes_what_is_no_longer_produced(release,
                                                                                  course,
                                                                                  tmp_path):
    clone = tmp_path / "clone"
    shutil.copytree(release, clone)
    (clone / ".git").mkdir()
    (clone / ".git" / "HEAD").write_text("ref: refs/heads/main\n")
    (clone / "LICENSE").write_text("the instructor's own file\n")
    manifest = json.loads((clone / MANIFEST).read_text())
    manifest["files"] += ["old/gone.txt", "wheels/kinlib-0.0.9-py3-none-any.whl"]
    (clone / MANIFEST).write_text(json.dumps(manifest))
    (clone / "old").mkdir()
    (clone / "old/gone.txt").write_text("from an earlier release\n")
    (clone / "wheels/kinlib-0.0.9-py3-none-any.whl").write_bytes(b"an older wheel")
    (clone / "README.md").write_text("edited by hand\n")

    out = _assign("--root", course, "--student-repo", clone, cwd=tmp_path)  # no --repo-url
    assert out.returncode == 0, out.stdout + out.stderr
    assert "\n  wrote README.md\n" in out.stdout + "\n"
    assert out.stdout.count("  wrote ") == 1, out.stdout  # the same wheel: the same bytes
    assert "removed old/gone.txt" in out.stdout
    assert not (clone / "old").exists() and not (clone / "wheels/kinlib-0.0.9-py3-none-any.whl"
                                                 ).exists()
    assert (clone / ".git/HEAD").read_text() == "ref: refs/heads/main\n"
    assert (clone / "LICENSE").read_text() == "the instructor's own file\n"
    assert (clone / "README.md").read_bytes() == (release / "README.md").read_bytes()
    assert _files(clone) == _files(release) | {"LICENSE"}
    assert json.loads((clone / MANIFEST).read_text()) == json.loads(
        (release / MANIFEST).read_text())  # the Binder address kept


# --- refusals ---------------------------------------------------------------------------

@pytest.fixture
def small(tmp_path) -> Path:
    """The course's editions alone: a release is refused before kinlib's wheel is built."""
    return _copy_course(tmp_path / "course", ("pyproject.toml", "instructor", "notebooks",
                                              "assignments"))


def _refused(course: Path, dest: Path, match: str, *more):
    with pytest.raises(KinlibError, match=match):
        main(["--root", str(course), "--student-repo", str(dest), *more])


def test_a_folder_that_is_neither_empty_nor_a_release_is_refused_with_exit_status_2(small):
    dest = small.parent / "full"
    dest.mkdir()
    (dest / "notes.txt").write_text("mine\n")
    out = _assign("--root", small, "--student-repo", dest, cwd=small.parent)
    assert out.returncode == 2, out.stdout + out.stderr
    assert "Traceback" not in out.stderr
    assert out.stderr.startswith("python -m kinlib.assign: ")
    assert "is not empty (notes.txt) and holds no student release" in out.stderr
    assert [p.name for p in dest.iterdir()] == ["notes.txt"]  # nothing written


def test_folders_that_would_publish_or_mix_with_the_course_repository_are_refused(small):
    for dest in (small, small.parent):
        _refused(small, dest, "is the course repository or holds it.*solutions")
    for dest in (small / "notebooks" / "student", small / "instructor" / "student",
                 small / "student"):
        _refused(small, dest, "inside the course repository .* not under build/")
        assert not dest.exists()
    assert check_destination(small, small / "build" / "student-repo", BEGIN) is None


def test_stale_or_missing_student_editions_are_refused(small):
    nb = small / "notebooks" / "01_spatial_descriptions.ipynb"
    nb.write_text(nb.read_text().replace("Spatial", "Spacial", 1))
    _refused(small, small.parent / "out", r"out of date \(.*01_spatial_descriptions.*make release")
    nb.unlink()
    _refused(small, small.parent / "out", "missing or out of date")
    assert not (small.parent / "out").exists()


def test_a_broken_manifest_or_instructor_files_in_a_previous_release_are_refused(small):
    dest = small.parent / "previous"
    dest.mkdir()
    record = {"format": "kinlib student release", "files": ["README.md"]}
    for files, match in ((["../outside.txt"], "not a path inside the student repository"),
                         (["/etc/passwd"], "not a path inside"), ([".git/config"], "not a path")):
        (dest / MANIFEST).write_text(json.dumps({**record, "files": files}))
        _refused(small, dest, match)
    (dest / MANIFEST).write_text(json.dumps({"files": []}))
    _refused(small, dest, "not the manifest of a kinlib student release")
    (dest / MANIFEST).write_text(json.dumps(record))
    shutil.copy2(small / "instructor" / "01_spatial_descriptions.ipynb", dest / "extra.ipynb")
    _refused(small, dest, r"holds instructor files .*extra\.ipynb")
    (dest / "extra.ipynb").unlink()
    (dest / "instructor").mkdir()
    (dest / "instructor" / "notes.md").write_text("answers\n")
    _refused(small, dest, r"instructor/notes\.md")


def test_bad_options_are_refused(small):
    _refused(small, small.parent / "out", "expected the student repository's https address",
             "--repo-url", "ftp://example.org/x")
    with pytest.raises(SystemExit) as exc:
        main(["--root", str(small), "--repo-url", URL])
    assert exc.value.code == 2


def test_a_release_does_not_overwrite_files_it_did_not_write(tmp_path):
    (tmp_path / "README.md").write_text("the instructor's\n")
    previous = {"format": "kinlib student release", "files": ["notebooks/01.ipynb"]}
    with pytest.raises(KinlibError, match=r"would overwrite README\.md, which the previous"):
        write_files(tmp_path, {"README.md": b"new"}, previous, {})
    assert (tmp_path / "README.md").read_text() == "the instructor's\n"
