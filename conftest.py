"""Session-wide test set-up: exercise checks, the course site's build, hypothesis.

The 3-D viewer is a widget (``kinlib.viz.Scene``): it needs no server, so the session
starts none.

The instructor edition of the notebooks (``instructor/``) runs under nbval, and every
exercise's check must say "right" there: ``pytest_runtest_call`` reads the check outputs
(``application/vnd.kinlib.check+json``) of each cell nbval ran and fails the cell if one is
not right; the notebook's last cell also fails unless every exercise of the notebook was
checked, once each, in order.

The course site the browser tests read (``tests/test_site.py``) comes from the student
edition as JupyterLab ran it (``tests/test_lab.py``: kernels on kinlib's numpy path,
``KINLIB_NUMBA=0``, as for a student without numba; widget state saved): each notebook
JupyterLab saved goes to the session's folder (the ``site_feed`` fixture), and when the
JupyterLab module ends, ``python -m kinlib.site --executed`` exports them in the background.
So the student edition runs once for both, and nbval runs the instructor edition compiled.
A session without the whole JupyterLab run (``pytest tests/test_site.py``, or ``-k``) builds
the site by executing the notebooks instead, from ``pytest_collection_finish``, while the
other tests run; so does a JupyterLab run that did not save every notebook. The ``site``
fixture waits for the build. Under pytest-xdist (``make test`` runs two workers) the build
is shared: the controller makes its folder (``$KINLIB_TEST_SITE``), the first process to
ask starts it, and whichever worker runs the site's tests waits for its exit code there.
The build belongs to the session, not to the worker that started it (a worker whose share
of the tests ends early must not take the build with it): it ends when it is done, when
the session's first process (the xdist controller, or pytest itself) exits, whose
``pytest_unconfigure`` stops it, or when that process dies (the build's wrapper watches it).
"""

from __future__ import annotations

import json
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent
INSTRUCTOR = ROOT / "instructor"

_state: dict = {}


def _hypothesis_profile() -> None:
    """Property tests draw the same examples on every run (reproducible CI); set
    ``HYPOTHESIS_PROFILE=explore`` to draw new random examples locally."""
    from hypothesis import settings

    settings.register_profile("kinlib", derandomize=True, print_blob=True)
    settings.register_profile("explore", derandomize=False, print_blob=True)
    settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "kinlib"))


SITE_ENV = "KINLIB_TEST_SITE"  # the session's site-build folder, shared with xdist workers
#: run by the build's own process: the site, its log, and its exit code in a file when done
SITE_OWNER_ENV = "KINLIB_TEST_SESSION_PID"  # the session's first process: owns the build
#: run by the build's own process (a new process group, whose leader writes ``pid``): the
#: site, its log, and its exit code in a file when done; ended if the owner dies
SITE_BUILD = """import os, subprocess, sys, time
folder, jobs, owner, executed = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4:]
with open(folder + "/pid", "w") as fh:
    fh.write(str(os.getpid()))
with open(folder + "/build.log", "wb") as log:
    source = ["--executed", "--notebooks", executed[0]] if executed else []
    build = subprocess.Popen([sys.executable, "-m", "kinlib.site", "--out", folder + "/site",
                              "--jobs", jobs, *source], stdout=log, stderr=subprocess.STDOUT,
                             env=dict(os.environ, KINLIB_NUMBA="0"))
    while build.poll() is None:
        try:
            os.kill(owner, 0)
        except ProcessLookupError:  # the test session is gone: so is its build
            build.kill()
            build.wait()
            sys.exit(1)
        time.sleep(0.5)
with open(folder + "/rc.tmp", "w") as fh:
    fh.write(str(build.returncode))
os.replace(folder + "/rc.tmp", folder + "/rc")
"""


#: run once by the controller before the workers start: numba compiles kinlib's kernels into
#: its cache (kinlib/__pycache__), so the workers, notebook kernels and the site build load
#: them instead of each compiling them at once on a clean clone. Two processes side by side
#: (the FK, Jacobian and conversion kernels; the IK loop), one per core: about half the
#: time of one after the other (numba compiles one function at a time in a process)
WARM_KERNELS = (
    'import kinlib; kinlib.prepare_kernels(["fk", "jacobian", "link_poses", "conversions"])',
    'import kinlib; kinlib.prepare_kernels(["ik"])',
)


def pytest_configure(config):
    _hypothesis_profile()
    if hasattr(config, "workerinput"):
        return  # an xdist worker: the controller made the folder
    if getattr(config.option, "numprocesses", None) and not config.option.collectonly:
        warm = [subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.DEVNULL,
                                 stderr=subprocess.DEVNULL) for script in WARM_KERNELS]
        for process in warm:
            process.wait()
    os.environ[SITE_OWNER_ENV] = str(os.getpid())
    if not os.environ.get(SITE_ENV):
        _state["site_folder"] = tempfile.mkdtemp(prefix="kinlib-site-")
        os.environ[SITE_ENV] = _state["site_folder"]


def _start_site_build(jobs: int, executed: Path | None = None) -> None:
    """``python -m kinlib.site`` into the session's folder, in the background, once per
    session whichever process asks first (owned by the session, see above); when it ends,
    the folder holds ``build.log`` and ``rc``. ``executed``: a folder of notebooks that have
    run (JupyterLab's, saved with their widget state), exported without running them."""
    folder = os.environ[SITE_ENV]
    try:
        os.close(os.open(os.path.join(folder, "started"), os.O_CREAT | os.O_EXCL))
    except FileExistsError:
        return  # another process of the session started it
    _state["site_build"] = subprocess.Popen(  # kept, to reap it if it is ours
        [sys.executable, "-c", SITE_BUILD, folder, str(jobs), os.environ[SITE_OWNER_ENV],
         *([str(executed)] if executed is not None else [])],
        stdin=subprocess.DEVNULL, start_new_session=True, cwd=os.path.dirname(__file__))


#: the files that take longest, in this order before all others: ``make test`` hands files to
#: its two workers in collection order (``--no-loadscope-reorder``), so the long ones start
#: at once and the short ones fill in around them
FIRST = ("tests/test_lab.py", "tests/test_lab_cleanup.py",
         "tests/test_urdf_errors.py", "tests/test_grader_hostile.py", "tests/test_sym_helpers.py")


#: this one after the other test files, its site comes from the JupyterLab run (the first
#: file), but before the notebooks under nbval and the doctests: many short files, which
#: keep the other worker busy while this one runs
LATE = "tests/test_site.py"


def _rank(item) -> int:
    path = item.nodeid.split("::")[0]
    if path in FIRST:
        return FIRST.index(path)
    if path == LATE:
        return len(FIRST) + 1
    return len(FIRST) if path.startswith("tests/") else len(FIRST) + 2


def pytest_collection_modifyitems(session, config, items):
    items.sort(key=_rank)  # stable


#: the browser suite's run of the student edition in JupyterLab (tests/test_lab.py)
LAB_RUNS = "tests/test_lab.py::test_notebook_runs_in_jupyterlab["
NOTEBOOKS = ROOT / "notebooks"


def _course_notebooks() -> set[str]:
    """The file names of the course's notebooks (the student edition)."""
    return {p.name for p in NOTEBOOKS.glob("[0-9][0-9]_*.ipynb")}


def pytest_collection_finish(session):
    if session.config.option.collectonly:
        return
    if not any("site" in getattr(item, "fixturenames", ()) for item in session.items):
        return
    runs = sum(item.nodeid.startswith(LAB_RUNS) for item in session.items)
    if runs and runs == len(_course_notebooks()):
        _state["lab_feeds_site"] = True  # JupyterLab runs them all: the site from its saves
    else:
        _start_site_build(jobs=1)  # one notebook at a time: the tests run on the other core


class SiteFeed:
    """What the JupyterLab run (tests/test_lab.py) hands the site build: each notebook as
    JupyterLab saved it after *Run All Cells*, on the numpy path, widget state included.
    :meth:`done` starts the site's export from them when the run saved every notebook of
    the course; otherwise (a failed or partial run) the build executes the notebooks
    itself, so that the site's tests still read a site. Nothing happens unless the session
    collected the site's tests and the whole JupyterLab run."""

    def __init__(self):
        self.folder = Path(os.environ[SITE_ENV]) / "notebooks"
        self.active = bool(_state.get("lab_feeds_site"))
        if self.active:
            self.folder.mkdir(exist_ok=True)

    def save(self, name: str, nb: dict) -> None:
        if self.active:
            tmp = self.folder / f"{name}.ipynb.tmp"
            tmp.write_text(json.dumps(nb))
            os.replace(tmp, self.folder / f"{name}.ipynb")

    def done(self) -> None:
        if not self.active:
            return
        expected = _course_notebooks()
        if expected and {p.name for p in self.folder.glob("*.ipynb")} == expected:
            _start_site_build(jobs=1, executed=self.folder)
        else:
            _start_site_build(jobs=2)


@pytest.fixture(scope="session")
def site_feed():
    """The JupyterLab run's notebooks for the site build (:class:`SiteFeed`)."""
    return SiteFeed()


@pytest.fixture(scope="session")
def site():
    """The course site (a folder), from the build started when the session was collected
    (by this process or another worker of the session), or from one started now. Fails
    with the build's log if the build failed."""
    if not _state.get("lab_feeds_site"):  # (else the JupyterLab run starts it when done)
        _start_site_build(jobs=2)  # does nothing if the build was started
    folder = Path(os.environ[SITE_ENV])
    waited, deadline = time.monotonic(), time.monotonic() + 900
    while not (folder / "rc").exists():
        if time.monotonic() > deadline:
            pytest.fail("the site build did not finish in 900 s")
        time.sleep(0.5)
    log = (folder / "build.log").read_text(errors="replace")
    assert (folder / "rc").read_text() == "0", f"the site build failed:\n{log[-4000:]}"
    lines = log.strip().splitlines()
    print(f"site build: {lines[0]}; {lines[-1]} (waited {time.monotonic() - waited:.1f} s)")
    return folder / "site"


def _code_cells(path: Path) -> int:
    import nbformat

    cached = _state.setdefault("code_cells", {})
    if path not in cached:
        nb = nbformat.read(path, as_version=4)
        cached[path] = sum(c.cell_type == "code" for c in nb.cells)
    return cached[path]


@pytest.hookimpl(wrapper=True)
def pytest_runtest_call(item):
    result = yield
    if type(item).__name__ == "IPyNbCell" and Path(item.fspath).parent == INSTRUCTOR:
        _judge_instructor_cell(item)
    return result


def _judge_instructor_cell(item) -> None:
    from kinlib.check import exercises, results

    path = Path(item.fspath)
    checks = results(list(item.test_outputs or ()))
    seen = _state.setdefault("checked", {}).setdefault(path.stem, [])
    seen.extend(c["exercise"] for c in checks)
    wrong = [c for c in checks if c["status"] != "right"]
    assert not wrong, f"the solution of exercise {wrong[0]['exercise']} is not right: " \
                      f"{wrong[0]['status']}: {wrong[0]['message']}"
    if item.cell_num == _code_cells(path) - 1:
        expected = [e.id for e in exercises(path.stem[:2])]
        assert seen == expected, f"{path.name}: exercises checked {seen}, expected {expected}"


def _stop_site_build(folder: Path) -> None:
    """End the session's site build (its whole process group) if it still runs."""
    try:
        leader = int((folder / "pid").read_text())
    except (OSError, ValueError):
        return  # never started
    if not (folder / "rc").exists():
        try:
            os.killpg(leader, signal.SIGKILL)  # the wrapper and the build under it
        except ProcessLookupError:
            pass


def pytest_unconfigure(config):
    folder = _state.pop("site_folder", None)
    if folder is not None:  # the session's owner: the build ends with it
        _stop_site_build(Path(folder))
        shutil.rmtree(folder, ignore_errors=True)
        os.environ.pop(SITE_ENV, None)
    build = _state.pop("site_build", None)
    if build is not None and build.poll() is None and folder is not None:
        build.wait()  # our own child, killed above: reaped
