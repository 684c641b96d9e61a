"""Unit quaternions, Hamilton convention, scalar first [w, x, y, z].

References: Hamilton's table i² = j² = k² = ijk = −1, the product formula and the matrix
typed out from seed 000, scipy's Rotation and Slerp (scalar last: converted by index
shuffling here), and geometric facts.
"""

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from reference import random_unit_vectors
from scipy.spatial.transform import Rotation, Slerp

import kinlib as kl

PI = np.pi
SQRT_HALF = np.sqrt(0.5)

# --------------------------------------------------------------------------- references


def hamilton_seed(p, q):
    """(r1, v1)(r2, v2) = (r1 r2 − v1·v2, r1 v2 + r2 v1 + v1 × v2) (seed 000)."""
    p, q = np.broadcast_arrays(np.asarray(p, float), np.asarray(q, float))
    r1, v1, r2, v2 = p[..., 0], p[..., 1:], q[..., 0], q[..., 1:]
    r = r1 * r2 - np.sum(v1 * v2, axis=-1)
    v = r1[..., None] * v2 + r2[..., None] * v1 + np.cross(v1, v2)
    return np.concatenate([r[..., None], v], axis=-1)


def hamilton_expanded(p, q):
    """(a+bi+cj+dk)(e+fi+gj+hk), expanded as on seed 000's slide."""
    a, b, c, d = np.moveaxis(np.asarray(p, float), -1, 0)
    e, f, g, h = np.moveaxis(np.asarray(q, float), -1, 0)
    return np.stack(
        [
            a * e - b * f - c * g - d * h,
            a * f + b * e + c * h - d * g,
            a * g - b * h + c * e + d * f,
            a * h + b * g - c * f + d * e,
        ],
        axis=-1,
    )


def matrix_seed(q):
    """Seed 000's inhomogeneous quaternion → matrix formula (for unit q), typed out."""
    q0, q1, q2, q3 = np.moveaxis(np.asarray(q, float), -1, 0)
    rows = [
        [1 - 2 * (q2**2 + q3**2), 2 * (q1 * q2 - q0 * q3), 2 * (q0 * q2 + q1 * q3)],
        [2 * (q1 * q2 + q0 * q3), 1 - 2 * (q1**2 + q3**2), 2 * (q2 * q3 - q0 * q1)],
        [2 * (q1 * q3 - q0 * q2), 2 * (q0 * q1 + q2 * q3), 1 - 2 * (q1**2 + q2**2)],
    ]
    return np.stack([np.stack(r, axis=-1) for r in rows], axis=-2)


def xyzw(q):
    """Scalar last, by index shuffling (what scipy wants)."""
    return np.asarray(q)[..., [1, 2, 3, 0]]


def wxyz(q):
    return np.asarray(q)[..., [3, 0, 1, 2]]


def scipy_matrix(q):
    return Rotation.from_quat(xyzw(q)).as_matrix()


def conj(q):
    return np.asarray(q) * np.array([1.0, -1.0, -1.0, -1.0])


def canonical(q):
    """The representative with w >= 0."""
    q = np.asarray(q, float)
    return np.where(q[..., :1] < 0, -q, q)


def max_err(A, B):
    return float(np.abs(np.asarray(A) - np.asarray(B)).max(initial=0.0))


def err_up_to_sign(p, q):
    return min(max_err(p, q), max_err(p, -np.asarray(q)))


def rotation_angle_between(p, q):
    """Rotation angle of p⁻¹ q for unit p, q: 2 atan2(|v|, |w|) of the relative quaternion."""
    rel = hamilton_seed(conj(p), q)
    return 2.0 * np.arctan2(np.linalg.norm(rel[..., 1:], axis=-1), np.abs(rel[..., 0]))


def random_unit_quaternions(n, seed):
    return random_unit_vectors(n, np.random.default_rng(seed), dim=4)


# --------------------------------------------------------------------------- strategies

coords = st.floats(-10.0, 10.0)
quaternions = st.tuples(*[coords] * 4).map(np.array)  # any, possibly zero
vectors = st.tuples(*[coords] * 3).map(np.array)


@st.composite
def nonzero_quaternions(draw):
    q = draw(quaternions)
    assume(np.linalg.norm(q) > 1e-3)
    return q


@st.composite
def unit_quaternions(draw):
    """Unit quaternions: generic, exact half turns (w = 0) and near half turns."""
    v = np.array(draw(st.tuples(*[st.floats(-1.0, 1.0)] * 3)))
    kind = draw(st.sampled_from(["generic", "generic", "half-turn", "near-half-turn"]))
    if kind == "generic":
        q = np.concatenate([[draw(st.floats(-1.0, 1.0))], v])
        n = np.linalg.norm(q)
        assume(n > 1e-3)
        return q / n
    n = np.linalg.norm(v)
    assume(n > 1e-3)
    u = v / n
    if kind == "half-turn":
        return np.concatenate([[0.0], u])
    w = draw(st.floats(1e-12, 1e-4)) * draw(st.sampled_from([-1.0, 1.0]))
    return np.concatenate([[w], np.sqrt(1.0 - w * w) * u])


# --------------------------------------------------------------------------- product


def test_hamilton_table():
    one, i, j, k = np.eye(4)
    mul = kl.quat_multiply
    for x in (i, j, k):
        assert np.array_equal(mul(x, x), -one)
        assert np.array_equal(mul(one, x), x) and np.array_equal(mul(x, one), x)
    assert np.array_equal(mul(mul(i, j), k), -one)  # ijk = −1
    assert np.array_equal(mul(i, j), k) and np.array_equal(mul(j, i), -k)
    assert np.array_equal(mul(j, k), i) and np.array_equal(mul(k, j), -i)
    assert np.array_equal(mul(k, i), j) and np.array_equal(mul(i, k), -j)


def test_quat_multiply_matches_seed_formulas_batch():
    rng = np.random.default_rng(300)
    p, q = rng.normal(size=(2, 1000, 4)) * 3
    out = kl.quat_multiply(p, q)
    assert out.shape == (1000, 4)
    assert max_err(out, hamilton_seed(p, q)) < 1e-13
    assert max_err(out, hamilton_expanded(p, q)) < 1e-13
    # broadcasting over leading dimensions
    a, b = p[:5, None], q[None, :7]
    out = kl.quat_multiply(a, b)
    assert out.shape == (5, 7, 4)
    assert max_err(out, hamilton_seed(a, b)) < 1e-13
    assert max_err(kl.quat_multiply(p, q[0]), hamilton_seed(p, q[0])) < 1e-13


@settings(max_examples=300, deadline=None)
@given(p=quaternions, q=quaternions, r=quaternions)
def test_quat_multiply_algebra(p, q, r):
    pq = kl.quat_multiply(p, q)
    scale = 1.0 + np.linalg.norm(p) * np.linalg.norm(q)
    assert max_err(pq, hamilton_seed(p, q)) <= 1e-14 * scale
    assert max_err(pq, hamilton_expanded(p, q)) <= 1e-14 * scale
    # associativity
    scale3 = scale * (1.0 + np.linalg.norm(r))
    left = kl.quat_multiply(pq, r)
    right = kl.quat_multiply(p, kl.quat_multiply(q, r))
    assert max_err(left, right) <= 1e-13 * scale3
    # |pq| = |p| |q|
    assert abs(np.linalg.norm(pq) - np.linalg.norm(p) * np.linalg.norm(q)) <= 1e-14 * scale
    # conj(pq) = conj(q) conj(p)
    assert max_err(kl.quat_conjugate(pq), hamilton_seed(conj(q), conj(p))) <= 1e-14 * scale


# --------------------------------------------------------------------------- conjugate, inverse


@settings(max_examples=300, deadline=None)
@given(q=nonzero_quaternions())
def test_conjugate_inverse_normalize(q):
    assert np.array_equal(kl.quat_conjugate(q), [q[0], -q[1], -q[2], -q[3]])
    n2 = float(q @ q)
    inv = kl.quat_inverse(q)
    assert max_err(inv, conj(q) / n2) <= 1e-15 * np.abs(q).max() / n2
    assert max_err(hamilton_seed(q, inv), [1, 0, 0, 0]) < 1e-14
    assert max_err(hamilton_seed(inv, q), [1, 0, 0, 0]) < 1e-14
    u = kl.quat_normalize(q)
    assert abs(np.linalg.norm(u) - 1.0) < 1e-15
    assert max_err(u * np.linalg.norm(q), q) <= 1e-15 * np.linalg.norm(q) * 4


def test_zero_quaternion_raises():
    for fn in (kl.quat_inverse, kl.quat_normalize, kl.matrix_from_quat):
        with pytest.raises(kl.KinlibError, match="zero quaternion"):
            fn([0.0, 0.0, 0.0, 0.0])
    with pytest.raises(kl.KinlibError):
        kl.quat_rotate([0.0, 0.0, 0.0, 0.0], [1.0, 2.0, 3.0])
    batch = random_unit_quaternions(5, seed=301)
    batch[2] = 0.0
    with pytest.raises(kl.KinlibError, match=r"q\[2\]"):
        kl.quat_normalize(batch)
    with pytest.raises(kl.KinlibError, match=r"q\[2\]"):
        kl.quat_inverse(batch)


def test_conjugate_inverse_normalize_batched():
    rng = np.random.default_rng(302)
    q = rng.normal(size=(6, 7, 4))
    assert np.array_equal(kl.quat_conjugate(q), conj(q))
    n = np.linalg.norm(q, axis=-1, keepdims=True)
    assert max_err(kl.quat_normalize(q), q / n) < 1e-15
    assert max_err(kl.quat_inverse(q), conj(q) / n**2) < 1e-13


# --------------------------------------------------------------------------- rotating vectors


def test_quat_rotate_batch():
    rng = np.random.default_rng(303)
    q = rng.normal(size=(1000, 4))  # not unit: quat_rotate normalises
    v = rng.normal(size=(1000, 3)) * 5
    out = kl.quat_rotate(q, v)
    assert out.shape == (1000, 3)
    R = scipy_matrix(q)
    assert max_err(out, np.einsum("nij,nj->ni", R, v)) < 1e-13
    assert max_err(out, Rotation.from_quat(xyzw(q)).apply(v)) < 1e-13
    assert max_err(out, np.einsum("nij,nj->ni", kl.matrix_from_quat(q), v)) < 1e-13
    # q (0, v) q⁻¹, with an inverse that is not a conjugate for non-unit q
    inv = conj(q) / np.sum(q * q, axis=-1, keepdims=True)
    p = np.concatenate([np.zeros((1000, 1)), v], axis=-1)
    qpq = hamilton_seed(hamilton_seed(q, p), inv)
    assert np.abs(qpq[:, 0]).max() < 1e-13
    assert max_err(out, qpq[:, 1:]) < 1e-13
    # one rotation, many vectors
    assert max_err(kl.quat_rotate(q[0], v), v @ R[0].T) < 1e-13


@settings(max_examples=300, deadline=None)
@given(q=unit_quaternions(), v=vectors)
def test_quat_rotate_property(q, v):
    out = kl.quat_rotate(q, v)
    assert max_err(out, matrix_seed(q) @ v) < 1e-13
    assert max_err(out, kl.matrix_from_quat(q) @ v) < 1e-13
    qpq = kl.quat_multiply(kl.quat_multiply(q, np.concatenate([[0.0], v])), kl.quat_inverse(q))
    assert abs(qpq[0]) < 1e-13
    assert max_err(out, qpq[1:]) < 1e-13
    assert max_err(kl.quat_rotate(-q, v), out) < 1e-13


@settings(max_examples=300, deadline=None)
@given(q1=unit_quaternions(), q2=unit_quaternions())
def test_composition_order(q1, q2):
    # first q1, then q2: q2 q1 ↔ R2 R1 (seed 000: q3 = q2 q1)
    R1, R2 = scipy_matrix(q1), scipy_matrix(q2)
    assert max_err(kl.matrix_from_quat(kl.quat_multiply(q2, q1)), R2 @ R1) < 1e-13
    v = np.array([0.3, -1.2, 2.0])
    both = kl.quat_rotate(kl.quat_multiply(q2, q1), v)
    assert max_err(both, kl.quat_rotate(q2, kl.quat_rotate(q1, v))) < 1e-13


def test_composition_order_is_not_commutative():
    qx = kl.quat_from_axis_angle([1.0, 0.0, 0.0], PI / 2)
    qz = kl.quat_from_axis_angle([0.0, 0.0, 1.0], PI / 2)
    # x first then z: e_y → e_z (about x) → e_z (about z)
    assert max_err(kl.quat_rotate(kl.quat_multiply(qz, qx), [0.0, 1.0, 0.0]), [0, 0, 1]) < 1e-15
    # z first then x: e_y → −e_x → −e_x
    assert max_err(kl.quat_rotate(kl.quat_multiply(qx, qz), [0.0, 1.0, 0.0]), [-1, 0, 0]) < 1e-15


# --------------------------------------------------------------------------- matrices


def test_converters_are_index_shuffles():
    rng = np.random.default_rng(304)
    q = rng.normal(size=(3, 5, 4))
    assert np.array_equal(kl.quat_xyzw_from_wxyz(q), q[..., [1, 2, 3, 0]])
    assert np.array_equal(kl.quat_wxyz_from_xyzw(q), q[..., [3, 0, 1, 2]])
    assert np.array_equal(kl.quat_wxyz_from_xyzw(kl.quat_xyzw_from_wxyz(q)), q)
    assert np.array_equal(kl.quat_xyzw_from_wxyz([1.0, 2.0, 3.0, 4.0]), [2.0, 3.0, 4.0, 1.0])
    assert np.array_equal(kl.quat_wxyz_from_xyzw([2.0, 3.0, 4.0, 1.0]), [1.0, 2.0, 3.0, 4.0])


@pytest.mark.parametrize("n", [100, 3000])  # small batches: numpy; large: compiled kernels
def test_matrix_from_quat_and_back_match_scipy(n):
    q = random_unit_quaternions(n, seed=305)
    q[:10, 0] = 0.0  # exact half turns
    q[10:20, 0] = 1e-9  # near half turns
    q[:20] /= np.linalg.norm(q[:20], axis=-1, keepdims=True)
    R = kl.matrix_from_quat(q)
    assert R.shape == (n, 3, 3)
    assert max_err(R, Rotation.from_quat(kl.quat_xyzw_from_wxyz(q)).as_matrix()) < 1e-15 * 4
    assert max_err(R, matrix_seed(q)) < 1e-15 * 4
    assert max_err(kl.matrix_from_quat(3.7 * q), R) < 1e-15 * 4  # normalised first
    back = kl.quat_from_matrix(R)
    assert back.shape == (n, 4)
    assert np.all(back[:, 0] >= 0)
    ref = kl.quat_wxyz_from_xyzw(Rotation.from_matrix(R).as_quat(canonical=True))
    assert max_err(back[10:], ref[10:]) < 1e-14
    assert max(err_up_to_sign(back[i], ref[i]) for i in range(10)) < 1e-14  # w = 0
    assert max_err(back[10:], canonical(q[10:])) < 1e-14
    assert max(err_up_to_sign(back[i], q[i]) for i in range(10)) < 1e-14
    R2 = R.reshape(n // 10, 10, 3, 3)
    assert max_err(kl.quat_from_matrix(R2), back.reshape(n // 10, 10, 4)) < 1e-15
    assert max_err(kl.matrix_from_quat(q.reshape(n // 10, 10, 4)), R2) < 1e-15


@settings(max_examples=500, deadline=None)
@given(q=unit_quaternions())
def test_quaternion_matrix_round_trip(q):
    R = kl.matrix_from_quat(q)
    assert max_err(R, matrix_seed(q)) < 1e-15 * 4
    assert max_err(R, scipy_matrix(q)) < 1e-15 * 4
    assert max_err(kl.matrix_from_quat(-q), R) < 1e-15  # q and −q: the same rotation
    for M in (R, matrix_seed(q)):
        back = kl.quat_from_matrix(M)
        assert back[0] >= 0.0
        assert abs(np.linalg.norm(back) - 1.0) < 1e-15 * 2
        if abs(q[0]) > 1e-13:
            assert max_err(back, canonical(q)) < 1e-12
        else:  # a half turn: w = 0 and both signs of the vector part qualify
            assert err_up_to_sign(back, q) < 1e-12
        assert max_err(kl.matrix_from_quat(back), M) < 1e-14


@settings(max_examples=300, deadline=None)
@given(u=st.tuples(*[st.floats(-1.0, 1.0)] * 3).map(np.array))
def test_quat_from_matrix_exact_half_turns(u):
    assume(np.linalg.norm(u) > 1e-3)
    u = u / np.linalg.norm(u)
    R = 2.0 * np.outer(u, u) - np.eye(3)  # 180° about u, trace −1
    assert np.trace(R) == pytest.approx(-1.0, abs=4e-15)  # the construction itself rounds
    q = kl.quat_from_matrix(R)
    assert q[0] >= 0.0
    assert abs(q[0]) < 1e-15
    assert min(max_err(q[1:], u), max_err(q[1:], -u)) < 1e-14


def test_checkpoints_seed000():
    expected = {
        "identity": ([1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 1.0], 0.0, np.eye(3)),
        "180 about z": ([0.0, 0.0, 0.0, 1.0], [0.0, 0.0, 1.0], PI, kl.rotz(PI)),
        "90 about y": ([SQRT_HALF, 0.0, SQRT_HALF, 0.0], [0.0, 1.0, 0.0], PI / 2, kl.roty(PI / 2)),
        "-90 about x": (
            [SQRT_HALF, -SQRT_HALF, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            -PI / 2,
            kl.rotx(-PI / 2),
        ),
    }
    for name, (q, axis, angle, R) in expected.items():
        assert max_err(kl.quat_from_axis_angle(axis, angle), q) < 1e-15, name
        assert max_err(kl.quat_from_matrix(R), q) < 1e-15, name
        assert max_err(kl.matrix_from_quat(q), R) < 1e-15, name
    # −90° about x is +90° about −x
    q = kl.quat_from_axis_angle([-1.0, 0.0, 0.0], PI / 2)
    assert max_err(q, [SQRT_HALF, -SQRT_HALF, 0.0, 0.0]) < 1e-15
    assert np.array_equal(kl.quat_from_matrix(np.eye(3)), [1.0, 0.0, 0.0, 0.0])
    assert np.array_equal(kl.quat_from_matrix(np.diag([-1.0, -1.0, 1.0])), [0.0, 0.0, 0.0, 1.0])


# --------------------------------------------------------------------------- axis-angle


@settings(max_examples=300, deadline=None)
@given(
    u=st.tuples(*[st.floats(-1.0, 1.0)] * 3).map(np.array),
    theta=st.floats(-2 * PI, 2 * PI),
    scale=st.floats(0.01, 100.0),
)
def test_quat_axis_angle_round_trip(u, theta, scale):
    assume(np.linalg.norm(u) > 1e-3)
    u = u / np.linalg.norm(u)
    q = kl.quat_from_axis_angle(u * 2.5, theta)
    assert max_err(q, np.concatenate([[np.cos(theta / 2)], np.sin(theta / 2) * u])) < 1e-15
    assert max_err(kl.matrix_from_quat(q), Rotation.from_rotvec(u * theta).as_matrix()) < 1e-14
    axis, angle = kl.axis_angle_from_quat(q * scale)  # normalised first
    assert 0.0 <= angle <= PI
    assert abs(np.linalg.norm(axis) - 1.0) < 1e-14
    # hand-derived: θ mod 2π in [0, π] is the angle about u, else 2π − it about −u
    folded = theta % (2 * PI)
    sign = 1.0 if folded <= PI else -1.0
    folded = min(folded, 2 * PI - folded)
    assert abs(angle - folded) < 1e-12
    if 1e-6 < folded < PI - 1e-6:
        assert max_err(axis, sign * u) < 1e-9
    elif folded >= PI - 1e-6:
        assert min(max_err(axis, u), max_err(axis, -u)) < 1e-9
    assert max_err(kl.quat_from_axis_angle(axis, angle), canonical(q)) < 1e-12


def test_axis_angle_from_quat_identity_and_batch():
    axis, angle = kl.axis_angle_from_quat([1.0, 0.0, 0.0, 0.0])
    assert np.array_equal(axis, [1.0, 0.0, 0.0]) and angle == 0.0
    axis, angle = kl.axis_angle_from_quat([-2.0, 0.0, 0.0, 0.0])  # −1 is the identity too
    assert angle == 0.0
    # tiny angles, where |v|² underflows: the axis is still a unit vector
    for theta in (1e-155, 1e-200, 1e-290):
        u = np.array([0.48, -0.6, 0.64])
        axis, angle = kl.axis_angle_from_quat(np.concatenate([[1.0], np.sin(theta / 2) * u]))
        assert max_err(axis, u) < 1e-15
        assert abs(angle - theta) <= 1e-15 * theta
    rng = np.random.default_rng(306)
    u = rng.normal(size=(4, 6, 3))
    u /= np.linalg.norm(u, axis=-1, keepdims=True)
    t = rng.uniform(0, PI, size=(4, 6))
    q = kl.quat_from_axis_angle(u, t)
    assert q.shape == (4, 6, 4)
    axis, angle = kl.axis_angle_from_quat(q)
    assert axis.shape == (4, 6, 3) and angle.shape == (4, 6)
    assert max_err(angle, t) < 1e-14
    assert max_err(axis, u) < 1e-12


# --------------------------------------------------------------------------- slerp


def test_slerp_endpoints_and_hand_example():
    q0 = [1.0, 0.0, 0.0, 0.0]
    q1 = [np.cos(PI / 4), 0.0, 0.0, np.sin(PI / 4)]  # 90° about z
    half = kl.quat_slerp(q0, q1, 0.5)
    assert max_err(half, [np.cos(PI / 8), 0.0, 0.0, np.sin(PI / 8)]) < 1e-15  # 45°
    qs = random_unit_quaternions(200, seed=307)
    a, b = qs[:100], qs[100:]
    assert max_err(kl.quat_slerp(a, b, 0.0), a) < 1e-15
    b_short = np.where(np.sum(a * b, axis=-1, keepdims=True) < 0, -b, b)
    assert max_err(kl.quat_slerp(a, b, 1.0), b_short) < 1e-15


@settings(max_examples=300, deadline=None)
@given(q0=unit_quaternions(), q1=unit_quaternions(), t=st.floats(0.0, 1.0))
def test_slerp_constant_speed_shortest_path(q0, q1, t):
    q = kl.quat_slerp(q0, q1, t)
    assert abs(np.linalg.norm(q) - 1.0) < 1e-15 * 2
    total = rotation_angle_between(q0, q1)  # in [0, π]: the short way round
    assert abs(rotation_angle_between(q0, q) - t * total) < 1e-12
    assert abs(rotation_angle_between(q, q1) - (1.0 - t) * total) < 1e-12
    # shortest path: −q1 is the same rotation and gives the same curve (unless q1 q0⁻¹ is
    # a half turn, when both ways round are equally short)
    if abs(q0 @ q1) > 1e-9:
        assert max_err(kl.quat_slerp(q0, -q1, t), q) < 1e-15 * 4
    # non-unit input is normalised
    assert max_err(kl.quat_slerp(3.0 * q0, 0.5 * q1, t), q) < 1e-15 * 4


def test_slerp_matches_scipy():
    qs = random_unit_quaternions(60, seed=308)
    times = np.linspace(0.0, 1.0, 11)
    for a, b in zip(qs[:30], qs[30:], strict=True):
        ref = Slerp([0.0, 1.0], Rotation.from_quat(xyzw(np.stack([a, b]))))(times).as_matrix()
        ours = kl.quat_slerp(a, b, times)
        assert ours.shape == (11, 4)
        assert max_err(kl.matrix_from_quat(ours), ref) < 1e-13


def test_slerp_batched_t():
    qs = random_unit_quaternions(10, seed=309)
    a, b = qs[:5], qs[5:]
    t = np.linspace(0.0, 1.0, 7)
    # one pair, t of shape (M,)
    out = kl.quat_slerp(a[0], b[0], t)
    assert out.shape == (7, 4)
    for m in range(7):
        assert max_err(out[m], kl.quat_slerp(a[0], b[0], t[m])) < 1e-15
    # N pairs, t of shape (M, 1): every pair at every time
    out = kl.quat_slerp(a, b, t[:, None])
    assert out.shape == (7, 5, 4)
    for m in range(7):
        for n in range(5):
            assert max_err(out[m, n], kl.quat_slerp(a[n], b[n], t[m])) < 1e-15
    # N pairs, t of shape (N,): pairwise
    out = kl.quat_slerp(a, b, t[:5])
    assert out.shape == (5, 4)
    for n in range(5):
        assert max_err(out[n], kl.quat_slerp(a[n], b[n], t[n])) < 1e-15


@settings(max_examples=200, deadline=None)
@given(
    q0=unit_quaternions(),
    u=st.tuples(*[st.floats(-1.0, 1.0)] * 3).map(np.array),
    eps=st.floats(1e-15, 1e-6),
    t=st.floats(0.0, 1.0),
)
def test_slerp_tiny_angles(q0, u, eps, t):
    assume(np.linalg.norm(u) > 1e-3)
    u = u / np.linalg.norm(u)

    def small(theta):
        return np.concatenate([[np.cos(theta / 2)], np.sin(theta / 2) * u])

    # from the identity: the vector part must be accurate in relative terms
    q = kl.quat_slerp([1.0, 0.0, 0.0, 0.0], small(eps), t)
    assert np.all(np.isfinite(q))
    assert abs(q[0] - np.cos(t * eps / 2)) < 1e-15
    assert max_err(q[1:], np.sin(t * eps / 2) * u) <= 1e-9 * np.sin(eps / 2)
    # from anywhere: absolutely accurate
    q1 = hamilton_seed(q0, small(eps))
    q = kl.quat_slerp(q0, q1, t)
    assert np.all(np.isfinite(q))
    assert max_err(q, hamilton_seed(q0, small(t * eps))) < 1e-14
    # the same quaternion twice
    assert max_err(kl.quat_slerp(q0, q0, t), q0) < 1e-15


def test_slerp_between_opposite_and_equal_quaternions():
    q = random_unit_quaternions(1, seed=310)[0]
    for t in (0.0, 0.3, 1.0):
        assert max_err(kl.quat_slerp(q, q, t), q) < 1e-15
        assert max_err(kl.quat_slerp(q, -q, t), q) < 1e-15  # −q is the same rotation


@pytest.mark.parametrize("t", [-0.1, 1.1, -1e-12, 1.0 + 1e-12, [0.0, 0.5, 2.0]])
def test_slerp_rejects_t_outside_unit_interval(t):
    with pytest.raises(kl.KinlibError, match=r"\[0, 1\]"):
        kl.quat_slerp([1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 1.0], t)
