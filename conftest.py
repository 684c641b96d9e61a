"""Session-wide test set-up: one meshcat server for the whole pytest run.

``pytest_configure`` starts ``python -m meshcat.servers.zmqserver`` in its own process
group and exports its addresses as ``KINLIB_MESHCAT_ZMQ_URL`` / ``KINLIB_MESHCAT_WEB_URL``
(and its pid as ``KINLIB_MESHCAT_SERVER_PID``), so every ``RobotVisualizer`` in the tests
and in notebooks run by nbval (whose kernels inherit the environment) talks to it.
``pytest_unconfigure`` ends the whole process group and restores the environment. Hooks,
not fixtures: nbval kills kernels hard and fixture teardown is skipped on some exits, which
leaks servers. If ``KINLIB_MESHCAT_ZMQ_URL`` is already set, that server is used and none
is started. See DEVELOPERS.md.
"""

from __future__ import annotations

import os
import queue
import signal
import subprocess
import sys
import tempfile
import threading
import time

ZMQ_ENV = "KINLIB_MESHCAT_ZMQ_URL"
WEB_ENV = "KINLIB_MESHCAT_WEB_URL"
PID_ENV = "KINLIB_MESHCAT_SERVER_PID"
START_TIMEOUT = 30.0

_state: dict = {}


def _drain(stream, lines: queue.Queue) -> None:
    """Read the server's stdout until it closes (so its pipe never fills up)."""
    for raw in iter(stream.readline, b""):
        lines.put(raw.decode("utf-8", "replace").strip())
    stream.close()


def _start_server() -> tuple[subprocess.Popen, str, str, str]:
    log = tempfile.NamedTemporaryFile(prefix="kinlib-meshcat-", suffix=".log", delete=False)
    env = dict(os.environ, PYTHONUNBUFFERED="1")
    proc = subprocess.Popen(
        [sys.executable, "-m", "meshcat.servers.zmqserver"],
        stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=log, env=env,
        start_new_session=True,
    )
    log.close()
    lines: queue.Queue = queue.Queue()
    threading.Thread(target=_drain, args=(proc.stdout, lines), daemon=True).start()
    urls: dict[str, str] = {}
    deadline = time.monotonic() + START_TIMEOUT
    while len(urls) < 2:
        left = deadline - time.monotonic()
        if left <= 0 or proc.poll() is not None:
            _stop_server(proc)
            with open(log.name, encoding="utf-8", errors="replace") as fh:
                tail = fh.read()[-2000:]
            os.unlink(log.name)
            why = "timed out" if left <= 0 else f"exited with code {proc.returncode}"
            raise RuntimeError(f"meshcat server {why} before printing its URLs; its stderr:\n"
                               f"{tail}")
        try:
            line = lines.get(timeout=min(left, 0.2))
        except queue.Empty:
            continue
        for key in ("zmq_url", "web_url"):
            if line.startswith(key + "="):
                urls[key] = line[len(key) + 1:]
    return proc, urls["zmq_url"], urls["web_url"], log.name


def _stop_server(proc: subprocess.Popen) -> None:
    """SIGTERM the server's process group, wait, then SIGKILL if it is still there."""
    for sig, wait in ((signal.SIGTERM, 5.0), (signal.SIGKILL, 5.0)):
        try:
            os.killpg(proc.pid, sig)
        except ProcessLookupError:
            break
        try:
            proc.wait(timeout=wait)
            break
        except subprocess.TimeoutExpired:
            continue
    if proc.poll() is None:
        proc.wait(timeout=5.0)


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
    proc, zmq_url, web_url, log = _start_server()
    _state.update(proc=proc, log=log,
                  saved={k: os.environ.get(k) for k in (ZMQ_ENV, WEB_ENV, PID_ENV)})
    os.environ[ZMQ_ENV] = zmq_url
    os.environ[WEB_ENV] = web_url
    os.environ[PID_ENV] = str(proc.pid)


def pytest_unconfigure(config):
    proc = _state.pop("proc", None)
    if proc is None:
        return
    _stop_server(proc)
    for key, value in _state.pop("saved").items():
        if value is None:
            os.environ.pop(key, None)
        else:
            os.environ[key] = value
    try:
        os.unlink(_state.pop("log"))
    except OSError:
        pass
