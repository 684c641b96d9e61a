"""Where a submission runs: the isolation tiers, tried in order.

1. **bubblewrap** (:mod:`kinlib.grade._bwrap`): its own namespaces, a file system that
   holds only the runtime and the allowed libraries, no network, its own PID namespace.
   Used wherever bwrap can make its namespaces.
2. **container** (:mod:`kinlib.grade._container`): where a root grader cannot make
   namespaces (Docker's default profile: Gradescope, most CI containers), each submission
   runs as a fresh unprivileged uid with the same limits, Landlock and seccomp where the
   kernel has them, and every process of that uid killed when it ends. A probe proves the
   tier's promises before anything is graded.

:func:`find_isolation` returns the first that works (or the one asked for: the ``sandbox``
argument, or ``KINLIB_SANDBOX=bubblewrap|container`` in the environment when that is
``"auto"``, e.g. to insist on bubblewrap), else raises
:class:`~kinlib.grade._bwrap.SandboxUnavailable` saying why and what to fix. Grading with
no isolation at all is only ever the caller's explicit choice (``unsandboxed=True``).
"""

from __future__ import annotations

import functools
import os

from ..errors import KinlibError
from ._bwrap import FIX, Sandbox, SandboxUnavailable, find_sandbox
from ._container import Container, container, judge_probe, probe_request, refuse_unless_root
from ._sandbox import Worker, WorkerDied, WorkerTimeout

__all__ = ["find_isolation", "TIERS", "TIER_ENV"]

#: what ``tier`` may ask for: the first that works, or one of them
TIERS = ("auto", "bubblewrap", "container")
#: the environment variable that picks a tier where the caller leaves it "auto"
TIER_ENV = "KINLIB_SANDBOX"


def find_isolation(blocked=(), tier: str = "auto", unreadable=(),
                   unwritable=()) -> Sandbox | Container:
    """The isolation submissions run in here (see the module's text).

    ``unreadable`` and ``unwritable`` are the paths the container tier's probe must find
    hidden from a submission (the secret, other hand-ins; where results are written),
    besides kinlib itself; the bubblewrap sandbox shows none of them anyway.
    """
    if tier == "auto":
        tier = os.environ.get(TIER_ENV) or "auto"
        if tier not in TIERS:
            raise KinlibError(f"{TIER_ENV}: expected one of {TIERS}, got {tier!r}")
    if tier not in TIERS:
        raise KinlibError(f"sandbox: expected one of {TIERS}, got {tier!r}")
    why = "the container tier was asked for"
    if tier in ("auto", "bubblewrap"):
        try:
            return find_sandbox(blocked)
        except SandboxUnavailable as exc:
            if tier == "bubblewrap":
                raise
            why = str(exc).replace(f"; {FIX}", "")
    refuse_unless_root(why)

    def norm(paths) -> tuple[str, ...]:
        return tuple(sorted({os.path.abspath(os.fspath(p)) for p in paths}))
    return _probed(tuple(blocked), norm(unreadable), norm(unwritable), why)


@functools.lru_cache(maxsize=16)
def _probed(blocked: tuple[str, ...], unreadable: tuple[str, ...],
            unwritable: tuple[str, ...], why: str) -> Container:
    """The container tier, once its probe has passed (remembered per protected paths)."""
    tier = container(blocked)
    try:
        with Worker(sandbox=tier, memory_mb=2048, cpu_s=60, blocked=blocked) as w:
            w.request(probe_request(unreadable, unwritable))
            reply = w.receive(60.0)
    except (WorkerDied, WorkerTimeout, OSError) as exc:
        raise SandboxUnavailable(
            f"bubblewrap cannot run here ({why}), and the container tier could not start a "
            f"confined process ({exc}): the Python runtime ({tier.python}) and the "
            f"libraries must be readable by every user. {FIX}") from None
    judge_probe(tier, reply, why)
    return tier
