"""PUMA 560 forward kinematics: kinlib vs pinocchio and the Robotics Toolbox, one run.

Run with ``make bench`` (or ``python bench/bench_fk.py [--n N] [--repeat R]``).

* batched: kinlib ``robot.fk(Q)`` on N configurations at once, per configuration, against
  pinocchio's ``forwardKinematics`` called in a Python loop (the usual way to use it from
  Python) and the Robotics Toolbox's ``DHRobot.fkine(Q)`` (which takes the whole batch).
  Batches of 4096 or more are spread over the CPU cores; the one-thread figure is
  printed too.
* single: one configuration per call (what a slider update costs): kinlib ``robot.fk(q)``
  against the Robotics Toolbox's compiled ``ETS.fkine(q)``.

All peers are built from the same robot: pinocchio from kinlib's URDF export, the toolbox
from the same DH table; the script first checks that they agree with kinlib to 1e-12.
Each pair is timed interleaved, best of R repeats; the ratio kinlib/peer is what to read
(below 1.0: kinlib is faster).
"""

from __future__ import annotations

import argparse
import sys
import warnings

import numpy as np
from timing import best_time  # bench/timing.py (the script's folder is on sys.path)

import kinlib
from kinlib.kinematics import _fk
from kinlib.robots import puma560


def peers(robot):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        import pinocchio as pin
        import roboticstoolbox as rtb
    model = pin.buildModelFromXML(robot.to_urdf())
    data = model.createData()
    tip = model.getFrameId(robot.tip)
    dh = rtb.DHRobot([rtb.RevoluteDH(d=r.d, a=r.a, alpha=r.alpha, offset=r.offset)
                      for r in robot.dh_rows])
    return pin, model, data, tip, dh, dh.ets()


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=10_000)
    ap.add_argument("--repeat", type=int, default=7)
    args = ap.parse_args(argv)
    kinlib.prepare_kernels()  # compiled kernels from the first timed call (bench_first_call)
    robot = puma560()
    pin, model, data, tip, dh, ets = peers(robot)
    rng = np.random.default_rng(0)
    Q = rng.uniform(robot.limits[:, 0], robot.limits[:, 1], (args.n, robot.dof))

    # the timed pairs compute the same poses
    ours = robot.fk(Q[:50])
    for i in range(50):
        pin.framesForwardKinematics(model, data, Q[i])
        assert np.allclose(data.oMf[tip].homogeneous, ours[i], atol=1e-12)
        assert np.allclose(dh.fkine(Q[i]).A, ours[i], atol=1e-12)
        assert np.allclose(ets.fkine(Q[i]).A, ours[i], atol=1e-12)

    def pin_loop():
        for q in Q:
            pin.forwardKinematics(model, data, q)

    def pin_frames_loop():
        for q in Q:
            pin.framesForwardKinematics(model, data, q)

    robot.fk(Q)  # compile/load the kernel outside the timing
    t_kl = best_time(lambda: robot.fk(Q), args.repeat)
    cores = _fk.THREADS
    threads = cores if Q.shape[0] >= _fk.PARALLEL_MIN else 1
    _fk.THREADS = 1  # the same kernel on one thread
    try:
        t_kl_1 = best_time(lambda: robot.fk(Q), args.repeat)
    finally:
        _fk.THREADS = cores
    t_pin = best_time(pin_loop, args.repeat)
    t_pinf = best_time(pin_frames_loop, args.repeat)
    t_rtb = best_time(lambda: dh.fkine(Q), max(1, args.repeat // 3))
    m = 2000
    q1 = Q[:m]

    def kl_single():
        for q in q1:
            robot.fk(q)

    def ets_single():
        for q in q1:
            ets.fkine(q)

    t_kl1 = best_time(kl_single, args.repeat)
    t_ets1 = best_time(ets_single, args.repeat)

    n = args.n
    print(f"PUMA 560 forward kinematics, N = {n} configurations, best of {args.repeat}; "
          f"kinlib batched FK uses {threads} thread(s)")
    print(f"{'case':52s} {'kinlib µs':>10s} {'peer µs':>10s} {'ratio':>7s}")
    rows = [
        ("batched fk vs pinocchio forwardKinematics loop", t_kl / n, t_pin / n),
        ("  same, kinlib on one thread", t_kl_1 / n, t_pin / n),
        ("batched fk vs pinocchio framesForwardKinematics loop", t_kl / n, t_pinf / n),
        ("batched fk vs RTB DHRobot.fkine(Q)", t_kl / n, t_rtb / n),
        ("single fk(q) vs RTB ETS.fkine(q)", t_kl1 / m, t_ets1 / m),
    ]
    for name, a, b in rows:
        print(f"{name:52s} {a * 1e6:10.3f} {b * 1e6:10.3f} {a / b:7.3f}")
    sincos_pays(robot, Q, args.repeat)
    return 0


def sincos_pays(robot, Q, repeat) -> None:
    """The chain kernel with kinlib's fdlibm sincos (one argument reduction for both)
    against the same kernel calling numba's sin and cos, one thread: is the port worth
    keeping? (the answers agree to a few ulps)"""
    import types

    try:
        import numba
    except ImportError:
        return
    K = _fk._compiled()
    if K is None:
        return

    @numba.njit
    def libm_sincos(x):
        return np.sin(x), np.cos(x)

    f = K.chain.py_func
    libm = numba.njit(nogil=True)(types.FunctionType(
        f.__code__, {**f.__globals__, "sincos": libm_sincos}, "chain_libm"))
    ch = robot.chain_table()
    ours, theirs = K.chain(Q, ch.ints, ch.floats, ch.D), libm(Q, ch.ints, ch.floats, ch.D)
    assert np.abs(ours - theirs).max() < 1e-14
    t_ours = best_time(lambda: K.chain(Q, ch.ints, ch.floats, ch.D), repeat)
    t_libm = best_time(lambda: libm(Q, ch.ints, ch.floats, ch.D), repeat)
    n = len(Q)
    print(f"{'chain kernel: fdlibm sincos vs numba sin + cos':52s} {t_ours / n * 1e6:10.3f} "
          f"{t_libm / n * 1e6:10.3f} {t_ours / t_libm:7.3f}")


if __name__ == "__main__":
    sys.exit(main())
