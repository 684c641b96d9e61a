"""Homogeneous transforms: layout, closed-form inverse, compounding, mapping points and free
vectors, similarity transforms, and the rigid-transform check.

Expected values come from plain numpy (``np.linalg.inv``, ``R @ p + t``, 4×4 products with
homogeneous coordinates), from scipy's ``Rotation`` or from geometric facts (points on a
rotation axis stay put) — never from the kinlib function under test.
"""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from reference import unit_vectors
from scipy.spatial.transform import Rotation

import kinlib as kl

# --------------------------------------------------------------------------- strategies

coords = st.floats(-100.0, 100.0, allow_nan=False, allow_infinity=False)
vec3 = st.tuples(coords, coords, coords).map(np.array)
angles = st.floats(-2 * np.pi, 2 * np.pi, allow_nan=False, allow_infinity=False)

# Special rotations typed by hand: identity, half turns about the coordinate axes, quarter turns.
SPECIAL_ROTATIONS = [
    np.eye(3),
    np.diag([1.0, -1.0, -1.0]),
    np.diag([-1.0, 1.0, -1.0]),
    np.diag([-1.0, -1.0, 1.0]),
    np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]),
    np.array([[0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]]),
]


@st.composite
def generic_rotations(draw):
    """Rotation matrices built by scipy from a (normalised) random quaternion."""
    q = np.array(draw(st.tuples(*[st.floats(-1.0, 1.0)] * 4)))
    if q @ q < 1e-6:
        q = np.array([0.0, 0.0, 0.0, 1.0])
    return Rotation.from_quat(q).as_matrix()  # scipy: [x, y, z, w]


rotations = st.one_of(generic_rotations(), st.sampled_from(SPECIAL_ROTATIONS))



def hom(R, p):
    """A 4×4 homogeneous transform assembled with plain numpy."""
    T = np.eye(4)
    T[:3, :3] = R
    T[:3, 3] = p
    return T


@st.composite
def rigid_transforms(draw):
    return hom(draw(rotations), draw(vec3))


def random_transforms(n, seed):
    rng = np.random.default_rng(seed)
    Rs = Rotation.random(n, rng=rng).as_matrix()
    ps = rng.uniform(-10.0, 10.0, (n, 3))
    T = np.zeros((n, 4, 4))
    T[:, :3, :3] = Rs
    T[:, :3, 3] = ps
    T[:, 3, 3] = 1.0
    return T


def apply_h(T, p):
    """T applied to a point p with a homogeneous 1, as a plain matrix-vector product."""
    return (T @ np.append(p, 1.0))[:3]


TOL = 1e-9

# --------------------------------------------------------------------------- transform()


@settings(max_examples=50, deadline=None)
@given(R=rotations, p=vec3)
def test_transform_layout(R, p):
    T = kl.transform(R, p)
    assert T.shape == (4, 4)
    assert T.dtype == np.float64
    np.testing.assert_array_equal(T[:3, :3], R)
    np.testing.assert_array_equal(T[:3, 3], p)
    np.testing.assert_array_equal(T[3], [0.0, 0.0, 0.0, 1.0])


def test_transform_defaults():
    np.testing.assert_array_equal(kl.transform(), np.eye(4))
    R = Rotation.from_rotvec([0.1, -0.2, 0.3]).as_matrix()
    np.testing.assert_array_equal(kl.transform(R), hom(R, np.zeros(3)))
    np.testing.assert_array_equal(kl.transform(p=[1.0, 2.0, 3.0]), hom(np.eye(3), [1, 2, 3]))
    # lists are accepted as well as arrays
    np.testing.assert_array_equal(kl.transform(R.tolist(), [4, 5, 6]), hom(R, [4.0, 5.0, 6.0]))


@pytest.mark.parametrize(
    ("r_shape", "p_shape", "out_shape"),
    [
        ((5,), (), (5,)),
        ((), (5,), (5,)),
        ((5,), (5,), (5,)),
        ((2, 1), (4,), (2, 4)),
        ((1,), (3, 1), (3, 1)),
    ],
)
def test_transform_batches_broadcast(r_shape, p_shape, out_shape):
    rng = np.random.default_rng(1)
    n_r = int(np.prod(r_shape))
    R = Rotation.random(n_r, rng=rng).as_matrix().reshape(r_shape + (3, 3))
    p = rng.normal(size=p_shape + (3,))
    T = kl.transform(R, p)
    assert T.shape == out_shape + (4, 4)
    Rb = np.broadcast_to(R, out_shape + (3, 3))
    pb = np.broadcast_to(p, out_shape + (3,))
    for idx in np.ndindex(out_shape):
        np.testing.assert_array_equal(T[idx], hom(Rb[idx], pb[idx]))


def test_transform_rejects_non_rotation():
    with pytest.raises(kl.KinlibError, match="not a rotation"):
        kl.transform(2.0 * np.eye(3), [0.0, 0.0, 0.0])
    with pytest.raises(kl.KinlibError, match="reflection"):
        kl.transform(np.diag([1.0, 1.0, -1.0]))


# --------------------------------------------------------------------------- inverse


@settings(max_examples=100, deadline=None)
@given(T=rigid_transforms())
def test_transform_inverse_equals_linalg_inv(T):
    Ti = kl.transform_inverse(T)
    np.testing.assert_allclose(Ti, np.linalg.inv(T), rtol=0, atol=TOL)
    np.testing.assert_allclose(T @ Ti, np.eye(4), rtol=0, atol=TOL)
    np.testing.assert_allclose(Ti @ T, np.eye(4), rtol=0, atol=TOL)
    # the bottom row is exact, not merely close
    np.testing.assert_array_equal(Ti[3], [0.0, 0.0, 0.0, 1.0])


@settings(max_examples=50, deadline=None)
@given(T=rigid_transforms(), p=vec3)
def test_transform_inverse_undoes_the_mapping(T, p):
    # ^B p = ^B T_A ^A p  with  ^A p = ^A T_B ^B p
    p_A = apply_h(T, p)
    np.testing.assert_allclose(apply_h(kl.transform_inverse(T), p_A), p, rtol=0, atol=TOL)


def test_transform_inverse_batched():
    T = random_transforms(50, seed=2).reshape(5, 10, 4, 4)
    Ti = kl.transform_inverse(T)
    assert Ti.shape == (5, 10, 4, 4)
    np.testing.assert_allclose(Ti, np.linalg.inv(T), rtol=0, atol=TOL)


def test_transform_inverse_of_inverse_is_identity_map():
    T = random_transforms(20, seed=3)
    np.testing.assert_allclose(kl.transform_inverse(kl.transform_inverse(T)), T, atol=1e-12)


# --------------------------------------------------------------------------- compounding


@settings(max_examples=75, deadline=None)
@given(T_AB=rigid_transforms(), T_BC=rigid_transforms(), p_C=vec3)
def test_compounding_maps_points_like_applying_both(T_AB, T_BC, p_C):
    T_AC = T_AB @ T_BC
    p_B = T_BC[:3, :3] @ p_C + T_BC[:3, 3]
    p_A = T_AB[:3, :3] @ p_B + T_AB[:3, 3]
    np.testing.assert_allclose(kl.transform_points(T_AC, p_C), p_A, rtol=0, atol=TOL)
    np.testing.assert_allclose(
        kl.transform_points(T_AB, kl.transform_points(T_BC, p_C)), p_A, rtol=0, atol=TOL
    )
    # ^C T_A = ^C T_B ^B T_A
    np.testing.assert_allclose(
        kl.transform_inverse(T_AC),
        kl.transform_inverse(T_BC) @ kl.transform_inverse(T_AB),
        rtol=0,
        atol=TOL,
    )


# --------------------------------------------------------------------------- points


@settings(max_examples=75, deadline=None)
@given(T=rigid_transforms(), p=vec3)
def test_transform_points_is_R_p_plus_t(T, p):
    out = kl.transform_points(T, p)
    assert out.shape == (3,)
    np.testing.assert_allclose(out, T[:3, :3] @ p + T[:3, 3], rtol=0, atol=TOL)
    np.testing.assert_allclose(out, apply_h(T, p), rtol=0, atol=TOL)


def test_transform_points_one_transform_many_points():
    T = random_transforms(1, seed=4)[0]
    P = np.random.default_rng(5).normal(size=(7, 3))
    out = kl.transform_points(T, P)
    assert out.shape == (7, 3)
    np.testing.assert_allclose(out, P @ T[:3, :3].T + T[:3, 3], rtol=0, atol=TOL)


def test_transform_points_many_transforms_one_point():
    T = random_transforms(6, seed=6)
    p = np.array([0.3, -1.2, 2.5])
    out = kl.transform_points(T, p)
    assert out.shape == (6, 3)
    for i in range(6):
        np.testing.assert_allclose(out[i], apply_h(T[i], p), rtol=0, atol=TOL)


def test_transform_points_pairwise():
    T = random_transforms(8, seed=7)
    P = np.random.default_rng(8).normal(size=(8, 3))
    out = kl.transform_points(T, P)
    assert out.shape == (8, 3)
    for i in range(8):
        np.testing.assert_allclose(out[i], apply_h(T[i], P[i]), rtol=0, atol=TOL)


def test_transform_points_outer_broadcast():
    T = random_transforms(3, seed=9)[:, None]  # (3, 1, 4, 4)
    P = np.random.default_rng(10).normal(size=(5, 3))  # (5, 3)
    out = kl.transform_points(T, P)
    assert out.shape == (3, 5, 3)
    for i in range(3):
        for j in range(5):
            np.testing.assert_allclose(out[i, j], apply_h(T[i, 0], P[j]), rtol=0, atol=TOL)


def test_transform_points_batches_that_do_not_broadcast():
    with pytest.raises(kl.KinlibError, match="do not broadcast"):
        kl.transform_points(random_transforms(2, seed=11), np.zeros((3, 3)))


# --------------------------------------------------------------------------- free vectors


@settings(max_examples=75, deadline=None)
@given(T=rigid_transforms(), a=vec3, b=vec3)
def test_transform_vectors_ignore_translation(T, a, b):
    v = kl.transform_vectors(T, a)
    np.testing.assert_allclose(v, T[:3, :3] @ a, rtol=0, atol=TOL)
    # a free vector carries a homogeneous 0
    np.testing.assert_allclose(v, (T @ np.append(a, 0.0))[:3], rtol=0, atol=TOL)
    # the same as with the translation removed
    np.testing.assert_allclose(v, kl.transform_vectors(hom(T[:3, :3], [0, 0, 0]), a), atol=TOL)
    # lengths are kept
    np.testing.assert_allclose(np.linalg.norm(v), np.linalg.norm(a), rtol=0, atol=TOL)
    # the difference of two mapped points is the mapped difference vector
    np.testing.assert_allclose(
        kl.transform_points(T, a) - kl.transform_points(T, b),
        kl.transform_vectors(T, a - b),
        rtol=0,
        atol=TOL,
    )


def test_transform_vectors_pure_translation_is_identity():
    T = hom(np.eye(3), [10.0, 5.0, -3.0])
    V = np.random.default_rng(12).normal(size=(4, 3))
    np.testing.assert_array_equal(kl.transform_vectors(T, V), V)


def test_transform_vectors_batched():
    T = random_transforms(6, seed=13)
    V = np.random.default_rng(14).normal(size=(6, 3))
    out = kl.transform_vectors(T, V)
    assert out.shape == (6, 3)
    np.testing.assert_allclose(out, np.einsum("nij,nj->ni", T[:, :3, :3], V), atol=TOL)


# --------------------------------------------------------------------------- similarity


@settings(max_examples=75, deadline=None)
@given(T_AB=rigid_transforms(), k=unit_vectors(), theta=angles, c_B=vec3, x_A=vec3)
def test_similarity_transform_rotates_about_the_mapped_axis(T_AB, k, theta, c_B, x_A):
    # The operator Op_B turns by θ about the line through c_B with direction k (both in {B}).
    R_k = Rotation.from_rotvec(theta * k).as_matrix()
    Op_B = hom(R_k, c_B - R_k @ c_B)
    # The same operator written in {A}: ^A T_B Op_B (^A T_B)^-1.
    Op_A = T_AB @ Op_B @ kl.transform_inverse(T_AB)
    R_AB, p_AB = T_AB[:3, :3], T_AB[:3, 3]
    k_A, c_A = R_AB @ k, R_AB @ c_B + p_AB  # the axis seen from {A}
    # points on the mapped axis stay where they are
    for s in (-3.0, 0.0, 2.5):
        on_axis = c_A + s * k_A
        np.testing.assert_allclose(apply_h(Op_A, on_axis), on_axis, rtol=0, atol=TOL)
    # its rotation part turns by θ about k_A
    R_expected = Rotation.from_rotvec(theta * k_A).as_matrix()
    np.testing.assert_allclose(Op_A[:3, :3], R_expected, rtol=0, atol=TOL)
    # and any point turns about the mapped line
    np.testing.assert_allclose(
        apply_h(Op_A, x_A), c_A + R_expected @ (x_A - c_A), rtol=0, atol=1e-8
    )
    np.testing.assert_array_equal(Op_A[3], [0.0, 0.0, 0.0, 1.0])


def test_similarity_transform_of_a_rotation_about_z():
    # Frame {B} sits at (1, 2, 0) in {A}, turned 90° about z. A quarter turn about B's z axis
    # is a quarter turn about the vertical line through (1, 2, 0) in {A}: (2, 2, 0) -> (1, 3, 0).
    T_AB = hom(np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]), [1.0, 2.0, 0.0])
    Op_B = hom(np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]), [0.0, 0.0, 0.0])
    Op_A = T_AB @ Op_B @ kl.transform_inverse(T_AB)
    np.testing.assert_allclose(apply_h(Op_A, [2.0, 2.0, 0.0]), [1.0, 3.0, 0.0], atol=1e-15)
    np.testing.assert_allclose(apply_h(Op_A, [1.0, 2.0, 7.0]), [1.0, 2.0, 7.0], atol=1e-15)


# --------------------------------------------------------------------------- check_transform


@settings(max_examples=25, deadline=None)
@given(T=rigid_transforms())
def test_check_transform_accepts_rigid_transforms(T):
    out = kl.check_transform(T)
    assert out.dtype == np.float64
    np.testing.assert_array_equal(out, T)
    np.testing.assert_array_equal(kl.check_transform(T.tolist()), T)


@pytest.mark.parametrize(
    "row",
    [
        [0.0, 0.0, 1.0, 1.0],
        [0.0, 0.0, 0.0, 2.0],
        [1.0, 0.0, 0.0, 1.0],
        [0.0, 0.0, 0.0, 0.0],
        [0.0, 1e-3, 0.0, 1.0],
    ],
)
def test_check_transform_rejects_bad_bottom_rows(row):
    T = hom(np.eye(3), [1.0, 2.0, 3.0])
    T[3] = row
    for f in (kl.check_transform, kl.transform_inverse):
        with pytest.raises(kl.KinlibError) as info:
            f(T)
        msg = str(info.value)
        assert "bottom row" in msg and "[0, 0, 0, 1]" in msg
    with pytest.raises(kl.KinlibError, match="bottom row"):
        kl.transform_points(T, [0.0, 0.0, 0.0])
    with pytest.raises(kl.KinlibError, match="bottom row"):
        kl.transform_vectors(T, [0.0, 0.0, 0.0])


@pytest.mark.parametrize(
    ("block", "words"),
    [
        (2.0 * np.eye(3), ["not a rotation", "orthonormal"]),
        (np.diag([1.0, 1.0, -1.0]), ["not a rotation", "det", "reflection"]),
        (-np.eye(3), ["not a rotation", "det"]),
        (np.array([[1.0, 0.5, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]), ["orthonormal"]),
        (np.zeros((3, 3)), ["not a rotation"]),
        (1.001 * Rotation.from_rotvec([0.3, 0.2, 0.1]).as_matrix(), ["orthonormal"]),
    ],
)
def test_check_transform_rejects_non_rotation_blocks(block, words):
    T = hom(block, [1.0, 2.0, 3.0])
    for f in (kl.check_transform, kl.transform_inverse, kl.dual_quat_from_transform):
        with pytest.raises(kl.KinlibError) as info:
            f(T)
        msg = str(info.value)
        for w in words:
            assert w in msg, msg
        assert "T[:3, :3]" in msg  # says which part of T is wrong


def test_check_transform_names_the_bad_member_of_a_batch():
    T = random_transforms(4, seed=15)
    T[2, 3] = [0.0, 0.0, 0.5, 1.0]
    with pytest.raises(kl.KinlibError, match=r"T\[2\]: the bottom row"):
        kl.check_transform(T)
    T = random_transforms(4, seed=16)
    T[1, :3, :3] *= 3.0
    with pytest.raises(kl.KinlibError, match=r"\[1\]"):
        kl.check_transform(T)


def test_check_transform_uses_the_given_name_and_wrong_shape():
    with pytest.raises(kl.KinlibError, match="T_ee: the bottom row"):
        kl.check_transform(np.ones((4, 4)), name="T_ee")
    with pytest.raises(kl.KinlibError) as info:
        kl.check_transform(np.eye(3))
    msg = str(info.value)
    assert "expected" in msg and "(..., 4, 4)" in msg and "(3, 3)" in msg


def test_check_transform_tolerance():
    T = hom(np.eye(3), [0.0, 0.0, 0.0])
    T[:3, :3] *= 1.0 + 1e-4
    with pytest.raises(kl.KinlibError, match="orthonormal"):
        kl.check_transform(T)
    np.testing.assert_array_equal(kl.check_transform(T, tol=1e-3), T)
    for bad_tol in ("a", np.nan, -1.0, [1e-3, 1e-2], None):
        with pytest.raises(kl.KinlibError, match="tol"):
            kl.check_transform(T, tol=bad_tol)
