"""What notebooks 12 (angular velocity, the geometric Jacobian) and 13 (singularities,
manipulability) teach, as tests of kinlib against routes that do not go through the code
under test: sympy's own differentiation and cross product, finite differences of the
forward kinematics, scipy's rotations, the closed forms of the planar 2R arm, and answers
worked out by hand. The notebooks keep only their key results in their final checks."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from scipy.optimize import brentq
from scipy.spatial.transform import Rotation

import kinlib as kl
from kinlib.check import check
from kinlib.robots import planar_2r, puma560
from kinlib.symbolic import lambdify_batched, simplify_rotation, sym_equal, trig_reduce

L1, L2 = 1.0, 0.8
H = 1e-6

a_sym = sp.Matrix(sp.symbols("a_x a_y a_z", real=True))
b_sym = sp.Matrix(sp.symbols("b_x b_y b_z", real=True))
al, be, ga = sp.symbols("alpha beta gamma", real=True)
ad, bd, gd = sp.symbols(r"\dot{\alpha} \dot{\beta} \dot{\gamma}", real=True)
t = sp.Symbol("t", real=True)
angles_t = [sp.Function(n, real=True)(t) for n in ("alpha", "beta", "gamma")]
TO_SYMBOLS = {**{sp.Derivative(f, t): d for f, d in zip(angles_t, (ad, bd, gd), strict=True)},
              **dict(zip(angles_t, (al, be, ga), strict=True))}


def omega_of(R_of_t):
    """vee(Ṙ Rᵀ) of a sympy rotation in the functions angles_t, in plain symbols."""
    return simplify_rotation(kl.vee((R_of_t.diff(t) * R_of_t.T).subs(TO_SYMBOLS)))


def dR(R, t0, h=1e-5):
    return (R(t0 + h) - R(t0 - h)) / (2 * h)


def jacobian_fd(robot, q, h=H):
    """[v; ω] columns from central differences of robot.fk: v from positions, ω from
    log(R(q + h e_i) R(q − h e_i)ᵀ) / 2h (scipy's rotation vector, not kinlib's log)."""
    q = np.asarray(q, dtype=float)
    cols = []
    for i in range(robot.dof):
        e = np.zeros(robot.dof)
        e[i] = h
        Tp, Tm = robot.fk(q + e), robot.fk(q - e)
        v = (Tp[:3, 3] - Tm[:3, 3]) / (2 * h)
        w = Rotation.from_matrix(Tp[:3, :3] @ Tm[:3, :3].T).as_rotvec() / (2 * h)
        cols.append(np.concatenate([v, w]))
    return np.array(cols).T


def scara():
    return kl.Robot.from_dh([kl.DHRow(a=0.4, alpha=0.0, d=0.35), kl.DHRow(a=0.3, alpha=np.pi),
                             kl.DHRow(a=0.0, alpha=0.0, joint="prismatic", limits=(0.0, 0.25)),
                             kl.DHRow(a=0.0, alpha=0.0, d=0.05)], name="scara")


# -- notebook 12 · 1: skew-symmetric matrices -----------------------------------------------
def test_skew_is_the_cross_product_matrix():
    S = kl.skew(a_sym)
    assert S + S.T == sp.zeros(3, 3)
    assert sp.expand(S * b_sym - a_sym.cross(b_sym)) == sp.zeros(3, 1)   # sympy's cross
    assert sp.expand(S * a_sym) == sp.zeros(3, 1)                        # a spans the null space
    rng = np.random.default_rng(0)
    a, b = rng.normal(size=(2, 300, 3))
    np.testing.assert_allclose(np.einsum("nij,nj->ni", kl.skew(a), b), np.cross(a, b),
                               atol=1e-14)
    np.testing.assert_array_equal(kl.vee(kl.skew(a)), a)


def test_rotating_a_skew_matrix_rotates_its_vector():
    R = kl.rotz(al) * kl.roty(be) * kl.rotx(ga)                       # every rotation
    assert sym_equal(R * kl.skew(a_sym) * R.T, kl.skew(R * a_sym))
    k, phi = sp.symbols("k_x k_y k_z", real=True), sp.Symbol("varphi", real=True)
    R_k = kl.matrix_from_axis_angle(k, phi)
    assert sym_equal(R_k * kl.skew(a_sym) * R_k.T, kl.skew(R_k * a_sym), unit=[k])
    assert not sym_equal(R_k * kl.skew(a_sym) * R_k.T, kl.skew(R_k * a_sym))   # needs |k| = 1
    Rs = Rotation.random(200, random_state=1).as_matrix()                  # scipy's rotations
    a = np.random.default_rng(2).normal(size=(200, 3))
    np.testing.assert_allclose(Rs @ kl.skew(a) @ Rs.transpose(0, 2, 1),
                               kl.skew(np.einsum("nij,nj->ni", Rs, a)), atol=1e-13)


# -- notebook 12 · 2: Ṙ = S(ω) R --------------------------------------------------------------
def test_rz_of_theta_spins_about_z_at_theta_dot():
    th = sp.Function("theta", real=True)(t)
    W = sp.simplify(kl.rotz(th).diff(t) * kl.rotz(th).T)
    assert W == sp.Matrix([[0, -th.diff(t), 0], [th.diff(t), 0, 0], [0, 0, 0]])
    assert kl.vee(W).T == sp.Matrix([[0, 0, th.diff(t)]])


def test_R_dot_R_transposed_is_skew_for_every_zyx_trajectory_and_gives_the_euler_rates():
    R = (kl.rotz(al) * kl.roty(be) * kl.rotx(ga)).subs(dict(zip((al, be, ga), angles_t,
                                                               strict=True)))
    W = (R.diff(t) * R.T).subs(TO_SYMBOLS)
    assert trig_reduce(W + W.T) == sp.zeros(3, 3)
    omega = simplify_rotation(kl.vee(W))
    assert sym_equal(omega, kl.euler_rate_matrix([al, be, ga], "ZYX") * sp.Matrix([ad, bd, gd]))
    # and numerically: kl.angular_velocity of a finite difference agrees with it
    f = lambdify_batched([[al, be, ga], [ad, bd, gd]], omega)
    ts = np.linspace(0.0, 3.0, 13)

    def phi(s):
        return np.stack([np.sin(1.3 * s), 0.4 * np.cos(2 * s), 0.5 * s], axis=-1)

    def phidot(s):
        return np.stack([1.3 * np.cos(1.3 * s), -0.8 * np.sin(2 * s), 0.5 + 0 * s], axis=-1)

    def R_num(s):
        return kl.matrix_from_euler(phi(s), "ZYX")

    w_fd = kl.angular_velocity(R_num(ts), dR(R_num, ts))
    np.testing.assert_allclose(w_fd, f(phi(ts), phidot(ts)), atol=1e-8)
    np.testing.assert_allclose(kl.rotation_derivative(R_num(ts), w_fd), dR(R_num, ts), atol=1e-8)


def test_tilting_turntable_in_the_fixed_and_the_body_frame():
    """Exercise 12.1's answers, against the hand derivation ω = γ̇ x + α̇ Rx(γ) z, and the
    mistakes it names: the body frame, the product in the other order, unturned axes, −ω."""
    R = kl.rotx(angles_t[2]) * kl.rotz(angles_t[0])
    space = sp.Matrix([gd, -ad * sp.sin(ga), ad * sp.cos(ga)])
    body = sp.Matrix([gd * sp.cos(al), -gd * sp.sin(al), ad])          # Rᵀ ω
    assert sym_equal(omega_of(R), space)
    assert sym_equal(simplify_rotation(kl.vee((R.T * R.diff(t)).subs(TO_SYMBOLS))), body)
    assert sym_equal(simplify_rotation(kl.rotz(al).T * kl.rotx(ga).T * space), body)
    assert check("12.1", space).status == "right"
    assert check("12.1", list(space)).status == "right"
    assert check("12.1", body).key == "frame" and check("12.1", -space).key == "sign"
    other_order = omega_of(kl.rotz(angles_t[0]) * kl.rotx(angles_t[2]))
    assert sym_equal(other_order, sp.Matrix([gd * sp.cos(al), gd * sp.sin(al), ad]))
    assert check("12.1", other_order).key == "order"
    assert check("12.1", sp.Matrix([gd, 0, ad])).key == "axis"


@pytest.mark.parametrize("seed", range(3))
def test_constant_spin_and_tip_velocities(seed):
    rng = np.random.default_rng(seed)
    w, R0 = rng.normal(size=3), Rotation.random(random_state=seed).as_matrix()

    def R(s):
        return Rotation.from_rotvec(np.multiply.outer(s, w)).as_matrix() @ R0   # scipy's exp

    ts = np.linspace(0.0, 3.0, 7)
    np.testing.assert_allclose(kl.angular_velocity(R(ts), dR(R, ts)), np.tile(w, (7, 1)),
                               atol=1e-8)
    np.testing.assert_allclose(kl.rotation_derivative(R0, w), np.cross(w, R0.T).T, atol=1e-14)


# -- notebook 12 · 3: adding angular velocities ---------------------------------------------
@pytest.mark.parametrize("seed", range(3))
def test_angular_velocities_add_once_in_one_frame(seed):
    rng = np.random.default_rng(seed)
    w01, w12 = rng.normal(size=(2, 3))
    A, B = Rotation.random(2, random_state=seed).as_matrix()

    def R01(s):
        return Rotation.from_rotvec(np.multiply.outer(s, w01)).as_matrix() @ A

    def R12(s):
        return Rotation.from_rotvec(np.multiply.outer(s, w12)).as_matrix() @ B

    def R02(s):
        return R01(s) @ R12(s)

    ts = np.linspace(0.0, 3.0, 7)
    w02 = kl.angular_velocity(R02(ts), dR(R02, ts))
    np.testing.assert_allclose(w02, w01 + np.einsum("nij,j->ni", R01(ts), w12), atol=1e-8)
    np.testing.assert_allclose(kl.add_angular_velocities(np.stack([R01(ts), R12(ts)], axis=1),
                                                         [w01, w12]), w02, atol=1e-8)
    assert np.abs(w02 - (w01 + w12)).max() > 0.1                       # frames matter


def test_the_elementary_chain_is_the_zyx_formula():
    rng = np.random.default_rng(5)
    phi, rate = rng.uniform(-1.5, 1.5, (2, 20, 3))
    chain = np.stack([kl.rotz(phi[:, 0]), kl.roty(phi[:, 1]), kl.rotx(phi[:, 2])], axis=1)
    rates = rate[:, :, None] * np.array([[0, 0, 1], [0, 1, 0], [1, 0, 0]])
    c, s = np.cos, np.sin
    a, b = phi[:, 0], phi[:, 1]
    by_hand = (rate[:, [0]] * [0, 0, 1]                                  # α̇ z
               + rate[:, [1]] * np.stack([-s(a), c(a), 0 * a], axis=1)   # β̇ Rz(α) y
               + rate[:, [2]] * np.stack([c(a) * c(b), s(a) * c(b), -s(b)], axis=1))
    np.testing.assert_allclose(kl.add_angular_velocities(chain, rates), by_hand, atol=1e-14)


def test_the_turntable_and_the_wheel():
    """Exercise 12.2: at Rz(π/2) the turntable's x axis is the base y axis: ω = (0, 5, 2)."""
    def R(s):
        return Rotation.from_euler("ZX", [np.pi / 2 + 2 * s, 5 * s]).as_matrix()

    np.testing.assert_allclose(kl.angular_velocity(R(0.0), dR(R, 0.0)), [0, 5, 2], atol=1e-8)
    assert check("12.2", np.array([0.0, 5.0, 2.0])).status == "right"
    assert check("12.2", np.array([5.0, 0.0, 2.0])).key == "frame"


# -- notebook 12 · 4: the geometric Jacobian --------------------------------------------------
def jacobian_by_hand(robot, q):
    """The column formula of seed 004, from the link frames."""
    poses = robot.link_poses(q)
    o_n = poses[robot.tip][:3, 3]
    cols = []
    for joint in robot.traversal():
        z, o = poses[joint.parent][:3, 2], poses[joint.parent][:3, 3]
        cols.append(np.concatenate([z, 0 * z]) if joint.type == "prismatic"
                    else np.concatenate([np.cross(z, o_n - o), z]))
    return np.array(cols).T


@pytest.mark.parametrize("seed", range(4))
def test_column_formula_robot_jacobian_and_finite_differences_agree(seed):
    rng = np.random.default_rng(seed)
    for robot in (puma560(), scara()):
        lo, hi = np.nan_to_num(robot.limits, posinf=np.pi, neginf=-np.pi).T
        q = rng.uniform(lo, hi)
        J = robot.jacobian(q)
        np.testing.assert_allclose(jacobian_by_hand(robot, q), J, atol=1e-12)
        np.testing.assert_allclose(jacobian_fd(robot, q), J, atol=1e-6)


def test_a_revolute_column_is_the_velocity_of_a_point_turning_about_the_axis():
    """Exercise 12.3's reference: a column from turning o_n about the line (z, o) by ±h
    (scipy's rotation) passes the check on every case."""
    def column_fd(z, o, o_n):
        def turned(angle):
            return o + Rotation.from_rotvec(angle * np.asarray(z)).apply(o_n - o)

        return np.concatenate([(turned(H) - turned(-H)) / (2 * H), z])

    assert check("12.3", column_fd).status == "right"


def test_scara_slide_and_puma_shoulder_columns():
    J = scara().jacobian([0.4, -0.9, 0.12, 0.7])
    np.testing.assert_allclose(J[:, 2], [0, 0, -1, 0, 0, 0], atol=1e-15)   # z2 points down
    assert check("12.4", "b").status == "right"
    puma = puma560()
    q = puma.poses["ready"] + [0.3, 0.2, -0.4, 0.5, 0.3, 0.2]
    poses = puma.link_poses(q)
    z1, o1, o6 = poses["link1"][:3, 2], poses["link1"][:3, 3], poses["link6"][:3, 3]
    np.testing.assert_allclose(jacobian_fd(puma, q)[:3, 1], np.cross(z1, o6 - o1), atol=1e-8)


# -- notebook 13 · 1: the planar 2R Jacobian ---------------------------------------------------
t1, t2 = sp.symbols("theta_1 theta_2", real=True)
l1s, l2s = sp.symbols("l_1 l_2", positive=True)
X = l1s * sp.cos(t1) + l2s * sp.cos(t1 + t2)
Y = l1s * sp.sin(t1) + l2s * sp.sin(t1 + t2)


def test_2r_jacobian_is_seed_001s_matrix_and_its_determinant():
    J = sp.Matrix([X, Y, t1 + t2]).jacobian([t1, t2])
    s1, c1, s12, c12 = sp.sin(t1), sp.cos(t1), sp.sin(t1 + t2), sp.cos(t1 + t2)
    seed = sp.Matrix([[-l1s * s1 - l2s * s12, -l2s * s12], [l1s * c1 + l2s * c12, l2s * c12],
                      [1, 1]])
    assert J - seed == sp.zeros(3, 2)
    assert sp.simplify(J[:2, :].det()) == l1s * l2s * sp.sin(t2)
    assert check("13.1", l1s * l2s * sp.sin(t2)).status == "right"
    q = np.random.default_rng(3).uniform(-np.pi, np.pi, (200, 2))
    J_kl = kl.planar_2r_jacobian(q[:, 0], q[:, 1], L1, L2)
    np.testing.assert_allclose(lambdify_batched([t1, t2, l1s, l2s], J)(q[:, 0], q[:, 1], L1, L2),
                               J_kl, atol=1e-12)
    np.testing.assert_allclose(planar_2r(L1, L2).jacobian(q)[:, [0, 1, 5], :], J_kl, atol=1e-12)


# -- notebook 13 · 2: singularities -----------------------------------------------------------
@pytest.mark.parametrize("th2", [0.0, np.pi])
def test_at_a_singularity_the_tip_cannot_move_along_the_arm(th2):
    th1 = 0.3
    J = kl.planar_2r_jacobian(th1, th2, L1, L2)[:2]
    U, s, Vt = np.linalg.svd(J)
    assert s[1] < 1e-12
    assert abs(abs(U[:, 1] @ [np.cos(th1), np.sin(th1)]) - 1) < 1e-12     # along the arm
    np.testing.assert_allclose(J @ Vt[1], 0, atol=1e-12)
    if th2 == 0.0:                                # the still motion: q̇ ∝ (l2, −(l1 + l2))
        assert abs(abs(Vt[1] @ [L2, -(L1 + L2)]) - np.hypot(L2, L1 + L2)) < 1e-12
        np.testing.assert_allclose(s[0], np.hypot(L1 + L2, L2), rtol=1e-12)   # J = t (l1+l2, l2)
    assert check("13.2", "a").status == "right"


def test_joint_speeds_explode_along_the_arm_and_not_across():
    th1, th2 = 0.3, np.linspace(-np.pi, np.pi, 200)[1:-1] + 1e-3
    J = kl.planar_2r_jacobian(th1, th2, L1, L2)[:, :2]
    p = kl.planar_2r_fk(th1, th2, L1, L2)[:, :2, 3]
    r = np.hypot(L1 + L2 * np.cos(th2), L2 * np.sin(th2))                 # law of cosines
    np.testing.assert_allclose(np.linalg.norm(p, axis=1), r, atol=1e-12)
    along, across = p / r[:, None], np.stack([-p[:, 1], p[:, 0]], axis=1) / r[:, None]
    qd_along = np.linalg.norm(np.linalg.solve(J, along[..., None])[..., 0], axis=1)
    qd_across = np.linalg.solve(J, across[..., None])[..., 0]
    assert np.all(qd_along >= r / (L1 * L2 * np.abs(np.sin(th2))) - 1e-9)
    np.testing.assert_allclose(qd_across, np.stack([1 / r, 0 * r], axis=1), atol=1e-9)


def test_joint_velocities_for_a_tip_velocity_by_hand():
    """Exercise 13.3: J(0, π/2) = [[−l2, −l2], [l1, 0]] (seed 001), so q̇ = (0, 1/l2)."""
    np.testing.assert_allclose(kl.planar_2r_jacobian(0.0, np.pi / 2, L1, L2)[:2],
                               [[-L2, -L2], [L1, 0]], atol=1e-15)
    assert check("13.3", np.array([0.0, 1 / L2])).status == "right"
    assert check("13.3", np.array([[-L2, L1], [-L2, 0]]) @ [-1, 0]).key == "transposed"


# -- notebook 13 · 3-4: manipulability ---------------------------------------------------------
@pytest.mark.parametrize("q", [(0.3, 1.1), (-1.0, 2.5), (2.0, -0.4)])
def test_velocity_ellipse_is_the_image_of_the_unit_circle(q):
    J = kl.planar_2r_jacobian(*q, L1, L2)[:2]
    U, sig = kl.velocity_ellipsoid(J)
    s = np.linspace(0, 2 * np.pi, 73)
    image = J @ np.stack([np.cos(s), np.sin(s)])
    np.testing.assert_allclose(np.linalg.norm((U.T @ image) / sig[:, None], axis=0), 1,
                               atol=1e-12)
    np.testing.assert_allclose(np.linalg.norm(image, axis=0).max(), sig[0], rtol=1e-3)
    np.testing.assert_allclose(kl.manipulability(J), L1 * L2 * abs(np.sin(q[1])), rtol=1e-12)


def test_manipulability_ignores_theta1_and_is_l1_l2_sin_theta2():
    g = -np.pi + 2 * np.pi * np.arange(61) / 61
    T1, T2 = np.meshgrid(g, g, indexing="ij")
    J = kl.planar_2r_jacobian(T1, T2, L1, L2)[..., :2, :]
    c, s = np.cos(T1), np.sin(T1)
    R = np.stack([np.stack([c, -s], -1), np.stack([s, c], -1)], -2)       # planar rotation
    np.testing.assert_allclose(J, R @ kl.planar_2r_jacobian(0.0, T2, L1, L2)[..., :2, :],
                               atol=1e-12)
    w = kl.manipulability(J)
    np.testing.assert_allclose(w, L1 * L2 * np.abs(np.sin(T2)), atol=1e-12)
    assert np.ptp(w, axis=0).max() < 1e-12
    assert check("13.4", L1 * L2).status == "right"
    assert check("13.4", (L1 * L2) ** 2).key == "squared"


def test_puma_manipulability_ignores_q1_and_q6_and_vanishes_at_elbow_and_shoulder():
    puma = puma560()
    rng = np.random.default_rng(11)
    q = rng.uniform(puma.limits[:, 0], puma.limits[:, 1], (50, 6))
    w = kl.manipulability(puma.jacobian(q))
    np.testing.assert_allclose(kl.manipulability(puma.jacobian(q + [1.0, 0, 0, 0, 0, -2.0])), w,
                               atol=1e-12)
    a3, d4 = puma.dh_rows[2].a, puma.dh_rows[3].d
    q_elbow = [0.0, -0.5, np.arctan2(d4, a3), 0.0, 0.6, 0.0]               # a3 sin q3 = d4 cos q3
    s = np.linalg.svd(jacobian_fd(puma, q_elbow), compute_uv=False)
    assert s[-1] < 1e-6 * s[0] and kl.manipulability(puma.jacobian(q_elbow)) < 1e-9

    def wrist_x(q2, q3=0.3):                       # the wrist centre above the shoulder: x = 0
        return puma.link_poses([0.0, q2, q3, 0.0, 0.6, 0.0])["link4"][0, 3]

    q2 = brentq(wrist_x, -2.5, -0.8)
    q_shoulder = [0.0, q2, 0.3, 0.0, 0.6, 0.0]
    s = np.linalg.svd(jacobian_fd(puma, q_shoulder), compute_uv=False)
    assert s[-1] < 1e-6 * s[0]
    assert kl.manipulability(puma.jacobian(q_shoulder)) < 1e-6 * np.median(w)
