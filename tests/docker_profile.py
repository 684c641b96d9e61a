"""Run a command as a root process in a Docker container with the default profile would:
``python tests/docker_profile.py [--memory-cgroup DIR] -- COMMAND ...`` (as root).

Gradescope runs its autograders in Docker containers with Docker's default profile. Two
things in that profile stop bubblewrap, and both are emulated here, then ``COMMAND`` is
executed:

- the seccomp profile, for a process without ``CAP_SYS_ADMIN``: ``unshare``, ``setns`` and
  ``clone`` with any namespace flag are refused (EPERM), ``clone3`` answers ENOSYS (so the
  C library falls back to ``clone``, whose flags can be checked);
- the capability bounding set cut to Docker's default list, ``CapBnd`` 00000000a80425fb
  (chown, dac_override, fowner, fsetid, kill, setgid, setuid, setpcap, net_bind_service,
  net_raw, sys_chroot, mknod, audit_write, setfcap): after ``exec`` root has those only.

With ``--memory-cgroup DIR`` the process first joins that (memory) cgroup, as a container's
processes are in the container's: its memory limit is the container's.

This is the tests' own emulation, written apart from kinlib's confinement code
(:mod:`kinlib.grade._confine`) so that a mistake in one cannot hide in the other; the
tests check it stops bwrap and ``unshare -U`` while root can still change its uid.
"""

from __future__ import annotations

import ctypes
import os
import platform
import struct
import sys

#: Docker's default capabilities (their numbers, linux/capability.h)
DOCKER_CAPS = (0, 1, 3, 4, 5, 6, 7, 8, 10, 13, 18, 27, 29, 31)
DOCKER_CAPBND = sum(1 << c for c in DOCKER_CAPS)  # == 0xa80425fb
_SYSCALLS = {  # unshare, setns, clone, clone3; the audit architecture
    "x86_64": (272, 308, 56, 435, 0xC000003E),
    "aarch64": (97, 268, 220, 435, 0xC00000B7),
}
_CLONE_NEWS = 0x7E020080
_EPERM, _ENOSYS = 1, 38


def _filter() -> bytes:
    unshare, setns, clone, clone3, audit = _SYSCALLS[platform.machine()]
    ld, jeq, jset, ret = 0x20, 0x15, 0x45, 0x06
    allow, errno = 0x7FFF0000, 0x00050000
    insns = [
        (ld, 0, 0, 4),                  # 0: arch
        (jeq, 0, 8, audit),             # 1: another ABI: allowed (-> 10)
        (ld, 0, 0, 0),                  # 2: nr
        (jeq, 8, 0, unshare),           # 3: -> 12 (EPERM)
        (jeq, 7, 0, setns),             # 4: -> 12
        (jeq, 8, 0, clone3),            # 5: -> 14 (ENOSYS)
        (jeq, 0, 4, clone),             # 6: not clone -> 11 (allow)
        (ld, 0, 0, 16),                 # 7: clone's flags (low half)
        (jset, 3, 2, _CLONE_NEWS),      # 8: a namespace -> 12, else -> 11
        (ret, 0, 0, allow),             # 9: (unused)
        (ret, 0, 0, allow),             # 10
        (ret, 0, 0, allow),             # 11
        (ret, 0, 0, errno | _EPERM),    # 12
        (ret, 0, 0, allow),             # 13: (unused)
        (ret, 0, 0, errno | _ENOSYS),   # 14
    ]
    return b"".join(struct.pack("=HBBI", code, jt, jf, k) for code, jt, jf, k in insns)


class _Fprog(ctypes.Structure):
    _fields_ = [("len", ctypes.c_ushort), ("filter", ctypes.c_void_p)]


def enter_docker_profile() -> None:
    """Install the seccomp filter and cut the bounding set (see the module's text)."""
    libc = ctypes.CDLL(None, use_errno=True)
    code = _filter()
    buf = ctypes.create_string_buffer(code, len(code))
    prog = _Fprog(len(code) // 8, ctypes.cast(buf, ctypes.c_void_p))
    if libc.prctl(22, ctypes.c_ulong(2), ctypes.byref(prog), ctypes.c_ulong(0),
                  ctypes.c_ulong(0)) != 0:  # PR_SET_SECCOMP, SECCOMP_MODE_FILTER
        raise OSError(ctypes.get_errno(), "seccomp")
    with open("/proc/sys/kernel/cap_last_cap") as fh:
        last = int(fh.read())
    for cap in range(last + 1):
        if cap not in DOCKER_CAPS and libc.prctl(24, ctypes.c_ulong(cap), 0, 0, 0) != 0:
            raise OSError(ctypes.get_errno(), f"PR_CAPBSET_DROP {cap}")


def main(argv: list[str]) -> None:
    if "--" not in argv:
        raise SystemExit("usage: docker_profile.py [--memory-cgroup DIR] -- COMMAND ...")
    options, command = argv[:argv.index("--")], argv[argv.index("--") + 1:]
    if options[:1] == ["--memory-cgroup"]:
        with open(os.path.join(options[1], "cgroup.procs"), "w") as fh:
            fh.write(str(os.getpid()))
    enter_docker_profile()
    os.execvp(command[0], command)


if __name__ == "__main__":
    main(sys.argv[1:])
