"""kinlib without a compiler: the numpy path against the compiled (numba) one, one run.

Run with ``make bench`` (or ``python bench/bench_numpy.py [--repeat R]``).

A student who installs kinlib without the ``fast`` extra, or on a platform without numba,
gets the numpy path (``KINLIB_NUMBA=0`` forces it). Both paths run here in one process,
interleaved: the numpy one by switching the compiled kernels off for the call. Read:

* single ``fk``: one PUMA 560 configuration per call through ``robot.fk`` (checks
  included), numpy / compiled (goal: at most 5);
* IK per iteration: unreachable PUMA 560 targets (every restart runs to its end, so the
  iterations are many and alike), seconds per iteration and target, numpy / compiled
  (goal: at most 10), for one target and for a batch of 64 solved together (the numpy
  loop is vectorised across the targets still running);
* PUMA 560 IK on the numpy path, seconds per target: the median of 20 random reachable
  targets (q uniform within the joint limits, from the default start; goal: 20 ms) and an
  unreachable one (goal: 0.5 s), with ``robot.ik``'s defaults (tolerance 1e-6 m and rad,
  30 iterations, 100 restarts).

The machine is noisy: the ratios, taken in one run, are what to compare across runs.
"""

from __future__ import annotations

import argparse
import contextlib

import numpy as np
from timing import best_time  # bench/timing.py (the script's folder is on sys.path)

from kinlib import prepare_kernels, transform
from kinlib.kinematics import _fk
from kinlib.robots import puma560


@contextlib.contextmanager
def numpy_path():
    """kinlib's compiled kernels switched off (as with KINLIB_NUMBA=0) inside the block:
    no kernel is ever ready (FK, Jacobian and the IK loop all ask ``_fk.kernel``)."""
    kernel = _fk.kernel
    _fk.kernel = lambda *args, **kwargs: None
    try:
        yield
    finally:
        _fk.kernel = kernel


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args(argv)
    if not all(prepare_kernels(["fk", "jacobian", "ik"]).values()):  # compiled, or loaded
        raise SystemExit("numba is not installed (or KINLIB_NUMBA=0): nothing to compare")
    robot = puma560()
    q = np.array([0.3, -0.6, 1.2, 0.2, 0.5, -0.4])
    reachable, unreachable = robot.fk(q), transform(p=[2.0, 0.0, 0.5])
    with numpy_path():  # same answers on both paths (and warm both)
        np.testing.assert_allclose(robot.fk(q), puma560().fk(q), atol=0)
        assert robot.ik(reachable).success and not robot.ik(unreachable).success
    assert robot.ik(reachable).success

    calls = 2000
    fk_c = best_time(lambda: [robot.fk(q) for _ in range(calls)], args.repeat) / calls
    with numpy_path():
        fk_n = best_time(lambda: [robot.fk(q) for _ in range(calls)], args.repeat) / calls
    # the IK pair interleaved, one run of each at a time (the machine's speed drifts)
    ik_c = ik_n = np.inf
    for _ in range(args.repeat):
        ik_c = min(ik_c, best_time(lambda: robot.ik(unreachable), 1))
        with numpy_path():
            ik_n = min(ik_n, best_time(lambda: robot.ik(unreachable), 1))
    iters = robot.ik(unreachable).iterations
    with numpy_path():
        assert robot.ik(unreachable).iterations == iters  # the same work on both paths
    far = np.broadcast_to(unreachable, (64, 4, 4))
    batch_c = best_time(lambda: robot.ik(far), args.repeat)
    lim = robot.limits
    # (not seed 0: robot.ik draws its random starts from seed 0 and would start at the answers)
    targets = robot.fk(np.random.default_rng(2024).uniform(lim[:, 0], lim[:, 1], (20, 6)))
    with numpy_path():
        batch_n = best_time(lambda: robot.ik(far), 1)
        times = [best_time(lambda t=t: robot.ik(t), 3) for t in targets]
        reached = robot.ik(targets).success.mean()

    print(f"PUMA 560, numpy path vs compiled, best of {args.repeat} (one process, interleaved)")
    print(f"  single fk per call:        compiled {fk_c * 1e6:7.1f} us   numpy "
          f"{fk_n * 1e6:7.1f} us   ratio {fk_n / fk_c:5.2f}  (goal <= 5)")
    print(f"  IK per iteration, 1 target: compiled {ik_c / iters * 1e6:6.2f} us   numpy "
          f"{ik_n / iters * 1e6:7.1f} us   ratio {ik_n / ik_c:6.1f}  (goal <= 10; "
          f"{iters} iterations)")
    per = 64 * iters
    print(f"  IK per iteration, 64:      compiled {batch_c / per * 1e6:6.2f} us   numpy "
          f"{batch_n / per * 1e6:7.1f} us   ratio {batch_n / batch_c:6.1f}  (per target)")
    print(f"  numpy IK, reachable:       median {np.median(times) * 1e3:6.2f} ms, max "
          f"{max(times) * 1e3:6.1f} ms over 20 targets ({reached:.0%} solved; goal <= 20 ms)")
    print(f"  numpy IK, unreachable:     {ik_n:7.3f} s  ({iters} iterations; goal <= 0.5 s)")


if __name__ == "__main__":
    main()
