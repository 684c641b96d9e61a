"""The grader's side of the student's process: start it, limit it, talk to it, kill it.

The student's code runs in ``python -I .../_worker.py`` (see there), inside the bubblewrap
sandbox of :mod:`kinlib.grade._bwrap` (or, only when the instructor asks for it, without
one), a child in its own process group, with

- a memory limit (``RLIMIT_AS``), a CPU-time backstop (``RLIMIT_CPU``), a file-size limit
  (``RLIMIT_FSIZE``), no core files, and in the sandbox a cap on processes;
- one thread for the numeric libraries, ``MPLBACKEND=Agg``, ``HOME`` in its own directory;
- ``PR_SET_PDEATHSIG`` (Linux) and bwrap's ``--die-with-parent``: it dies with the grader.

Every read from it has a deadline; a process that overstays one, or dies, is killed
(SIGKILL, which it cannot catch or ignore) with its whole process group, and in the sandbox
with its whole PID namespace; the caller starts a new one. Replies are JSON lines of at most
:data:`kinlib.grade._wire.MAX_LINE` bytes.
"""

from __future__ import annotations

import json
import os
import resource
import select
import selectors
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from .._process import die_with as _die_with
from ._bwrap import LIB_DIR, NPROC, Sandbox, worker_env
from ._container import Container
from ._wire import MAX_LINE, WireError, dumps, loads

__all__ = ["Worker", "WorkerDied", "WorkerTimeout", "BLOCKED"]

#: modules a submission may not import: kinlib and the peer libraries that would do the work
BLOCKED = ("kinlib", "scipy", "pytransform3d", "roboticstoolbox", "spatialmath",
           "modern_robotics", "transforms3d", "pinocchio", "pin")

#: seconds a request may take to be read by the student's process (a request is at most a
#: few hundred kilobytes: the cells or one function's cases)
REQUEST_TIMEOUT = 30.0


class WorkerDied(RuntimeError):
    """The student's process ended (or sent something unreadable and was killed)."""


class WorkerTimeout(RuntimeError):
    """The student's process did not answer in time (it has been killed)."""


def _limits(memory_mb: int, cpu_s: int, parent: int):
    die = _die_with(parent)

    def setup() -> None:
        die()
        mem = memory_mb * 1024 * 1024
        resource.setrlimit(resource.RLIMIT_AS, (mem, mem))
        resource.setrlimit(resource.RLIMIT_CPU, (cpu_s, cpu_s + 5))
        resource.setrlimit(resource.RLIMIT_FSIZE, (64 * 1024 * 1024,) * 2)
        resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
    return setup


class Worker:
    """One student process. Use :meth:`request` / :meth:`receive`; :meth:`kill` always.

    ``sandbox``: a :class:`~kinlib.grade._bwrap.Sandbox` (see
    :func:`~kinlib.grade._bwrap.find_sandbox`), a
    :class:`~kinlib.grade._container.Container` (the container tier), or None for a plain
    child process with the grader's own rights (the unsandboxed mode: no boundary at all).
    """

    def __init__(self, *, sandbox: Sandbox | Container | None, memory_mb: int = 4096,
                 cpu_s: int = 600, blocked=BLOCKED, nproc: int = NPROC):
        self.sandbox = sandbox
        self.dir = None if sandbox is not None else tempfile.mkdtemp(prefix="kinlib-grade-")
        self._launch = None  # the container tier's uid and working directory
        to_child_r, self._to_child = os.pipe()
        self._from_child, from_child_w = os.pipe()
        config = {"fds": [to_child_r, from_child_w], "blocked": list(blocked)}
        if isinstance(sandbox, Container):
            argv, cwd, env, self._launch = sandbox.launch(config, nproc)
        elif sandbox is not None:
            config.update(path=[LIB_DIR], uid=sandbox.uid(), nproc=nproc)
            argv, cwd, env = sandbox.argv([json.dumps(config)]), "/", {}
        else:
            argv = [sys.executable, "-I", str(Path(__file__).with_name("_worker.py")),
                    json.dumps(config)]
            cwd = self.dir
            env = worker_env(self.dir, os.environ.get("PATH", "/usr/bin:/bin"))
        try:
            self.proc = subprocess.Popen(
                argv, pass_fds=(to_child_r, from_child_w), cwd=cwd, env=env,
                stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                start_new_session=True, preexec_fn=_limits(memory_mb, cpu_s, os.getpid()))
        except BaseException:
            for fd in (to_child_r, from_child_w, self._to_child, self._from_child):
                os.close(fd)
            if self.dir is not None:
                shutil.rmtree(self.dir, ignore_errors=True)
            if self._launch is not None:
                self.sandbox.cleanup(self._launch)
            raise
        os.close(to_child_r)
        os.close(from_child_w)
        os.set_blocking(self._from_child, False)
        os.set_blocking(self._to_child, False)  # (requests are written with a deadline)
        self._buffer = bytearray()
        self._selector = selectors.DefaultSelector()
        self._selector.register(self._from_child, selectors.EVENT_READ)
        self.alive = True

    # -- talking ----------------------------------------------------------------------------
    def request(self, message: dict, timeout: float = REQUEST_TIMEOUT) -> None:
        """Send one request within ``timeout`` seconds: ``WorkerDied`` if the process is
        gone, or does not read it in time (a submission can stop reading its requests, or
        shrink their pipe: the grader never waits on it for ever; it is then killed)."""
        if not self.alive:
            raise WorkerDied("the process is not running")
        data = dumps(message)
        deadline = time.monotonic() + timeout
        try:
            view = memoryview(data)
            while view:
                try:
                    n = os.write(self._to_child, view)
                except BlockingIOError:
                    left = deadline - time.monotonic()
                    if left <= 0:
                        self.kill()
                        raise WorkerDied(f"it did not read the grader's request within "
                                         f"{timeout:g} s") from None
                    select.select([], [self._to_child], [], min(left, 1.0))
                    continue
                view = view[n:]
        except OSError:  # BrokenPipeError: it has ended
            why = self._death()
            self.kill()
            raise WorkerDied(why) from None

    def receive(self, timeout: float) -> dict:
        """The next reply, waiting at most ``timeout`` seconds.

        Raises :class:`WorkerTimeout` (process killed), :class:`WorkerDied` (process ended,
        or sent a line that is too long or not a JSON object: then it is killed).
        """
        deadline = time.monotonic() + timeout
        while True:
            cut = self._buffer.find(b"\n")
            if cut >= 0:
                line = bytes(self._buffer[:cut])
                del self._buffer[:cut + 1]
                try:
                    return loads(line)
                except WireError as exc:
                    self.kill()
                    raise WorkerDied(f"it sent an unreadable message ({exc})") from None
            if len(self._buffer) > MAX_LINE:
                self.kill()
                raise WorkerDied(f"it sent a message longer than {MAX_LINE} bytes")
            left = deadline - time.monotonic()
            if left <= 0:
                self.kill()
                raise WorkerTimeout(f"no answer within {timeout:g} s")
            if not self._selector.select(left):
                continue
            try:
                chunk = os.read(self._from_child, 1 << 20)
            except BlockingIOError:
                continue
            if not chunk:
                why = self._death()
                self.kill()
                raise WorkerDied(why)
            self._buffer += chunk

    def _death(self) -> str:
        try:
            code = self.proc.wait(timeout=2.0)
        except subprocess.TimeoutExpired:
            return "it stopped answering"
        if code < 0:
            name = signal.Signals(-code).name if -code in signal.Signals._value2member_map_ \
                else str(-code)
            hint = {"SIGKILL": " (killed: perhaps the memory limit)",
                    "SIGXCPU": " (the CPU-time limit)", "SIGXFSZ": " (the file-size limit)",
                    "SIGSEGV": " (a crash)"}.get(name, "")
            return f"the process was ended by {name}{hint}"
        return f"the process exited with code {code}"

    # -- ending -----------------------------------------------------------------------------
    def kill(self) -> None:
        """End the process group (SIGKILL) and, in the container tier, every process of
        its uid; reap it. Idempotent."""
        if self.alive:
            self.alive = False
            try:
                os.killpg(self.proc.pid, signal.SIGKILL)
            except (ProcessLookupError, PermissionError):
                pass
            try:
                self.proc.wait(timeout=10.0)
            except subprocess.TimeoutExpired:
                pass
            if self._launch is not None:  # what it started in sessions of its own too
                self.sandbox.end(self._launch)

    def close(self) -> None:
        """Kill the process and remove its working directory."""
        self.kill()
        if self._selector is not None:
            self._selector.close()
            self._selector = None
            for fd in (self._to_child, self._from_child):
                try:
                    os.close(fd)
                except OSError:
                    pass
        if self.dir is not None:
            shutil.rmtree(self.dir, ignore_errors=True)
        if self._launch is not None:
            self.sandbox.cleanup(self._launch)
            self._launch = None

    def __enter__(self) -> Worker:
        return self

    def __exit__(self, *exc) -> None:
        self.close()
