"""Axis-angle: Rodrigues' matrix and vector formulas, the inverse problem, exp/log of SO(3).

References: the element-wise Rodrigues matrix typed out from the lecture notes (Craig's
R_K(θ), seed 002; seed 001 eq. 4.64), scipy's rotation vectors, scipy.linalg.expm (an
independent matrix exponential) and a Hamilton product written in this file.
"""

import numpy as np
import pytest
import scipy.linalg
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from reference import random_unit_vectors, unit_vectors
from scipy.spatial.transform import Rotation

import kinlib as kl

PI = np.pi

# --------------------------------------------------------------------------- helpers


def rodrigues_textbook(k, theta):
    """Craig's R_K(θ) (seed 002), typed out: k_x k_x vθ + cθ, k_x k_y vθ − k_z sθ, ...

    ``k`` unit, shape (..., 3); ``theta`` shape (...).
    """
    k = np.asarray(k, dtype=float)
    kx, ky, kz = k[..., 0], k[..., 1], k[..., 2]
    c, s = np.cos(theta), np.sin(theta)
    v = 1.0 - c
    rows = [
        [kx * kx * v + c, kx * ky * v - kz * s, kx * kz * v + ky * s],
        [kx * ky * v + kz * s, ky * ky * v + c, ky * kz * v - kx * s],
        [kx * kz * v - ky * s, ky * kz * v + kx * s, kz * kz * v + c],
    ]
    return np.stack([np.stack(np.broadcast_arrays(*r), axis=-1) for r in rows], axis=-2)


def skew_textbook(w):
    wx, wy, wz = w
    return np.array([[0.0, -wz, wy], [wz, 0.0, -wx], [-wy, wx, 0.0]])


def hamilton(p, q):
    """(r1, v1)(r2, v2) = (r1 r2 − v1·v2, r1 v2 + r2 v1 + v1 × v2), seed 000."""
    r1, v1, r2, v2 = p[..., 0], p[..., 1:], q[..., 0], q[..., 1:]
    r = r1 * r2 - np.sum(v1 * v2, axis=-1)
    v = r1[..., None] * v2 + r2[..., None] * v1 + np.cross(v1, v2)
    return np.concatenate([r[..., None], v], axis=-1)


def max_err(A, B):
    return float(np.abs(np.asarray(A) - np.asarray(B)).max(initial=0.0))




# --------------------------------------------------------------------------- forward


def test_matrix_from_axis_angle_matches_textbook_and_scipy_batch():
    rng = np.random.default_rng(200)
    u = random_unit_vectors(2000, rng)
    t = rng.uniform(-2 * PI, 2 * PI, size=2000)
    R = kl.matrix_from_axis_angle(u, t)
    assert R.shape == (2000, 3, 3)
    # 1e-14, not 1e-15: kinlib evaluates 1 − cos θ as 2 sin²(θ/2), the textbook does not
    assert max_err(R, rodrigues_textbook(u, t)) < 1e-14
    assert max_err(R, Rotation.from_rotvec(u * t[:, None]).as_matrix()) < 1e-14
    # the axis is normalised first
    scale = rng.uniform(1e-6, 1e6, size=(2000, 1))
    assert max_err(kl.matrix_from_axis_angle(u * scale, t), R) < 1e-15
    # one axis, many angles; many axes, one angle
    assert max_err(kl.matrix_from_axis_angle(u[0], t), rodrigues_textbook(u[0], t)) < 1e-15
    assert max_err(kl.matrix_from_axis_angle(u, 0.7), rodrigues_textbook(u, 0.7)) < 1e-15
    Rb = kl.matrix_from_axis_angle(u.reshape(40, 50, 3), t.reshape(40, 50))
    assert max_err(Rb, R.reshape(40, 50, 3, 3)) < 1e-15


@settings(max_examples=300, deadline=None)
@given(u=unit_vectors(), t=st.floats(-4 * PI, 4 * PI))
def test_matrix_from_axis_angle_property(u, t):
    R = kl.matrix_from_axis_angle(u, t)
    # a few ulps: both formulas round differently (found: 1.1e-15 at t = 9 rad)
    assert max_err(R, rodrigues_textbook(u, t)) < 4e-15
    assert max_err(R, Rotation.from_rotvec(u * t).as_matrix()) < 1e-14
    assert max_err(R @ u, u) < 4e-15  # the axis is fixed
    assert np.trace(R) == pytest.approx(1.0 + 2.0 * np.cos(t), abs=1e-14)


@pytest.mark.parametrize(
    ("axis", "fn"), [([1.0, 0, 0], kl.rotx), ([0, 1.0, 0], kl.roty), ([0, 0, 1.0], kl.rotz)]
)
def test_matrix_from_axis_angle_about_coordinate_axes(axis, fn):
    for t in np.linspace(-7, 7, 29):
        assert max_err(kl.matrix_from_axis_angle(axis, t), fn(t)) < 1e-15


def test_matrix_from_axis_angle_rejects_zero_axis():
    with pytest.raises(kl.KinlibError, match="axis"):
        kl.matrix_from_axis_angle([0.0, 0.0, 0.0], 1.0)


# --------------------------------------------------------------------------- vector formula


def test_rodrigues_rotate_matches_matrix_and_quaternion_conjugation():
    rng = np.random.default_rng(201)
    u = random_unit_vectors(1000, rng)
    t = rng.uniform(-2 * PI, 2 * PI, size=1000)
    v = rng.normal(size=(1000, 3)) * 10
    out = kl.rodrigues_rotate(v, u, t)
    assert out.shape == (1000, 3)
    R = Rotation.from_rotvec(u * t[:, None]).as_matrix()
    assert max_err(out, np.einsum("nij,nj->ni", R, v)) < 1e-13
    q = np.concatenate([np.cos(t / 2)[:, None], np.sin(t / 2)[:, None] * u], axis=-1)
    q_inv = q * [1.0, -1.0, -1.0, -1.0]
    p = np.concatenate([np.zeros((1000, 1)), v], axis=-1)
    conj = hamilton(hamilton(q, p), q_inv)
    assert np.abs(conj[:, 0]).max() < 1e-13
    assert max_err(out, conj[:, 1:]) < 1e-13
    # lengths are kept, the component along the axis is kept
    assert np.allclose(np.linalg.norm(out, axis=-1), np.linalg.norm(v, axis=-1), rtol=1e-14)
    assert np.allclose(np.sum(out * u, axis=-1), np.sum(v * u, axis=-1), atol=1e-13)
    # broadcasting one axis and angle over many vectors
    one = kl.rodrigues_rotate(v, u[0] * 3.0, t[0])
    assert max_err(one, v @ Rotation.from_rotvec(u[0] * t[0]).as_matrix().T) < 1e-13


@settings(max_examples=300, deadline=None)
@given(
    v=st.tuples(*[st.floats(-100.0, 100.0)] * 3).map(np.array),
    u=unit_vectors(),
    t=st.floats(-4 * PI, 4 * PI),
)
def test_rodrigues_rotate_property(v, u, t):
    out = kl.rodrigues_rotate(v, u, t)
    assert max_err(out, rodrigues_textbook(u, t) @ v) < 1e-12
    q = np.concatenate([[np.cos(t / 2)], np.sin(t / 2) * u])
    conj = hamilton(hamilton(q, np.concatenate([[0.0], v])), q * [1, -1, -1, -1])
    assert max_err(out, conj[1:]) < 1e-12


def test_rodrigues_rotate_quarter_turns():
    # geometric facts: z × x = y, so a quarter turn about z takes x to y, and so on
    e = np.eye(3)
    for i in range(3):
        j, k = (i + 1) % 3, (i + 2) % 3
        assert max_err(kl.rodrigues_rotate(e[j], e[i], PI / 2), e[k]) < 1e-15
        assert max_err(kl.rodrigues_rotate(e[j], e[i], PI), -e[j]) < 1e-15
        assert max_err(kl.rodrigues_rotate(e[i], e[i], 1.234), e[i]) < 1e-15


# --------------------------------------------------------------------------- inverse problem


def _check_inverse(R):
    """axis_angle_from_matrix(R): the documented ranges, and R is reproduced."""
    axis, angle = kl.axis_angle_from_matrix(R)
    assert axis.shape == (3,)
    assert np.ndim(angle) == 0
    assert 0.0 <= angle <= PI
    assert abs(np.linalg.norm(axis) - 1.0) < 1e-14
    assert max_err(kl.matrix_from_axis_angle(axis, angle), R) < 1e-9
    assert max_err(rodrigues_textbook(axis, angle), R) < 1e-9
    return axis, angle


def test_axis_angle_from_matrix_at_angle_zero_exactly():
    for R in (np.eye(3), kl.matrix_from_axis_angle([0.3, -1.0, 2.0], 0.0), kl.rotz(0.0)):
        axis, angle = _check_inverse(R)
        assert angle == 0.0
        assert np.array_equal(axis, [1.0, 0.0, 0.0])  # the documented choice


@settings(max_examples=300, deadline=None)
@given(u=unit_vectors(), theta=st.floats(1e-12, 1e-4))
def test_axis_angle_from_matrix_small_angles(u, theta):
    R = rodrigues_textbook(u, theta)
    axis, angle = _check_inverse(R)
    # accurate in relative terms: arccos((tr R − 1)/2) would give 0 or garbage here
    assert abs(angle - theta) <= 1e-9 * theta
    assert max_err(axis, u) < 1e-9


@settings(max_examples=300, deadline=None)
@given(u=unit_vectors(), theta=st.floats(1e-4, PI - 1e-4))
def test_axis_angle_from_matrix_generic(u, theta):
    R = rodrigues_textbook(u, theta)
    axis, angle = _check_inverse(R)
    assert abs(angle - theta) < 1e-12
    assert max_err(axis, u) < 1e-9
    # a negative angle comes back as the positive one about the flipped axis
    axis, angle = kl.axis_angle_from_matrix(rodrigues_textbook(u, -theta))
    assert abs(angle - theta) < 1e-12
    assert max_err(axis, -u) < 1e-9


@settings(max_examples=300, deadline=None)
@given(u=unit_vectors(), delta=st.floats(1e-12, 1e-4))
def test_axis_angle_from_matrix_near_pi(u, delta):
    theta = PI - delta
    R = rodrigues_textbook(u, theta)
    axis, angle = _check_inverse(R)
    assert abs(angle - theta) < 1e-12
    assert max_err(axis, u) < 1e-9  # θ < π: the axis sign is determined


@settings(max_examples=300, deadline=None)
@given(u=unit_vectors())
def test_axis_angle_from_matrix_at_pi_exactly(u):
    # the exact half turn about u: R = 2 u uᵀ − I (no sin θ rounding at all)
    R_exact = 2.0 * np.outer(u, u) - np.eye(3)
    for R in (R_exact, rodrigues_textbook(u, PI)):
        axis, angle = _check_inverse(R)
        assert abs(angle - PI) < 1e-12
        assert min(max_err(axis, u), max_err(axis, -u)) < 1e-9  # u and −u: same rotation


def test_axis_angle_from_matrix_batch_matches_scipy():
    rng = np.random.default_rng(202)
    u = random_unit_vectors(3000, rng)
    t = rng.uniform(0.0, PI, size=3000)
    t[:100] = PI - 10.0 ** rng.uniform(-12, -4, size=100)
    t[100:200] = 10.0 ** rng.uniform(-12, -4, size=100)
    t[200] = 0.0
    R = rodrigues_textbook(u, t)
    axis, angle = kl.axis_angle_from_matrix(R)
    assert axis.shape == (3000, 3) and angle.shape == (3000,)
    assert np.all((angle >= 0) & (angle <= PI))
    assert np.allclose(np.linalg.norm(axis, axis=-1), 1.0, atol=1e-14, rtol=0)
    rv = Rotation.from_matrix(R).as_rotvec()
    assert max_err(axis * angle[:, None], rv) < 1e-9
    assert max_err(kl.log_so3(R), rv) < 1e-9
    assert np.all(np.abs(angle - t) <= 1e-12 + 1e-9 * t)
    defined = np.arange(3000) != 200  # at angle 0 the axis is arbitrary
    assert max_err(axis[defined], u[defined]) < 1e-9
    Rb = R.reshape(30, 100, 3, 3)
    axis_b, angle_b = kl.axis_angle_from_matrix(Rb)
    assert axis_b.shape == (30, 100, 3) and angle_b.shape == (30, 100)
    assert max_err(axis_b.reshape(-1, 3), axis) < 1e-15
    assert max_err(angle_b.ravel(), angle) < 1e-15


@settings(max_examples=200, deadline=None)
@given(q=st.tuples(*[st.floats(-1.0, 1.0)] * 4))
def test_log_so3_matches_scipy_rotvec(q):
    q = np.array(q)
    assume(np.linalg.norm(q) > 1e-3)
    R = Rotation.from_quat(q).as_matrix()
    w = kl.log_so3(R)
    rv = Rotation.from_matrix(R).as_rotvec()
    theta = np.linalg.norm(rv)
    assert np.linalg.norm(w) <= PI + 1e-15
    if theta < PI - 1e-6:
        assert max_err(w, rv) < 1e-9
    else:  # a half turn: w and −w are the same rotation
        assert min(max_err(w, rv), max_err(w, -rv)) < 1e-9


# --------------------------------------------------------------------------- exp / log


def test_exp_so3_of_zero_is_identity_exactly():
    assert np.array_equal(kl.exp_so3([0.0, 0.0, 0.0]), np.eye(3))
    assert np.array_equal(kl.log_so3(np.eye(3)), [0.0, 0.0, 0.0])
    Z = kl.exp_so3(np.zeros((4, 5, 3)))
    assert Z.shape == (4, 5, 3, 3)
    assert np.array_equal(Z, np.broadcast_to(np.eye(3), (4, 5, 3, 3)))


def test_exp_so3_matches_expm_batch():
    rng = np.random.default_rng(203)
    u = random_unit_vectors(500, rng)
    t = np.concatenate([rng.uniform(0, 3 * PI, 480), 10.0 ** rng.uniform(-300, -1, 20)])
    w = u * t[:, None]
    R = kl.exp_so3(w)
    expected = scipy.linalg.expm(np.stack([skew_textbook(x) for x in w]))
    assert max_err(R, expected) < 1e-12
    assert max_err(R, Rotation.from_rotvec(w).as_matrix()) < 1e-14


@settings(max_examples=300, deadline=None)
@given(u=unit_vectors(), theta=st.floats(0.0, 10.0))
def test_exp_so3_matches_expm(u, theta):
    w = u * theta
    R = kl.exp_so3(w)
    assert max_err(R, scipy.linalg.expm(skew_textbook(w))) < 1e-12  # expm: scaling+squaring
    assert max_err(R, rodrigues_textbook(u, theta)) < 1e-14


@settings(max_examples=300, deadline=None)
@given(u=unit_vectors(), exponent=st.floats(-290.0, -4.0))
def test_exp_log_tiny_vectors(u, exponent):
    w = u * 10.0**exponent
    R = kl.exp_so3(w)
    # e^[w] = I + [w] + O(|w|²): the off-diagonal entries are w itself, to rounding
    n = 10.0**exponent  # |w|; np.linalg.norm(w) would underflow below ~1e-154
    assert max_err(R - np.eye(3), skew_textbook(w)) <= 1e-15 * n + n**2
    # back in relative terms, also where |w|² underflows (below ~1e-154); kinlib calls
    # rotations below 1e-300 rad the identity, hence the range of exponents
    axis, angle = kl.axis_angle_from_matrix(R)
    assert abs(np.linalg.norm(axis) - 1.0) < 1e-14
    assert max_err(axis, u) < 1e-9
    assert abs(angle - n) <= 1e-9 * n
    assert np.linalg.norm(kl.log_so3(R) - w) <= 1e-9 * n


@settings(max_examples=300, deadline=None)
@given(u=unit_vectors(), theta=st.floats(0.0, PI - 1e-6))
def test_log_exp_round_trip(u, theta):
    w = u * theta
    back = kl.log_so3(kl.exp_so3(w))
    assert np.linalg.norm(back - w) <= 1e-12 + 1e-9 * theta


@settings(max_examples=200, deadline=None)
@given(u=unit_vectors(), theta=st.floats(PI, 20.0))
def test_log_of_large_rotation_vectors_is_the_short_equivalent(u, theta):
    R = kl.exp_so3(u * theta)
    w = kl.log_so3(R)
    assert np.linalg.norm(w) <= PI + 1e-15
    assert max_err(kl.exp_so3(w), R) < 1e-9
    # hand-derived: the angle folded into [0, π]
    folded = theta % (2 * PI)
    folded = min(folded, 2 * PI - folded)
    assert abs(np.linalg.norm(w) - folded) < 1e-9


def test_the_unchecked_log_of_the_ik_loop_is_log_so3():
    """The IK loop takes the log of checked rotations without re-checking them
    (_log_so3_unchecked): the same rotation vectors as log_so3, to a few ulps,
    at random rotations and at the edges (no rotation, tiny angles, half turns)."""
    from kinlib.spatial.axis_angle import _log_so3_unchecked

    exp_so3, log_so3 = kl.exp_so3, kl.log_so3

    rng = np.random.default_rng(7)
    w = rng.normal(size=(200, 3))
    angles = np.concatenate([rng.uniform(0, np.pi, 190), [0.0, 1e-300, 1e-12, 1e-6, 1.0,
                                                          np.pi - 1e-9, np.pi, np.pi, 3.0,
                                                          np.pi - 1e-12]])
    w = w / np.linalg.norm(w, axis=1, keepdims=True) * angles[:, None]
    R = exp_so3(w)
    fast, reference = _log_so3_unchecked(R), log_so3(R)
    near_pi = angles > np.pi - 1e-6  # ±u are the same half turn: compare the rotations
    np.testing.assert_allclose(fast[~near_pi], reference[~near_pi], rtol=0, atol=2e-15)
    np.testing.assert_allclose(exp_so3(fast), R, rtol=0, atol=1e-14)
    np.testing.assert_allclose(np.linalg.norm(fast, axis=1), angles, rtol=0, atol=1e-8)


def test_unchecked_log_agrees_with_log_so3_at_every_angle():
    """The IK loop's log map (no input checks; the antisymmetric part up to 3 rad, the
    quaternion route beyond) against the rotation vectors the rotations were made from,
    across its switch at 3 rad and up to π; scipy's ``as_rotvec`` is the independent
    reference."""
    from kinlib.spatial.axis_angle import _log_so3_unchecked

    rng = np.random.default_rng(5)
    axes = rng.normal(size=(13, 3))
    axes /= np.linalg.norm(axes, axis=1, keepdims=True)
    angles = np.array([0.0, 1e-12, 1e-6, 0.3, 1.5, 2.9, 3.0 - 1e-9, 3.0, 3.0 + 1e-9, 3.1,
                       np.pi - 1e-6, np.pi - 1e-10, 2.0])
    w = axes * angles[:, None]
    R = Rotation.from_rotvec(w).as_matrix()
    got = _log_so3_unchecked(R)
    np.testing.assert_allclose(got, w, atol=1e-9)  # (near π: the angle of R to ~1e-10)
    np.testing.assert_allclose(got, Rotation.from_matrix(R).as_rotvec(), atol=1e-9)
    np.testing.assert_allclose(got, kl.log_so3(R), atol=1e-12)
    small = angles < 3.0
    np.testing.assert_allclose(got[small], w[small], rtol=1e-12, atol=1e-15)
