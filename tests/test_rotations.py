"""Elementary rotations, skew/vee, the rotation checks and the nearest rotation.

Expected values come from matrices typed out as in the textbooks, from scipy, from plain
numpy (np.cross, an SVD written here, scipy.linalg.polar) or from geometric facts — never
from the kinlib function under test.
"""

import re
import warnings

import numpy as np
import pytest
import scipy.linalg
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

import kinlib as kl

TAU = 2 * np.pi

# --------------------------------------------------------------------------- strategies

finite_angles = st.floats(-4 * np.pi, 4 * np.pi, allow_nan=False, allow_infinity=False)
vec3 = st.tuples(*[st.floats(-1e3, 1e3, allow_nan=False)] * 3).map(np.array)


@st.composite
def rotation_matrices(draw):
    """Rotation matrices from unit quaternions (scipy builds the matrix)."""
    q = np.array(draw(st.tuples(*[st.floats(-1.0, 1.0)] * 4)))
    if np.dot(q, q) < 1e-6:
        q = np.array([0.0, 0.0, 0.0, 1.0])
    return Rotation.from_quat(q).as_matrix()  # scipy: xyzw; any unit q is a rotation


def random_rotations(n, seed):
    return Rotation.random(n, rng=np.random.default_rng(seed)).as_matrix()


def textbook_rx(t):
    c, s = np.cos(t), np.sin(t)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def textbook_ry(t):
    c, s = np.cos(t), np.sin(t)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def textbook_rz(t):
    c, s = np.cos(t), np.sin(t)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


AXES = [
    (kl.rotx, textbook_rx, "x", 0),
    (kl.roty, textbook_ry, "y", 1),
    (kl.rotz, textbook_rz, "z", 2),
]
AXIS_IDS = ["rotx", "roty", "rotz"]

# --------------------------------------------------------------------------- rotx/roty/rotz


@pytest.mark.parametrize(("fn", "textbook", "letter", "axis"), AXES, ids=AXIS_IDS)
def test_elementary_rotation_at_right_angles_exactly(fn, textbook, letter, axis):
    # Geometric facts: a quarter turn about z takes x to y, about x takes y to z, about
    # y takes z to x (right-handed, active).
    e = np.eye(3)
    nxt, nxt2 = (axis + 1) % 3, (axis + 2) % 3
    R = fn(np.pi / 2)
    assert np.allclose(R @ e[nxt], e[nxt2], atol=1e-15, rtol=0)
    assert np.allclose(R @ e[nxt2], -e[nxt], atol=1e-15, rtol=0)
    assert np.array_equal(R @ e[axis], e[axis])
    assert np.array_equal(fn(0.0), np.eye(3))


@pytest.mark.parametrize(("fn", "textbook", "letter", "axis"), AXES, ids=AXIS_IDS)
@pytest.mark.parametrize("t", [0.0, 0.3, -1.1, np.pi / 2, np.pi, -np.pi, 2.5, 7.0, 1e-9])
def test_elementary_rotation_equals_textbook_matrix(fn, textbook, letter, axis, t):
    R = fn(t)
    assert R.shape == (3, 3)
    assert R.dtype == np.float64
    assert np.allclose(R, textbook(t), atol=1e-15, rtol=0)


@pytest.mark.parametrize(("fn", "textbook", "letter", "axis"), AXES, ids=AXIS_IDS)
def test_elementary_rotation_batched_matches_scipy(fn, textbook, letter, axis):
    rng = np.random.default_rng(1)
    t = rng.uniform(-10, 10, size=(40, 25))
    R = fn(t)
    assert R.shape == (40, 25, 3, 3)
    expected = Rotation.from_euler(letter, t.reshape(-1, 1)).as_matrix().reshape(40, 25, 3, 3)
    assert np.abs(R - expected).max() < 1e-14
    # and against the typed-out matrix, element by element
    for idx in [(0, 0), (7, 3), (39, 24)]:
        assert np.allclose(R[idx], textbook(t[idx]), atol=1e-15, rtol=0)


@pytest.mark.parametrize(("fn", "textbook", "letter", "axis"), AXES, ids=AXIS_IDS)
@settings(max_examples=150, deadline=None)
@given(a=finite_angles, b=finite_angles)
def test_elementary_rotation_properties(fn, textbook, letter, axis, a, b):
    Ra, Rb = fn(a), fn(b)
    # rotations about one axis compose by adding angles, and the inverse is the transpose
    assert np.allclose(Ra @ Rb, textbook(a + b), atol=1e-13, rtol=0)
    assert np.allclose(Ra.T @ Ra, np.eye(3), atol=1e-15, rtol=0)
    assert abs(np.linalg.det(Ra) - 1.0) < 1e-14
    assert np.allclose(fn(-a), Ra.T, atol=1e-15, rtol=0)
    assert np.allclose(Ra, Rotation.from_euler(letter, a).as_matrix(), atol=1e-14, rtol=0)


# --------------------------------------------------------------------------- skew / vee


def test_skew_typed_out():
    S = kl.skew([1.0, 2.0, 3.0])
    assert np.array_equal(S, [[0.0, -3.0, 2.0], [3.0, 0.0, -1.0], [-2.0, 1.0, 0.0]])


@settings(max_examples=300, deadline=None)
@given(a=vec3, b=vec3)
def test_skew_is_the_cross_product_matrix(a, b):
    S = kl.skew(a)
    assert np.allclose(S @ b, np.cross(a, b), rtol=0, atol=1e-9 * (1 + np.abs(a).max() ** 2))
    assert np.array_equal(S, -S.T)
    assert np.array_equal(kl.vee(S), a)


def test_skew_vee_batched():
    rng = np.random.default_rng(2)
    a = rng.normal(size=(1000, 3))
    b = rng.normal(size=(1000, 3))
    S = kl.skew(a)
    assert S.shape == (1000, 3, 3)
    assert np.allclose(np.einsum("nij,nj->ni", S, b), np.cross(a, b), atol=1e-14, rtol=0)
    assert np.array_equal(kl.vee(S), a)
    a4 = a.reshape(10, 100, 3)
    assert np.array_equal(kl.vee(kl.skew(a4)), a4)


@pytest.mark.parametrize(
    "M",
    [
        np.eye(3),
        [[0.0, -3.0, 2.0], [3.0, 0.0, -1.0], [-2.0, 1.0, 1e-3]],
        [[0.0, -3.0, 2.0], [3.0, 0.0, -1.0], [-2.0, 1.1, 0.0]],
        np.ones((3, 3)),
    ],
    ids=["identity", "diagonal-entry", "asymmetric-pair", "ones"],
)
def test_vee_rejects_non_skew_matrices(M):
    with pytest.raises(kl.KinlibError, match="skew"):
        kl.vee(M)


def test_vee_rejects_a_non_skew_matrix_in_a_batch_and_names_it():
    S = kl.skew(np.random.default_rng(3).normal(size=(6, 3)))
    S[4, 0, 0] = 0.5
    with pytest.raises(kl.KinlibError, match=re.escape("S[4]")):
        kl.vee(S)


# --------------------------------------------------------------------------- is_rotation


def test_is_rotation_true_for_random_rotations():
    R = random_rotations(2000, seed=4)
    ok = kl.is_rotation(R)
    assert ok.shape == (2000,)
    assert ok.dtype == bool
    assert ok.all()
    assert kl.is_rotation(R[0]) is True
    assert kl.is_rotation(R.reshape(40, 50, 3, 3)).shape == (40, 50)
    # check_rotation returns the same values as a float array
    assert np.array_equal(kl.check_rotation(R), R)


@settings(max_examples=300, deadline=None)
@given(R=rotation_matrices())
def test_is_rotation_true_for_rotations_from_quaternions(R):
    assert kl.is_rotation(R) is True
    assert kl.is_rotation(R, tol=1e-12) is True
    kl.check_rotation(R, tol=1e-12)


def _orth_error(M):
    """max |MᵀM − I| over the nine entries, computed here independently."""
    M = np.asarray(M, dtype=float)
    return np.abs(np.swapaxes(M, -1, -2) @ M - np.eye(3)).max(axis=(-2, -1))


def _bad_matrices():
    rng = np.random.default_rng(5)
    R = random_rotations(3, seed=6)
    shear = np.eye(3)
    shear[0, 1] = 0.05
    return {
        "scaled": (1.01 * R[0], "orthonormal"),
        "shrunk": (0.9 * R[1], "orthonormal"),
        "sheared": (R[2] @ shear, "orthonormal"),
        "noisy": (R[0] + 1e-3 * rng.normal(size=(3, 3)), "orthonormal"),
        "reflection-z": (np.diag([1.0, 1.0, -1.0]), "det"),
        "point-reflection": (-R[1], "det"),
        "mirrored-rotation": (R[2] @ np.diag([1.0, -1.0, 1.0]), "det"),
        "zero": (np.zeros((3, 3)), "orthonormal"),
    }


BAD = _bad_matrices()


@pytest.mark.parametrize("name", list(BAD))
def test_is_rotation_false_and_check_rotation_says_why(name):
    M, what = BAD[name]
    assert kl.is_rotation(M) is False
    with pytest.raises(kl.KinlibError) as info:
        kl.check_rotation(M)
    msg = str(info.value)
    assert what in msg
    if what == "orthonormal":
        assert "det" not in msg.replace("determinant", "")
        # the size of the error, as max |RᵀR − I| (3 significant digits)
        assert f"{_orth_error(M):.3g}" in msg
    else:
        assert "orthonormal" not in msg
        assert _orth_error(M) < 1e-12
        det = np.linalg.det(M)
        assert det == pytest.approx(-1.0, abs=1e-12)
        assert re.search(r"det R = -1,", msg), msg
        assert "reflection" in msg


def test_check_rotation_error_size_scales_with_the_error():
    for s, text in [(1.01, "0.0201"), (1.1, "0.21"), (1.0 + 1e-4, "0.0002")]:
        with pytest.raises(kl.KinlibError, match=re.escape(text)):
            kl.check_rotation(s * np.eye(3))
    # within the tolerance: accepted, and the tolerance argument is honoured
    kl.check_rotation((1.0 + 1e-8) * np.eye(3))
    with pytest.raises(kl.KinlibError, match="orthonormal"):
        kl.check_rotation((1.0 + 1e-8) * np.eye(3), tol=1e-10)
    assert kl.is_rotation((1.0 + 1e-8) * np.eye(3), tol=1e-10) is False


@pytest.mark.parametrize("name", ["scaled", "sheared", "reflection-z", "point-reflection"])
def test_check_rotation_names_the_bad_matrix_in_a_batch(name):
    M, what = BAD[name]
    batch = random_rotations(8, seed=7)
    batch[3] = M
    ok = kl.is_rotation(batch)
    assert ok.tolist() == [True, True, True, False, True, True, True, True]
    with pytest.raises(kl.KinlibError, match=re.escape("R[3]")) as info:
        kl.check_rotation(batch)
    assert what in str(info.value)
    # a batch large enough for the compiled kernels (kinlib._accel.MIN_BATCH)
    big = random_rotations(5000, seed=13)
    big[[3, 4000]] = M
    assert np.flatnonzero(~kl.is_rotation(big)).tolist() == [3, 4000]
    with pytest.raises(kl.KinlibError, match=re.escape("R[3] (and 1 more of 5000)")) as info:
        kl.check_rotation(big)
    assert what in str(info.value)
    # two-dimensional batch: the index has two parts
    batch2 = np.broadcast_to(np.eye(3), (2, 5, 3, 3)).copy()
    batch2[1, 2] = M
    with pytest.raises(kl.KinlibError, match=re.escape("R[1, 2]")):
        kl.check_rotation(batch2)


def test_check_rotation_uses_the_given_name():
    with pytest.raises(kl.KinlibError, match=r"^R_AB\[1\]"):
        kl.check_rotation(np.stack([np.eye(3), 2 * np.eye(3)]), name="R_AB")


def test_is_rotation_false_for_non_finite():
    M = np.eye(3)
    M[1, 1] = np.nan
    assert kl.is_rotation(M) is False
    M[1, 1] = np.inf
    assert kl.is_rotation(np.stack([np.eye(3), M])).tolist() == [True, False]
    big = random_rotations(5000, seed=14)  # compiled-kernel path
    big[10, 0, 0] = np.nan
    big[20, 2, 1] = -np.inf
    assert np.flatnonzero(~kl.is_rotation(big)).tolist() == [10, 20]


#: finite entries whose products overflow: RᵀR and det R come out NaN (inf − inf), and a
#: NaN compared with the tolerance is never "too large" (check_rotation accepted this once)
OVERFLOWING = np.array([[1e200, 1e200, 1e200], [1e200, -1e200, 1e200], [1e200, 1e200, -1e200]])


def test_a_matrix_whose_checks_overflow_is_no_rotation():
    kl.prepare_kernels(["conversions"])  # the batch of 5000 below: the compiled kernel
    for R, where in ((OVERFLOWING, r"R"), (np.stack([np.eye(3), OVERFLOWING]), r"R\[1\]"),
                     (np.concatenate([random_rotations(4999, seed=3), OVERFLOWING[None]]),
                      r"R\[4999\]")):
        with warnings.catch_warnings():
            warnings.simplefilter("error")  # and no overflow warning on the way
            with pytest.raises(kl.KinlibError, match=where + " is not a rotation matrix"):
                kl.check_rotation(R)
            assert not np.asarray(kl.is_rotation(R)).ravel()[-1]


def test_one_matrix_is_judged_to_the_bit_as_in_a_batch():
    """One matrix takes a scalar path, a batch numpy's: the same sums in the same order."""
    from kinlib.spatial.rotations import _rotation_errors_numpy

    rng = np.random.default_rng(4)
    M = np.concatenate([rng.normal(size=(500, 3, 3)), random_rotations(500, seed=5),
                        random_rotations(500, seed=6) + rng.normal(size=(500, 3, 3)) * 1e-7])
    err, det = _rotation_errors_numpy(M)
    one = np.array([_rotation_errors_numpy(np.ascontiguousarray(m)) for m in M])
    np.testing.assert_array_equal(one[:, 0], err)
    np.testing.assert_array_equal(one[:, 1], det)


# --------------------------------------------------------------------------- nearest_rotation


def _procrustes(M):
    """argmin over SO(3) of |R − M|_F: U diag(1, 1, det(U Vᵀ)) Vᵀ (Umeyama), written here."""
    out = np.empty_like(M)
    for n, m in enumerate(M.reshape(-1, 3, 3)):
        U, _, Vt = np.linalg.svd(m)
        D = np.diag([1.0, 1.0, np.linalg.det(U @ Vt)])
        out.reshape(-1, 3, 3)[n] = U @ D @ Vt
    return out


def test_nearest_rotation_of_a_rotation_is_itself():
    R = random_rotations(500, seed=8)
    assert np.abs(kl.nearest_rotation(R) - R).max() < 1e-14
    assert np.abs(kl.nearest_rotation(np.eye(3)) - np.eye(3)).max() < 1e-15


def test_nearest_rotation_of_noisy_rotations():
    rng = np.random.default_rng(9)
    R = random_rotations(1000, seed=10)
    M = R + 1e-3 * rng.normal(size=R.shape)
    N = kl.nearest_rotation(M)
    assert N.shape == M.shape
    assert kl.is_rotation(N, tol=1e-13).all()
    # closer to the clean rotation than the noisy matrix was
    d_clean = np.linalg.norm(N - R, axis=(-2, -1))
    d_noisy = np.linalg.norm(M - R, axis=(-2, -1))
    assert np.all(d_clean < d_noisy)
    # the polar factor of M (scipy) is the nearest orthogonal matrix; det M > 0 here
    assert np.all(np.linalg.det(M) > 0)
    for n in range(0, 1000, 50):
        P, _ = scipy.linalg.polar(M[n])
        assert np.abs(N[n] - P).max() < 1e-12
    assert np.abs(N - _procrustes(M)).max() < 1e-12


def test_nearest_rotation_beats_every_nearby_rotation():
    rng = np.random.default_rng(11)
    M = rng.normal(size=(20, 3, 3))  # far from SO(3), both signs of det
    assert (np.linalg.det(M) < 0).any() and (np.linalg.det(M) > 0).any()
    N = kl.nearest_rotation(M)
    assert kl.is_rotation(N, tol=1e-12).all()
    assert np.abs(N - _procrustes(M)).max() < 1e-10
    best = np.linalg.norm(N - M, axis=(-2, -1))
    for scale in (1e-1, 1e-3):
        w = scale * rng.normal(size=(20, 200, 3))
        nearby = N[:, None] @ Rotation.from_rotvec(w.reshape(-1, 3)).as_matrix().reshape(
            20, 200, 3, 3
        )
        d = np.linalg.norm(nearby - M[:, None], axis=(-2, -1))
        assert np.all(d >= best[:, None] - 1e-12)
    # and every random rotation is no closer either
    others = random_rotations(5000, seed=12)
    d = np.linalg.norm(others[None] - M[:, None], axis=(-2, -1))
    assert np.all(d >= best[:, None] - 1e-12)


def test_nearest_rotation_of_a_reflection_flips_the_smallest_direction():
    # diag(1, 2, −3): the nearest rotation flips the axis of the smallest singular value
    # (x): distance² 4 + 1 + 4 = 9 to diag(−1, 1, −1), more to every other candidate.
    N = kl.nearest_rotation(np.diag([1.0, 2.0, -3.0]))
    assert np.allclose(N, np.diag([-1.0, 1.0, -1.0]), atol=1e-15, rtol=0)
    assert np.linalg.det(N) == pytest.approx(1.0, abs=1e-15)


@settings(max_examples=300, deadline=None)
@given(R=rotation_matrices(), noise=st.lists(st.floats(-0.3, 0.3), min_size=9, max_size=9))
def test_nearest_rotation_property(R, noise):
    M = R + np.reshape(noise, (3, 3))
    N = kl.nearest_rotation(M)
    assert kl.is_rotation(N, tol=1e-12)
    expected = _procrustes(M)
    # the optimum is unique and well conditioned unless M is (nearly) singular, or
    # det M < 0 with two equal smallest singular values (then the flip is ambiguous)
    sv = np.linalg.svd(M, compute_uv=False)
    if sv[2] > 1e-6 and (np.linalg.det(M) > 0 or sv[1] - sv[2] > 1e-6):
        assert np.allclose(N, expected, atol=1e-9, rtol=0)
    assert np.linalg.norm(N - M) <= np.linalg.norm(expected - M) + 1e-12
    assert np.linalg.norm(N - M) <= np.linalg.norm(R - M) + 1e-12
