"""Unit dual quaternions and screw motion (Daniilidis 1999, Kenwright 2012; seed 000).

The expected values come from a Hamilton product written out in this file (not kinlib's),
from scipy's ``Rotation``, from plain 4×4 matrix algebra and from the geometry of a screw
(points on the axis slide along it; the axis direction is fixed by the rotation).
"""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from reference import unit_vectors
from scipy.spatial.transform import Rotation

import kinlib as kl

# --------------------------------------------------------------------------- helpers


def hprod(p, q):
    """Hamilton product (r1, v1)(r2, v2) = (r1 r2 − v1·v2, r1 v2 + r2 v1 + v1 × v2)."""
    p, q = np.asarray(p, float), np.asarray(q, float)
    r1, v1, r2, v2 = p[0], p[1:], q[0], q[1:]
    return np.concatenate([[r1 * r2 - v1 @ v2], r1 * v2 + r2 * v1 + np.cross(v1, v2)])


def qconj(q):
    return np.array([q[0], -q[1], -q[2], -q[3]])


def dq_prod(a, b):
    """(a_r + ε a_d)(b_r + ε b_d) = a_r b_r + ε (a_r b_d + a_d b_r), with ε² = 0."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    return np.concatenate([hprod(a[:4], b[:4]), hprod(a[:4], b[4:]) + hprod(a[4:], b[:4])])


def quat_wxyz(R):
    """Unit quaternion [w, x, y, z] of R, by scipy (which stores [x, y, z, w])."""
    x, y, z, w = Rotation.from_matrix(R).as_quat()
    return np.array([w, x, y, z])


def dq_of(R, t):
    """The dual quaternion [q_r, ½ (0, t) q_r] built here, independently of kinlib."""
    qr = quat_wxyz(R)
    return np.concatenate([qr, 0.5 * hprod(np.r_[0.0, t], qr)])


def hom(R, p):
    T = np.eye(4)
    T[:3, :3] = R
    T[:3, 3] = p
    return T


def screw_transform(l, c, theta, d):
    """Rotation θ about the line through c with unit direction l, then d along l."""
    R = Rotation.from_rotvec(theta * np.asarray(l)).as_matrix()
    return hom(R, c - R @ c + d * np.asarray(l))


def assert_same_up_to_sign(a, b, atol):
    if np.abs(a - b).max() > np.abs(a + b).max():
        b = -b
    np.testing.assert_allclose(a, b, rtol=0, atol=atol)


TOL = 1e-9

# --------------------------------------------------------------------------- strategies

coords = st.floats(-100.0, 100.0, allow_nan=False, allow_infinity=False)
vec3 = st.tuples(coords, coords, coords).map(np.array)



@st.composite
def generic_rotations(draw):
    q = np.array(draw(st.tuples(*[st.floats(-1.0, 1.0)] * 4)))
    if q @ q < 1e-6:
        q = np.array([0.0, 0.0, 0.0, 1.0])
    return Rotation.from_quat(q).as_matrix()


half_turns = unit_vectors().map(lambda u: Rotation.from_rotvec(np.pi * u).as_matrix())
axis_half_turns = st.sampled_from(
    [np.diag([1.0, -1.0, -1.0]), np.diag([-1.0, 1.0, -1.0]), np.diag([-1.0, -1.0, 1.0])]
)
rotations = st.one_of(generic_rotations(), half_turns, axis_half_turns, st.just(np.eye(3)))


@st.composite
def rigid_transforms(draw):
    return hom(draw(rotations), draw(vec3))


@st.composite
def screw_friendly_transforms(draw, max_angle=np.pi):
    """Rotation angle in [0.01, max_angle]: the screw axis is well defined."""
    theta = draw(st.floats(0.01, max_angle))
    u = draw(unit_vectors())
    return hom(Rotation.from_rotvec(theta * u).as_matrix(), draw(vec3))


# --------------------------------------------------------------------------- conversions


@settings(max_examples=125, deadline=None)
@given(T=rigid_transforms())
def test_round_trip_through_dual_quaternion(T):
    dq = kl.dual_quat_from_transform(T)
    assert dq.shape == (8,)
    np.testing.assert_allclose(kl.transform_from_dual_quat(dq), T, rtol=0, atol=TOL)
    # a unit dual quaternion: |q_r| = 1 and q_r · q_d = 0; w_r >= 0 by convention
    assert abs(np.linalg.norm(dq[:4]) - 1.0) < 1e-12
    assert abs(dq[:4] @ dq[4:]) < 1e-9
    assert dq[0] >= 0.0


@settings(max_examples=75, deadline=None)
@given(T=rigid_transforms())
def test_dual_quaternion_matches_its_definition(T):
    expected = dq_of(T[:3, :3], T[:3, 3])
    assert_same_up_to_sign(kl.dual_quat_from_transform(T), expected, TOL)
    # and the way back reads t = 2 q_d q_r*
    np.testing.assert_allclose(
        kl.transform_from_dual_quat(expected), T, rtol=0, atol=TOL
    )
    np.testing.assert_allclose(
        2.0 * hprod(expected[4:], qconj(expected[:4]))[1:], T[:3, 3], rtol=0, atol=TOL
    )


@pytest.mark.parametrize(
    "axis", [[1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 0], [1, -2, 3], [0, -1, 1e-9]]
)
def test_half_turn_round_trip(axis):
    u = np.asarray(axis, float) / np.linalg.norm(axis)
    R = 2.0 * np.outer(u, u) - np.eye(3)  # a half turn about u, typed from its definition
    T = hom(R, [0.5, -2.0, 3.0])
    dq = kl.dual_quat_from_transform(T)
    np.testing.assert_allclose(kl.transform_from_dual_quat(dq), T, rtol=0, atol=TOL)
    assert abs(dq[0]) < 1e-12  # cos(π/2) = 0
    assert_same_up_to_sign(dq[1:4], u, 1e-12)


def test_identity():
    dq = kl.dual_quat_from_transform(np.eye(4))
    np.testing.assert_array_equal(dq, [1, 0, 0, 0, 0, 0, 0, 0])
    np.testing.assert_array_equal(kl.transform_from_dual_quat([1, 0, 0, 0, 0, 0, 0, 0]), np.eye(4))


def test_batched_conversions():
    rng = np.random.default_rng(1)
    T = np.stack([hom(R, p) for R, p in zip(
        Rotation.random(12, rng=rng).as_matrix(), rng.normal(size=(12, 3)), strict=True
    )]).reshape(3, 4, 4, 4)
    dq = kl.dual_quat_from_transform(T)
    assert dq.shape == (3, 4, 8)
    for idx in np.ndindex(3, 4):
        assert_same_up_to_sign(dq[idx], dq_of(T[idx][:3, :3], T[idx][:3, 3]), TOL)
    np.testing.assert_allclose(kl.transform_from_dual_quat(dq), T, rtol=0, atol=TOL)


# --------------------------------------------------------------------------- products


@settings(max_examples=75, deadline=None)
@given(Ta=rigid_transforms(), Tb=rigid_transforms())
def test_multiply_composes_like_matrices(Ta, Tb):
    a, b = dq_of(Ta[:3, :3], Ta[:3, 3]), dq_of(Tb[:3, :3], Tb[:3, 3])
    ab = kl.dual_quat_multiply(a, b)
    np.testing.assert_allclose(ab, dq_prod(a, b), rtol=0, atol=TOL)
    np.testing.assert_allclose(kl.transform_from_dual_quat(ab), Ta @ Tb, rtol=0, atol=TOL)


def test_multiply_basis_elements():
    # i j = k in the real part; ε-parts combine linearly: (1 + ε i)(1 + ε j) = 1 + ε (i + j)
    i = [0, 1, 0, 0, 0, 0, 0, 0]
    j = [0, 0, 1, 0, 0, 0, 0, 0]
    np.testing.assert_array_equal(kl.dual_quat_multiply(i, j), [0, 0, 0, 1, 0, 0, 0, 0])
    a = [1, 0, 0, 0, 0, 1, 0, 0]
    b = [1, 0, 0, 0, 0, 0, 1, 0]
    np.testing.assert_array_equal(kl.dual_quat_multiply(a, b), [1, 0, 0, 0, 0, 1, 1, 0])


def test_multiply_batched_broadcast():
    rng = np.random.default_rng(2)
    a = rng.normal(size=(5, 1, 8))
    b = rng.normal(size=(3, 8))
    out = kl.dual_quat_multiply(a, b)
    assert out.shape == (5, 3, 8)
    for i in range(5):
        for j in range(3):
            np.testing.assert_allclose(out[i, j], dq_prod(a[i, 0], b[j]), atol=1e-12)


# --------------------------------------------------------------------------- points


@settings(max_examples=75, deadline=None)
@given(T=rigid_transforms(), p=vec3)
def test_transform_point_matches_matrix_and_sandwich(T, p):
    R, t = T[:3, :3], T[:3, 3]
    dq = dq_of(R, t)
    out = kl.dual_quat_transform_point(dq, p)
    np.testing.assert_allclose(out, R @ p + t, rtol=0, atol=TOL)
    np.testing.assert_allclose(out, kl.transform_points(T, p), rtol=0, atol=TOL)
    # the literal sandwich q̂ (1 + ε p) q̂̄*, with q̂̄* = q_r* − ε q_d*
    conj = np.concatenate([qconj(dq[:4]), -qconj(dq[4:])])
    s = dq_prod(dq_prod(dq, np.r_[1.0, 0, 0, 0, 0.0, p]), conj)
    np.testing.assert_allclose(s[:4], [1.0, 0.0, 0.0, 0.0], rtol=0, atol=TOL)
    assert abs(s[4]) < TOL
    np.testing.assert_allclose(out, s[5:], rtol=0, atol=TOL)


def test_transform_point_broadcasting():
    rng = np.random.default_rng(3)
    Rs, ts = Rotation.random(6, rng=rng).as_matrix(), rng.normal(size=(6, 3))
    dqs = np.stack([dq_of(R, t) for R, t in zip(Rs, ts, strict=True)])
    P = rng.normal(size=(6, 3))
    # one motion, many points
    np.testing.assert_allclose(
        kl.dual_quat_transform_point(dqs[0], P), P @ Rs[0].T + ts[0], rtol=0, atol=TOL
    )
    # many motions, one point
    np.testing.assert_allclose(
        kl.dual_quat_transform_point(dqs, P[0]), Rs @ P[0] + ts, rtol=0, atol=TOL
    )
    # pairwise
    np.testing.assert_allclose(
        kl.dual_quat_transform_point(dqs, P),
        np.einsum("nij,nj->ni", Rs, P) + ts,
        rtol=0,
        atol=TOL,
    )
    with pytest.raises(kl.KinlibError, match="do not broadcast"):
        kl.dual_quat_transform_point(dqs, P[:4])


# --------------------------------------------------------------------------- conjugate


@settings(max_examples=75, deadline=None)
@given(T=rigid_transforms())
def test_conjugate_is_the_inverse_motion(T):
    dq = kl.dual_quat_from_transform(T)
    c = kl.dual_quat_conjugate(dq)
    np.testing.assert_array_equal(c, dq * [1, -1, -1, -1, 1, -1, -1, -1])
    np.testing.assert_allclose(kl.transform_from_dual_quat(c), np.linalg.inv(T), rtol=0, atol=TOL)
    np.testing.assert_allclose(dq_prod(dq, c), np.eye(8)[0], rtol=0, atol=TOL)
    np.testing.assert_allclose(dq_prod(c, dq), np.eye(8)[0], rtol=0, atol=TOL)


# --------------------------------------------------------------------------- screws


@settings(max_examples=75, deadline=None)
@given(
    l=unit_vectors(),
    c=vec3,
    theta=st.floats(-2 * np.pi, 2 * np.pi),
    d=st.floats(-50.0, 50.0),
)
def test_dual_quat_from_screw_matches_formula_and_geometry(l, c, theta, d):
    m = np.cross(c, l)  # the moment of the line through c with direction l
    dq = kl.dual_quat_from_screw(l, m, theta, d)
    # seed 000 "Screw motion": (cos θ/2, sin θ/2 l) + ε (−d/2 sin θ/2, sin θ/2 m + d/2 cos θ/2 l)
    ch, sh = np.cos(theta / 2), np.sin(theta / 2)
    expected = np.concatenate([[ch], sh * l, [-d / 2 * sh], sh * m + d / 2 * ch * l])
    np.testing.assert_allclose(dq, expected, rtol=0, atol=1e-12)
    np.testing.assert_allclose(
        kl.transform_from_dual_quat(dq), screw_transform(l, c, theta, d), rtol=0, atol=TOL
    )


@settings(max_examples=100, deadline=None)
@given(T=screw_friendly_transforms())
def test_screw_parameters_describe_the_motion(T):
    R, t = T[:3, :3], T[:3, 3]
    l, m, theta, d = kl.screw_from_dual_quat(dq_of(R, t))
    assert l.shape == (3,) and m.shape == (3,)
    assert abs(np.linalg.norm(l) - 1.0) < 1e-12
    # l is the direction the rotation leaves fixed
    np.testing.assert_allclose(R @ l, l, rtol=0, atol=TOL)
    # m is a moment: perpendicular to l
    assert abs(l @ m) < TOL * (1 + np.linalg.norm(m))
    # θ is the rotation angle of R (scipy, and the trace where acos is well conditioned)
    assert 0.0 <= theta <= np.pi
    np.testing.assert_allclose(theta, Rotation.from_matrix(R).magnitude(), rtol=0, atol=TOL)
    if 0.1 < theta < np.pi - 0.1:
        np.testing.assert_allclose(
            theta, np.arccos((np.trace(R) - 1) / 2), rtol=0, atol=TOL
        )
    # d is the translation along the axis
    np.testing.assert_allclose(d, l @ t, rtol=0, atol=TOL)
    # c = l × m lies on the axis (m = c × l): it only slides along l by d
    c = np.cross(l, m)
    tol = TOL * (1 + np.linalg.norm(c))
    np.testing.assert_allclose(R @ c + t, c + d * l, rtol=0, atol=tol)
    # so does every other point of the axis
    np.testing.assert_allclose(R @ (c + 2 * l) + t, c + 2 * l + d * l, rtol=0, atol=tol)
    # the screw rebuilds the whole motion
    np.testing.assert_allclose(screw_transform(l, c, theta, d), T, rtol=0, atol=tol)


@settings(max_examples=100, deadline=None)
@given(T=rigid_transforms())
def test_screw_round_trip(T):
    dq = kl.dual_quat_from_transform(T)
    l, m, theta, d = kl.screw_from_dual_quat(dq)
    assert_same_up_to_sign(kl.dual_quat_from_screw(l, m, theta, d), dq, TOL)


@settings(max_examples=50, deadline=None)
@given(T=rigid_transforms())
def test_q_and_minus_q_give_the_same_screw(T):
    dq = dq_of(T[:3, :3], T[:3, 3])
    l1, m1, t1, d1 = kl.screw_from_dual_quat(dq)
    l2, m2, t2, d2 = kl.screw_from_dual_quat(-dq)
    if abs(t1 - np.pi) < 1e-6:
        # a half turn about l is a half turn about −l; (l, m, d) then flip together
        s = np.sign(l1 @ l2)
        l2, m2, d2 = s * l2, s * m2, s * d2
    np.testing.assert_allclose(t1, t2, rtol=0, atol=TOL)
    np.testing.assert_allclose(l1, l2, rtol=0, atol=TOL)
    np.testing.assert_allclose(m1, m2, rtol=0, atol=TOL * (1 + np.linalg.norm(m1)))
    np.testing.assert_allclose(d1, d2, rtol=0, atol=TOL)


@settings(max_examples=50, deadline=None)
@given(t=vec3.filter(lambda v: np.linalg.norm(v) > 1e-3))
def test_pure_translation_screw(t):
    l, m, theta, d = kl.screw_from_dual_quat(dq_of(np.eye(3), t))
    assert theta == 0.0
    np.testing.assert_allclose(l, t / np.linalg.norm(t), rtol=0, atol=1e-12)
    np.testing.assert_allclose(d, np.linalg.norm(t), rtol=0, atol=TOL)
    np.testing.assert_array_equal(m, [0.0, 0.0, 0.0])


def test_identity_screw():
    l, m, theta, d = kl.screw_from_dual_quat([1, 0, 0, 0, 0, 0, 0, 0])
    assert theta == 0.0 and d == 0.0
    assert abs(np.linalg.norm(l) - 1.0) < 1e-15
    np.testing.assert_array_equal(m, [0.0, 0.0, 0.0])
    np.testing.assert_array_equal(kl.dual_quat_from_screw(l, m, theta, d), np.eye(8)[0])


def test_hand_worked_screw():
    # A quarter turn about the vertical line through c = (1, 0, 0), plus a lift of 0.5 along
    # it, takes the origin to R (0 − c) + c + 0.5 z = (0, −1, 0) + (1, 0, 0) + (0, 0, 0.5).
    R = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    c = np.array([1.0, 0.0, 0.0])
    T = hom(R, -R @ c + c + [0.0, 0.0, 0.5])
    np.testing.assert_array_equal(T[:3, 3], [1.0, -1.0, 0.5])
    dq = kl.dual_quat_from_transform(T)
    origin = [0.0, 0.0, 0.0]
    np.testing.assert_allclose(kl.dual_quat_transform_point(dq, origin), [1, -1, 0.5], atol=1e-15)
    l, m, theta, d = kl.screw_from_dual_quat(dq)
    np.testing.assert_allclose(l, [0.0, 0.0, 1.0], atol=1e-15)
    np.testing.assert_allclose(theta, np.pi / 2, atol=1e-15)
    np.testing.assert_allclose(d, 0.5, atol=1e-15)
    # m = c × l = (1, 0, 0) × (0, 0, 1) = (0, −1, 0); and l × m gives c back
    np.testing.assert_allclose(m, [0.0, -1.0, 0.0], atol=1e-15)
    np.testing.assert_allclose(np.cross(l, m), c, atol=1e-15)
    # and the way back
    dq2 = kl.dual_quat_from_screw([0, 0, 1], [0, -1, 0], np.pi / 2, 0.5)
    np.testing.assert_allclose(kl.dual_quat_transform_point(dq2, origin), [1, -1, 0.5], atol=1e-15)
    np.testing.assert_allclose(kl.transform_from_dual_quat(dq2), T, atol=1e-15)


def test_half_turn_screw():
    # a half turn about the line through (0, 2, 0) along x, with 3 along it
    l, c = np.array([1.0, 0.0, 0.0]), np.array([0.0, 2.0, 0.0])
    T = screw_transform(l, c, np.pi, 3.0)
    lo, m, theta, d = kl.screw_from_dual_quat(dq_of(T[:3, :3], T[:3, 3]))
    np.testing.assert_allclose(theta, np.pi, atol=1e-12)
    s = np.sign(lo @ l)  # ±l are the same half turn
    np.testing.assert_allclose(s * lo, l, atol=1e-12)
    np.testing.assert_allclose(s * d, 3.0, atol=1e-12)
    np.testing.assert_allclose(np.cross(lo, m), c, atol=1e-12)


def test_screw_batched():
    rng = np.random.default_rng(4)
    Rs, ts = Rotation.random(7, rng=rng).as_matrix(), rng.normal(size=(7, 3))
    dqs = np.stack([dq_of(R, t) for R, t in zip(Rs, ts, strict=True)])
    l, m, theta, d = kl.screw_from_dual_quat(dqs)
    assert l.shape == (7, 3) and m.shape == (7, 3) and theta.shape == (7,) and d.shape == (7,)
    for i in range(7):
        li, mi, ti, di = kl.screw_from_dual_quat(dqs[i])
        np.testing.assert_allclose(l[i], li, atol=1e-15)
        np.testing.assert_allclose(m[i], mi, atol=1e-15)
        np.testing.assert_allclose(theta[i], ti, atol=1e-15)
        np.testing.assert_allclose(d[i], di, atol=1e-15)
        np.testing.assert_allclose(d[i], np.einsum("i,i", l[i], ts[i]), atol=TOL)
    back = kl.dual_quat_from_screw(l, m, theta, d)
    assert back.shape == (7, 8)
    for i in range(7):
        assert_same_up_to_sign(back[i], dqs[i], TOL)


# --------------------------------------------------------------------------- validation


@pytest.mark.parametrize(
    ("l", "m"),
    [([0, 0, 1], [0, 0, 1]), ([1, 0, 0], [0.5, 1.0, 0.0]), ([1, 1, 1], [1, 0, 0])],
)
def test_moment_must_be_perpendicular(l, m):
    with pytest.raises(kl.KinlibError, match="perpendicular"):
        kl.dual_quat_from_screw(l, m, 0.5, 1.0)


@pytest.mark.parametrize(
    ("dq", "words"),
    [
        (2 * np.eye(8)[0], ["unit dual quaternion", "norm 2"]),
        (np.r_[0.6, 0, 0, 0, 0, 0, 0, 0], ["unit dual quaternion", "norm 0.6"]),
        (np.zeros(8), ["unit dual quaternion"]),
        (np.r_[1.0, 0, 0, 0, 1.0, 0, 0, 0], ["unit dual quaternion", "real·dual"]),
        (np.r_[0, 0, 0, 1.0, 0, 0, 0, 0.1], ["unit dual quaternion", "real·dual"]),
    ],
)
def test_non_unit_dual_quaternions_are_rejected(dq, words):
    for f in (
        kl.transform_from_dual_quat,
        kl.screw_from_dual_quat,
        lambda x: kl.dual_quat_transform_point(x, [1.0, 2.0, 3.0]),
    ):
        with pytest.raises(kl.KinlibError) as info:
            f(dq)
        for w in words:
            assert w in str(info.value)


def test_non_unit_member_of_a_batch_is_named():
    dqs = np.tile(np.eye(8)[0], (4, 1))
    dqs[3, 0] = 1.5
    with pytest.raises(kl.KinlibError, match=r"dq\[3\]"):
        kl.transform_from_dual_quat(dqs)


# --------------------------------------------------------------------------- ScLERP


def sclerp(T0, T1, t):
    return kl.transform_from_dual_quat(
        kl.dual_quat_sclerp(kl.dual_quat_from_transform(T0), kl.dual_quat_from_transform(T1), t)
    )


@settings(max_examples=150, deadline=None)
@given(rigid_transforms(), unit_vectors(), vec3, st.floats(0.0, 3.1), st.floats(-5.0, 5.0),
       st.floats(0.0, 1.0))
def test_sclerp_follows_the_screw(T0, l, c, theta, d, t):
    # the relative motion is a screw built here with scipy; ScLERP applies the fraction t of it
    T1 = T0 @ screw_transform(l, c / 10.0, theta, d)
    expected = T0 @ screw_transform(l, c / 10.0, t * theta, t * d)
    np.testing.assert_allclose(sclerp(T0, T1, t), expected, rtol=0, atol=1e-9)


@settings(max_examples=60, deadline=None)
@given(rigid_transforms(), rigid_transforms())
def test_sclerp_endpoints(T0, T1):
    np.testing.assert_allclose(sclerp(T0, T1, 0.0), T0, rtol=0, atol=1e-9)
    np.testing.assert_allclose(sclerp(T0, T1, 1.0), T1, rtol=0, atol=1e-9)


@settings(max_examples=60, deadline=None)
@given(rigid_transforms(), screw_friendly_transforms(max_angle=np.pi - 1e-3), rigid_transforms(),
       st.floats(0.0, 1.0))
def test_sclerp_does_not_depend_on_the_world_or_the_body_frame(T0, Trel, G, t):
    # left-invariance: moving both ends by G moves the path by G; right-invariance: changing
    # the body frame by H (attached to the body) changes every pose by H
    T1 = T0 @ Trel
    path = sclerp(T0, T1, t)
    np.testing.assert_allclose(sclerp(G @ T0, G @ T1, t), G @ path, rtol=0, atol=1e-8)
    H = hom(Rotation.from_rotvec([0.3, -0.2, 0.5]).as_matrix(), [0.4, 1.0, -2.0])
    np.testing.assert_allclose(sclerp(T0 @ H, T1 @ H, t), path @ H, rtol=0, atol=1e-8)


def test_sclerp_pure_translation_is_linear():
    T0, T1 = hom(np.eye(3), [1.0, 2.0, 3.0]), hom(np.eye(3), [-1.0, 0.0, 7.0])
    ts = np.linspace(0.0, 1.0, 11)
    out = sclerp(T0, T1, ts)
    line = (1 - ts)[:, None] * [1, 2, 3] + ts[:, None] * [-1, 0, 7]
    np.testing.assert_allclose(out[:, :3, 3], line, rtol=0, atol=1e-14)
    np.testing.assert_allclose(out[:, :3, :3], np.broadcast_to(np.eye(3), (11, 3, 3)), atol=1e-15)


@pytest.mark.parametrize("theta", [1e-4, 1e-7, 1e-10, 1e-13, 0.0])
def test_sclerp_accurate_for_tiny_rotations(theta):
    # the screw axis runs off to infinity as θ → 0; the result must not
    l, c = np.array([0.0, 0.6, 0.8]), np.array([3.0, 1.0, -2.0])
    T0 = hom(Rotation.from_rotvec([0.2, 0.1, -0.4]).as_matrix(), [0.5, 0.5, 0.5])
    for offset in ([0.0, 0.0, 0.0], [5.0, -7.0, 1.0]):  # plus a perpendicular slide
        Trel = screw_transform(l, c, theta, 0.7)
        Trel[:3, 3] += offset
        T1 = T0 @ Trel
        got = sclerp(T0, T1, 0.25)
        # at θ → 0 the motion is a translation: a quarter of it
        expected = T0 @ screw_transform(l, c, 0.25 * theta, 0.25 * 0.7)
        expected[:3, 3] += T0[:3, :3] @ (0.25 * np.asarray(offset))
        # exact without the slide; with it, the true screw differs from a straight slide by
        # about t(1 - t) θ |slide| / 2, and must not blow up
        slack = theta * np.linalg.norm(offset)
        np.testing.assert_allclose(got, expected, rtol=0, atol=1e-12 + slack)


def test_sclerp_takes_the_short_way_and_ignores_the_sign():
    T0, T1 = np.eye(4), hom(Rotation.from_rotvec([0.0, 0.0, 1.2]).as_matrix(), [0.0, 0.0, 1.0])
    a, b = kl.dual_quat_from_transform(T0), kl.dual_quat_from_transform(T1)
    mid = kl.transform_from_dual_quat(kl.dual_quat_sclerp(a, -b, 0.5))
    np.testing.assert_allclose(mid, sclerp(T0, T1, 0.5), atol=1e-12)
    half = Rotation.from_rotvec([0, 0, 0.6]).as_matrix()
    np.testing.assert_allclose(mid[:3, :3], half, atol=1e-12)


def test_sclerp_rotation_matches_slerp():
    T0 = hom(Rotation.from_rotvec([0.1, 0.2, 0.3]).as_matrix(), [1.0, 0.0, 0.0])
    T1 = hom(Rotation.from_rotvec([-1.0, 0.5, 2.0]).as_matrix(), [0.0, 4.0, 2.0])
    ts = np.linspace(0, 1, 7)
    dq = kl.dual_quat_sclerp(kl.dual_quat_from_transform(T0), kl.dual_quat_from_transform(T1), ts)
    q = kl.quat_slerp(kl.quat_from_matrix(T0[:3, :3]), kl.quat_from_matrix(T1[:3, :3]), ts)
    assert_same_up_to_sign(dq[:, :4], q, atol=1e-12)


def test_sclerp_batched_broadcast():
    T0 = hom(np.eye(3), [0.0, 0.0, 0.0])
    T1 = np.stack([screw_transform([0, 0, 1.0], [1.0, 0, 0], th, 0.5) for th in (0.5, 1.0, 2.0)])
    a, b = kl.dual_quat_from_transform(T0), kl.dual_quat_from_transform(T1)
    out = kl.dual_quat_sclerp(a, b[:, None, :], np.array([0.0, 0.5, 1.0, 0.2]))
    assert out.shape == (3, 4, 8)
    for i in range(3):
        for j, t in enumerate([0.0, 0.5, 1.0, 0.2]):
            np.testing.assert_allclose(out[i, j], kl.dual_quat_sclerp(a, b[i], t), atol=1e-15)
