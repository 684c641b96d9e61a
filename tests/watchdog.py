"""A watchdog for calls that must not hang: not a speed test.

``with no_hang("what"):`` lets the block run for up to ``WATCHDOG_SECONDS`` (a bound a
millisecond operation cannot reach on any machine, however busy) and then interrupts it
with an AssertionError, so an infinite loop fails the test instead of stalling the suite.
Speed itself is measured in ``bench/``, never asserted in a test.
"""

from __future__ import annotations

import signal
import threading
from contextlib import contextmanager

__all__ = ["WATCHDOG_SECONDS", "no_hang"]

WATCHDOG_SECONDS = 120.0


@contextmanager
def no_hang(what: str, seconds: float = WATCHDOG_SECONDS):
    if threading.current_thread() is not threading.main_thread() or not hasattr(
            signal, "setitimer"):
        yield  # signals reach the main thread only (and not on Windows): no watchdog
        return

    def fire(signum, frame):
        raise AssertionError(f"{what}: still running after {seconds:g} s: a hang")

    previous = signal.signal(signal.SIGALRM, fire)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)
