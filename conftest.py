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
"""

from __future__ import annotations

import os
import tempfile

from kinlib._viewer_server import ViewerServer, start_server

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


def pytest_unconfigure(config):
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
