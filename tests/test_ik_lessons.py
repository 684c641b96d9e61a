"""What notebooks 10 and 11 (inverse kinematics) show, as tests of kinlib: the 2R arm's
closed form against seed 001's formulas written out here, its elbows, workspace, solution
counts and unreachable targets against brute force; the PUMA 560's eight solutions against
the structure of a spherical wrist, joint limits, batched and warm-started IK, and what the
solver reports for targets out of reach."""

import numpy as np
import pytest
import sympy as sp

import kinlib as kl
from kinlib.robots import planar_2r, puma560
from kinlib.robots.puma560 import PUMA560_TABLE
from kinlib.symbolic import sym_equal, trig_reduce

L1, L2 = 1.0, 0.7


def wrap(a):
    return (np.asarray(a) + np.pi) % (2 * np.pi) - np.pi


def tip(t1, t2, l1=L1, l2=L2):
    """Seed 001: x = l1 c1 + l2 c12, y = l1 s1 + l2 s12."""
    return np.stack([l1 * np.cos(t1) + l2 * np.cos(t1 + t2),
                     l1 * np.sin(t1) + l2 * np.sin(t1 + t2)], axis=-1)


def seed_ik(x, y, l1, l2, sign):
    """Seed 001's closed form, literally: sign +1 is s2 ≥ 0."""
    c2 = (x**2 + y**2 - l1**2 - l2**2) / (2 * l1 * l2)
    s2 = sign * np.sqrt(1 - c2**2)
    return np.arctan2(y, x) - np.arctan2(l2 * s2, l1 + l2 * c2), np.arctan2(s2, c2)


def annulus(rng, n, l1=L1, l2=L2, margin=0.0):
    r = np.sqrt(rng.uniform((abs(l1 - l2) + margin)**2, (l1 + l2 - margin)**2, n))
    a = rng.uniform(-np.pi, np.pi, n)
    return r * np.cos(a), r * np.sin(a)


# -- notebook 10 · the planar 2R arm ---------------------------------------------------------

def test_the_law_of_cosines_drops_theta1():
    t1, t2 = sp.symbols("theta_1 theta_2", real=True)
    l1, l2 = sp.symbols("l_1 l_2", positive=True)
    r2 = (l1 * sp.cos(t1) + l2 * sp.cos(t1 + t2))**2 + (l1 * sp.sin(t1) + l2 * sp.sin(t1 + t2))**2
    reduced = trig_reduce(r2)
    assert t1 not in reduced.free_symbols
    assert sp.simplify(reduced - (l1**2 + l2**2 + 2 * l1 * l2 * sp.cos(t2))) == 0
    assert sym_equal(r2, l1**2 + l2**2 + 2 * l1 * l2 * sp.cos(t2))
    assert not sym_equal(r2, l1**2 + l2**2 - 2 * l1 * l2 * sp.cos(t2))   # the interior angle


@pytest.mark.parametrize("l1, l2", [(1.0, 0.7), (0.6, 0.9), (0.8, 0.8)])
def test_planar_ik_is_seed_001s_formula_for_both_elbows(l1, l2):
    x, y = annulus(np.random.default_rng(1), 4000, l1, l2, margin=1e-6)
    arm = planar_2r(l1, l2)
    for elbow, sign in (("up", -1), ("down", +1)):
        sol = kl.planar_2r_ik(x, y, l1, l2, elbow=elbow)
        th1, th2 = seed_ik(x, y, l1, l2, sign)
        assert sol.success.all()
        assert np.abs(wrap(sol.theta1 - th1)).max() < 1e-9 and np.abs(sol.theta2 - th2).max() < 1e-9
        assert np.abs(tip(sol.theta1, sol.theta2, l1, l2) - np.stack([x, y], -1)).max() < 1e-9
        q = np.stack([sol.theta1, sol.theta2], axis=1)
        assert np.abs(arm.fk(q)[:, :2, 3] - np.stack([x, y], -1)).max() < 1e-9   # the robot model


def test_acos_for_the_polar_angle_mirrors_targets_below_the_x_axis():
    x, y = annulus(np.random.default_rng(3), 500, margin=1e-3)
    for elbow in ("up", "down"):
        sol = kl.planar_2r_ik(x, y, L1, L2, elbow=elbow)
        beta = np.arctan2(y, x) - sol.theta1                          # θ1 = φ − β
        mirrored = tip(np.arccos(x / np.hypot(x, y)) - beta, sol.theta2)
        assert np.abs(mirrored - np.stack([x, np.abs(y)], -1)).max() < 1e-9
    # and θ2 = arccos c2 is always the elbow "down" one
    down = kl.planar_2r_ik(x, y, L1, L2, elbow="down")
    c2 = (x**2 + y**2 - L1**2 - L2**2) / (2 * L1 * L2)
    assert np.abs(np.arccos(c2) - down.theta2).max() < 1e-9


def test_the_elbows_are_mirror_images_in_the_line_to_the_target():
    s = np.linspace(0, 2 * np.pi, 24, endpoint=False)
    path = np.array([0.8, 0.2]) + 0.5 * np.stack([np.cos(s), np.sin(s)], axis=1)
    up, down = (kl.planar_2r_ik(path[:, 0], path[:, 1], L1, L2, elbow=e) for e in ("up", "down"))
    phi = np.arctan2(path[:, 1], path[:, 0])
    assert (up.theta2 < 0).all() and np.allclose(up.theta2, -down.theta2)
    assert np.allclose(wrap(up.theta1 + down.theta1 - 2 * phi), 0)
    # the "up" elbow lies counter-clockwise of the line base → target, "down" clockwise
    for sol, side in ((up, 1), (down, -1)):
        elbow = L1 * np.stack([np.cos(sol.theta1), np.sin(sol.theta1)], axis=1)
        cross = path[:, 0] * elbow[:, 1] - path[:, 1] * elbow[:, 0]   # z of target × elbow
        assert (side * cross > 0).all()
        assert np.abs(tip(sol.theta1, sol.theta2) - path).max() < 1e-12


def test_the_workspace_is_the_annulus():
    rng = np.random.default_rng(2)
    radii = np.linalg.norm(tip(*rng.uniform(-np.pi, np.pi, (2, 4000))), axis=1)
    assert abs(L1 - L2) - 1e-12 <= radii.min() < abs(L1 - L2) + 0.02
    assert L1 + L2 - 0.02 < radii.max() <= L1 + L2 + 1e-12
    # and kinlib calls exactly the annulus reachable
    g = np.linspace(-2.0, 2.0, 161)
    X, Y = np.meshgrid(g, g)
    r = np.hypot(X, Y)
    clear = (np.abs(r - (L1 + L2)) > 1e-9) & (np.abs(r - abs(L1 - L2)) > 1e-9)
    inside = (r >= abs(L1 - L2)) & (r <= L1 + L2)
    reachable = kl.planar_2r_ik(X, Y, L1, L2).success
    assert (reachable[clear] == inside[clear]).all()


def n_solutions(r, l1=L1, l2=L2, tol=1e-6):
    up, down = (kl.planar_2r_ik(r, 0.0, l1, l2, elbow=e) for e in ("up", "down"))
    if not up.success:
        return 0
    same = abs(wrap(up.theta1 - down.theta1)) < tol and abs(up.theta2 - down.theta2) < tol
    return 1 if same else 2


def theta2_roots(r, l1=L1, l2=L2, n=20_001):
    """Brute force: the θ2 in (−π, π] with l1² + l2² + 2 l1 l2 cos θ2 = r², counted by sign
    changes (a double root, where the curve only touches zero, by its extremum)."""
    t = np.linspace(-np.pi, np.pi, n)
    f = l1**2 + l2**2 + 2 * l1 * l2 * np.cos(t) - r**2
    crossings = int(np.sum(np.sign(f[:-1]) * np.sign(f[1:]) < 0))
    touches = int(np.isclose(f.max(), 0, atol=1e-12) or np.isclose(f.min(), 0, atol=1e-12))
    return crossings + touches


@pytest.mark.parametrize("r, count", [(0.1, 0), (0.3, 1), (0.55, 2), (1.0, 2), (1.7, 1),
                                      (1.9, 0)])
def test_the_number_of_solutions_along_a_ray(r, count):
    assert n_solutions(r) == count == theta2_roots(r)


def test_on_the_circles_the_elbows_coincide_stretched_or_folded():
    for r, theta2 in ((L1 + L2, 0.0), (abs(L1 - L2), np.pi)):
        up, down = (kl.planar_2r_ik(r, 0.0, L1, L2, elbow=e) for e in ("up", "down"))
        assert up.success and up.theta2 == down.theta2 == theta2 and up.theta1 == down.theta1


def test_equal_links_reach_the_base_with_any_theta1():
    l = 0.8
    theta1 = np.linspace(-np.pi, np.pi, 9)
    assert np.abs(tip(theta1, np.pi, l, l)).max() < 1e-12
    assert np.abs(kl.planar_2r_fk(theta1, np.pi, l, l)[:, :2, 3]).max() < 1e-12
    sol = kl.planar_2r_ik(0.0, 0.0, l, l)
    assert sol.success and sol.theta2 == np.pi and sol.theta1 == 0.0


@pytest.mark.parametrize("p", [(2.2, 0.9), (0.12, -0.15), (-1.0, -1.6), (0.0, 0.05),
                               (-0.2, 0.1)])
def test_unreachable_targets_get_the_closest_configuration(p):
    p = np.array(p)
    r = np.linalg.norm(p)
    sol = kl.planar_2r_ik(*p, L1, L2)
    assert not sol.success and np.isfinite([sol.theta1, sol.theta2]).all()
    stretched = r > L1 + L2
    assert np.isclose(sol.theta2, 0.0 if stretched else np.pi)
    got = np.linalg.norm(tip(sol.theta1, sol.theta2) - p)
    assert np.isclose(got, r - (L1 + L2) if stretched else abs(L1 - L2) - r)
    g = np.linspace(-np.pi, np.pi, 721)
    best = np.linalg.norm(tip(*np.meshgrid(g, g)) - p, axis=-1).min()   # brute force
    assert best - 1e-4 < got <= best + 1e-12


# -- notebook 11 · numerical IK on the PUMA 560 ----------------------------------------------

Q_TRUE = np.array([0.3, -0.5, 1.0, 2.0, 0.6, 0.0])
D6 = PUMA560_TABLE[5][4] / 1000


@pytest.fixture(scope="module")
def robot():
    return puma560()


def distinct(qs, tol=1e-3):
    out = []
    for q in qs:
        if all(np.abs(wrap(q - p)).max() > tol for p in out):
            out.append(q)
    return np.array(out)


def pose_error(T, T_target):
    return np.concatenate([T_target[:3, 3] - T[:3, 3], kl.log_so3(T_target[:3, :3] @ T[:3, :3].T)])


def rotation_angle(Ra, Rb):
    c = (np.trace(np.swapaxes(Ra, -1, -2) @ Rb, axis1=-2, axis2=-1) - 1) / 2
    return np.arccos(np.clip(c, -1, 1))


def test_damped_least_squares_by_hand_converges_fast(robot):
    T_target = robot.fk(Q_TRUE)
    q, errors = robot.poses["ready"].copy(), []
    for _ in range(11):
        e = pose_error(robot.fk(q), T_target)
        errors.append(np.linalg.norm(e))
        J = robot.jacobian(q)
        step = J.T @ np.linalg.solve(J @ J.T + 0.01**2 * np.eye(6), e)
        # the notebook iterates with kinlib's functions: the same numbers as the formulas
        assert np.abs(kl.pose_error(robot.fk(q), T_target) - e).max() < 1e-14
        assert np.abs(kl.dls_step(J, e, 0.01) - step).max() < 1e-9 * (1 + np.abs(step).max())
        q = q + step
    assert errors[-1] < 1e-12
    small = [k for k, err in enumerate(errors) if err < 1e-2]
    assert all(errors[k + 1] < errors[k] / 20 for k in small[:-1])   # each step: ×1/100 or so
    assert np.allclose(robot.fk(q), T_target, atol=1e-12)
    assert not np.allclose(q, Q_TRUE, atol=1e-3)                        # another solution
    # the push-through identity of the two forms of the step, for a square and a wide J, and
    # both are the least-squares solution of [J; λI] Δq = [e; 0] (the notebook's comparison)
    rng = np.random.default_rng(4)
    e = pose_error(robot.fk(robot.poses["ready"]), T_target)
    for J in (robot.jacobian(robot.poses["ready"]), rng.normal(size=(6, 7))):
        m, n = J.shape
        a = J.T @ np.linalg.inv(J @ J.T + 0.1**2 * np.eye(m))
        b = np.linalg.inv(J.T @ J + 0.1**2 * np.eye(n)) @ J.T
        assert np.abs(a - b).max() < 1e-12
        stacked = np.linalg.lstsq(np.vstack([J, 0.1 * np.eye(n)]),
                                  np.concatenate([e, np.zeros(n)]), rcond=None)[0]
        assert np.abs(a @ e - stacked).max() < 1e-12
        assert np.abs(kl.dls_step(J, e, 0.1) - stacked).max() < 1e-12


def test_the_puma_has_eight_solutions_shoulder_elbow_and_wrist_flip(robot):
    T_target = robot.fk(Q_TRUE)
    q0s = np.random.default_rng(10).uniform(robot.limits[:, 0], robot.limits[:, 1], (200, 6))
    many = robot.ik(np.broadcast_to(T_target, (200, 4, 4)), q0=q0s)
    sols = distinct(many.q[many.success])
    assert len(sols) == 8
    assert np.abs(robot.fk(sols) - T_target).max() < 1e-5
    assert any(np.abs(wrap(s - Q_TRUE)).max() < 1e-4 for s in sols)
    # 4 arm configurations (shoulder × elbow), each with its wrist flipped: q4 + π, −q5, q6 + π
    assert len(distinct(np.c_[sols[:, :3], np.zeros((8, 3))])) == 4
    for s in sols:
        flipped = s + np.array([0, 0, 0, np.pi, 0, np.pi])
        flipped[4] = -s[4]
        assert np.allclose(robot.fk(flipped), T_target, atol=1e-5)
        assert any(np.abs(wrap(flipped - o)).max() < 1e-4 for o in sols)
    # all eight share the wrist centre, d6 behind the tool point along the tool's z axis
    centre = T_target[:3, 3] - D6 * T_target[:3, 2]
    assert np.abs(robot.link_poses(sols)["link4"][:, :3, 3] - centre).max() < 1e-5


def test_joint_limits_remove_solutions_of_the_ready_pose(robot):
    free = kl.Robot.from_dh([kl.DHRow(a=a / 1000, alpha=np.deg2rad(al), d=d / 1000)
                             for _, _, al, a, d, _ in PUMA560_TABLE])
    assert np.isinf(free.limits).all()
    T_ready = robot.fk(robot.poses["ready"])
    q0s = np.random.default_rng(10).uniform(robot.limits[:, 0], robot.limits[:, 1], (200, 6))
    stack = np.broadcast_to(T_ready, (200, 4, 4))
    lim_run, free_run = robot.ik(stack, q0=q0s), free.ik(stack, q0=wrap(q0s))
    limited = distinct(lim_run.q[lim_run.success])
    unlimited = distinct(free_run.q[free_run.success])
    assert len(unlimited) == 8 and 0 < len(limited) < 8
    lo, hi = robot.limits.T
    assert ((limited >= lo - 1e-12) & (limited <= hi + 1e-12)).all()
    assert np.allclose(free.fk(unlimited), T_ready, atol=1e-5)

    def in_range(q):
        shifted = q + 2 * np.pi * np.arange(-2, 3)[:, None]
        return ((shifted >= lo) & (shifted <= hi)).any(axis=0).all()

    missing = [q for q in unlimited if not any(np.abs(wrap(q - p)).max() < 1e-3 for p in limited)]
    assert len(missing) == 8 - len(limited) and not any(in_range(q) for q in missing)


def test_batched_ik_reports_its_errors_truthfully(robot):
    rng = np.random.default_rng(11)
    T = robot.fk(rng.uniform(robot.limits[:, 0], robot.limits[:, 1], (200, 6)))
    batch = robot.ik(T)
    assert batch.success.mean() >= 0.97
    reached = robot.fk(batch.q)
    pos = np.linalg.norm(reached[:, :3, 3] - T[:, :3, 3], axis=1)
    rot = rotation_angle(reached[:, :3, :3], T[:, :3, :3])
    np.testing.assert_allclose(batch.position_error, pos, atol=1e-12)
    np.testing.assert_allclose(batch.rotation_error, rot, atol=1e-7)
    assert (batch.success == ((pos < 1e-6) & (rot < 1e-6 * 1.01))).all()


def test_warm_started_ik_follows_a_straight_line_continuously(robot):
    q = robot.poses["ready"]
    T_start = robot.fk(q)
    s = np.linspace(0, 1, 40)
    T_path = np.broadcast_to(T_start, (40, 4, 4)).copy()
    T_path[:, :3, 3] = T_start[:3, 3] + s[:, None] * np.array([-0.25, -0.35, 0.1])
    qs = []
    for T in T_path:
        step = robot.ik(T, q0=q)
        assert step.success
        q = step.q
        qs.append(q)
    qs = np.array(qs)
    assert np.abs(np.diff(qs, axis=0)).max() < 0.1
    tool = robot.fk(qs)
    assert np.abs(tool[:, :3, 3] - T_path[:, :3, 3]).max() < 1e-6
    assert np.abs(tool[:, :3, :3] - T_start[:3, :3]).max() < 1e-6


def test_targets_out_of_reach_fail_after_bounded_work(robot):
    T_far = robot.fk(Q_TRUE)
    T_far[:3, 3] *= 2.0 / np.linalg.norm(T_far[:3, 3])
    far = robot.ik(T_far)
    far_pos = robot.ik(T_far[:3, 3], position_only=True)
    assert not far.success and not far_pos.success
    assert far.iterations <= (100 + 1) * 30
    poses = robot.link_poses(np.random.default_rng(5).uniform(*robot.limits.T, (20_000, 6)))
    reach = np.linalg.norm(poses[robot.tip][:, :3, 3], axis=1).max()
    # the stretched arm: at least as close as any sampled configuration, and not much closer
    assert 2.0 - reach - 1e-3 < far_pos.position_error <= 2.0 - reach + 1e-9
    assert far_pos.position_error <= far.position_error < far_pos.position_error + 0.05
    # a reachable point with the tool turned back: the wrist centre would be out of reach
    T_out = robot.fk(np.array([0.0, 0.0, 1.2, 0.0, 0.0, 0.0]))
    T_in = T_out.copy()
    T_in[:3, :3] = T_out[:3, :3] @ kl.rotx(np.pi)
    wrist_reach = np.linalg.norm(poses["link4"][:, :3, 3], axis=1).max()
    assert np.linalg.norm(T_in[:3, 3] - D6 * T_in[:3, 2]) > wrist_reach + 0.05
    assert robot.ik(T_out).success
    inward = robot.ik(T_in)
    assert not inward.success and inward.position_error > 0.01
