"""Cayley's formula R = (I − S)⁻¹ (I + S), S = skew(s), s = tan(θ/2) u (seed 002).

References: the literal formula evaluated here with np.linalg.inv, scipy's rotation
vectors, the closed form s = vee(R − Rᵀ) / (1 + tr R) written out here.
"""

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from reference import random_unit_vectors, unit_vectors
from scipy.spatial.transform import Rotation

import kinlib as kl

PI = np.pi
I3 = np.eye(3)


def skew_textbook(s):
    s = np.asarray(s, dtype=float)
    x, y, z = s[..., 0], s[..., 1], s[..., 2]
    zero = np.zeros_like(x)
    return np.stack(
        [
            np.stack([zero, -z, y], axis=-1),
            np.stack([z, zero, -x], axis=-1),
            np.stack([-y, x, zero], axis=-1),
        ],
        axis=-2,
    )


def cayley_literal(s):
    """(I − S)⁻¹ (I + S) with an explicit matrix inverse."""
    S = skew_textbook(s)
    return np.linalg.inv(I3 - S) @ (I3 + S)


def cayley_params_textbook(R):
    """s = [r32 − r23, r13 − r31, r21 − r12] / (1 + tr R) (= tan(θ/2) u)."""
    R = np.asarray(R)
    v = np.stack(
        [R[..., 2, 1] - R[..., 1, 2], R[..., 0, 2] - R[..., 2, 0], R[..., 1, 0] - R[..., 0, 1]],
        axis=-1,
    )
    return v / (1.0 + np.trace(R, axis1=-2, axis2=-1))[..., None]


def max_err(A, B):
    return float(np.abs(np.asarray(A) - np.asarray(B)).max(initial=0.0))



params = st.tuples(*[st.floats(-300.0, 300.0)] * 3).map(np.array)



# --------------------------------------------------------------------------- forward


def test_matrix_from_cayley_equals_literal_formula_batch():
    rng = np.random.default_rng(400)
    s = random_unit_vectors(1000, rng) * 10.0 ** rng.uniform(-8, 2.5, size=(1000, 1))
    R = kl.matrix_from_cayley(s)
    assert R.shape == (1000, 3, 3)
    assert max_err(R, cayley_literal(s)) < 1e-11
    assert kl.is_rotation(R, tol=1e-14).all()
    Rb = kl.matrix_from_cayley(s.reshape(10, 100, 3))
    assert Rb.shape == (10, 100, 3, 3)
    assert max_err(Rb.reshape(-1, 3, 3), R) < 1e-15
    assert np.array_equal(kl.matrix_from_cayley([0.0, 0.0, 0.0]), I3)


@settings(max_examples=400, deadline=None)
@given(s=params)
def test_matrix_from_cayley_property(s):
    R = kl.matrix_from_cayley(s)
    # np.linalg.inv loses about (1 + |s|²) ulps: the closed form is the more accurate one
    assert max_err(R, cayley_literal(s)) <= 1e-9
    assert max_err(R.T @ R, I3) < 1e-14
    assert abs(np.linalg.det(R) - 1.0) < 1e-14
    assert max_err(R @ s, s) <= 1e-14 * (1.0 + np.linalg.norm(s))  # s is the axis


@settings(max_examples=400, deadline=None)
@given(u=unit_vectors(), theta=st.floats(-PI + 1e-3, PI - 1e-3))
def test_cayley_parameters_are_tan_half_angle_times_axis(u, theta):
    s = np.tan(theta / 2) * u
    R_rotvec = Rotation.from_rotvec(theta * u).as_matrix()
    assert max_err(kl.matrix_from_cayley(s), R_rotvec) < 1e-12
    back = kl.cayley_from_matrix(R_rotvec)
    assert np.linalg.norm(back - s) <= 1e-9 * max(1.0, np.linalg.norm(s))
    assert max_err(back, cayley_params_textbook(R_rotvec)) <= 1e-9 * max(1.0, abs(s).max())


def test_cayley_quarter_turn_by_hand():
    # tan(45°) = 1: s = e_z is a quarter turn about z, e_x → e_y
    R = kl.matrix_from_cayley([0.0, 0.0, 1.0])
    assert max_err(R, [[0, -1, 0], [1, 0, 0], [0, 0, 1]]) < 1e-15
    assert max_err(kl.cayley_from_matrix(kl.rotz(PI / 2)), [0, 0, 1]) < 1e-15
    assert max_err(kl.cayley_from_matrix(kl.rotx(-PI / 2)), [-1, 0, 0]) < 1e-15


# --------------------------------------------------------------------------- round trips


@settings(max_examples=400, deadline=None)
@given(s=params)
def test_cayley_round_trip_from_parameters(s):
    back = kl.cayley_from_matrix(kl.matrix_from_cayley(s))
    assert np.linalg.norm(back - s) <= 1e-9 * max(1.0, np.linalg.norm(s))


@settings(max_examples=400, deadline=None)
@given(q=st.tuples(*[st.floats(-1.0, 1.0)] * 4).map(np.array))
def test_cayley_round_trip_from_matrices(q):
    assume(np.linalg.norm(q) > 1e-3)
    q = q / np.linalg.norm(q)
    assume(abs(q[3]) > np.sin(0.5e-3))  # scipy xyzw: w = cos(θ/2); θ at least 1e-3 from π
    R = Rotation.from_quat(q).as_matrix()
    s = kl.cayley_from_matrix(R)
    assert max_err(kl.matrix_from_cayley(s), R) < 1e-9
    assert max_err(cayley_literal(s), R) < 1e-9
    # s = tan(θ/2) u, u, θ from scipy
    rv = Rotation.from_matrix(R).as_rotvec()
    theta = np.linalg.norm(rv)
    expected = np.tan(theta / 2) * rv / theta if theta > 0 else np.zeros(3)
    assert np.linalg.norm(s - expected) <= 1e-9 * max(1.0, np.linalg.norm(expected))


def test_cayley_round_trip_batch():
    R = Rotation.random(3000, rng=np.random.default_rng(401)).as_matrix()
    s = kl.cayley_from_matrix(R)
    assert s.shape == (3000, 3)
    assert max_err(kl.matrix_from_cayley(s), R) < 1e-9
    far = np.trace(R, axis1=1, axis2=2) > -1.0 + 1e-3
    ref = cayley_params_textbook(R[far])
    rel = np.linalg.norm(s[far] - ref, axis=-1) / np.maximum(1.0, np.linalg.norm(ref, axis=-1))
    assert rel.max() < 1e-9


# --------------------------------------------------------------------------- half turns


@pytest.mark.parametrize(
    "R",
    [kl.rotz(PI), kl.rotx(PI), kl.roty(-PI), np.diag([1.0, -1.0, -1.0])],
    ids=["rotz(pi)", "rotx(pi)", "roty(-pi)", "diag(1,-1,-1)"],
)
def test_half_turn_has_no_cayley_parameters(R):
    with pytest.raises(kl.KinlibError, match="180"):
        kl.cayley_from_matrix(R)


@settings(max_examples=200, deadline=None)
@given(u=unit_vectors())
def test_half_turn_about_random_axis_raises(u):
    for R in (2.0 * np.outer(u, u) - I3, Rotation.from_rotvec(PI * u).as_matrix()):
        with pytest.raises(kl.KinlibError, match="180"):
            kl.cayley_from_matrix(R)


def test_half_turn_in_a_batch_is_named():
    R = Rotation.random(6, rng=np.random.default_rng(402)).as_matrix()
    R[4] = kl.rotz(PI)
    with pytest.raises(kl.KinlibError, match=r"R\[4\].*180"):
        kl.cayley_from_matrix(R)


@settings(max_examples=300, deadline=None)
@given(u=unit_vectors(), delta=st.floats(1e-6, 1e-3), side=st.sampled_from([-1.0, 1.0]))
def test_near_half_turn_still_works(u, delta, side):
    theta = side * (PI - delta)
    R = Rotation.from_rotvec(theta * u).as_matrix()
    s = kl.cayley_from_matrix(R)
    assert np.all(np.isfinite(s))
    expected = np.tan(theta / 2) * u  # |s| ≈ 2/δ, up to 2e6
    assert np.linalg.norm(s - expected) <= 1e-9 * np.linalg.norm(expected)
    assert max_err(kl.matrix_from_cayley(s), R) < 1e-9
    assert max_err(kl.matrix_from_cayley(expected), R) < 1e-9
