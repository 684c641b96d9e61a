"""The one timer every benchmark uses: best of R wall-clock runs."""

from __future__ import annotations

import time

import numpy as np

__all__ = ["best_time"]


def best_time(fn, repeat: int) -> float:
    """The shortest of ``repeat`` runs of ``fn()``, in seconds."""
    best = np.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best
