"""The worked examples and formulas of the lecture notes, as tests.

Seeds (OCR'd slides) live in ``/work/shared/seeds/``:

* seed 000 = ``000_442a6a0b0428d99e.txt`` (AutoRob: axis-angle rotation and quaternions)
* seed 002 = ``002_10edf345cb45535f.txt`` (Lecture 2: spatial descriptions and transformations)

Each test cites its seed and slide title. Expected values are worked by hand here or typed in
from the slides (after checking them: a few slide matrices are garbled), never computed with
the kinlib function under test.
"""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from reference import unit_vectors
from scipy.spatial.transform import Rotation

import kinlib as kl

# --------------------------------------------------------------------------- helpers


def Rx(t):
    c, s = np.cos(t), np.sin(t)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def Ry(t):
    c, s = np.cos(t), np.sin(t)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def Rz(t):
    c, s = np.cos(t), np.sin(t)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def skew3(v):
    """The standard skew matrix [v]x with [v]x b = v × b."""
    x, y, z = v
    return np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])


def hprod(p, q):
    """Hamilton product, seed 000 'Quaternions in 3D': (ae−bf−cg−dh) + (af+be+ch−dg)i + ..."""
    a, b, c, d = p
    e, f, g, h = q
    return np.array(
        [
            a * e - b * f - c * g - d * h,
            a * f + b * e + c * h - d * g,
            a * g - b * h + c * e + d * f,
            a * h + b * g - c * f + d * e,
        ]
    )


def hom(R, p):
    T = np.eye(4)
    T[:3, :3] = R
    T[:3, 3] = p
    return T


TOL = 1e-12

# --------------------------------------------------------------------------- strategies

angles = st.floats(-np.pi, np.pi, allow_nan=False)
coords = st.floats(-100.0, 100.0, allow_nan=False)
vec3 = st.tuples(coords, coords, coords).map(np.array)



@st.composite
def rotations(draw):
    q = np.array(draw(st.tuples(*[st.floats(-1.0, 1.0)] * 4)))
    if q @ q < 1e-6:
        q = np.array([0.0, 0.0, 0.0, 1.0])
    return Rotation.from_quat(q).as_matrix()


@st.composite
def unit_quaternions(draw):
    q = np.array(draw(st.tuples(*[st.floats(-1.0, 1.0)] * 4)))
    return q / np.linalg.norm(q) if q @ q > 1e-6 else np.array([1.0, 0.0, 0.0, 0.0])


# =========================================================================== seed 002


def test_seed002_general_transformation_example():
    # seed 002, "Mappings: Changing Description from Frame to Frame / General Transformation /
    # Example": {B} is rotated 30° about Z_A and translated 10 in X_A and 5 in Y_A;
    # ^B P = [3, 7, 0]. Find ^A P = ^A R_B ^B P + ^A P_BORG.
    c30, s30 = np.sqrt(3) / 2, 0.5
    expected = np.array([10 + 3 * c30 - 7 * s30, 5 + 3 * s30 + 7 * c30, 0.0])
    np.testing.assert_allclose(expected, [9.098, 12.562, 0.0], atol=5e-4)  # the slide's numbers
    T_AB = kl.transform(kl.rotz(np.deg2rad(30.0)), [10.0, 5.0, 0.0])
    np.testing.assert_allclose(kl.transform_points(T_AB, [3.0, 7.0, 0.0]), expected, atol=TOL)
    # the same with the 4×4 operator on [^B P; 1]
    np.testing.assert_allclose((T_AB @ [3.0, 7.0, 0.0, 1.0])[:3], expected, atol=TOL)
    # and T_AB's layout as on the slide: [[c30, −s30, 0, 10], [s30, c30, 0, 5], [0 0 1 0]]
    typed = np.array(
        [[c30, -s30, 0.0, 10.0], [s30, c30, 0.0, 5.0], [0.0, 0.0, 1.0, 0.0], [0, 0, 0, 1.0]]
    )
    np.testing.assert_allclose(T_AB, typed, atol=TOL)


@settings(max_examples=30, deadline=None)
@given(R_AB=rotations(), P_B=vec3)
def test_seed002_rows_of_R_AB_are_the_axes_of_A_in_B(R_AB, P_B):
    # seed 002, "Mappings: Frame to Frame / Rotation": ^A p_x = ^B X_A · ^B P, ... and
    # "the rows of ^A R_B are ^B X_A^T, ^B Y_A^T and ^B Z_A^T".
    R_BA = np.linalg.inv(R_AB)  # the axes of {A} written in {B} are its columns
    X_A, Y_A, Z_A = R_BA[:, 0], R_BA[:, 1], R_BA[:, 2]
    P_A = kl.transform_points(kl.transform(R_AB), P_B)
    np.testing.assert_allclose(P_A, [X_A @ P_B, Y_A @ P_B, Z_A @ P_B], atol=1e-10)
    np.testing.assert_allclose(R_AB, np.stack([X_A, Y_A, Z_A]), atol=TOL)
    # so R_AB.T = R_BA, which is the rotation block of the inverse transform
    np.testing.assert_allclose(R_AB.T, R_BA, atol=TOL)
    np.testing.assert_allclose(kl.transform_inverse(kl.transform(R_AB))[:3, :3], R_BA, atol=TOL)


@settings(max_examples=40, deadline=None)
@given(R=rotations(), p=vec3, P_B=vec3)
def test_seed002_closed_form_inverse(R, p, P_B):
    # seed 002, "Transformation Arithmetic / Inverting a Transform":
    # ^B T_A = [[^A R_B^T, −^A R_B^T ^A P_BORG], [0 0 0 1]] = ^A T_B^-1
    T_AB = hom(R, p)
    typed = hom(R.T, -R.T @ p)
    T_BA = kl.transform_inverse(T_AB)
    np.testing.assert_allclose(T_BA, typed, atol=1e-10)
    np.testing.assert_allclose(T_BA, np.linalg.inv(T_AB), atol=1e-10)
    # the derivation: ^A R_B^T (^A P − ^A P_BORG) = ^B P
    P_A = kl.transform_points(T_AB, P_B)
    np.testing.assert_allclose(R.T @ (P_A - p), P_B, atol=1e-10)
    np.testing.assert_allclose(kl.transform_points(T_BA, P_A), P_B, atol=1e-10)


@settings(max_examples=30, deadline=None)
@given(R_AB=rotations(), R_BC=rotations(), P_B=vec3, P_C=vec3, X=vec3)
def test_seed002_compound_transformations(R_AB, R_BC, P_B, P_C, X):
    # seed 002, "Transformation Arithmetic / Compound Transformations":
    # ^A T_C = [[^A R_B ^B R_C, ^A R_B ^B P_CORG + ^A P_BORG], [0 0 0 1]], and
    # ^A P = ^A T_B (^B T_C ^C P) = (^A T_B ^B T_C) ^C P.
    T_AB, T_BC = kl.transform(R_AB, P_B), kl.transform(R_BC, P_C)
    T_AC = hom(R_AB @ R_BC, R_AB @ P_C + P_B)
    np.testing.assert_allclose(T_AB @ T_BC, T_AC, atol=1e-10)
    direct = kl.transform_points(T_AC, X)
    np.testing.assert_allclose(kl.transform_points(T_AB, kl.transform_points(T_BC, X)), direct,
                               atol=1e-10)
    np.testing.assert_allclose(direct, R_AB @ (R_BC @ X + P_C) + P_B, atol=1e-10)


def test_seed002_operators():
    # seed 002, "Operators / Translation": T_Trans(Q) = [[1 0 0 qx], [0 1 0 qy], [0 0 1 qz],
    # [0 0 0 1]] moves ^A P_1 to ^A P_2 = ^A P_1 + ^A Q.
    Q, P1 = np.array([1.0, -2.0, 0.5]), np.array([4.0, 5.0, 6.0])
    T_trans = np.array([[1, 0, 0, 1.0], [0, 1, 0, -2.0], [0, 0, 1, 0.5], [0, 0, 0, 1.0]])
    np.testing.assert_array_equal(kl.transform(p=Q), T_trans)
    np.testing.assert_array_equal(kl.transform_points(T_trans, P1), P1 + Q)
    # "Operators / Rotation": T_Rot for K = Z_hat, θ = 90°: (1, 0, 0) -> (0, 1, 0)
    T_rot = np.array([[0.0, -1, 0, 0], [1.0, 0, 0, 0], [0, 0, 1.0, 0], [0, 0, 0, 1.0]])
    np.testing.assert_allclose(kl.transform(kl.rotz(np.pi / 2)), T_rot, atol=TOL)
    np.testing.assert_array_equal(kl.transform_points(T_rot, [1.0, 0, 0]), [0.0, 1.0, 0.0])


def test_seed002_free_vectors_only_rotate():
    # seed 002, "Transformation of Free Vectors": for free vectors (velocities, moments) only
    # the rotation matrix relating the two systems is used.
    T = hom(Rz(np.deg2rad(30.0)), [10.0, 5.0, 0.0])
    v = np.array([3.0, 7.0, 0.0])
    np.testing.assert_allclose(kl.transform_vectors(T, v), Rz(np.deg2rad(30.0)) @ v, atol=TOL)


@settings(max_examples=40, deadline=None)
@given(s=vec3.map(lambda v: v / 10.0))
def test_seed002_cayley_formula(s):
    # seed 002, "More on Representation of Orientation": Cayley's formula
    # R = (I_3 − S)^-1 (I_3 + S). The slide's S matrix is garbled (it places s_x where s_z
    # belongs); the standard skew matrix of s = (s_x, s_y, s_z) is used here.
    S = skew3(s)
    expected = np.linalg.solve(np.eye(3) - S, np.eye(3) + S)
    R = kl.matrix_from_cayley(s)
    np.testing.assert_allclose(R, expected, atol=1e-10)
    # a proper orthonormal matrix, specified by just three parameters
    np.testing.assert_allclose(R.T @ R, np.eye(3), atol=1e-10)
    assert np.linalg.det(R) == pytest.approx(1.0, abs=1e-10)
    # ... s = tan(θ/2) k for a rotation θ about k (scipy gives θ and k)
    rotvec = Rotation.from_matrix(expected).as_rotvec()
    theta = np.linalg.norm(rotvec)
    tol = 1e-9 * (1 + np.linalg.norm(s))
    if theta > 1e-6:
        np.testing.assert_allclose(np.tan(theta / 2) * rotvec / theta, s, atol=tol)
    np.testing.assert_allclose(kl.cayley_from_matrix(expected), s, atol=tol)


@settings(max_examples=40, deadline=None)
@given(k=unit_vectors(), theta=st.floats(0.0, 2 * np.pi))
def test_seed002_euler_parameter_matrix(k, theta):
    # seed 002, "Euler Parameters": ε = K sin(θ/2), ε4 = cos(θ/2) (ε4 is the scalar part, kinlib's
    # w), and the rotation matrix R_ε typed from the slide.
    e1, e2, e3 = k * np.sin(theta / 2)
    e4 = np.cos(theta / 2)
    assert e1**2 + e2**2 + e3**2 + e4**2 == pytest.approx(1.0, abs=1e-12)  # unit
    R_eps = np.array(
        [
            [1 - 2 * e2**2 - 2 * e3**2, 2 * (e1 * e2 - e3 * e4), 2 * (e1 * e3 + e2 * e4)],
            [2 * (e1 * e2 + e3 * e4), 1 - 2 * e1**2 - 2 * e3**2, 2 * (e2 * e3 - e1 * e4)],
            [2 * (e1 * e3 - e2 * e4), 2 * (e2 * e3 + e1 * e4), 1 - 2 * e1**2 - 2 * e2**2],
        ]
    )
    np.testing.assert_allclose(kl.matrix_from_quat([e4, e1, e2, e3]), R_eps, atol=TOL)
    np.testing.assert_allclose(kl.quat_from_axis_angle(k, theta), [e4, e1, e2, e3], atol=TOL)
    # and R_ε is the rotation about K by θ (seed 002, "Equivalent Angle-Axis": R_K(θ))
    np.testing.assert_allclose(R_eps, Rotation.from_rotvec(theta * k).as_matrix(), atol=1e-10)


@settings(max_examples=40, deadline=None)
@given(k=unit_vectors(), theta=st.floats(0.0, np.pi - 0.1))
def test_seed002_euler_parameters_inverse_problem(k, theta):
    # seed 002, "Euler Parameters / The Inverse Problem": ε4 = ½ √(1 + r11 + r22 + r33),
    # ε = 1/(4 ε4) [r32 − r23, r13 − r31, r21 − r12]  (ill defined only as ε4 -> 0)
    R = Rotation.from_rotvec(theta * k).as_matrix()
    e4 = 0.5 * np.sqrt(1 + np.trace(R))
    eps = np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]]) / (4 * e4)
    np.testing.assert_allclose(kl.quat_from_matrix(R), np.r_[e4, eps], atol=1e-10)


@pytest.mark.parametrize("k", [[1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 0], [2, -1, 3]])
def test_seed002_euler_parameters_at_180_degrees(k):
    # seed 002, "Euler Parameters / The Inverse Problem": if ε4 = 0, θ = 180° and ε = K, with
    # ε_i² = (1 + 2 r_ii − tr A) / 4.
    k = np.asarray(k, float) / np.linalg.norm(k)
    A = 2 * np.outer(k, k) - np.eye(3)  # a half turn about k
    eps_sq = (1 + 2 * np.diag(A) - np.trace(A)) / 4
    q = kl.quat_from_matrix(A)
    assert abs(q[0]) < TOL
    np.testing.assert_allclose(q[1:] ** 2, eps_sq, atol=TOL)
    np.testing.assert_allclose(np.abs(q[1:]), np.abs(k), atol=TOL)


@settings(max_examples=40, deadline=None)
@given(k=unit_vectors(), theta=st.floats(0.1, np.pi - 0.1))
def test_seed002_angle_axis_inverse_problem(k, theta):
    # seed 002, "Equivalent Angle-Axis / The Inverse Problem":
    # θ = acos((r11 + r22 + r33 − 1)/2), K = 1/(2 sin θ) [r32 − r23, r13 − r31, r21 − r12]
    # (θ in [0, 180°]; generic angles, away from the ill-defined 0 and 180°).
    c, s, v = np.cos(theta), np.sin(theta), 1 - np.cos(theta)
    kx, ky, kz = k
    # R_K(θ) typed from the slide
    R = np.array(
        [
            [kx * kx * v + c, kx * ky * v - kz * s, kx * kz * v + ky * s],
            [kx * ky * v + kz * s, ky * ky * v + c, ky * kz * v - kx * s],
            [kx * kz * v - ky * s, ky * kz * v + kx * s, kz * kz * v + c],
        ]
    )
    np.testing.assert_allclose(kl.matrix_from_axis_angle(k, theta), R, atol=TOL)
    th = np.arccos((np.trace(R) - 1) / 2)
    K = np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]]) / (2 * np.sin(th))
    axis, angle = kl.axis_angle_from_matrix(R)
    np.testing.assert_allclose(angle, th, atol=1e-10)
    np.testing.assert_allclose(axis, K, atol=1e-10)
    np.testing.assert_allclose(angle, theta, atol=1e-10)
    np.testing.assert_allclose(axis, k, atol=1e-10)


@pytest.mark.parametrize("theta", [-2.0, -0.3, 0.0, 0.7, np.pi])
def test_seed002_angle_axis_principal_axes(theta):
    # seed 002, "Equivalent Angle-Axis / Example": for K = X, Y or Z, R_K(θ) is R_X(θ), ...
    for axis, typed in (([1, 0, 0], Rx), ([0, 1, 0], Ry), ([0, 0, 1], Rz)):
        np.testing.assert_allclose(kl.matrix_from_axis_angle(axis, theta), typed(theta), atol=TOL)


@settings(max_examples=40, deadline=None)
@given(
    a=st.floats(-np.pi + 1e-3, np.pi - 1e-3),
    b=st.floats(-np.pi / 2 + 1e-3, np.pi / 2 - 1e-3),
    g=st.floats(-np.pi + 1e-3, np.pi - 1e-3),
)
def test_seed002_zyx_euler_and_xyz_fixed_angles(a, b, g):
    # seed 002, "Z-Y-X Euler Angles": ^A R_B = R_Z(α) R_Y(β) R_X(γ), typed out
    ca, sa, cb, sb, cg, sg = np.cos(a), np.sin(a), np.cos(b), np.sin(b), np.cos(g), np.sin(g)
    R = np.array(
        [
            [ca * cb, ca * sb * sg - sa * cg, ca * sb * cg + sa * sg],
            [sa * cb, sa * sb * sg + ca * cg, sa * sb * cg - ca * sg],
            [-sb, cb * sg, cb * cg],
        ]
    )
    np.testing.assert_allclose(kl.matrix_from_euler([a, b, g], "ZYX"), R, atol=TOL)
    # "X-Y-Z Fixed Angles": ^A R_B,XYZ(γ, β, α) is the same matrix (angles in letter order)
    np.testing.assert_allclose(kl.matrix_from_euler([g, b, a], "xyz"), R, atol=TOL)
    # "Z-Y-X Euler Angles / The Inverse Problem": β = Atan2(−r31, √(r11² + r21²)),
    # α = Atan2(r21/cβ, r11/cβ), γ = Atan2(r32/cβ, r33/cβ)
    beta = np.arctan2(-R[2, 0], np.hypot(R[0, 0], R[1, 0]))
    cbeta = np.cos(beta)
    alpha = np.arctan2(R[1, 0] / cbeta, R[0, 0] / cbeta)
    gamma = np.arctan2(R[2, 1] / cbeta, R[2, 2] / cbeta)
    np.testing.assert_allclose(kl.euler_from_matrix(R, "ZYX"), [alpha, beta, gamma], atol=1e-9)
    np.testing.assert_allclose([alpha, beta, gamma], [a, b, g], atol=1e-9)


@settings(max_examples=30, deadline=None)
@given(a=st.floats(-3.0, 3.0), g=st.floats(-3.0, 3.0))
def test_seed002_zyx_singularity(a, g):
    # seed 002, "Z-Y-X Euler Angles / Singularity of the Inverse Problem": for β = +90°,
    # R = [[0, s(γ−α), c(γ−α)], [0, c(γ−α), −s(γ−α)], [−1, 0, 0]]; choose α = 0 and
    # γ = Atan2(r12, r22). For β = −90°, α = 0 and γ = −Atan2(r12, r22).
    up = kl.matrix_from_euler([a, np.pi / 2, g], "ZYX")
    d = g - a
    typed = np.array([[0, np.sin(d), np.cos(d)], [0, np.cos(d), -np.sin(d)], [-1.0, 0, 0]])
    np.testing.assert_allclose(up, typed, atol=TOL)
    ang = kl.euler_from_matrix(typed, "ZYX")
    np.testing.assert_allclose(ang[:2], [0.0, np.pi / 2], atol=TOL)
    gamma = np.arctan2(typed[0, 1], typed[1, 1])
    assert abs(np.sin(ang[2] - gamma)) < 1e-9 and np.cos(ang[2] - gamma) > 0
    down = Rz(a) @ Ry(-np.pi / 2) @ Rx(g)
    ang = kl.euler_from_matrix(down, "ZYX")
    np.testing.assert_allclose(ang[:2], [0.0, -np.pi / 2], atol=1e-9)
    gamma = -np.arctan2(down[0, 1], down[1, 1])
    assert abs(np.sin(ang[2] - gamma)) < 1e-9 and np.cos(ang[2] - gamma) > 0


# =========================================================================== seed 000


@settings(max_examples=50, deadline=None)
@given(a=unit_vectors(), b=vec3, theta=st.floats(-2 * np.pi, 2 * np.pi))
def test_seed000_rodrigues_derivation(a, b, theta):
    # seed 000, "Rodrigues Axis-Angle Rotation": b = b_par + b_perp with b_par = a (a·b)
    # (vector projection) and b_perp = −a × (a × b); only b_perp turns, in the plane of
    # b_perp and a × b: b'_perp = b_perp cos θ + (a × b) sin θ.
    b_par = a * (a @ b)
    b_perp = -np.cross(a, np.cross(a, b))
    np.testing.assert_allclose(b_par + b_perp, b, atol=1e-10)
    scale = 1 + np.linalg.norm(b)
    np.testing.assert_allclose(kl.rodrigues_rotate(b_par, a, theta), b_par, atol=1e-10 * scale)
    np.testing.assert_allclose(
        kl.rodrigues_rotate(b_perp, a, theta),
        b_perp * np.cos(theta) + np.cross(a, b) * np.sin(theta),
        atol=1e-10 * scale,
    )
    # "Rodrigues Rotation Formula": b' = b_par + b_perp cos θ + a × b sin θ
    # = (1 − cos θ)(a·b) a + b cos θ + a × b sin θ
    b1 = b_par + b_perp * np.cos(theta) + np.cross(a, b) * np.sin(theta)
    b2 = (1 - np.cos(theta)) * (a @ b) * a + b * np.cos(theta) + np.cross(a, b) * np.sin(theta)
    np.testing.assert_allclose(kl.rodrigues_rotate(b, a, theta), b1, atol=1e-10 * scale)
    np.testing.assert_allclose(kl.rodrigues_rotate(b, a, theta), b2, atol=1e-10 * scale)
    # "Rodrigues and Quaternion Equivalency": q b q* with q = (cos α/2, a sin α/2)
    q = np.r_[np.cos(theta / 2), a * np.sin(theta / 2)]
    qbq = hprod(hprod(q, np.r_[0.0, b]), q * [1, -1, -1, -1])
    np.testing.assert_allclose(qbq[1:], b2, atol=1e-10 * scale)
    np.testing.assert_allclose(kl.quat_rotate(q, b), b2, atol=1e-10 * scale)


@settings(max_examples=40, deadline=None)
@given(u=unit_vectors(), theta=st.floats(-2 * np.pi, 2 * np.pi))
def test_seed000_rodrigues_matrix(u, theta):
    # seed 000, "Rodrigues Rotation Matrix": R = cos θ I + sin θ [u]x + (1 − cos θ) u ⊗ u,
    # and the "resulting rotation matrix" typed entry by entry.
    c, s = np.cos(theta), np.sin(theta)
    ux, uy, uz = u
    typed = np.array(
        [
            [c + ux**2 * (1 - c), ux * uy * (1 - c) - uz * s, ux * uz * (1 - c) + uy * s],
            [uy * ux * (1 - c) + uz * s, c + uy**2 * (1 - c), uy * uz * (1 - c) - ux * s],
            [uz * ux * (1 - c) - uy * s, uz * uy * (1 - c) + ux * s, c + uz**2 * (1 - c)],
        ]
    )
    compact = c * np.eye(3) + s * skew3(u) + (1 - c) * np.outer(u, u)
    np.testing.assert_allclose(typed, compact, atol=TOL)
    np.testing.assert_allclose(kl.matrix_from_axis_angle(u, theta), typed, atol=TOL)
    # "cross product is multiplication with skew symmetric matrix"
    np.testing.assert_allclose(kl.skew(u) @ [1.0, 2.0, 3.0], np.cross(u, [1.0, 2.0, 3.0]), atol=TOL)


h = np.sqrt(0.5)
CHECKPOINTS = [
    # seed 000, "Checkpoint": (axis, angle, quaternion from the slide, the matrix typed by hand)
    ("no rotation", [0, 0, 1], 0.0, [1, 0, 0, 0], np.eye(3)),
    ("180 about z", [0, 0, 1], np.pi, [0, 0, 0, 1], np.diag([-1.0, -1.0, 1.0])),
    ("90 about y", [0, 1, 0], np.pi / 2, [h, 0, h, 0], [[0, 0, 1], [0, 1, 0], [-1, 0, 0]]),
    ("-90 about x", [1, 0, 0], -np.pi / 2, [h, -h, 0, 0], [[1, 0, 0], [0, 0, 1], [0, -1, 0]]),
]


@pytest.mark.parametrize(
    ("name", "axis", "angle", "q", "R"), CHECKPOINTS, ids=[c[0] for c in CHECKPOINTS]
)
def test_seed000_quaternion_checkpoints(name, axis, angle, q, R):
    q, R = np.asarray(q, float), np.asarray(R, float)
    np.testing.assert_allclose(kl.quat_from_axis_angle(axis, angle), q, atol=TOL)
    got = kl.quat_from_matrix(R)
    if q[0] == 0.0:  # a half turn: q and −q are the same rotation ("Restating")
        got = got * np.sign(got @ q)
    np.testing.assert_allclose(got, q, atol=TOL)
    np.testing.assert_allclose(kl.matrix_from_quat(q), R, atol=TOL)


@settings(max_examples=50, deadline=None)
@given(q=unit_quaternions())
def test_seed000_quaternion_to_rotation_matrix(q):
    # seed 000, "Quaternion to Rotation Matrix": inhomogeneous and homogeneous conversion of
    # q = [q0 q1 q2 q3] (q0 the scalar part), typed from the slide.
    q0, q1, q2, q3 = q
    inhomogeneous = np.array(
        [
            [1 - 2 * (q2**2 + q3**2), 2 * (q1 * q2 - q0 * q3), 2 * (q0 * q2 + q1 * q3)],
            [2 * (q1 * q2 + q0 * q3), 1 - 2 * (q1**2 + q3**2), 2 * (q2 * q3 - q0 * q1)],
            [2 * (q1 * q3 - q0 * q2), 2 * (q0 * q1 + q2 * q3), 1 - 2 * (q1**2 + q2**2)],
        ]
    )
    homogeneous = np.array(
        [
            [q0**2 + q1**2 - q2**2 - q3**2, 2 * (q1 * q2 - q0 * q3), 2 * (q0 * q2 + q1 * q3)],
            [2 * (q1 * q2 + q0 * q3), q0**2 - q1**2 + q2**2 - q3**2, 2 * (q2 * q3 - q0 * q1)],
            [2 * (q1 * q3 - q0 * q2), 2 * (q0 * q1 + q2 * q3), q0**2 - q1**2 - q2**2 + q3**2],
        ]
    )
    np.testing.assert_allclose(kl.matrix_from_quat(q), inhomogeneous, atol=TOL)
    np.testing.assert_allclose(kl.matrix_from_quat(q), homogeneous, atol=TOL)
    # "Quaternions q and −q give the same rotation"
    np.testing.assert_allclose(kl.matrix_from_quat(-q), inhomogeneous, atol=TOL)
    # "Rotation matrix to quaternion can also be performed" (w >= 0: q or −q)
    back = kl.quat_from_matrix(inhomogeneous)
    np.testing.assert_allclose(back * np.sign(back @ q), q, atol=1e-9)


def test_seed000_rotation_of_a_point_by_quaternion():
    # seed 000, "Example": "Rotation of point v = 0 + [1 | 0] by quaternion
    # w = 3π/4 + [0 sin(π/4) cos(π/4)]". Read as: v = 0 + [1 0 0] (a pure quaternion), and
    # w the unit quaternion with half-angle 3π/4 (a rotation of θ = 3π/2) about the unit axis
    # u = [0, sin(π/4), cos(π/4)]: w = cos(3π/4) + u sin(3π/4).
    # By hand (Rodrigues): u·v = 0, u × v = [0, √½, −√½], cos θ = 0, sin θ = −1, so
    # v' = v cos θ + (u × v) sin θ = [0, −√½, √½].
    u = np.array([0.0, np.sin(np.pi / 4), np.cos(np.pi / 4)])
    w = np.r_[np.cos(3 * np.pi / 4), np.sin(3 * np.pi / 4) * u]
    expected = np.array([0.0, -h, h])
    # the conjugation v' = w v w^-1 of the "Rotation by Quaternion" slide, with w^-1 = w̄
    vv = hprod(hprod(w, [0.0, 1.0, 0.0, 0.0]), w * [1, -1, -1, -1])
    np.testing.assert_allclose(vv, np.r_[0.0, expected], atol=TOL)
    np.testing.assert_allclose(kl.quat_rotate(w, [1.0, 0.0, 0.0]), expected, atol=TOL)
    np.testing.assert_allclose(
        kl.quat_rotate(kl.quat_from_axis_angle(u, 3 * np.pi / 2), [1.0, 0.0, 0.0]), expected,
        atol=TOL,
    )
    np.testing.assert_allclose(kl.rodrigues_rotate([1.0, 0, 0], u, 3 * np.pi / 2), expected,
                               atol=TOL)


@settings(max_examples=30, deadline=None)
@given(a=angles, b=angles, g=angles)
def test_seed000_euler_angle_orders(a, b, g):
    # seed 000, "Euler Angles": R = R_x(Θx) R_y(Θy) R_z(Θz), rotations about the moving axes:
    np.testing.assert_allclose(kl.matrix_from_euler([a, b, g], "XYZ"), Rx(a) @ Ry(b) @ Rz(g),
                               atol=TOL)
    # "AutoRob uses XYZ order: R_z R_y R_x (X then Y then Z)": fixed axes, x first
    np.testing.assert_allclose(kl.matrix_from_euler([a, b, g], "xyz"), Rz(g) @ Ry(b) @ Rx(a),
                               atol=TOL)
    # "Example: ZYZ Euler angles": z by α, then the new y' by β, then the new z'' by γ
    np.testing.assert_allclose(kl.matrix_from_euler([a, b, g], "ZYZ"), Rz(a) @ Ry(b) @ Rz(g),
                               atol=TOL)


@settings(max_examples=50, deadline=None)
@given(a=angles, g=angles)
def test_seed000_gimbal_lock_product(a, g):
    # seed 000, "Gimbal Lock / Consider a few examples": R = R_x(α) R_y(β) R_z(γ) with β = π/2
    # is [[0, 0, 1], [sin(α+γ), cos(α+γ), 0], [−cos(α+γ), sin(α+γ), 0]]: only α + γ matters.
    s, c = np.sin(a + g), np.cos(a + g)
    typed = np.array([[0.0, 0.0, 1.0], [s, c, 0.0], [-c, s, 0.0]])
    np.testing.assert_allclose(kl.matrix_from_euler([a, np.pi / 2, g], "XYZ"), typed, atol=TOL)
    # the intermediate step on the slide: R_x(α) R_y(π/2) = [[0 0 1], [sα cα 0], [−cα sα 0]]
    np.testing.assert_allclose(
        kl.matrix_from_euler([a, np.pi / 2, 0.0], "XYZ"),
        [[0, 0, 1], [np.sin(a), np.cos(a), 0], [-np.cos(a), np.sin(a), 0]],
        atol=TOL,
    )
    assert kl.euler_gimbal_lock(typed, "XYZ")


def test_seed000_gimbal_lock_example():
    # seed 000, "Gimbal lock example", rotation order X then Y then Z (moving axes):
    # after 90° about x and 90° about the new y, "the current z-axis aligns with the initial
    # x-axis", and a rotation about the new z "occurs about the initial x-axis".
    R2 = kl.matrix_from_euler([np.pi / 2, np.pi / 2, 0.0], "XYZ")
    np.testing.assert_allclose(R2[:, 2], [1.0, 0.0, 0.0], atol=TOL)
    for g in (0.3, np.pi / 2, -1.2):
        np.testing.assert_allclose(
            kl.matrix_from_euler([np.pi / 2, np.pi / 2, g], "XYZ"), Rx(g) @ R2, atol=TOL
        )
