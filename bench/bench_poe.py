"""SE(3) and the product of exponentials: kinlib vs the Modern Robotics library, one run.

Run with ``make bench`` (or ``python bench/bench_poe.py [--n N] [--repeat R]``).

* ``exp_se3`` / ``log_se3`` on N twists at once, per twist, against Modern Robotics'
  ``MatrixExp6`` / ``MatrixLog6`` called in a Python loop (its functions take one twist);
* PUMA 560 PoE forward kinematics ``poe_fk(M, S, Q)`` and ``space_jacobian(S, Q)`` on N
  configurations at once, per configuration, against ``FKinSpace`` / ``JacobianSpace``;
* the same for one configuration per call (what a student's loop does).

Modern Robotics orders twists [ω; v], kinlib [v; ω]: the screw axes are reordered, and
every pair is checked to agree (1e-10) before timing. The peer loops run on N // 20
inputs (they are slow) and are reported per item.
"""

from __future__ import annotations

import argparse

import modern_robotics as mr
import numpy as np
from timing import best_time  # bench/timing.py (the script's folder is on sys.path)

import kinlib as kl
from kinlib.robots import puma560


def mr_order(x):
    return np.concatenate([x[3:], x[:3]])


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=20_000)
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args(argv)
    kl.prepare_kernels()  # compiled kernels from the first timed call (bench_first_call)
    rng = np.random.default_rng(0)
    n, m, r = args.n, max(args.n // 20, 1), args.repeat

    xi = np.concatenate([rng.normal(size=(n, 3)), rng.uniform(-1, 1, (n, 3))], axis=1)
    T = kl.exp_se3(xi)
    mr_xi = [mr.VecTose3(mr_order(x)) for x in xi[:m]]
    for i in range(20):
        assert np.allclose(T[i], mr.MatrixExp6(mr_xi[i]), atol=1e-10)
        assert np.allclose(mr_order(kl.log_se3(T[i])), mr.se3ToVec(mr.MatrixLog6(T[i])),
                           atol=1e-10)

    robot = puma560()
    S, M = kl.screw_axes(robot)
    S_mr = np.stack([mr_order(s) for s in S.T], axis=1)
    Q = rng.uniform(robot.limits[:, 0], robot.limits[:, 1], (n, robot.dof))
    for q in Q[:20]:
        assert np.allclose(kl.poe_fk(M, S, q), mr.FKinSpace(M, S_mr, q), atol=1e-10)
        assert np.allclose(mr_order(kl.space_jacobian(S, q)), mr.JacobianSpace(S_mr, q),
                           atol=1e-10)

    rows = [
        ("exp_se3, batched", best_time(lambda: kl.exp_se3(xi), r) / n,
         best_time(lambda: [mr.MatrixExp6(x) for x in mr_xi], r) / m),
        ("log_se3, batched", best_time(lambda: kl.log_se3(T), r) / n,
         best_time(lambda: [mr.MatrixLog6(t) for t in T[:m]], r) / m),
        ("PoE FK (PUMA 560), batched", best_time(lambda: kl.poe_fk(M, S, Q), r) / n,
         best_time(lambda: [mr.FKinSpace(M, S_mr, q) for q in Q[:m]], r) / m),
        ("space Jacobian (PUMA 560), batched", best_time(lambda: kl.space_jacobian(S, Q), r) / n,
         best_time(lambda: [mr.JacobianSpace(S_mr, q) for q in Q[:m]], r) / m),
        ("PoE FK, one configuration per call",
         best_time(lambda: [kl.poe_fk(M, S, q) for q in Q[:m]], r) / m,
         best_time(lambda: [mr.FKinSpace(M, S_mr, q) for q in Q[:m]], r) / m),
        ("space Jacobian, one configuration per call",
         best_time(lambda: [kl.space_jacobian(S, q) for q in Q[:m]], r) / m,
         best_time(lambda: [mr.JacobianSpace(S_mr, q) for q in Q[:m]], r) / m),
    ]
    print(f"{'case':45s} {'kinlib µs':>10s} {'MR µs':>10s} {'ratio':>7s}")
    for name, ours, theirs in rows:
        print(f"{name:45s} {ours * 1e6:10.2f} {theirs * 1e6:10.2f} {ours / theirs:7.3f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
