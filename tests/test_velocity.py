"""Angular velocity, its addition along a chain, point velocities, Euler rates and the
analytic Jacobian, against finite differences and scipy."""

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.linalg import expm
from scipy.spatial.transform import Rotation

import kinlib as kl
from kinlib.kinematics.analytic import analytic_jacobian
from kinlib.robots import panda, puma560, ur5


def S(w):
    return np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])


def vee(M):
    return np.array([M[2, 1] - M[1, 2], M[0, 2] - M[2, 0], M[1, 0] - M[0, 1]]) / 2


vec3 = st.tuples(*[st.floats(-3, 3)] * 3).map(np.array)


@settings(max_examples=100, deadline=None)
@given(vec3, st.integers(0, 2**31))
def test_angular_velocity_of_exp_trajectories(w, seed):
    R0 = Rotation.random(random_state=seed).as_matrix()
    t, h = 0.7, 1e-6
    R = expm(S(w) * t) @ R0                        # Ṙ = S(ω) R exactly
    R_dot = (expm(S(w) * (t + h)) - expm(S(w) * (t - h))) @ R0 / (2 * h)
    np.testing.assert_allclose(kl.angular_velocity(R, R_dot, tol=1e-6), w, atol=1e-7)
    np.testing.assert_allclose(kl.rotation_derivative(R, w), S(w) @ R, atol=1e-13)
    np.testing.assert_allclose(kl.angular_velocity(R, kl.rotation_derivative(R, w)), w,
                               atol=1e-12)


def test_angular_velocity_batched_and_not_a_derivative():
    rng = np.random.default_rng(1)
    R = Rotation.random(5, random_state=2).as_matrix()
    w = rng.normal(size=(5, 3))
    np.testing.assert_allclose(kl.angular_velocity(R, kl.rotation_derivative(R, w)), w,
                               atol=1e-12)
    bad = kl.rotation_derivative(R, w)
    bad[3] = np.eye(3)
    with pytest.raises(kl.KinlibError, match=r"R_dot\[3\]: not the derivative of a rotation"):
        kl.angular_velocity(R, bad)


@settings(max_examples=60, deadline=None)
@given(st.integers(1, 5), st.integers(0, 2**31))
def test_addition_of_angular_velocities(n, seed):
    """R⁰ₙ(t) = Π Rᵢ(t), Rᵢ(t) = expm(S(wᵢ) t) Rᵢ0 with wᵢ in frame i−1: the sum formula
    equals vee(Ṙ Rᵀ) of the product, by finite differences."""
    rng = np.random.default_rng(seed)
    w = rng.normal(size=(n, 3))
    R0 = Rotation.random(n, random_state=seed).as_matrix()

    def chain(t):
        out = np.eye(3)
        for i in range(n):
            out = out @ expm(S(w[i]) * t) @ R0[i]
        return out

    t, h = 0.4, 1e-6
    rel = np.array([expm(S(w[i]) * t) @ R0[i] for i in range(n)])
    fd = vee((chain(t + h) - chain(t - h)) / (2 * h) @ chain(t).T)
    np.testing.assert_allclose(kl.add_angular_velocities(rel, w), fd, atol=1e-7)


@pytest.mark.parametrize("model", [puma560, ur5, panda], ids=lambda m: m.__name__)
def test_addition_of_angular_velocities_equals_the_jacobian_angular_rows(model):
    """Seed 004: ω⁰ₙ = Σ R⁰ᵢ₋₁ ẑ q̇ᵢ. Relative rotations and joint rates from the robot's
    link frames; the sum must equal J_ω q̇."""
    robot = model()
    rng = np.random.default_rng(7)
    q = rng.uniform(-1, 1, robot.dof)
    qd = rng.normal(size=robot.dof)
    poses = robot.link_poses(q)
    chain = [j for j in robot.traversal() if j.movable]
    rel, omegas, prev = [], [], np.eye(3)
    for jt in chain:
        R_joint = poses[jt.child][:3, :3] @ np.linalg.inv(jt.post[:3, :3])  # origin·motion
        rel.append(prev.T @ R_joint)              # R^{i-1}_i, from the last joint frame
        omegas.append(np.zeros(3))
        prev = R_joint
    # joint i turns frame i about its own z (its axis): ω^{i-1}_{i-1,i} = R^{i-1}_i ẑ q̇ᵢ
    for i, jt in enumerate(chain):
        omegas[i] = rel[i] @ (jt.axis * qd[i])
    w = kl.add_angular_velocities(np.array(rel), np.array(omegas))
    np.testing.assert_allclose(w, robot.jacobian(q)[3:] @ qd, atol=1e-12)


@settings(max_examples=60, deadline=None)
@given(vec3, vec3, vec3, vec3, st.integers(0, 2**31))
def test_point_velocity(p_local, w, v, d0, seed):
    R0 = Rotation.random(random_state=seed).as_matrix()

    def p_world(t):
        return expm(S(w) * t) @ R0 @ p_local + d0 + v * t

    h = 1e-6
    fd = (p_world(h) - p_world(-h)) / (2 * h)
    np.testing.assert_allclose(kl.point_velocity(R0, v, w, p_local), fd, atol=1e-6)


@pytest.mark.parametrize("seq", kl.EULER_SEQUENCES)
def test_euler_rate_matrix_for_all_24_sequences(seq):
    rng = np.random.default_rng(abs(hash(seq)) % 2**32)
    a = rng.uniform(-1.2, 1.2, (10, 3))
    ad = rng.normal(size=(10, 3))
    E = kl.euler_rate_matrix(a, seq)
    h = 1e-6
    for i in range(10):
        R = kl.matrix_from_euler(a[i], seq)
        R_dot = (kl.matrix_from_euler(a[i] + h * ad[i], seq)
                 - kl.matrix_from_euler(a[i] - h * ad[i], seq)) / (2 * h)
        np.testing.assert_allclose(E[i] @ ad[i], vee(R_dot @ R.T), atol=1e-8)
    # singular exactly at gimbal lock: the middle angle at ±π/2 (Tait–Bryan) or 0, π (Euler)
    proper = seq[0].lower() == seq[2].lower()
    for middle in ((0.0, np.pi) if proper else (np.pi / 2, -np.pi / 2)):
        lock = np.array([0.4, middle, -0.9])
        assert abs(np.linalg.det(kl.euler_rate_matrix(lock, seq))) < 1e-12
        assert kl.euler_rates_singular(lock, seq)
    assert not kl.euler_rates_singular(np.array([0.4, 1.0, -0.9]), seq)


def test_euler_rate_matrix_symbolic_zyx():
    a, b, g = sp.symbols("alpha beta gamma")
    E = kl.euler_rate_matrix([a, b, g], "ZYX")
    assert isinstance(E, sp.Matrix)
    num = sp.lambdify((a, b, g), E)(0.3, -0.5, 1.1)
    np.testing.assert_allclose(num, kl.euler_rate_matrix([0.3, -0.5, 1.1], "ZYX"), atol=1e-15)
    assert sp.simplify(E.det() + sp.cos(b)) == 0  # det E = −cos β: zero at β = ±π/2


@pytest.mark.parametrize("seq", ["ZYX", "xyz", "ZYZ"])
def test_analytic_jacobian_against_finite_differences_of_the_angles(seq):
    robot = puma560()
    q = np.array([0.3, -0.7, 1.1, 0.4, 0.6, -0.2])
    Ja = robot.analytic_jacobian(q, seq=seq)
    h = 1e-6
    for i in range(6):
        dq = np.zeros(6)
        dq[i] = h
        phi_p = kl.euler_from_matrix(robot.fk(q + dq)[:3, :3], seq)
        phi_m = kl.euler_from_matrix(robot.fk(q - dq)[:3, :3], seq)
        np.testing.assert_allclose(Ja[3:, i], (phi_p - phi_m) / (2 * h), atol=1e-7)
        np.testing.assert_allclose(Ja[:3, i], robot.jacobian(q)[:3, i], atol=0)
    np.testing.assert_allclose(analytic_jacobian(robot, q[None], None, seq)[0], Ja, atol=1e-15)
    # q, then link, then seq: as fk(q, link) and jacobian(q, link)
    np.testing.assert_array_equal(robot.analytic_jacobian(q, robot.tip, seq), Ja)


def test_analytic_jacobian_at_gimbal_lock_raises():
    robot = puma560()
    # find q whose tip orientation has ZYX pitch at π/2: solve IK for such a target
    T = robot.fk(np.array([0.3, -0.7, 1.1, 0.4, 0.6, -0.2]))
    T[:3, :3] = kl.matrix_from_euler([0.2, np.pi / 2, 0.0], "ZYX")
    sol = robot.ik(T, position_only=False)
    assert sol.success
    with pytest.raises(kl.KinlibError, match="gimbal lock"):
        robot.analytic_jacobian(sol.q, seq="ZYX")
    robot.analytic_jacobian(sol.q, seq="XYZ")  # another sequence is fine there


def test_analytic_jacobian_takes_link_before_seq():
    """The old order (q, seq, link) is caught: a sequence where the link goes is named."""
    robot = puma560()
    q = np.array([0.3, -0.7, 1.1, 0.4, 0.6, -0.2])
    with pytest.raises(kl.KinlibError, match=r"'ZYX' is an Euler sequence.*\(q, link, seq\)"):
        robot.analytic_jacobian(q, "ZYX")
    with pytest.raises(kl.KinlibError, match="ZYX"):
        analytic_jacobian(robot, q, "ZYX", "link6")
    # a middle link: its own rows, not the tip's (the last joints leave it alone)
    Ja3 = robot.analytic_jacobian(q, "link3", "ZYX")
    assert Ja3.shape == (6, 6) and np.all(Ja3[:, 3:] == 0)
    with pytest.raises(kl.KinlibError, match="seq"):
        robot.analytic_jacobian(q, "link3", "ZYXZ")


def test_bad_input():
    with pytest.raises(kl.KinlibError, match="need the same n"):
        kl.add_angular_velocities(np.stack([np.eye(3)] * 2), np.zeros((3, 3)))
    with pytest.raises(kl.KinlibError, match="rotations"):
        kl.add_angular_velocities(np.ones((2, 3, 3)), np.zeros((2, 3)))
    with pytest.raises(kl.KinlibError, match="omegas"):
        kl.add_angular_velocities(np.stack([np.eye(3)] * 2), [[0, 0, np.nan], [0, 0, 0]])
    with pytest.raises(kl.KinlibError, match="seq"):
        kl.euler_rate_matrix([0.1, 0.2, 0.3], "ZYx")
