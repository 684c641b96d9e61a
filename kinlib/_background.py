"""Compiled kernels made ready in the background, so that no call waits for numba (private).

numba compiles a kernel the first time it is called, which takes seconds (a student's very
first ``fk``, ``jacobian`` and ``ik`` after installing kinlib: about 6 s in all), and loads
it from its on-disk cache in every later process (still 0.1–0.8 s). Here, the first call that
could use a kernel asks for it with :func:`ready`: that starts its preparation (compile, or
load from the cache) in kinlib's one background thread and answers None, and the caller
takes its numpy path, which computes the same thing (the tests compare both paths).
Once the kernel is ready, every later call uses it. The thread handles one kernel after
another (numba compiles one function at a time in a process anyway), and numba's
compiler releases Python's GIL while LLVM optimises, so the caller's own work goes on
beside it.

A call that would be much slower on the numpy path than the compile takes (a batch of a
hundred thousand configurations) asks with ``wait=True`` instead, as does
:func:`kinlib.prepare_kernels`. A kernel that cannot be prepared (numba missing, or a numba
or Python the kernels do not support) leaves its callers on the numpy path for good; a
failure other than a missing numba is reported once, as a ``RuntimeWarning`` raised in the
caller's thread (never in the background one).

The thread is not a daemon: a script that ends while a kernel is compiling waits for it (as
it would have waited for the compile in its first call), so the kernel is in numba's cache
for the next run and the interpreter never shuts down under a running compiler. In a
child made by ``fork``, a kernel that was being prepared when the parent forked is left to
the numpy path (the child has no background thread, and numba's compiler lock may be held
by the parent's); kernels ready before the fork stay ready.
"""

from __future__ import annotations

import collections
import os
import threading
import warnings
from collections.abc import Callable

__all__ = ["KernelsUnavailable", "compiled", "peek", "ready", "warn_once"]


class KernelsUnavailable(Exception):
    """Raised by a preparation whose kernels cannot be built here; its text is the warning
    the callers get (once)."""


class _Slot:
    """One kernel: being prepared (``done`` not set), ready (``kernel``), or unavailable
    (``kernel`` None, ``error`` the warning to give, if any)."""

    __slots__ = ("done", "error", "kernel", "prepare")

    def __init__(self, prepare: Callable[[], object]):
        self.prepare = prepare
        self.done = threading.Event()
        self.kernel = None
        self.error: str | None = None


_lock = threading.Lock()
_slots: dict[str, _Slot] = {}
_ready: dict[str, object] = {}  # the kernels ready: a call's one dict lookup
_jobs: collections.deque[tuple[str, _Slot]] = collections.deque()
_worker: threading.Thread | None = None
_warned: set[str] = set()


def warn_once(message: str, stacklevel: int = 3) -> None:
    """A ``RuntimeWarning`` with ``message``, the first time this process meets it."""
    with _lock:
        if message in _warned:
            return
        _warned.add(message)
    warnings.warn(message, RuntimeWarning, stacklevel=stacklevel)


def _run(slot: _Slot, key: str) -> None:
    try:
        slot.kernel = slot.prepare()
        if slot.kernel is not None:
            _ready[key] = slot.kernel
    except KernelsUnavailable as exc:
        slot.error = str(exc)
    except BaseException as exc:  # whatever stops it, the callers use numpy
        slot.error = (f"kinlib: a compiled kernel could not be prepared, so the numpy path is "
                      f"used ({type(exc).__name__}: {exc}); set KINLIB_NUMBA=0 to skip it")
    finally:
        slot.prepare = None  # (it may hold the first call's arrays)
        slot.done.set()


def _drain() -> None:
    global _worker
    while True:
        with _lock:
            if not _jobs:
                _worker = None
                return
            key, slot = _jobs.popleft()
        _run(slot, key)


def ready(key: str, prepare: Callable[[], object], *, wait: bool = False):
    """The kernel ``prepare()`` returns, once it is ready; else None (use the numpy path).

    A kernel once ready costs its callers one dict lookup. ``prepare`` imports the kernel
    and calls it once on an empty batch of the caller's argument types (numba compiles it
    for those types, or loads it from its cache), and returns it; None if numba is not
    installed; or raises :class:`KernelsUnavailable`.
    The first ask for ``key`` starts it in the background thread. ``wait=True`` waits for
    the kernel (or its failure) instead of answering None while it is prepared.
    """
    global _worker
    kernel = _ready.get(key)
    if kernel is not None:
        return kernel
    with _lock:
        slot = _slots.get(key)
        if slot is None:
            slot = _slots[key] = _Slot(prepare)
            _jobs.append((key, slot))
            if _worker is None:
                _worker = threading.Thread(target=_drain, name="kinlib-kernels")
                _worker.start()
    if not slot.done.is_set():
        if not wait:
            return None
        slot.done.wait()
    if slot.error is not None:
        warn_once(slot.error)
    return slot.kernel


def compiled(key: str, load: Callable[[], object], name: str, example: Callable[[], tuple], *,
             wait: bool = False):
    """:func:`ready` for the kernel ``getattr(load(), name)`` (``load()``: the kernels'
    module or namespace, None without numba, or :class:`KernelsUnavailable`), prepared by a
    call on ``example()``, the caller's arguments with an empty batch."""
    kernel = _ready.get(key)
    if kernel is not None:
        return kernel

    def prepare():
        kernels = load()
        if kernels is None:
            return None
        fn = getattr(kernels, name)
        fn(*example())
        return fn

    return ready(key, prepare, wait=wait)


def peek(key: str):
    """The kernel of ``key`` if it is ready, else None (nothing is started)."""
    return _ready.get(key)


def _after_fork_in_child() -> None:
    """The parent's thread is not in the child: what it was preparing is given up."""
    global _worker, _lock
    _lock = threading.Lock()
    _worker = None
    _jobs.clear()
    for slot in _slots.values():
        if not slot.done.is_set():
            slot.prepare = None
            slot.done = threading.Event()
            slot.done.set()


if hasattr(os, "register_at_fork"):
    os.register_at_fork(after_in_child=_after_fork_in_child)
