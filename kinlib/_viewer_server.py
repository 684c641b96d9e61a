"""A meshcat server process that cannot outlive the Python process that started it.

meshcat starts its server with ``start_new_session=True`` and never stops it: a kernel
that is killed (nbval, "restart kernel" after a timeout, a crash) leaves the server behind,
holding its ports. kinlib starts the server itself instead:

- on Linux the child asks the kernel for ``PR_SET_PDEATHSIG``: it gets SIGTERM the moment
  its parent dies, *however* the parent dies (even SIGKILL);
- everywhere, an ``atexit`` handler ends it (and its process group) on a normal exit.

:func:`own_server` keeps one such server per process, started on first use; the test
session's ``conftest.py`` uses :func:`start_server` directly. This module imports neither
meshcat nor zmq, so the test set-up can use it without loading them.
"""

from __future__ import annotations

import atexit
import ctypes
import os
import queue
import signal
import subprocess
import sys
import threading
import time
from dataclasses import dataclass, field

from .errors import KinlibError

__all__ = ["ViewerServer", "start_server", "own_server"]

_PR_SET_PDEATHSIG = 1


def _die_with(parent: int):
    """A ``preexec_fn``: SIGTERM this child when ``parent`` dies (Linux; else a no-op)."""
    def setup() -> None:
        if not sys.platform.startswith("linux"):
            return
        try:
            libc = ctypes.CDLL(None, use_errno=True)
            libc.prctl(_PR_SET_PDEATHSIG, signal.SIGTERM, 0, 0, 0)
        except (OSError, AttributeError):
            return
        if os.getppid() != parent:  # the parent died before prctl took effect
            os._exit(1)
    return setup


def _drain(stream, lines: queue.Queue) -> None:
    """Read the server's stdout until it closes, so its pipe never fills up."""
    for raw in iter(stream.readline, b""):
        lines.put(raw.decode("utf-8", "replace").strip())
    stream.close()


@dataclass
class ViewerServer:
    """A running ``meshcat.servers.zmqserver``: its process and its two addresses."""

    proc: subprocess.Popen
    zmq_url: str
    web_url: str
    log: str | None = None
    _stopped: bool = field(default=False, repr=False)

    @property
    def pid(self) -> int:
        return self.proc.pid

    def stop(self) -> None:
        """SIGTERM the server's process group, wait, then SIGKILL if it is still there."""
        if self._stopped:
            return
        self._stopped = True
        for sig in (signal.SIGTERM, signal.SIGKILL):
            try:
                os.killpg(self.proc.pid, sig)
            except (ProcessLookupError, PermissionError):
                break
            try:
                self.proc.wait(timeout=5.0)
                break
            except subprocess.TimeoutExpired:
                continue
        if self.proc.poll() is None:
            self.proc.wait(timeout=5.0)


def start_server(*, log: str | None = None, timeout: float = 30.0,
                 die_with_parent: bool = True) -> ViewerServer:
    """Start ``python -m meshcat.servers.zmqserver`` in its own process group.

    Waits (at most ``timeout`` s) until it prints its ``zmq_url`` and ``web_url``. Its
    stderr goes to the file ``log`` (else it is discarded). With ``die_with_parent`` the
    server ends when this process ends, even if this process is killed.
    """
    err = open(log, "ab") if log else subprocess.DEVNULL  # closed below, once Popen has it
    try:
        proc = subprocess.Popen(
            [sys.executable, "-u", "-m", "meshcat.servers.zmqserver"],
            stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=err,
            env=dict(os.environ, PYTHONUNBUFFERED="1"), start_new_session=True,
            preexec_fn=_die_with(os.getpid()) if die_with_parent else None)
    finally:
        if log:
            err.close()
    lines: queue.Queue = queue.Queue()
    threading.Thread(target=_drain, args=(proc.stdout, lines), daemon=True).start()
    urls: dict[str, str] = {}
    deadline = time.monotonic() + timeout
    while len(urls) < 2:
        left = deadline - time.monotonic()
        if left <= 0 or proc.poll() is not None:
            ViewerServer(proc, "", "").stop()
            tail = ""
            if log:
                with open(log, encoding="utf-8", errors="replace") as fh:
                    tail = "; its stderr:\n" + fh.read()[-2000:]
            why = f"timed out after {timeout} s" if left <= 0 else \
                f"exited with code {proc.returncode}"
            raise KinlibError(f"the meshcat server {why} before printing its addresses{tail}")
        try:
            line = lines.get(timeout=min(left, 0.2))
        except queue.Empty:
            continue
        for key in ("zmq_url", "web_url"):
            if line.startswith(key + "="):
                urls[key] = line[len(key) + 1:]
    return ViewerServer(proc, urls["zmq_url"], urls["web_url"], log)


_OWN: dict[int, ViewerServer] = {}  # pid -> this process's server (a forked child starts anew)


def own_server() -> ViewerServer:
    """This process's meshcat server, started on first use and ended with the process.

    One per process, so all visualizers of a notebook share one viewer page.
    """
    server = _OWN.get(os.getpid())
    if server is None or server.proc.poll() is not None:
        server = start_server()
        _OWN[os.getpid()] = server
        atexit.register(server.stop)
    return server
