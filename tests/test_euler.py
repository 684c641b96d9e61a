"""Euler (intrinsic, UPPERCASE) and fixed (extrinsic, lowercase) angles: all 24 sequences.

References: scipy's Rotation (same upper/lower convention, angles in letter order), the
explicit products of rotx/roty/rotz, matrices typed out from the lecture notes (Craig's
RPY matrix, seed 000's gimbal-lock product) and hand-derived geometric facts.
"""

import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from reference import unit_vectors
from scipy.spatial.transform import Rotation

import kinlib as kl

PI = np.pi
SEQS = list(kl.EULER_SEQUENCES)
ELEMENTARY = {"x": kl.rotx, "y": kl.roty, "z": kl.rotz}

# --------------------------------------------------------------------------- helpers


def is_proper(seq):
    """First axis = last (ZYZ, xyx, ...): proper Euler; else Tait–Bryan."""
    return seq[0].lower() == seq[2].lower()


def singular_values(seq):
    """Middle angles at which the first and third axes line up."""
    return (0.0, PI) if is_proper(seq) else (PI / 2, -PI / 2)


def explicit_product(angles, seq):
    """Intrinsic "ABC": R_A(t1) R_B(t2) R_C(t3); extrinsic "abc": R_c(t3) R_b(t2) R_a(t1)."""
    angles = np.asarray(angles, dtype=float)
    mats = [ELEMENTARY[c.lower()](angles[..., n]) for n, c in enumerate(seq)]
    if seq.isupper():
        return mats[0] @ mats[1] @ mats[2]
    return mats[2] @ mats[1] @ mats[0]


def scipy_matrix(angles, seq):
    return Rotation.from_euler(seq, np.asarray(angles, dtype=float)).as_matrix()


def angle_diff(a, b):
    """|a − b| modulo 2π, in [0, π]."""
    return np.abs((np.asarray(a) - np.asarray(b) + PI) % (2 * PI) - PI)


def assert_ranges(ang, seq):
    """The documented output ranges (middle closed, outer (−π, π])."""
    mid = ang[..., 1]
    if is_proper(seq):
        assert np.all((mid >= 0.0) & (mid <= PI)), mid
    else:
        assert np.all((mid >= -PI / 2) & (mid <= PI / 2)), mid
    outer = ang[..., [0, 2]]
    assert np.all((outer > -PI) & (outer <= PI)), outer


def max_err(A, B):
    return float(np.abs(np.asarray(A) - np.asarray(B)).max(initial=0.0))


def distance_to_lock(mid, seq):
    """Distance of a canonical middle angle from its singular value(s)."""
    return min(abs(mid - s) for s in singular_values(seq))


def cube_rotations():
    """The 24 rotations of the cube: signed permutation matrices with det +1.

    Every Euler decomposition of these has multiples of π/2, many at gimbal lock, and
    the zeros come with both signs (−0.0 too), which trips up atan2-based code.
    """
    out = []
    for perm in [(0, 1, 2), (1, 2, 0), (2, 0, 1), (0, 2, 1), (2, 1, 0), (1, 0, 2)]:
        for signs in np.ndindex(2, 2, 2):
            s = np.where(np.array(signs) == 1, -1.0, 1.0)
            M = np.eye(3)[list(perm)] * s[:, None]  # 0 * −1 = −0.0
            if np.linalg.det(M) > 0:
                out.append(M)
    return np.array(out)


CUBE = cube_rotations()


outer_angles = st.floats(-PI, PI, exclude_min=True)
any_angles = st.floats(-3 * PI, 3 * PI)


@st.composite
def rotation_matrices(draw):
    """Rotations from random unit quaternions (scipy makes the matrix, xyzw order)."""
    return Rotation.from_quat(draw(unit_vectors(4))).as_matrix()


# --------------------------------------------------------------------------- (a) forward map


def test_there_are_24_sequences():
    assert len(SEQS) == 24
    assert len(set(SEQS)) == 24
    assert sum(s.isupper() for s in SEQS) == 12
    assert sum(is_proper(s) for s in SEQS) == 12
    assert {s.lower() for s in SEQS} == {
        "xyz", "xzy", "yxz", "yzx", "zxy", "zyx", "xyx", "xzx", "yxy", "yzy", "zxz", "zyz"
    }  # fmt: skip


@pytest.mark.parametrize("seq", SEQS)
def test_matrix_from_euler_matches_scipy_and_explicit_product(seq):
    rng = np.random.default_rng(100)
    ang = rng.uniform(-2 * PI, 2 * PI, size=(500, 3))
    ang[:50, 1] = rng.choice(singular_values(seq), size=50)  # lock is no special case here
    R = kl.matrix_from_euler(ang, seq)
    assert R.shape == (500, 3, 3)
    assert max_err(R, scipy_matrix(ang, seq)) < 1e-14
    assert max_err(R, explicit_product(ang, seq)) < 1e-14
    assert kl.is_rotation(R, tol=1e-14).all()


@pytest.mark.parametrize("seq", SEQS)
@settings(max_examples=25, deadline=None)
@given(a=any_angles, b=any_angles, c=any_angles)
def test_matrix_from_euler_property(seq, a, b, c):
    R = kl.matrix_from_euler([a, b, c], seq)
    assert max_err(R, scipy_matrix([a, b, c], seq)) < 1e-14
    assert max_err(R, explicit_product([a, b, c], seq)) < 1e-14
    # intrinsic ABC with angles (a, b, c) == extrinsic cba with (c, b, a)
    other = seq[::-1].swapcase()
    assert max_err(R, kl.matrix_from_euler([c, b, a], other)) < 1e-14


# --------------------------------------------------------------------------- (b) round trips


@st.composite
def in_range_angles(draw, seq, margin=1e-5):
    """Angles inside the documented output ranges, the middle ≥ margin away from lock."""
    a, c = draw(outer_angles), draw(outer_angles)
    if is_proper(seq):
        b = draw(st.floats(margin, PI - margin))
    else:
        b = draw(st.floats(-PI / 2 + margin, PI / 2 - margin))
    return np.array([a, b, c])


@pytest.mark.parametrize("seq", SEQS)
@settings(max_examples=50, deadline=None)
@given(data=st.data())
def test_round_trip_away_from_lock(seq, data):
    ang = data.draw(in_range_angles(seq))
    R = scipy_matrix(ang, seq)
    out = kl.euler_from_matrix(R, seq)
    assert out.shape == (3,)
    assert_ranges(out, seq)
    assert max_err(kl.matrix_from_euler(out, seq), R) < 1e-9
    assert abs(out[1] - ang[1]) < 1e-9  # the middle angle exactly
    assert angle_diff(out[[0, 2]], ang[[0, 2]]).max() < 1e-9  # π and −π+0 are one angle
    assert not kl.euler_gimbal_lock(R, seq, tol=1e-6)


# --------------------------------------------------------------------------- (c) at lock


@pytest.mark.parametrize("seq", SEQS)
@settings(max_examples=30, deadline=None)
@given(a=any_angles, c=any_angles, which=st.sampled_from([0, 1]))
def test_at_gimbal_lock_first_angle_is_zero(seq, a, c, which):
    singular = singular_values(seq)[which]
    R = kl.matrix_from_euler([a, singular, c], seq)
    assert max_err(R, scipy_matrix([a, singular, c], seq)) < 1e-14
    out = kl.euler_from_matrix(R, seq)
    assert_ranges(out, seq)
    assert out[0] == 0.0  # first in letter order, for extrinsic sequences too
    assert abs(out[1] - singular) < 1e-12
    assert max_err(kl.matrix_from_euler(out, seq), R) < 1e-9
    assert max_err(explicit_product([0.0, singular, out[2]], seq), R) < 1e-9
    assert kl.euler_gimbal_lock(R, seq) is True
    assert kl.euler_gimbal_lock(R, seq, tol=1e-12) is True


def _lock_third_angle(seq, a, b, c):
    """Hand-derived third angle at lock, with the first set to 0.

    At the singular middle angle the first and third axes are parallel (or anti-parallel),
    so the outer rotations add (or subtract). For an intrinsic sequence the first axis,
    seen after the middle rotation, is ±(third axis); which sign is found from the middle
    rotation applied to the third axis (a geometric fact computed with the typed-out
    elementary matrices below, not with kinlib).
    """
    axes = "xyz"
    low = seq.lower()
    first, mid, third = (axes.index(ch) for ch in low)
    basic = {
        0: lambda t: np.array([[1, 0, 0], [0, np.cos(t), -np.sin(t)], [0, np.sin(t), np.cos(t)]]),
        1: lambda t: np.array([[np.cos(t), 0, np.sin(t)], [0, 1, 0], [-np.sin(t), 0, np.cos(t)]]),
        2: lambda t: np.array([[np.cos(t), -np.sin(t), 0], [np.sin(t), np.cos(t), 0], [0, 0, 1]]),
    }
    e = np.eye(3)
    if seq.isupper():
        # R_A(a) R_B(b) R_C(c) = R_B(b) R_{R_B(b)ᵀ e_A}(a) R_C(c), and R_B(b)ᵀ e_A = σ e_C
        sigma = np.round(basic[mid](b).T @ e[first])[third]
        return sigma * a + c
    # extrinsic: R_c(c) R_b(b) R_a(a) = R_c(c) R_{R_b(b) e_a}(a) R_b(b), R_b(b) e_a = σ e_c
    sigma = np.round(basic[mid](b) @ e[first])[third]
    return sigma * a + c


@pytest.mark.parametrize("seq", SEQS)
def test_at_gimbal_lock_third_angle_carries_the_rotation(seq):
    rng = np.random.default_rng(101)
    for which in (0, 1):
        b = singular_values(seq)[which]
        for a, c in rng.uniform(-PI, PI, size=(20, 2)):
            R = explicit_product([a, b, c], seq)
            out = kl.euler_from_matrix(R, seq)
            assert out[0] == 0.0
            assert angle_diff(out[2], _lock_third_angle(seq, a, b, c)) < 1e-12


# --------------------------------------------------------------------------- (d) near lock


@pytest.mark.parametrize("seq", SEQS)
@settings(max_examples=30, deadline=None)
@given(
    a=outer_angles,
    c=outer_angles,
    which=st.sampled_from([0, 1]),
    side=st.sampled_from([-1.0, 1.0]),
    delta=st.floats(1e-10, 1e-5),
)
def test_near_gimbal_lock(seq, a, c, which, side, delta):
    singular = singular_values(seq)[which]
    b = singular + side * delta
    R = scipy_matrix([a, b, c], seq)
    out = kl.euler_from_matrix(R, seq)
    assert_ranges(out, seq)
    assert max_err(kl.matrix_from_euler(out, seq), R) < 1e-9
    # the middle angle is still found to rounding accuracy: δ from its singular value
    assert abs(distance_to_lock(out[1], seq) - delta) < 1e-12
    assert kl.euler_gimbal_lock(R, seq, tol=1e-4) is True
    assert kl.euler_gimbal_lock(R, seq, tol=1e-12) is False
    assert kl.euler_gimbal_lock(R, seq, tol=delta * 0.99) is False
    assert kl.euler_gimbal_lock(R, seq, tol=delta * 1.01) is True


# --------------------------------------------------------------------------- (e) ranges


@settings(max_examples=120, deadline=None)
@given(R=rotation_matrices())
def test_output_ranges_for_random_rotations(R):
    for seq in SEQS:
        out = kl.euler_from_matrix(R, seq)
        assert_ranges(out, seq)
        assert max_err(kl.matrix_from_euler(out, seq), R) < 1e-9
        if kl.euler_gimbal_lock(R, seq, tol=1e-12):
            assert out[0] == 0.0


@pytest.mark.parametrize("seq", SEQS)
def test_output_ranges_batch_and_cube_rotations(seq):
    R = Rotation.random(3000, rng=np.random.default_rng(102)).as_matrix()
    R = np.concatenate([R, CUBE, -CUBE @ np.diag([1.0, 1.0, -1.0])])
    assert kl.is_rotation(R, tol=1e-12).all()
    out = kl.euler_from_matrix(R, seq)
    assert_ranges(out, seq)
    assert max_err(kl.matrix_from_euler(out, seq), R) < 1e-9
    cube = out[3000:]
    # the cube's rotations decompose into multiples of π/2
    assert np.abs(cube / (PI / 2) - np.round(cube / (PI / 2))).max() < 1e-12
    lock = kl.euler_gimbal_lock(R[3000:], seq)
    assert lock.any() and not lock.all()
    assert np.all(cube[lock, 0] == 0.0)


# --------------------------------------------------------------------------- (f) vs scipy


def _scipy_euler(R, seq):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # scipy warns at gimbal lock; such cases are skipped
        return Rotation.from_matrix(R).as_euler(seq)


def _compare_with_scipy(R, seq, ours):
    ref = _scipy_euler(R, seq)
    far = np.array([distance_to_lock(m, seq) for m in np.atleast_2d(ref)[:, 1]]) > 1e-4
    ours, ref = np.atleast_2d(ours)[far], np.atleast_2d(ref)[far]
    assert max_err(Rotation.from_euler(seq, ref).as_matrix(), R.reshape(-1, 3, 3)[far]) < 1e-12
    assert np.abs(ours[:, 1] - ref[:, 1]).max(initial=0.0) < 1e-9
    # scipy's outer angles are in [−π, π]; both are canonical up to π ≡ −π
    assert angle_diff(ours[:, [0, 2]], ref[:, [0, 2]]).max(initial=0.0) < 1e-9
    return far


@pytest.mark.parametrize("seq", SEQS)
def test_euler_from_matrix_matches_scipy(seq):
    R = Rotation.random(2000, rng=np.random.default_rng(103)).as_matrix()
    far = _compare_with_scipy(R, seq, kl.euler_from_matrix(R, seq))
    assert far.mean() > 0.99


@settings(max_examples=200, deadline=None)
@given(R=rotation_matrices(), seq=st.sampled_from(SEQS))
def test_euler_from_matrix_matches_scipy_property(R, seq):
    _compare_with_scipy(R, seq, kl.euler_from_matrix(R, seq))


# --------------------------------------------------------------------------- (g) seeds


def test_craig_zyx_euler_equals_xyz_fixed_angles_reversed():
    rng = np.random.default_rng(104)
    for alpha, beta, gamma in rng.uniform(-PI, PI, size=(20, 3)):
        R = kl.matrix_from_euler([alpha, beta, gamma], "ZYX")
        assert max_err(R, kl.matrix_from_euler([gamma, beta, alpha], "xyz")) < 1e-15
        assert max_err(R, kl.rotz(alpha) @ kl.roty(beta) @ kl.rotx(gamma)) < 1e-15
        if abs(beta) < PI / 2 - 1e-3:
            zyx = kl.euler_from_matrix(R, "ZYX")
            assert np.allclose(zyx, [alpha, beta, gamma], atol=1e-12, rtol=0)
            assert np.allclose(kl.euler_from_matrix(R, "xyz"), zyx[::-1], atol=1e-12, rtol=0)


def rpy_textbook(phi, theta, psi):
    """Craig eq. 2.64 / seed 001 eq. 4.66: Rz(φ) Ry(θ) Rx(ψ), typed out entry by entry."""
    cf, sf = np.cos(phi), np.sin(phi)
    ct, st_ = np.cos(theta), np.sin(theta)
    cp, sp = np.cos(psi), np.sin(psi)
    return np.array(
        [
            [cf * ct, cf * st_ * sp - sf * cp, cf * st_ * cp + sf * sp],
            [sf * ct, sf * st_ * sp + cf * cp, sf * st_ * cp - cf * sp],
            [-st_, ct * sp, ct * cp],
        ]
    )


def test_rpy_matrix_typed_out():
    rng = np.random.default_rng(105)
    for phi, theta, psi in rng.uniform(-PI, PI, size=(50, 3)):
        expected = rpy_textbook(phi, theta, psi)
        assert max_err(kl.matrix_from_euler([phi, theta, psi], "ZYX"), expected) < 1e-15
        # URDF rpy = fixed angles about x, y, z: the same matrix
        assert max_err(kl.matrix_from_euler([psi, theta, phi], "xyz"), expected) < 1e-15
    # a hand-checkable instance: Rz(90°) Ry(90°): x_B = Rz Ry e_x = −z_A, y_B = −x_A
    R = kl.matrix_from_euler([PI / 2, PI / 2, 0.0], "ZYX")
    assert np.allclose(R, [[0, -1, 0], [0, 0, 1], [-1, 0, 0]], atol=1e-15, rtol=0)


@settings(max_examples=200, deadline=None)
@given(a=any_angles, g=any_angles)
def test_seed000_gimbal_lock_product(a, g):
    # Rx(α) Ry(π/2) Rz(γ): "rotation now only occurs about z" (seed 000)
    expected = np.array(
        [
            [0.0, 0.0, 1.0],
            [np.sin(a + g), np.cos(a + g), 0.0],
            [-np.cos(a + g), np.sin(a + g), 0.0],
        ]
    )
    R = kl.rotx(a) @ kl.roty(PI / 2) @ kl.rotz(g)
    assert max_err(R, expected) < 1e-14
    assert max_err(kl.matrix_from_euler([a, PI / 2, g], "XYZ"), expected) < 1e-14
    out = kl.euler_from_matrix(expected, "XYZ")
    assert out[0] == 0.0
    assert abs(out[1] - PI / 2) < 1e-15
    assert angle_diff(out[2], a + g) < 1e-12
    assert -PI < out[2] <= PI
    assert kl.euler_gimbal_lock(expected, "XYZ") is True
    # the same matrix as fixed angles z-y-x (reversed letters and angles)
    out = kl.euler_from_matrix(expected, "zyx")
    assert out[0] == 0.0 and abs(out[1] - PI / 2) < 1e-15
    assert angle_diff(out[2], a + g) < 1e-12


def test_seed000_arm_experiment_is_a_quarter_turn_about_y():
    # Rz(90°) Ry(90°) Rx(90°), by hand:
    #   Ry Rx = [[0,0,1],[0,1,0],[-1,0,0]] @ [[1,0,0],[0,0,-1],[0,1,0]]
    #         = [[0,1,0],[0,0,-1],[-1,0,0]]
    #   Rz (Ry Rx) = [[0,-1,0],[1,0,0],[0,0,1]] @ that = [[0,0,1],[0,1,0],[-1,0,0]]
    # which is Ry(90°): the arm does not "return to the original pose", it ends up turned
    # a quarter about y (x → −z, z → x, y fixed).
    by_hand = np.array([[0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]])
    R = kl.rotz(PI / 2) @ kl.roty(PI / 2) @ kl.rotx(PI / 2)
    assert max_err(R, by_hand) < 1e-15
    assert np.allclose(R @ [0, 1, 0], [0, 1, 0], atol=1e-15, rtol=0)  # y is the axis
    assert np.allclose(R @ [1, 0, 0], [0, 0, -1], atol=1e-15, rtol=0)
    assert np.allclose(R @ [0, 0, 1], [1, 0, 0], atol=1e-15, rtol=0)
    assert np.trace(R) == pytest.approx(1.0 + 2 * np.cos(PI / 2), abs=1e-15)  # 90°
    assert max_err(R, Rotation.from_rotvec([0.0, PI / 2, 0.0]).as_matrix()) < 1e-15
    # with ZYX the middle angle is 90°: gimbal lock
    R_zyx = kl.matrix_from_euler([PI / 2, PI / 2, PI / 2], "ZYX")
    assert max_err(R_zyx, by_hand) < 1e-15
    for M in (R, by_hand):
        assert kl.euler_gimbal_lock(M, "ZYX") is True
        assert kl.euler_gimbal_lock(M, "xyz") is True
        out = kl.euler_from_matrix(M, "ZYX")
        assert np.allclose(out, [0.0, PI / 2, 0.0], atol=1e-15, rtol=0)  # Ry(90°) itself
        assert out[0] == 0.0
        out = kl.euler_from_matrix(M, "xyz")
        assert np.allclose(out, [0.0, PI / 2, 0.0], atol=1e-15, rtol=0)


def test_gimbal_lock_docstring_example():
    R = kl.matrix_from_euler([0.4, PI / 2, 0.3], "XYZ")
    assert np.allclose(kl.euler_from_matrix(R, "XYZ"), [0.0, PI / 2, 0.7], atol=1e-12, rtol=0)


def test_gimbal_lock_flag_default_tolerance():
    for seq in SEQS:
        far = 0.5 if is_proper(seq) else 0.2
        assert kl.euler_gimbal_lock(kl.matrix_from_euler([0.3, far, -0.2], seq), seq) is False
        for s in singular_values(seq):
            for d, expected in [(0.0, True), (5e-7, True), (2e-6, False)]:
                R = scipy_matrix([0.3, s + d, -0.2], seq)
                assert kl.euler_gimbal_lock(R, seq) is expected, (seq, s, d)


# --------------------------------------------------------------------------- (h) batches


@pytest.mark.parametrize("seq", SEQS)
def test_batched_equals_looping(seq):
    rng = np.random.default_rng(106)
    ang = rng.uniform(-PI, PI, size=(5, 7, 3))
    ang[1, :, 1] = singular_values(seq)[0]
    ang[3, 2:5, 1] = singular_values(seq)[1]
    ang[4, 0, 1] = singular_values(seq)[0] + 1e-8
    R = kl.matrix_from_euler(ang, seq)
    assert R.shape == (5, 7, 3, 3)
    out = kl.euler_from_matrix(R, seq)
    assert out.shape == (5, 7, 3)
    lock = kl.euler_gimbal_lock(R, seq)
    assert lock.shape == (5, 7)
    assert lock.dtype == bool
    assert lock[1].all() and lock[3, 2:5].all() and lock[4, 0] and not lock[0].any()
    for idx in np.ndindex(5, 7):
        assert np.allclose(R[idx], kl.matrix_from_euler(ang[idx], seq), atol=1e-15, rtol=0)
        assert np.allclose(out[idx], kl.euler_from_matrix(R[idx], seq), atol=1e-15, rtol=0)
        assert lock[idx] == kl.euler_gimbal_lock(R[idx], seq)
    assert max_err(kl.matrix_from_euler(out, seq), R) < 1e-9
