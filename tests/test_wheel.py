"""kinlib installs anywhere: a wheel built from the checkout, installed into a fresh virtual
environment outside the repository, has everything it reads at run time, runs the README's
first taste and grades an assignment in the sandbox; and where the compiled kernels cannot
be built (numba too old or too new for this Python: on 3.10 ``_fk_numba`` fails on
``co_qualname``), kinlib says so once and takes its numpy path.

The fresh environment has no pip and no packages of its own: kinlib alone is installed into
it (by the checkout's pip, ``--python``, from the wheel), and a ``.pth`` file appended *after*
that lends it the checkout environment's site-packages for the dependencies (a plain path
line: that folder's own ``.pth`` files, the editable install of kinlib among them, are not
run). Every command runs with the temporary folder as its working directory.
"""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
import sysconfig
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[1]
README = REPO / "README.md"


def _env(**extra) -> dict:
    """The environment of a command in the fresh venv: nothing pointing at the checkout."""
    env = {k: v for k, v in os.environ.items()
           if k not in ("PYTHONPATH", "PYTHONHOME", "PYTHONSTARTUP", "VIRTUAL_ENV")}
    return {**env, "PYTHONNOUSERSITE": "1", **extra}


def first_taste(text: str) -> str:
    """The code block under the README's ``## A first taste`` heading (a doctest).

    >>> first_taste("# x\\n## A first taste\\n\\nSay\\n\\n```python\\n>>> 1 + 1\\n2\\n```\\n")
    '>>> 1 + 1\\n2\\n'
    """
    m = re.search(r"^## A first taste\n.*?^```python\n(.*?)^```", text, re.M | re.S)
    assert m, "README.md: no ```python block under '## A first taste'"
    return m.group(1)


@pytest.fixture(scope="module")
def venv(tmp_path_factory) -> Path:
    """A fresh venv outside the repository with kinlib installed from a wheel of the
    checkout; its python."""
    tmp = tmp_path_factory.mktemp("wheel")
    assert REPO not in tmp.parents, tmp
    src = tmp / "src"  # the checkout's sources, so that the build leaves nothing behind
    src.mkdir()
    for name in ("pyproject.toml", "README.md"):
        shutil.copy2(REPO / name, src / name)
    shutil.copytree(REPO / "kinlib", src / "kinlib",
                    ignore=shutil.ignore_patterns("__pycache__", "*.pyc"))
    dist = tmp / "dist"
    build = subprocess.run([sys.executable, "-m", "pip", "wheel", "--quiet", "--no-deps",
                            "--no-build-isolation", "--no-index", "--wheel-dir", str(dist),
                            str(src)], cwd=tmp, capture_output=True, text=True, env=_env())
    assert build.returncode == 0, build.stdout + build.stderr
    (wheel,) = dist.glob("kinlib-*.whl")
    env_dir = tmp / "venv"
    base = getattr(sys, "_base_executable", None) or sys.executable
    subprocess.run([base, "-m", "venv", "--without-pip", str(env_dir)], check=True, cwd=tmp)
    python = env_dir / "bin" / "python"
    install = subprocess.run([sys.executable, "-m", "pip", "--python", str(python), "install",
                              "--quiet", "--no-deps", "--no-index", str(wheel)],
                             cwd=tmp, capture_output=True, text=True, env=_env())
    assert install.returncode == 0, install.stdout + install.stderr
    purelib = subprocess.run([str(python), "-c", "import sysconfig; "
                              "print(sysconfig.get_paths()['purelib'])"], cwd=tmp, check=True,
                             capture_output=True, text=True, env=_env()).stdout.strip()
    assert (Path(purelib) / "kinlib" / "__init__.py").exists()
    deps = sysconfig.get_paths()["purelib"]  # this (the checkout's) environment's packages
    (Path(purelib) / "_kinlib_test_deps.pth").write_text(deps + "\n")
    return python


def _run(python: Path, *args, cwd: Path, **env) -> subprocess.CompletedProcess:
    return subprocess.run([str(python), *args], cwd=cwd, capture_output=True, text=True,
                          env=_env(**env), timeout=600)


CHECK = """\
import doctest, importlib.util, sys
from pathlib import Path
import kinlib
venv, repo = Path(sys.argv[1]).resolve(), Path(sys.argv[2]).resolve()
here = Path(kinlib.__file__).resolve()
assert venv in here.parents, f"kinlib imported from {here}, not from {venv}"
for entry in sys.path:
    p = Path(entry or ".").resolve()
    assert p != repo, f"the repository is on sys.path: {entry!r}"
    if (p / "kinlib").exists():
        assert venv in p.parents, f"another kinlib on sys.path: {p / 'kinlib'}"
assert not [m for m in sys.modules if "editable" in m], "the editable install was loaded"
# what kinlib reads at run time came with the wheel
from kinlib.robots import autorob_test_robot
from kinlib.site import TEMPLATES
from kinlib.student import template
from kinlib.viz._widget import scene_js
assert autorob_test_robot().dof == 3
assert (Path(str(TEMPLATES)) / "kinlib_page.html.j2").is_file()
assert all(template(name) for name in ("README.md", "postBuild", "runtime.txt", "gitignore"))
assert "function" in scene_js()
worker = importlib.util.find_spec("kinlib.grade._worker").origin
assert venv in Path(worker).resolve().parents, worker
# the README's first taste, as the README has it
flags = doctest.NORMALIZE_WHITESPACE | doctest.ELLIPSIS
test = doctest.DocTestParser().get_doctest(Path("first_taste.txt").read_text(), {},
                                           "README first taste", "README.md", 0)
runner = doctest.DocTestRunner(optionflags=flags)
runner.run(test)
assert runner.failures == 0 and runner.tries >= 5, (runner.failures, runner.tries)
print("ok", here)
"""


def test_the_wheel_in_a_fresh_venv_runs_the_first_taste(venv, tmp_path):
    (tmp_path / "first_taste.txt").write_text(first_taste(README.read_text()))
    (tmp_path / "check.py").write_text(CHECK)
    out = _run(venv, "check.py", str(venv.parents[1]), str(REPO), cwd=tmp_path)
    assert out.returncode == 0, out.stdout + out.stderr
    assert out.stdout.startswith("ok ")


def test_the_wheel_grades_an_assignment_in_the_sandbox(venv, tmp_path):
    # the instructor's solution and the blank student edition, copied out of the repository
    for folder, edition in (("solution", "source"), ("blank", "release")):
        (tmp_path / folder).mkdir()
        shutil.copy2(REPO / "assignments" / edition / "01_rotations.ipynb", tmp_path / folder)
    out = _run(venv, "-m", "kinlib.grade", "--json", "--no-write", "--jobs", "2",
               "solution/01_rotations.ipynb", "blank/01_rotations.ipynb", cwd=tmp_path)
    assert out.returncode == 0, out.stdout + out.stderr
    results = {Path(r["submission"]).parent.name: r
               for r in map(json.loads, out.stdout.splitlines())}
    solution, blank = results["solution"], results["blank"]
    for r in (solution, blank):
        assert r["graded"] and r["assignment"] == "01_rotations", r
        assert r["sandbox"] and r["sandbox"].startswith("bubblewrap"), r["sandbox"]
        assert "warning" not in r
        assert r["max_score"] == sum(c["points"] for c in r["checks"]) > 0
    assert solution["score"] == solution["max_score"]
    assert all(c["passed"] == c["total"] > 0 for c in solution["checks"])
    assert blank["score"] == 0


def test_the_tools_name_their_folders_when_run_elsewhere(venv, tmp_path):
    """Outside the repository the defaults (instructor/, notebooks/ of the current
    directory) are missing: a clean message naming the option, exit status 2."""
    assign = _run(venv, "-m", "kinlib.assign", "--check", cwd=tmp_path)
    assert assign.returncode == 2, assign.stdout + assign.stderr
    assert "Traceback" not in assign.stderr
    assert "no source notebooks in" in assign.stderr and "--root" in assign.stderr
    site = _run(venv, "-m", "kinlib.site", "--out", "out", cwd=tmp_path)
    assert site.returncode == 2, site.stdout + site.stderr
    assert "Traceback" not in site.stderr and "--notebooks" in site.stderr
    assert not (tmp_path / "out").exists() and not (tmp_path / "build").exists()


# --- the compiled kernels: a failure to build them falls back to numpy ------------------

FALLBACK = """\
import importlib.abc, json, sys, warnings
import numpy as np

BROKEN = set(sys.argv[1].split(","))  # modules whose import fails as on Python 3.10


class Broken(importlib.abc.MetaPathFinder):
    def find_spec(self, name, path=None, target=None):
        if name in BROKEN:
            raise TypeError("replace() got an unexpected keyword argument 'co_qualname' "
                            "(simulated)")
        return None


sys.meta_path.insert(0, Broken())
if "numba" in BROKEN:
    sys.modules["numba"] = None  # numba not installed: no warning
warnings.simplefilter("error")  # any other warning fails the run
import kinlib as kl
from kinlib.kinematics import _fk, ik
from kinlib.robots import planar_2r, puma560
from kinlib.robots.puma560 import PUMA560_TABLE

caught = []
with warnings.catch_warnings(record=True) as caught:
    warnings.simplefilter("always")
    t1, t2, l1, l2 = 0.3, -1.1, 1.0, 0.5
    T = planar_2r(l1, l2).fk([t1, t2])
    closed = [l1 * np.cos(t1) + l2 * np.cos(t1 + t2), l1 * np.sin(t1) + l2 * np.sin(t1 + t2)]
    assert np.allclose(T[:2, 3], closed, atol=1e-12), (T, closed)
    robot = puma560()
    Q = np.random.default_rng(3).uniform(-1, 1, (50, 6))
    ref = []
    for q in Q:  # standard DH, row by row, from seed 001's table
        A = np.eye(4)
        for (_, _, alpha, a, d, _), qi in zip(PUMA560_TABLE, q):
            A = A @ kl.dh_transform(theta=qi, d=d / 1000, a=a / 1000, alpha=np.deg2rad(alpha))
        ref.append(A)
    assert np.allclose(robot.fk(Q), ref, atol=1e-12)
    near = robot.poses["ready"] + np.random.default_rng(1).uniform(-0.3, 0.3, (4, 6))
    sol = robot.ik(robot.fk(near))
    assert bool(sol.success.all()) and (sol.position_error < 1e-6).all(), sol
    kl.prepare_kernels()  # (the calls above started them: their failure is warned here)
fk_kernels, ik_kernels = _fk._compiled(), ik._compiled_ik()
print(json.dumps({"warnings": [str(w.message) for w in caught],
                  "categories": [w.category.__name__ for w in caught],
                  "fk": fk_kernels is not None, "ik": ik_kernels is not None}))
"""


@pytest.mark.parametrize("broken, fk, ik, warned", [
    ("kinlib.kinematics._fk_numba", False, False, "kinlib.kinematics._fk_numba"),
    ("kinlib.kinematics._ik_numba", True, False, "kinlib.kinematics._ik_numba"),
    ("numba", False, False, None),
])
def test_kernels_that_cannot_be_built_fall_back_to_numpy(broken, fk, ik, warned, tmp_path):
    script = tmp_path / "fallback.py"
    script.write_text(FALLBACK)
    env = {k: v for k, v in os.environ.items() if k != "KINLIB_NUMBA"}
    out = subprocess.run([sys.executable, str(script), broken], cwd=REPO, capture_output=True,
                         text=True, env=env, timeout=600)
    assert out.returncode == 0, out.stdout + out.stderr
    report = json.loads(out.stdout.strip().splitlines()[-1])
    assert (report["fk"], report["ik"]) == (fk, ik), report
    if warned is None:
        assert report["warnings"] == [], report  # numba missing: silently numpy
    else:
        assert report["categories"] == ["RuntimeWarning"], report  # once, not per call
        (message,) = report["warnings"]
        assert f"({warned}) could not be built" in message and "numpy" in message
        assert "'co_qualname' (simulated)" in message and "KINLIB_NUMBA=0" in message


def test_with_nothing_broken_the_kernels_are_used():
    """The control: the same script, nothing broken: the compiled kernels are used (numba
    is installed by the project's environment) and nothing warns."""
    out = subprocess.run([sys.executable, "-c", FALLBACK, "nothing"], cwd=REPO,
                         capture_output=True, text=True, timeout=600,
                         env={k: v for k, v in os.environ.items() if k != "KINLIB_NUMBA"})
    assert out.returncode == 0, out.stdout + out.stderr
    report = json.loads(out.stdout.strip().splitlines()[-1])
    assert report == {"warnings": [], "categories": [], "fk": True, "ik": True}
