"""Numeric IK: FK(ik(T)) == T whenever success is reported, for every robot; success rate on
reachable targets; unreachable targets are never reported as success and end in bounded
time; the compiled loop and the numpy reference agree."""

import numpy as np
import pytest

import kinlib as kl
from kinlib import IKResult, KinlibError
from kinlib.kinematics import ik
from kinlib.robots import autorob_test_robot, panda, planar_2r, puma560, three_dof_arm, ur5

MODELS = [planar_2r, three_dof_arm, puma560, ur5, panda]


def reachable_targets(robot, n, seed, link=None):
    lim = np.clip(robot.limits, -np.pi, np.pi)
    q = np.random.default_rng(seed).uniform(lim[:, 0], lim[:, 1], (n, robot.dof))
    return robot.fk(q, link=link)


def rotation_angle(Ra, Rb):
    c = (np.trace(np.swapaxes(Ra, -1, -2) @ Rb, axis1=-2, axis2=-1) - 1) / 2
    return np.arccos(np.clip(c, -1, 1))


def check_solutions(robot, T, sol, tol=1e-6, link=None):
    """Independent check of what success claims: pose error from FK, limits."""
    reached = robot.fk(sol.q, link=link)
    pos = np.linalg.norm(reached[..., :3, 3] - T[..., :3, 3], axis=-1)
    rot = rotation_angle(reached[..., :3, :3], T[..., :3, :3])
    ok = np.asarray(sol.success)
    assert (pos[ok] < tol).all() and (rot[ok] < tol * 1.01).all()
    lim = robot.limits
    assert ((sol.q >= lim[:, 0] - 1e-12) & (sol.q <= lim[:, 1] + 1e-12)).all()
    np.testing.assert_allclose(sol.position_error, pos, atol=1e-12)


@pytest.mark.parametrize("model", MODELS, ids=lambda m: m.__name__)
def test_reachable_targets(model):
    robot = model()
    T = reachable_targets(robot, 200, seed=11)
    sol = robot.ik(T)
    assert isinstance(sol, IKResult) and sol.q.shape == (200, robot.dof)
    check_solutions(robot, T, sol)
    assert np.mean(sol.success) >= 0.99
    assert (sol.iterations <= 101 * 30).all()


@pytest.mark.parametrize("model", [puma560, panda], ids=lambda m: m.__name__)
def test_numpy_reference_agrees_with_the_compiled_loop(model):
    """One method written twice (the numpy reference, vectorised over the targets, and
    the compiled loop, one target at a time): on every target the same success and the
    same number of iterations, and the same answer to rounding. A tenth of the targets
    are out of reach, so every restart runs to its end there."""
    robot = model()
    T = reachable_targets(robot, 100, seed=13)
    T[::10, :3, 3] *= 3.0
    fast = robot.ik(T, restarts=10)
    ref = ik.solve_ik(robot, T, compiled=False, restarts=10)
    check_solutions(robot, T, ref)
    assert 0.8 <= np.mean(ref.success) < 0.95  # the far ones fail
    np.testing.assert_array_equal(fast.success, ref.success)
    np.testing.assert_array_equal(fast.iterations, ref.iterations)
    ok = ref.success
    np.testing.assert_allclose(fast.q[ok], ref.q[ok], rtol=0, atol=1e-9)
    # not reached: after up to 330 steps the rounding of the two (sin/cos, summation order)
    # has drifted apart; both end at the same closest pose, to within a few micrometres (a
    # machine's libm and BLAS move the last digits: 2.3e-7 m apart on one of 16 here)
    np.testing.assert_allclose(fast.position_error[~ok], ref.position_error[~ok], rtol=1e-4,
                               atol=1e-6)


@pytest.mark.parametrize("lanes", [(1, 64, 64, 8192), (128, 128, 128, 8192), (1, 2, 2, 8192),
                                   (128, 128, 128, 64)], ids=lambda v: "-".join(map(str, v)))
def test_numpy_attempts_side_by_side_answer_as_one_after_another(lanes, monkeypatch):
    """The numpy path runs a target's restarts side by side; its answer must still be that
    of running them in order: the first attempt that succeeds (not the first to finish),
    and the steps of the attempts up to it, however many run at once (first lanes,
    window per target, growth, lanes in all). Six steps per attempt (to 1 mm and 1 mrad)
    make many attempts fail, so successes come at scattered attempts, several in flight
    at once."""
    for name, value in zip(("FIRST_LANES", "WINDOW_MAX", "GROWTH", "LANES_MAX"), lanes,
                           strict=True):
        monkeypatch.setattr(ik, name, value)
    robot = puma560()
    T = reachable_targets(robot, 60, seed=21)
    settings = dict(max_iterations=6, restarts=40, tol_position=1e-3, tol_rotation=1e-3)
    fast = robot.ik(T, **settings)
    ref = ik.solve_ik(robot, T, compiled=False, **settings)
    assert 0.5 < np.mean(ref.success) < 1.0 and len(set(ref.iterations.tolist())) > 20
    assert (ref.iterations[ref.success] > 6).mean() > 0.5  # decided after attempt 0
    np.testing.assert_array_equal(fast.success, ref.success)
    np.testing.assert_array_equal(fast.iterations, ref.iterations)
    np.testing.assert_allclose(fast.q[ref.success], ref.q[ref.success], rtol=0, atol=1e-9)


@pytest.mark.parametrize("lanes", [(1, 64, 64), (128, 128, 128)], ids=["1-64", "128"])
def test_numpy_path_runs_every_restart_of_an_unreachable_target(lanes, monkeypatch):
    """With the default 100 restarts an unreachable target runs all 101 attempts to their
    30th step on both paths (3,030 iterations: no attempt's damping grows past its bound
    this far out), and both end at the same closest pose. The numpy path launches them in
    windows: with (first lanes, window, growth) = (1, 64, 64), the setting of old, one, then
    64, then the last 36, where the second window's 64 failures in one step once overflowed
    the window's growth and the last 36 attempts were never run; with today's 128, the two
    targets 64 each, then the last 37 each."""
    for name, value in zip(("FIRST_LANES", "WINDOW_MAX", "GROWTH"), lanes, strict=True):
        monkeypatch.setattr(ik, name, value)
    robot = puma560()
    T = np.repeat(np.eye(4)[None], 2, axis=0)
    T[:, :3, 3] = [[2.0, 0.0, 0.5], [0.0, -1.5, 1.0]]  # both beyond the ~0.9 m reach
    fast = robot.ik(T)
    ref = ik.solve_ik(robot, T, compiled=False)
    assert not ref.success.any() and not fast.success.any()
    np.testing.assert_array_equal(ref.iterations, [101 * 30, 101 * 30])
    np.testing.assert_array_equal(fast.iterations, ref.iterations)
    np.testing.assert_allclose(fast.position_error, ref.position_error, rtol=1e-9)
    np.testing.assert_allclose(fast.q, ref.q, atol=1e-6)
    check_solutions(robot, T, ref)


@pytest.mark.parametrize("compiled", [None, False], ids=["compiled", "numpy"])
def test_an_empty_batch_of_targets(compiled):
    robot = puma560()
    sol = ik.solve_ik(robot, np.zeros((0, 4, 4)), compiled=compiled)
    assert sol.q.shape == (0, 6) and sol.success.shape == (0,) and sol.iterations.shape == (0,)


def test_unreachable_target_is_never_success():
    robot = puma560()
    T = np.eye(4)
    T[:3, 3] = [2.0, 0.0, 0.5]  # reach is under 1 m
    sol = robot.ik(T, restarts=3, max_iterations=20)
    assert sol.success is False
    assert sol.iterations == 4 * 20
    assert sol.position_error > 1.0
    check_solutions(robot, T, sol)


def test_orientation_the_planar_arm_cannot_reach():
    robot = planar_2r(1.0, 1.0)
    T = robot.fk([0.3, 0.5])
    T[:3, :3] = T[:3, :3] @ np.array([[1, 0, 0], [0, 0, -1], [0, 1, 0]])  # tilt out of plane
    sol = robot.ik(T, restarts=5)
    assert sol.success is False and sol.rotation_error > 1.0
    # the position alone is reachable
    pos = robot.ik(T, position_only=True)
    assert pos.success and pos.position_error < 1e-6


def test_position_only_with_points_and_a_branch():
    robot = autorob_test_robot()
    targets = robot.fk(np.random.default_rng(3).uniform(-3, 3, (30, 3)), link="link4")
    sol = robot.ik(targets[:, :3, 3], position_only=True, link="link4")
    reached = robot.fk(sol.q, link="link4")[:, :3, 3]
    assert np.mean(sol.success) >= 0.99
    assert (np.linalg.norm(reached - targets[:, :3, 3], axis=1)[sol.success] < 1e-6).all()
    with pytest.raises(KinlibError, match="several leaf links"):
        robot.ik(targets[0])


def test_starting_at_the_answer_takes_one_step():
    robot = ur5()
    q = np.array([0.3, -1.0, 1.2, -0.4, 0.8, 0.1])
    sol = robot.ik(robot.fk(q), q0=q)
    assert sol.success and sol.iterations == 1
    np.testing.assert_allclose(sol.q, q, atol=1e-12)


def test_batches_and_seeds():
    robot = puma560()
    T = reachable_targets(robot, 6, seed=13).reshape(2, 3, 4, 4)
    a = robot.ik(T, seed=5)
    assert a.q.shape == (2, 3, 6) and a.success.shape == (2, 3)
    b = robot.ik(T, seed=5)
    np.testing.assert_array_equal(a.q, b.q)
    single = robot.ik(T[1, 2], seed=5)
    assert isinstance(single.success, bool) and isinstance(single.iterations, int)


@pytest.mark.parametrize("kwargs, phrase", [
    ({"T_target": np.zeros((4, 4))}, "T_target"),
    ({"T_target": np.eye(3)}, "T_target"),
    ({"max_iterations": 0}, "max_iterations"),
    ({"restarts": -1}, "restarts"),
    ({"restarts": 2.5}, "restarts"),
    ({"tol_position": -1.0}, "tol_position"),
    ({"q0": [0.0] * 5}, "q0"),
    ({"q0": np.zeros((3, 6))}, "q0"),
])
def test_bad_input(kwargs, phrase):
    robot = puma560()
    args = {"T_target": robot.fk(np.zeros(6))} | kwargs
    with pytest.raises(KinlibError, match=phrase):
        robot.ik(**args)


def test_pose_error_against_scipy_rotation_vectors():
    """[p_t − p; log(R_t Rᵀ)^∨]: the translation to go and scipy's rotation vector of the
    rotation to go (base frame), batched."""
    from scipy.spatial.transform import Rotation

    rng = np.random.default_rng(4)
    R1, R2 = Rotation.random(50, random_state=1), Rotation.random(50, random_state=2)
    p1, p2 = rng.normal(size=(2, 50, 3))
    T, T_t = kl.transform(R1.as_matrix(), p1), kl.transform(R2.as_matrix(), p2)
    e = kl.pose_error(T, T_t)
    assert e.shape == (50, 6)
    np.testing.assert_allclose(e[:, :3], p2 - p1, atol=1e-15)
    np.testing.assert_allclose(e[:, 3:], (R2 * R1.inv()).as_rotvec(), atol=1e-12)
    np.testing.assert_allclose(kl.pose_error(T_t, T_t), 0, atol=1e-15)
    with pytest.raises(kl.KinlibError, match="T_target"):
        kl.pose_error(np.eye(4), np.eye(3))


def test_dls_step_minimises_the_damped_least_squares_problem():
    """The step solves min |J Δq − e|² + λ² |Δq|²: the same as least squares on the
    stacked system [J; λ I] Δq = [e; 0]; λ = 0 is the pseudo-inverse step."""
    rng = np.random.default_rng(5)
    for m, n in ((6, 6), (6, 7), (3, 2)):
        J, e = rng.normal(size=(m, n)), rng.normal(size=m)
        for lam in (0.0, 0.01, 0.5, 2.0):
            if lam == 0.0 and m > n:
                continue  # J Jᵀ singular: no undamped step for a tall J
            stacked = np.vstack([J, lam * np.eye(n)])
            expected = np.linalg.lstsq(stacked, np.r_[e, np.zeros(n)], rcond=None)[0]
            np.testing.assert_allclose(kl.dls_step(J, e, lam), expected, atol=1e-10)
    Js, es = rng.normal(size=(2, 4, 6, 6)), rng.normal(size=(2, 4, 6))
    np.testing.assert_allclose(kl.dls_step(Js[0], es[0], 0.1)[2],
                               kl.dls_step(Js[0][2], es[0][2], 0.1))
    with pytest.raises(kl.KinlibError, match="damping"):
        kl.dls_step(np.eye(2), np.ones(2), -1.0)
    with pytest.raises(kl.KinlibError, match="rows of J are dependent"):
        kl.dls_step(np.ones((2, 2)), np.ones(2), 0.0)
    with pytest.raises(kl.KinlibError, match="e: expected"):
        kl.dls_step(np.eye(3), np.ones(2), 0.1)
    with pytest.raises(kl.KinlibError, match=r"J.*NaN"):
        kl.dls_step(np.full((2, 2), np.nan), np.ones(2), 0.1)
    with pytest.raises(kl.KinlibError, match="J: expected a Jacobian"):
        kl.dls_step(np.ones(3), np.ones(3), 0.1)
