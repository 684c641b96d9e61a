"""Session-wide test set-up: one meshcat server for the whole pytest run.

``pytest_configure`` starts ``python -m meshcat.servers.zmqserver`` in its own process
group (:func:`kinlib._viewer_server.start_server`; it also dies if pytest is killed) and
exports its addresses as ``KINLIB_MESHCAT_ZMQ_URL`` / ``KINLIB_MESHCAT_WEB_URL`` (and its
pid as ``KINLIB_MESHCAT_SERVER_PID``), so every ``RobotVisualizer`` in the tests and in
notebooks run by nbval (whose kernels inherit the environment) talks to it.
``pytest_unconfigure`` ends the whole process group and restores the environment. Hooks,
not fixtures: nbval kills kernels hard and fixture teardown is skipped on some exits, which
leaks servers. If ``KINLIB_MESHCAT_ZMQ_URL`` is already set, that server is used and none
is started. See DEVELOPERS.md.

The course site the browser tests read (``tests/test_site.py``) is built in the background
from ``pytest_collection_finish`` when a collected test asks for it: ``python -m kinlib.site``
runs on the second core while the other tests run (one notebook at a time), and the
``site`` fixture waits for it. ``pytest_unconfigure`` stops it if it is still running.
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time

from kinlib._viewer_server import ViewerServer, _die_with, start_server

ZMQ_ENV = "KINLIB_MESHCAT_ZMQ_URL"
WEB_ENV = "KINLIB_MESHCAT_WEB_URL"
PID_ENV = "KINLIB_MESHCAT_SERVER_PID"
START_TIMEOUT = 30.0

_state: dict = {}


def _start_server() -> ViewerServer:
    log = tempfile.NamedTemporaryFile(prefix="kinlib-meshcat-", suffix=".log", delete=False)
    log.close()
    try:
        return start_server(log=log.name, timeout=START_TIMEOUT)
    except Exception:
        os.unlink(log.name)
        raise


def _hypothesis_profile() -> None:
    """Property tests draw the same examples on every run (reproducible CI); set
    ``HYPOTHESIS_PROFILE=explore`` to draw new random examples locally."""
    from hypothesis import settings

    settings.register_profile("kinlib", derandomize=True, print_blob=True)
    settings.register_profile("explore", derandomize=False, print_blob=True)
    settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "kinlib"))


def pytest_configure(config):
    _hypothesis_profile()
    if os.environ.get(ZMQ_ENV) or hasattr(config, "workerinput"):
        return  # a server is given (or an xdist worker: the controller started it)
    server = _start_server()
    _state.update(server=server,
                  saved={k: os.environ.get(k) for k in (ZMQ_ENV, WEB_ENV, PID_ENV)})
    os.environ[ZMQ_ENV] = server.zmq_url
    os.environ[WEB_ENV] = server.web_url
    os.environ[PID_ENV] = str(server.pid)


def pytest_collection_finish(session):
    if hasattr(session.config, "workerinput") or session.config.option.collectonly:
        return
    if not any("site" in getattr(item, "fixturenames", ()) for item in session.items):
        return
    folder = tempfile.mkdtemp(prefix="kinlib-site-")
    env = {k: v for k, v in os.environ.items() if not k.startswith("KINLIB_MESHCAT_")}
    with open(os.path.join(folder, "build.log"), "wb") as log:
        proc = subprocess.Popen([sys.executable, "-m", "kinlib.site", "--out",
                                 os.path.join(folder, "site"), "--jobs", "1"],
                                stdout=log, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL,
                                env=env, start_new_session=True, cwd=os.path.dirname(__file__),
                                preexec_fn=_die_with(os.getpid()))
    # read by the ``site`` fixture (tests/conftest.py)
    session.config.kinlib_site_build = _state["site_build"] = {
        "proc": proc, "folder": folder, "started": time.monotonic()}


def pytest_unconfigure(config):
    build = _state.pop("site_build", None)
    if build is not None:
        if build["proc"].poll() is None:
            build["proc"].kill()
            build["proc"].wait()
        import shutil

        shutil.rmtree(build["folder"], ignore_errors=True)
    server = _state.pop("server", None)
    if server is None:
        return
    server.stop()
    for key, value in _state.pop("saved").items():
        if value is None:
            os.environ.pop(key, None)
        else:
            os.environ[key] = value
    try:
        os.unlink(server.log)
    except OSError:
        pass
