"""PUMA 560 Jacobian and IK: kinlib vs pinocchio and the Robotics Toolbox, one run.

Run with ``make bench`` (or ``python bench/bench_diffkin.py [--n N] [--targets M]``).

* Jacobian: kinlib ``robot.jacobian(Q)`` on N configurations at once, per configuration,
  against pinocchio's ``computeFrameJacobian`` (LOCAL_WORLD_ALIGNED: [v; ω] of the tip
  frame's origin in base axes, the same quantity) called in a Python loop.
* IK, on the PUMA 560 and the 7-DOF Panda: M random reachable targets (FK of random q
  within the limits; seed 1, not kinlib's seed 0 for its own random starts). kinlib
  solves them all in one batched ``robot.ik(T, tol_position=tol, tol_rotation=tol)``; the
  Robotics Toolbox's compiled ``ETS.ik_LM(T, tol=tol, joint_limits=True, ilimit=30,
  slimit=100)`` solves them one by one (its tol bounds ½ eᵀe). ``--tol`` is 1e-13 by
  default. The toolbox's robot is built from kinlib's DH table (standard or modified) and
  checked against kinlib's FK first. Both are scored the same way, independently of what
  they report: success = position error < 1e-6 m, rotation error < 1e-6 rad, q within the
  limits. Time per target: kinlib batched total / M against the toolbox's median per
  call.

The Jacobians are checked against each other to 1e-12 before timing.
"""

from __future__ import annotations

import argparse
import sys
import time
import warnings

import numpy as np
from timing import best_time  # bench/timing.py (the script's folder is on sys.path)

import kinlib
from kinlib.kinematics import _fk
from kinlib.robots import panda, puma560


def score(robot, T, q):
    reached = robot.fk(q)
    pos = np.linalg.norm(reached[:, :3, 3] - T[:, :3, 3], axis=1)
    c = (np.einsum("nij,nij->n", reached[:, :3, :3], T[:, :3, :3]) - 1) / 2
    rot = np.arccos(np.clip(c, -1, 1))
    lim = robot.limits
    inside = ((q >= lim[:, 0] - 1e-9) & (q <= lim[:, 1] + 1e-9)).all(axis=1)
    return (pos < 1e-6) & (rot < 1e-6) & inside


def rtb_robot(robot, rtb):
    """The toolbox's DHRobot of kinlib's DH table (a fixed last row becomes its tool)."""
    from spatialmath import SE3

    link = rtb.RevoluteMDH if robot.dh_convention == "modified" else rtb.RevoluteDH
    rows = [r for r in robot.dh_rows if r.joint != "fixed"]
    zero = np.zeros(robot.dof)  # the fixed rows after the last joint: a constant tool
    tool = SE3(np.linalg.inv(robot.fk(zero, link=f"link{len(rows)}")) @ robot.fk(zero),
               check=False)
    peer = rtb.DHRobot([link(d=r.d, a=r.a, alpha=r.alpha, offset=r.offset, qlim=r.limits)
                        for r in rows], tool=tool)
    q = np.random.default_rng(3).uniform(robot.limits[:, 0], robot.limits[:, 1], robot.dof)
    ets = peer.ets()
    assert np.allclose(peer.fkine(q).A, robot.fk(q), atol=1e-12), robot.name
    assert np.allclose(ets.eval(q), robot.fk(q), atol=1e-12), robot.name
    return ets


#: solves of kinlib's whole batch, of which the median is reported
RUNS = 5


def ik_vs_rtb(robot, m, tol, rtb) -> None:
    rng = np.random.default_rng(1)
    Qt = rng.uniform(robot.limits[:, 0], robot.limits[:, 1], (m, robot.dof))
    T = robot.fk(Qt)
    robot.ik(T[:10], tol_position=tol, tol_rotation=tol)  # load the kernels outside

    def median_run(tolerance):
        """The median time of ``RUNS`` solves of the whole batch (one solve takes 20-40 ms,
        which one stray pause of this machine's scheduler can double: a median, as RTB's
        side is one), and the last solve."""
        times = []
        for _ in range(RUNS):
            t0 = time.perf_counter()
            sol = robot.ik(T, tol_position=tolerance, tol_rotation=tolerance)
            times.append(time.perf_counter() - t0)
        return float(np.median(times)), sol

    t_ik, sol = median_run(tol)
    cores, _fk.THREADS = _fk.THREADS, 1  # the same, on one core
    try:
        t_one, _ = median_run(tol)
    finally:
        _fk.THREADS = cores
    same = float(np.sqrt(2 * tol))  # RTB stops at ½|e|² < tol: |e| below this
    t_same, sol_same = median_run(same)
    ets = rtb_robot(robot, rtb)
    times, q_rtb = [], np.empty_like(Qt)
    for i in range(m):
        t0 = time.perf_counter()
        s = ets.ik_LM(T[i], tol=tol, joint_limits=True, ilimit=30, slimit=100)
        times.append(time.perf_counter() - t0)
        q_rtb[i] = s.q
    ok_kl, ok_rtb = score(robot, T, sol.q), score(robot, T, q_rtb)
    ok_same = score(robot, T, sol_same.q)
    assert ok_kl[np.asarray(sol.success)].all(), "kinlib reported a success that is not one"
    med = float(np.median(times))
    print(f"{robot.name + ': batched ik per target vs RTB ETS.ik_LM median':48s} "
          f"{t_ik / m * 1e6:10.1f} {med * 1e6:10.1f} {(t_ik / m) / med:7.3f}")
    print(f"{'  the same, kinlib on one core':48s} "
          f"{t_one / m * 1e6:10.1f} {med * 1e6:10.1f} {(t_one / m) / med:7.3f}")
    print(f"{'  kinlib at |e| < ' + f'{same:.2g}' + ' (RTB stops below it)':48s} "
          f"{t_same / m * 1e6:10.1f} {med * 1e6:10.1f} {(t_same / m) / med:7.3f}")
    print(f"  success (errors < 1e-6 m and 1e-6 rad, within limits): kinlib "
          f"{ok_kl.mean():.1%} ({ok_kl.sum()}/{m}; {ok_same.mean():.1%} at {same:.2g}), RTB "
          f"{ok_rtb.mean():.1%} ({ok_rtb.sum()}/{m}); kinlib iterations median "
          f"{np.median(sol.iterations):.0f}")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=10_000)
    ap.add_argument("--targets", type=int, default=500)
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--tol", type=float, default=1e-13)
    args = ap.parse_args(argv)
    kinlib.prepare_kernels()  # compiled kernels from the first timed call (bench_first_call)
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

    n = args.n
    print(f"PUMA 560 differential kinematics: Jacobian of N = {n} configurations (best of "
          f"{args.repeat})")
    print(f"{'case':48s} {'kinlib µs':>10s} {'peer µs':>10s} {'ratio':>7s}")
    print(f"{'batched jacobian vs pinocchio frame Jacobian loop':48s} {t_kl / n * 1e6:10.3f} "
          f"{t_pin / n * 1e6:10.3f} {t_kl / t_pin:7.3f}")
    print(f"IK: {args.targets} random reachable targets per robot, tolerance {args.tol:g} on "
          "both sides (kinlib tol_position = tol_rotation; RTB ik_LM tol, ilimit=30, "
          "slimit=100, joint limits on)")
    for model in (puma560, panda):
        ik_vs_rtb(model(), args.targets, args.tol, rtb)
    return 0


if __name__ == "__main__":
    sys.exit(main())
