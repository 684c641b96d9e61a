"""More checks of kinlib.spatial.velocity and kinlib.kinematics.singularity, each against an
independent reference: scipy rotation-vector trajectories, closed forms for det E and for the planar
2R velocity ellipsoid, batched calls against loops, and junk input."""

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

import kinlib as kl

H = 1e-6
vec3 = st.tuples(*[st.floats(-3, 3)] * 3).map(np.array)


def S(w):
    return np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])


def vee(M):
    return np.array([M[2, 1] - M[1, 2], M[0, 2] - M[2, 0], M[1, 0] - M[0, 1]]) / 2


def fd(f, t):
    return (f(t + H) - f(t - H)) / (2 * H)


# --------------------------------------------------------------------------- ω from Ṙ


@settings(max_examples=60, deadline=None)
@given(vec3, st.floats(-2, 2), st.integers(0, 2**31))
def test_angular_velocity_of_rotvec_trajectories(w, t, seed):
    """R(t) = Rot(ω t) R0 spins about the fixed ω; R(t) = R0 Rot(ω t) spins about the
    body axis ω, which in the fixed frame is R(t) ω."""
    R0 = Rotation.random(random_state=seed).as_matrix()

    def spatial(s):
        return Rotation.from_rotvec(w * s).as_matrix() @ R0

    def body(s):
        return R0 @ Rotation.from_rotvec(w * s).as_matrix()

    np.testing.assert_allclose(kl.angular_velocity(spatial(t), fd(spatial, t), tol=1e-6), w,
                               atol=1e-7)
    np.testing.assert_allclose(kl.angular_velocity(body(t), fd(body, t), tol=1e-6),
                               body(t) @ w, atol=1e-7)
    # round trip through Ṙ = S(ω) R, in both directions
    np.testing.assert_allclose(kl.rotation_derivative(spatial(t), w), fd(spatial, t),
                               atol=1e-7)


def test_angular_velocity_rejects_non_derivatives():
    R = Rotation.from_rotvec([0.1, 0.2, 0.3]).as_matrix()
    for bad in (np.eye(3), R, 2.0 * R, np.diag([0.0, 0.0, 1.0]) @ R):
        with pytest.raises(kl.KinlibError, match=r"^R_dot: not the derivative of a rotation"):
            kl.angular_velocity(R, bad)
    # scaled down below the tolerance, it is accepted as (nearly) zero motion
    np.testing.assert_allclose(kl.angular_velocity(R, 1e-12 * R), 0.0, atol=1e-11)


# --------------------------------------------------------------------------- batched = looped


def test_batched_equals_looped():
    rng = np.random.default_rng(11)
    R = Rotation.random(12, random_state=3).as_matrix().reshape(4, 3, 3, 3)
    w = rng.normal(size=(4, 3, 3))
    p = rng.normal(size=(4, 3, 3))
    v = rng.normal(size=(4, 3, 3))
    Rd = kl.rotation_derivative(R, w)
    out_w = kl.angular_velocity(R, Rd)
    out_p = kl.point_velocity(R, v, w, p)
    out_sum = kl.add_angular_velocities(R, w)          # 4 chains of n = 3
    angles = rng.uniform(-1, 1, (4, 3, 3))
    E = kl.euler_rate_matrix(angles, "zxz")
    for i in range(4):
        np.testing.assert_allclose(out_sum[i], kl.add_angular_velocities(R[i], w[i]),
                                   atol=0)
        for j in range(3):
            np.testing.assert_allclose(Rd[i, j], kl.rotation_derivative(R[i, j], w[i, j]),
                                       atol=0)
            np.testing.assert_allclose(out_w[i, j], kl.angular_velocity(R[i, j], Rd[i, j]),
                                       atol=1e-15)
            np.testing.assert_allclose(out_p[i, j],
                                       kl.point_velocity(R[i, j], v[i, j], w[i, j], p[i, j]),
                                       atol=1e-15)
            np.testing.assert_allclose(E[i, j], kl.euler_rate_matrix(angles[i, j], "zxz"),
                                       atol=1e-15)
    # broadcasting one rotation against many angular velocities
    assert kl.rotation_derivative(R[0, 0], w).shape == (4, 3, 3, 3)
    np.testing.assert_allclose(kl.rotation_derivative(R[0, 0], w)[1, 2], S(w[1, 2]) @ R[0, 0],
                               atol=1e-15)


def test_singularity_tools_batched_equals_looped():
    J = np.random.default_rng(5).normal(size=(3, 2, 6, 7))
    J[1, 1, :, 3] = J[1, 1, :, 2]                      # one rank-deficient member
    J[2, 0, 0] = 0.0
    funcs = (kl.singular_values, kl.manipulability, kl.condition_number, kl.is_near_singular)
    for f in funcs:
        out = f(J)
        for i in range(3):
            for j in range(2):
                np.testing.assert_allclose(out[i, j], f(J[i, j]), rtol=1e-12)
    axes, radii = kl.velocity_ellipsoid(J)
    assert axes.shape == (3, 2, 6, 6) and radii.shape == (3, 2, 6)


# --------------------------------------------------------------------------- Euler rates


def _middle_factor(seq, middle):
    """|det E| in closed form: det E = det[e_A, e_B, R_B(φ2) e_C] (move R_A out), which is
    ±e_C·R_B(φ2)e_C = ±cos φ2 for three different axes and ±e_C'·R_B(φ2)e_A = ±sin φ2 when
    the first axis is the last."""
    return abs(np.sin(middle)) if seq[0].lower() == seq[2].lower() else abs(np.cos(middle))


@pytest.mark.parametrize("seq", kl.EULER_SEQUENCES)
def test_det_of_the_rate_matrix_in_closed_form(seq):
    rng = np.random.default_rng(sum(map(ord, seq)))
    a = rng.uniform(-np.pi, np.pi, (200, 3))
    det = np.linalg.det(kl.euler_rate_matrix(a, seq))
    np.testing.assert_allclose(np.abs(det), _middle_factor(seq, a[:, 1]), atol=1e-13)
    # random angles (with the middle one away from its singular values) are not singular
    far = _middle_factor(seq, a[:, 1]) > 1e-3
    assert far.sum() > 150
    assert not kl.euler_rates_singular(a[far], seq).any()
    # at gimbal lock E has rank exactly 2: one ω direction cannot be produced
    proper = seq[0].lower() == seq[2].lower()
    lock = a.copy()
    lock[:, 1] = rng.choice([0.0, np.pi] if proper else [np.pi / 2, -np.pi / 2], 200)
    assert kl.euler_rates_singular(lock, seq).all()
    assert (np.linalg.matrix_rank(kl.euler_rate_matrix(lock, seq), tol=1e-9) == 2).all()


@pytest.mark.parametrize("intrinsic", ["ZYX", "XYZ", "ZXZ", "YXY"])
def test_extrinsic_is_intrinsic_reversed(intrinsic):
    """[a, b, g] in "ABC" is the same rotation as [g, b, a] in "cba": the same ω, with the
    rates reversed, so E_cba(g, b, a) = E_ABC(a, b, g) with the columns reversed."""
    extrinsic = intrinsic[::-1].lower()
    a = np.random.default_rng(2).uniform(-1, 1, (20, 3))
    np.testing.assert_allclose(kl.euler_rate_matrix(a[:, ::-1], extrinsic),
                               kl.euler_rate_matrix(a, intrinsic)[..., ::-1], atol=1e-15)


def test_symbolic_zyz_and_xyz():
    a, b, g = sp.symbols("a b g", real=True)
    E = kl.euler_rate_matrix([a, b, g], "ZYZ")
    assert isinstance(E, sp.Matrix)
    # by hand: det[e_z, e_y, R_y(b) e_z] = (e_z × e_y)·(sin b, 0, cos b) = −sin b
    assert sp.simplify(E.det() + sp.sin(b)) == 0
    num = sp.lambdify((a, b, g), E)(0.3, -0.5, 1.1)
    np.testing.assert_allclose(num, kl.euler_rate_matrix([0.3, -0.5, 1.1], "ZYZ"), atol=1e-15)
    # the extrinsic roll-pitch-yaw "xyz" reverses the ZYX columns: det = +cos b
    assert sp.simplify(kl.euler_rate_matrix([g, b, a], "xyz").det() - sp.cos(b)) == 0


# --------------------------------------------------------------------------- singularity


@pytest.mark.parametrize("t1", [-2.0, 0.4, 3.0])
def test_planar_2r_ellipsoid_at_the_stretched_singularity(t1):
    """Stretched out (θ2 = 0) the tip moves only across the arm, n = (−sin θ1, cos θ1):
    J = n [l1 + l2, l2], so σ1 = √((l1 + l2)² + l2²) along n and σ2 = 0."""
    l1, l2 = 0.8, 0.5
    axes, radii = kl.velocity_ellipsoid(kl.planar_2r_jacobian(t1, 0.0, l1, l2)[:2])
    np.testing.assert_allclose(radii, [np.hypot(l1 + l2, l2), 0.0], atol=1e-12)
    n = np.array([-np.sin(t1), np.cos(t1)])
    assert abs(abs(axes[:, 0] @ n) - 1.0) < 1e-12


def test_manipulability_is_invariant_under_rotations_of_task_and_joint_space():
    rng = np.random.default_rng(9)
    J = rng.normal(size=(6, 7))
    U = Rotation.random(2, random_state=1).as_matrix()
    Q6 = np.kron(np.eye(2), U[0])                      # rotate v and ω alike
    Q7 = np.linalg.qr(rng.normal(size=(7, 7)))[0]
    assert kl.manipulability(Q6 @ J @ Q7) == pytest.approx(kl.manipulability(J), rel=1e-12)
    assert kl.condition_number(Q6 @ J @ Q7) == pytest.approx(kl.condition_number(J),
                                                               rel=1e-10)
    assert kl.condition_number(J) >= 1.0
    # scaling J scales w by s^m and leaves the condition number and the singularity test alone
    assert kl.manipulability(3.0 * J) == pytest.approx(3.0**6 * kl.manipulability(J),
                                                       rel=1e-12)
    assert kl.is_near_singular(1e-9 * J) == kl.is_near_singular(J)


JUNK = ["abc", b"xyz", None, object(), {"a": 1}, [[1.0, 2.0], [3.0]], np.eye(2) * (1 + 1j),
        [["1", "0"], ["0", "1"]], 10**400, [1.0, 2.0], 3.0]
SINGULARITY_TOOLS = [kl.singular_values, kl.manipulability, kl.condition_number,
                     kl.velocity_ellipsoid, kl.is_near_singular]


@pytest.mark.parametrize("f", SINGULARITY_TOOLS, ids=lambda f: f.__name__)
@pytest.mark.parametrize("bad", JUNK, ids=range(len(JUNK)))
def test_singularity_tools_name_J_for_junk(f, bad):
    with pytest.raises(kl.KinlibError, match=r"^J: (expected|contains)"):
        f(bad)


@pytest.mark.parametrize("f", SINGULARITY_TOOLS, ids=lambda f: f.__name__)
def test_singularity_tools_name_the_batch_member_with_nan(f):
    J = np.stack([np.eye(6)] * 3)
    J[1, 2, 2] = np.inf
    with pytest.raises(kl.KinlibError, match=r"^J\[1.*NaN or infinity"):
        f(J)


@pytest.mark.parametrize("bad", JUNK[:8], ids=range(8))
def test_add_angular_velocities_names_its_arguments(bad):
    Rs, ws = np.stack([np.eye(3)] * 2), np.zeros((2, 3))
    with pytest.raises(kl.KinlibError, match=r"^rotations"):
        kl.add_angular_velocities(bad, ws)
    with pytest.raises(kl.KinlibError, match=r"^omegas"):
        kl.add_angular_velocities(Rs, bad)
    with pytest.raises(kl.KinlibError, match=r"^omegas"):
        kl.add_angular_velocities(Rs, [[0.0, 0.0, 0.0], [np.inf, 0.0, 0.0]])
