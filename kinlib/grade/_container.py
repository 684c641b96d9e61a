"""The container tier: isolation for a root grader where bubblewrap cannot make namespaces.

Docker's default profile, which Gradescope's autograder and most CI containers run under,
refuses new namespaces to a root process (its seccomp profile and the missing
``CAP_SYS_ADMIN``), so bwrap cannot start there. What such a container still lets root do
is what Gradescope's own guidance recommends: run the student's code as another user. This
tier does that and more; each submission's process (:mod:`kinlib.grade._confine` applies
it, before any of the submission's code runs):

- runs as a fresh unprivileged uid and gid that own nothing, with no supplementary groups:
  it cannot signal, trace or read the memory of the grader or of another submission, nor
  read or write a file except as "others" may;
- has the same resource limits as in the bubblewrap sandbox (memory, CPU time, file size,
  processes and open files of its uid, no core files) and is the out-of-memory killer's
  first choice;
- where the kernel has Landlock (Linux 5.13+, allowed by Docker's default seccomp profile
  since 2022), sees files only as in the bubblewrap sandbox: the Python runtime and the
  allowed libraries read-only (the runtime's ``site-packages`` left out), its own working
  directory writable, nothing else (not ``/proc``, not ``/tmp``, not the grader's files);
  from Landlock ABI 4 it cannot ``bind`` or ``connect`` TCP sockets, from ABI 6 not signal
  or reach abstract Unix sockets outside itself;
- on x86-64 and AArch64, a seccomp filter refuses every socket (Unix ones too), io_uring,
  namespaces, mounts, ``ptrace``, ``bpf`` and the kernel keyring;
- ends with everything it started: when the process ends, every process of its uid is
  killed (:func:`sweep`), and what it left in the world-writable directories is removed.

Without Landlock, files are protected by their permissions only. Before grading, a probe
(:func:`kinlib.grade._tiers.find_isolation`, :func:`judge_probe`) starts one confined
process and proves the promises hold here: it is not root, cannot open the grader's
kinlib (the reference, the grader's code) or the paths the caller names (the secret, the
results, other hand-ins), cannot create a file where results go, cannot make an IPv4,
IPv6 or Unix socket (where seccomp is available), and can import the libraries a submission may
use. If any fails, the tier is refused, naming the
fix (``chmod -R go-rwx``, a world-readable Python).

What it does not give, unlike bubblewrap: a private ``/tmp`` or file-system view without
Landlock, a PID namespace (the process can list other processes' command lines in
``/proc`` where Landlock is missing), a bound on the number of files it writes in its own
working directory (each at most 64 MiB), or a memory bound on the sandbox as a whole
(memory is limited per process).
"""

from __future__ import annotations

import atexit
import functools
import json
import os
import secrets
import shutil
import signal
import stat
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

from . import _confine
from ._bwrap import FIX, SandboxUnavailable, _hidden_dirs, _library_binds, worker_env

__all__ = ["Container", "container", "probe_request", "judge_probe", "refuse_unless_root",
           "sweep", "memory_limit_mb", "NOFILE"]

#: open files of a submission's process
NOFILE = 1024
#: devices a submission's process may read and write
DEVICES = ("/dev/null", "/dev/zero", "/dev/full", "/dev/random", "/dev/urandom")
#: world-writable directories emptied of what a submission's uid left there
SHARED_DIRS = ("/tmp", "/var/tmp", "/dev/shm")
@dataclass(frozen=True)
class Launch:
    """One confined process as started: its uid and working directory."""

    uid: int
    workdir: str


@dataclass(frozen=True)
class Container:
    """How to start one process in the container tier (see the module's text)."""

    python: str  # the base interpreter, readable by every user
    lib_dir: str  # links to the libraries a submission may use
    read: tuple[str, ...]  # Landlock's read-only rules
    landlock: int  # the Landlock ABI used (0: none)
    seccomp: str | None  # the architecture of the seccomp filter (None: none)
    workroot: str  # where each process's working directory is made
    tier = "container"

    def describe(self) -> str:
        what = ["unprivileged uid", "rlimits"]
        if self.landlock:
            covers = "files" + (", TCP" if self.landlock >= 4 else "") + \
                (", signals" if self.landlock >= 6 else "")
            what.append(f"Landlock ABI {self.landlock} ({covers})")
        else:
            what.append("file permissions (no Landlock)")
        what.append("seccomp (no network sockets)" if self.seccomp else "no seccomp filter")
        return "container tier: " + ", ".join(what)

    def launch(self, config: dict, nproc: int) -> tuple[list[str], str, dict, Launch]:
        """(argv, cwd, env, launch) of a worker with ``config`` (its pipes, blocked
        modules), confined to a fresh uid and working directory."""
        uid = 1_000_000_000 + secrets.randbelow(1_000_000_000)
        workdir = tempfile.mkdtemp(prefix="w", dir=self.workroot)
        os.chown(workdir, uid, uid)
        os.chmod(workdir, 0o700)
        config = {**config, "path": [self.lib_dir], "confine": {
            "uid": uid, "parent": os.getpid(), "nproc": nproc, "nofile": NOFILE,
            "landlock": self.landlock, "read": [*self.read, self.lib_dir],
            "write": [workdir], "devices": list(DEVICES), "seccomp": self.seccomp}}
        worker = str(Path(__file__).resolve().with_name("_worker.py"))
        env = {**worker_env(workdir, "/usr/bin:/bin"), "TMPDIR": workdir,
               "MPLCONFIGDIR": os.path.join(workdir, ".matplotlib")}
        argv = [self.python, "-I", "-S", "-B", worker, json.dumps(config)]  # (-B: root writes
        # nothing into the grader's folders while it loads the worker)
        return argv, workdir, env, Launch(uid, workdir)

    def end(self, launch: Launch) -> None:
        """Kill every process of the launch's uid (:func:`sweep`)."""
        sweep(launch.uid)

    def cleanup(self, launch: Launch) -> None:
        """Remove the launch's working directory and what its uid left in the shared
        directories (after :meth:`end`)."""
        _remove(launch.workdir)
        for folder in SHARED_DIRS:
            try:
                entries = list(os.scandir(folder))
            except OSError:
                continue
            for entry in entries:
                try:
                    st = entry.stat(follow_symlinks=False)
                    if st.st_uid != launch.uid:
                        continue
                    if stat.S_ISDIR(st.st_mode):
                        _remove(entry.path)
                    else:
                        os.unlink(entry.path)
                except OSError:
                    pass


def sweep(uid: int) -> None:
    """Kill every live process of ``uid`` (root only): the grader kills each process
    ``/proc`` shows for the uid, again until none is left. Nothing of that uid does the
    killing (a process of the same uid could stop or kill it first, where Landlock's signal
    scope is missing), and the uid's processes can neither hide from ``/proc`` nor signal
    root. A process forking meanwhile is found in the next round; there are at most
    ``NPROC`` of them at once."""
    for _ in range(1000):
        left = _processes_of(uid)
        if not left:
            return
        for pid in left:
            _kill_if_owned(pid, uid)
        time.sleep(0.002)


def _uid_and_state(pid: str) -> tuple[int | None, str]:
    try:
        with open(f"/proc/{pid}/status", encoding="utf-8", errors="replace") as fh:
            status = fh.read()
    except OSError:
        return None, ""
    uid = state = None
    for line in status.splitlines():
        if line.startswith("Uid:"):
            uid = int(line.split()[1])
        elif line.startswith("State:"):
            state = line.split()[1]
    return uid, state or ""


def _processes_of(uid: int) -> list[str]:
    """The live (not zombie) processes whose real uid is ``uid``."""
    try:
        pids = [p for p in os.listdir("/proc") if p.isdigit()]
    except OSError:
        return []
    owners = ((p, *_uid_and_state(p)) for p in pids)
    return [p for p, owner, state in owners if owner == uid and state not in ("Z", "X")]


def _kill_if_owned(pid: str, uid: int) -> None:
    """SIGKILL ``pid`` if it is still a process of ``uid`` (through a pidfd where the kernel
    has them, so that a pid reused meanwhile is never signalled)."""
    try:
        fd = os.pidfd_open(int(pid))
    except (AttributeError, OSError):
        fd = None
    try:
        if _uid_and_state(pid)[0] != uid:
            return
        if fd is not None:
            signal.pidfd_send_signal(fd, signal.SIGKILL)
        else:
            os.kill(int(pid), signal.SIGKILL)
    except OSError:
        pass
    finally:
        if fd is not None:
            os.close(fd)


def _remove(path: str) -> None:
    """Remove a tree a submission made, however deep (``rm -rf``, which walks it without
    recursion and follows no symbolic link, on this file system only; shutil's rmtree,
    which recurses once per level, where there is no ``rm``); never raises."""
    rm = shutil.which("rm", path="/usr/bin:/bin")
    try:
        if rm:
            subprocess.run([rm, "-rf", "--one-file-system", "--", path], env={},
                           stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                           stderr=subprocess.DEVNULL, timeout=120)
        else:
            shutil.rmtree(path, ignore_errors=True)
    except Exception:  # (a RecursionError, a timeout: the tree stays, the grading goes on)
        pass


def memory_limit_mb(cgroup_file: str = "/proc/self/cgroup",
                    mount: str = "/sys/fs/cgroup") -> int | None:
    """The memory limit of this process's cgroup and its parents (a container's limit), in
    MiB; None where there is none (cgroup v2 ``memory.max``, v1 ``memory.limit_in_bytes``).
    """
    limits = []
    try:
        with open(cgroup_file, encoding="utf-8") as fh:
            lines = fh.read().splitlines()
    except OSError:
        return None
    for line in lines:
        parts = line.split(":", 2)
        if len(parts) != 3:
            continue
        _, controllers, path = parts
        if controllers == "":
            base, name = mount, "memory.max"  # cgroup v2
        elif "memory" in controllers.split(","):
            base, name = os.path.join(mount, "memory"), "memory.limit_in_bytes"
        else:
            continue
        here = path.strip("/")
        while True:
            try:
                with open(os.path.join(base, here, name), encoding="utf-8") as fh:
                    text = fh.read().strip()
                if text.isdigit() and int(text) < 1 << 60:  # ("max", or v1's "no limit")
                    limits.append(int(text))
            except OSError:
                pass
            if not here:
                break
            here = os.path.dirname(here)
    return min(limits) >> 20 if limits else None


def _folder(prefix: str, mode: int) -> str:
    base = "/tmp" if os.path.isdir("/tmp") else tempfile.gettempdir()
    path = tempfile.mkdtemp(prefix=prefix, dir=base)
    os.chmod(path, mode)
    atexit.register(shutil.rmtree, path, True)
    return path


@functools.lru_cache(maxsize=4)
def _layout(blocked: tuple[str, ...]) -> tuple[str, str, tuple[str, ...], str]:
    """(interpreter, library folder, read rules, work root): made once per process."""
    python = os.path.realpath(getattr(sys, "_base_executable", None) or sys.executable)
    prefix = os.path.realpath(sys.base_prefix)
    lib_dir = _folder("kinlib-lib-", 0o755)
    libraries = []
    for src, dst in _library_binds(("numpy", "sympy", "matplotlib"), blocked):
        os.symlink(src, os.path.join(lib_dir, os.path.basename(dst)))
        libraries.append(src)
    trees = ["/usr", prefix, os.path.dirname(python), "/lib", "/lib64", "/lib32", "/bin",
             "/etc/ld.so.cache", "/etc/localtime"]
    hidden = _hidden_dirs({prefix, "/usr", "/usr/local"})
    read = tuple(_confine.read_rules(trees, hidden)) + tuple(sorted(set(libraries)))
    return python, lib_dir, read, _folder("kinlib-work-", 0o711)


def container(blocked=()) -> Container:
    """This machine's container tier for a grader blocking ``blocked``, not yet probed
    (:func:`kinlib.grade._tiers.find_isolation` probes it)."""
    python, lib_dir, rules, workroot = _layout(tuple(blocked))
    return Container(python, lib_dir, rules, _confine.landlock_abi(), _confine.seccomp_arch(),
                     workroot)


def probe_request(read=(), write=()) -> dict:
    """What the probe asks a confined process: kinlib (the reference, the grader's code) and
    ``read`` must not open, kinlib and ``write`` must not take a new file, the libraries a
    submission may use must import."""
    here = os.path.realpath(sys.modules[__package__.split(".")[0]].__path__[0])  # (kinlib)
    return {"op": "probe", "read": [here, *read], "write": [here, *write],
            "imports": ["numpy", "sympy", "matplotlib"]}


def judge_probe(container: Container, reply: dict, why: str) -> None:
    """Raise :class:`SandboxUnavailable`, naming each problem and its fix, unless the
    probe's ``reply`` shows every promise of the tier holding."""
    problems = []
    if reply.get("ev") != "probe":
        problems.append(f"the confined process answered {str(reply)[:200]}")
    if reply.get("uid") in (0, None) or reply.get("euid") in (0, None):
        problems.append("the submission's process is still root")
    if reply.get("imports"):
        problems.append("the libraries a submission may use cannot be imported by an "
                        f"unprivileged user: {'; '.join(map(str, reply['imports']))} (the "
                        f"Python runtime, {container.python}, and the libraries must be "
                        "readable by every user)")
    for key, how in (("readable", "can be read"), ("writable", "can be written")):
        if reply.get(key):
            paths = " ".join(map(str, reply[key]))
            problems.append(f"{paths} {how} by the submission's unprivileged user (fix: "
                            f"chmod -R go-rwx {paths})")
    if container.seccomp and reply.get("network"):
        problems.append(f"network sockets were not refused ({reply['network']})")
    if problems:
        raise SandboxUnavailable(f"bubblewrap cannot run here ({why}), and the container "
                                 f"tier cannot hold here: {'; '.join(problems)}. {FIX}")


def refuse_unless_root(why: str) -> None:
    """The container tier needs root (to hand each submission a uid of its own)."""
    if not sys.platform.startswith("linux"):
        raise SandboxUnavailable(f"no sandbox on {sys.platform}; {FIX}")
    if os.geteuid() != 0:
        raise SandboxUnavailable(
            f"bubblewrap cannot run here ({why}); the container tier, which runs "
            "submissions as another user, needs the grader to run as root. " + FIX)
