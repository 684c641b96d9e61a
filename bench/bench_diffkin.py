"""PUMA 560 Jacobian and IK: kinlib vs pinocchio and the Robotics Toolbox, one run.

Run with ``make bench`` (or ``python bench/bench_diffkin.py [--n N] [--targets M]``).

* Jacobian: kinlib ``robot.jacobian(Q)`` on N configurations at once, per configuration,
  against pinocchio's ``computeFrameJacobian`` (LOCAL_WORLD_ALIGNED: [v; ω] of the tip
  frame's origin in base axes, the same quantity) called in a Python loop.
* IK: M random reachable targets (FK of random q within the limits). kinlib solves them
  all in one batched ``robot.ik(T)``; the Robotics Toolbox's compiled ``ETS.ik_LM`` solves
  them one by one with joint limits on and a tolerance tight enough for the same errors.
  Both are scored the same way, independently of what they report: success = position
  error < 1e-6 m, rotation error < 1e-6 rad, q within the limits. Time per target: kinlib
  batched total / M against the toolbox's median per call.

The Jacobians are checked against each other to 1e-12 before timing.
"""

from __future__ import annotations

import argparse
import sys
import time
import warnings

import numpy as np
from timing import best_time  # bench/timing.py (the script's folder is on sys.path)

from kinlib.robots import puma560


def score(robot, T, q):
    reached = robot.fk(q)
    pos = np.linalg.norm(reached[:, :3, 3] - T[:, :3, 3], axis=1)
    c = (np.einsum("nij,nij->n", reached[:, :3, :3], T[:, :3, :3]) - 1) / 2
    rot = np.arccos(np.clip(c, -1, 1))
    lim = robot.limits
    inside = ((q >= lim[:, 0] - 1e-9) & (q <= lim[:, 1] + 1e-9)).all(axis=1)
    return (pos < 1e-6) & (rot < 1e-6) & inside


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=10_000)
    ap.add_argument("--targets", type=int, default=500)
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args(argv)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        import pinocchio as pin
        import roboticstoolbox as rtb

    robot = puma560()
    model = pin.buildModelFromXML(robot.to_urdf())
    data = model.createData()
    tip = model.getFrameId(robot.tip)
    rng = np.random.default_rng(0)
    Q = rng.uniform(robot.limits[:, 0], robot.limits[:, 1], (args.n, robot.dof))
    J = robot.jacobian(Q)
    for i in range(20):
        Jp = pin.computeFrameJacobian(model, data, Q[i], tip, pin.LOCAL_WORLD_ALIGNED)
        assert np.allclose(Jp, J[i], atol=1e-12)

    def pin_loop():
        for q in Q:
            pin.computeFrameJacobian(model, data, q, tip, pin.LOCAL_WORLD_ALIGNED)

    t_kl = best_time(lambda: robot.jacobian(Q), args.repeat)
    t_pin = best_time(pin_loop, args.repeat)

    # IK
    m = args.targets
    Qt = rng.uniform(robot.limits[:, 0], robot.limits[:, 1], (m, robot.dof))
    T = robot.fk(Qt)
    robot.ik(T[:10])  # load the compiled kernels outside the timing
    t0 = time.perf_counter()
    sol = robot.ik(T)
    t_ik = time.perf_counter() - t0
    ets = rtb.DHRobot([rtb.RevoluteDH(d=r.d, a=r.a, alpha=r.alpha, qlim=r.limits)
                       for r in robot.dh_rows]).ets()
    times, q_rtb = [], np.empty_like(Qt)
    for i in range(m):
        t0 = time.perf_counter()
        s = ets.ik_LM(T[i], tol=1e-14, joint_limits=True, ilimit=30, slimit=100)
        times.append(time.perf_counter() - t0)
        q_rtb[i] = s.q
    ok_kl, ok_rtb = score(robot, T, sol.q), score(robot, T, q_rtb)
    assert ok_kl[np.asarray(sol.success)].all(), "kinlib reported a success that is not one"

    n = args.n
    print(f"PUMA 560 differential kinematics: Jacobian of N = {n} configurations (best of "
          f"{args.repeat}); IK of {m} random reachable targets")
    print(f"{'case':48s} {'kinlib µs':>10s} {'peer µs':>10s} {'ratio':>7s}")
    print(f"{'batched jacobian vs pinocchio frame Jacobian loop':48s} {t_kl / n * 1e6:10.3f} "
          f"{t_pin / n * 1e6:10.3f} {t_kl / t_pin:7.3f}")
    med = float(np.median(times))
    print(f"{'batched ik per target vs RTB ETS.ik_LM median':48s} {t_ik / m * 1e6:10.1f} "
          f"{med * 1e6:10.1f} {(t_ik / m) / med:7.3f}")
    print(f"IK success (errors < 1e-6 m and 1e-6 rad, within limits): kinlib "
          f"{ok_kl.mean():.1%} ({ok_kl.sum()}/{m}), RTB ik_LM {ok_rtb.mean():.1%} "
          f"({ok_rtb.sum()}/{m}); kinlib iterations median {np.median(sol.iterations):.0f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
