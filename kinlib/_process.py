"""Child processes that cannot outlive their parent (Linux's parent-death signal).

Used where kinlib starts processes of its own: the grader's sandbox, and the test
harness's JupyterLab servers. A child started with
``preexec_fn=die_with(os.getpid())`` gets SIGTERM when that parent dies, however it dies
(even by SIGKILL), so nothing is left running behind a killed kernel or test run.
"""

from __future__ import annotations

import ctypes
import os
import signal
import sys

__all__ = ["die_with"]

_PR_SET_PDEATHSIG = 1


def die_with(parent: int):
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
