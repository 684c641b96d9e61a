"""Singularity tools against numpy and the planar 2R closed form |l1 l2 sin θ2|."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import kinlib as kl
from kinlib.robots import puma560


@pytest.mark.parametrize("shape", [(6, 6), (6, 7), (3, 2), (2, 2), (3, 6)])
def test_against_numpy(shape):
    rng = np.random.default_rng(sum(shape))
    J = rng.normal(size=(20,) + shape)
    s = kl.singular_values(J)
    np.testing.assert_allclose(s, np.linalg.svd(J, compute_uv=False), rtol=1e-12)
    assert (np.diff(s, axis=-1) <= 0).all()
    w = kl.manipulability(J)
    if shape[0] <= shape[1]:
        np.testing.assert_allclose(w, np.sqrt(np.linalg.det(J @ np.swapaxes(J, 1, 2))),
                                   rtol=1e-9)
    else:
        np.testing.assert_array_equal(w, 0.0)  # J Jᵀ (m > n) is always singular
    if shape[0] == shape[1]:
        np.testing.assert_allclose(w, np.abs(np.linalg.det(J)), rtol=1e-9)
    np.testing.assert_allclose(kl.condition_number(J), np.linalg.cond(J), rtol=1e-9)


def test_rank_deficient_gives_zero_not_nan():
    J = np.array([[1.0, 2.0, 3.0], [2.0, 4.0, 6.0]])
    assert kl.manipulability(J) < 1e-13 and np.isfinite(kl.manipulability(J))  # rounding
    assert kl.condition_number(np.zeros((2, 2))) == np.inf
    assert kl.is_near_singular(J) and kl.is_near_singular(np.zeros((6, 6)))
    assert not kl.is_near_singular(np.eye(6))


@settings(max_examples=100, deadline=None)
@given(st.floats(-np.pi, np.pi), st.floats(-np.pi, np.pi), st.floats(0.1, 2), st.floats(0.1, 2))
def test_planar_2r_closed_form(t1, t2, l1, l2):
    J = kl.planar_2r_jacobian(t1, t2, l1, l2)[:2]
    assert kl.manipulability(J) == pytest.approx(abs(l1 * l2 * np.sin(t2)), abs=1e-12)


def test_planar_2r_singular_and_not():
    for t2, singular in ((0.0, True), (np.pi, True), (np.pi / 2, False), (-np.pi / 2, False)):
        J = kl.planar_2r_jacobian(0.7, t2, 1.0, 0.6)[:2]
        assert bool(kl.is_near_singular(J)) is singular
        assert bool(kl.condition_number(J) > 1e12) is singular


@settings(max_examples=50, deadline=None)
@given(st.integers(0, 2**31))
def test_velocity_ellipsoid_contains_the_image_of_the_unit_ball(seed):
    rng = np.random.default_rng(seed)
    m, n = rng.integers(2, 7, 2)
    J = rng.normal(size=(m, n))
    axes, radii = kl.velocity_ellipsoid(J)
    assert axes.shape == (m, m) and radii.shape == (m,)
    np.testing.assert_allclose(axes.T @ axes, np.eye(m), atol=1e-12)
    qd = rng.normal(size=(200, n))
    qd /= np.linalg.norm(qd, axis=1, keepdims=True)
    v = qd @ J.T                                   # end-effector velocities, |q̇| = 1
    coords = v @ axes                              # in the principal frame
    k = int((radii > 1e-12).sum())
    inside = np.sum((coords[:, :k] / radii[:k]) ** 2, axis=1)
    assert (inside <= 1 + 1e-9).all()
    np.testing.assert_allclose(coords[:, k:], 0.0, atol=1e-9)  # nothing outside the range
    # the extreme points are reached: J vᵢ = σᵢ uᵢ for the right singular vectors
    Vt = np.linalg.svd(J)[2]
    for i in range(min(m, n)):
        assert abs(abs(axes[:, i] @ (J @ Vt[i])) - radii[i]) < 1e-9


def test_puma_wrist_singularity():
    robot = puma560()
    q = np.array([0.1, -0.5, 0.7, 0.3, 0.4, 0.2])
    assert not kl.is_near_singular(robot.jacobian(q))
    q[4] = 0.0
    J = robot.jacobian(q)
    assert kl.is_near_singular(J) and kl.manipulability(J) < 1e-12


def test_bad_input():
    with pytest.raises(kl.KinlibError, match="J: expected a matrix"):
        kl.manipulability([1.0, 2.0])
    with pytest.raises(kl.KinlibError, match="NaN"):
        kl.singular_values([[np.nan, 0], [0, 1]])
    with pytest.raises(kl.KinlibError, match="tol"):
        kl.is_near_singular(np.eye(2), tol=-1)
