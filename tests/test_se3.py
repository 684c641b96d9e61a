"""SE(3): hat/vee, exp and log, the adjoint — against scipy's matrix exponential and
logarithm, the Modern Robotics library (which orders twists [ω; v]), closed forms and
finite differences; near θ = 0 and θ = π; batched, symbolic, bad input."""

import modern_robotics as mr
import numpy as np
import pytest
import sympy as sp
from reference import random_unit_vectors
from scipy.linalg import expm, logm

import kinlib as kl


def mr_order(xi):
    """[v; ω] -> Modern Robotics' [ω; v]."""
    return np.concatenate([xi[3:], xi[:3]])


def random_twists(rng, n, angles):
    w = random_unit_vectors(n, rng) * np.asarray(angles)[:, None]
    return np.concatenate([rng.normal(size=(n, 3)), w], axis=1)


ANGLES = [0.0, 1e-12, 1e-7, 1e-4, 9.9e-4, 1.1e-3, 0.3, 1.0, 2.0, 3.0, np.pi - 1e-6, np.pi,
          4.0, 10.0]


def test_hat_and_vee_are_inverse_and_match_the_cross_product():
    rng = np.random.default_rng(0)
    xi = rng.normal(size=(5, 6))
    X = kl.hat_se3(xi)
    assert X.shape == (5, 4, 4)
    np.testing.assert_array_equal(kl.vee_se3(X), xi)
    p = rng.normal(size=3)
    # [ξ] applied to a point p (homogeneous 1) is ω × p + v: the velocity of the point
    np.testing.assert_allclose((X[0] @ np.append(p, 1.0))[:3],
                               np.cross(xi[0, 3:], p) + xi[0, :3])
    np.testing.assert_array_equal(X[:, 3, :], 0.0)


def test_vee_rejects_what_is_not_in_se3():
    T = kl.transform(kl.rotz(0.4), [1.0, 2.0, 3.0])
    with pytest.raises(kl.KinlibError, match="se\\(3\\)"):
        kl.vee_se3(T)  # a pose: not skew, bottom row not 0
    Tdot = kl.hat_se3([1, 0, 0, 0, 0, 1]) @ T  # Ṫ = [ξ] T: also not in se(3)
    with pytest.raises(kl.KinlibError, match="Ṫ T⁻¹"):
        kl.vee_se3(Tdot)
    np.testing.assert_allclose(kl.vee_se3(Tdot @ kl.transform_inverse(T)), [1, 0, 0, 0, 0, 1],
                               atol=1e-15)


@pytest.mark.parametrize("angle", ANGLES)
def test_exp_is_scipys_matrix_exponential(angle):
    rng = np.random.default_rng(int(angle * 1e6) % 2**32)
    for xi in random_twists(rng, 4, [angle] * 4):
        np.testing.assert_allclose(kl.exp_se3(xi), expm(kl.hat_se3(xi)), atol=1e-13, rtol=0)
        if angle == 0 or angle > 1e-6:  # below, MR rounds the rotation to none (NearZero)
            np.testing.assert_allclose(kl.exp_se3(xi),
                                       mr.MatrixExp6(mr.VecTose3(mr_order(xi))), atol=1e-12,
                                       rtol=0)


def test_exp_of_a_pure_translation_and_of_a_screw_about_an_offset_axis():
    np.testing.assert_array_equal(kl.exp_se3([1.0, 2.0, 3.0, 0, 0, 0]),
                                  kl.transform(p=[1.0, 2.0, 3.0]))
    # revolute joint about z through c = (1, 0, 0): S = [−ω × c; ω]; a half turn takes the
    # origin to (2, 0, 0) and turns by π
    c, w = np.array([1.0, 0, 0]), np.array([0, 0, 1.0])
    S = np.concatenate([-np.cross(w, c), w])
    T = kl.exp_se3(S, np.pi)
    np.testing.assert_allclose(T, kl.transform(kl.rotz(np.pi), [2.0, 0, 0]), atol=1e-15)
    # pitch h: one turn advances 2π h along the axis
    S_h = np.concatenate([-np.cross(w, c) + 0.1 * w, w])
    np.testing.assert_allclose(kl.exp_se3(S_h, 2 * np.pi), kl.transform(p=[0, 0, 0.2 * np.pi]),
                               atol=1e-14)


def test_exp_derivative_is_the_twist():
    """d/dt e^{[ξ]t} = [ξ] e^{[ξ]t}: Ṫ T⁻¹ = [ξ] (spatial) and T⁻¹ Ṫ = [ξ] (body)."""
    xi, t, h = np.array([0.3, -0.2, 0.5, 0.4, -1.1, 0.7]), 0.8, 1e-6
    Tdot = (kl.exp_se3(xi, t + h) - kl.exp_se3(xi, t - h)) / (2 * h)
    T = kl.exp_se3(xi, t)
    np.testing.assert_allclose(kl.vee_se3(Tdot @ kl.transform_inverse(T), tol=1e-6), xi,
                               atol=1e-8)
    np.testing.assert_allclose(kl.vee_se3(kl.transform_inverse(T) @ Tdot, tol=1e-6), xi,
                               atol=1e-8)


@pytest.mark.parametrize("angle", ANGLES[:11])
def test_log_inverts_exp(angle):
    rng = np.random.default_rng(int(angle * 1e7) % 2**32 + 1)
    xis = random_twists(rng, 6, [angle] * 6)
    T = kl.exp_se3(xis)
    got = kl.log_se3(T)
    np.testing.assert_allclose(kl.exp_se3(got), T, atol=1e-12, rtol=0)
    if angle < np.pi - 1e-3:  # the principal log is xi itself (at π, ±ω are both right)
        np.testing.assert_allclose(got, xis, atol=1e-9 if angle > 3 else 1e-12, rtol=0)
    if 1e-6 < angle < 3.0:
        for x, Ti in zip(got, T, strict=True):
            np.testing.assert_allclose(kl.hat_se3(x), logm(Ti).real, atol=1e-10)
            np.testing.assert_allclose(mr_order(x), mr.se3ToVec(mr.MatrixLog6(Ti)), atol=1e-9)


def test_log_at_a_half_turn_and_at_the_identity():
    T = kl.transform(kl.rotx(np.pi), [0.0, 1.0, 2.0])
    xi = kl.log_se3(T)
    assert np.isclose(np.linalg.norm(xi[3:]), np.pi)
    np.testing.assert_allclose(kl.exp_se3(xi), T, atol=1e-14)
    np.testing.assert_array_equal(kl.log_se3(kl.transform(p=[1.0, 2.0, 3.0])), [1, 2, 3, 0, 0, 0])
    tiny = kl.transform(kl.rotz(1e-10), [1.0, 0.0, 0.0])  # v = p − ½ ω × p + O(θ²)
    np.testing.assert_allclose(kl.log_se3(tiny), [1.0, -5e-11, 0, 0, 0, 1e-10], rtol=1e-9,
                               atol=1e-20)


def test_adjoint_moves_twists_between_frames():
    rng = np.random.default_rng(3)
    for R, p, xi in zip(kl.matrix_from_quat(rng.normal(size=(10, 4))), rng.normal(size=(10, 3)),
                        rng.normal(size=(10, 6)), strict=True):
        T = kl.transform(R, p)
        A = kl.adjoint(T)
        np.testing.assert_allclose(kl.hat_se3(A @ xi), T @ kl.hat_se3(xi) @ np.linalg.inv(T),
                                   atol=1e-12)
        np.testing.assert_allclose(mr_order(A @ xi), mr.Adjoint(T) @ mr_order(xi), atol=1e-12)
        np.testing.assert_allclose(kl.adjoint(kl.transform_inverse(T)), np.linalg.inv(A),
                                   atol=1e-12)
        # exp(Ad_T ξ) = T exp(ξ) T⁻¹
        np.testing.assert_allclose(kl.exp_se3(A @ xi), T @ kl.exp_se3(xi) @ np.linalg.inv(T),
                                   atol=1e-11)


def test_batched_shapes():
    rng = np.random.default_rng(4)
    xi = rng.normal(size=(2, 3, 6))
    T = kl.exp_se3(xi)
    assert T.shape == (2, 3, 4, 4)
    np.testing.assert_allclose(T[1, 2], kl.exp_se3(xi[1, 2]))
    assert kl.log_se3(T).shape == (2, 3, 6)
    assert kl.adjoint(T).shape == (2, 3, 6, 6)
    assert kl.exp_se3(xi[0, 0], np.linspace(0, 1, 5)).shape == (5, 4, 4)


def test_symbolic_exp_is_the_closed_form_and_matches_the_numbers():
    t = sp.symbols("theta", real=True)
    S = [0, -1, 0, 0, 0, 1]  # about z through (1, 0, 0)
    T = kl.exp_se3(S, t)
    assert isinstance(T, sp.MatrixBase)
    expected = sp.Matrix([[sp.cos(t), -sp.sin(t), 0, 1 - sp.cos(t)],
                          [sp.sin(t), sp.cos(t), 0, -sp.sin(t)],
                          [0, 0, 1, 0], [0, 0, 0, 1]])
    assert sp.simplify(T - expected) == sp.zeros(4, 4)
    np.testing.assert_allclose(np.array(T.subs(t, 0.7), dtype=float), kl.exp_se3(S, 0.7),
                               atol=1e-15)
    x = sp.symbols("v1 v2 v3 w1 w2 w3", real=True)
    general = kl.exp_se3(x)
    vals = dict(zip(x, [0.3, -0.1, 0.2, 0.5, 0.4, -0.9], strict=True))
    np.testing.assert_allclose(np.array(general.subs(vals).evalf(), dtype=float),
                               kl.exp_se3(list(vals.values())), atol=1e-14)
    prismatic = kl.exp_se3([0, 0, 1, 0, 0, 0], t)
    assert prismatic == sp.Matrix([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, t], [0, 0, 0, 1]])
    a, b = sp.symbols("a b")
    A = kl.adjoint(kl.transform(kl.rotz(a), [b, 0, 0]))
    assert isinstance(A, sp.MatrixBase) and A.shape == (6, 6)
    assert kl.vee_se3(kl.hat_se3(x)) == sp.Matrix(x)


@pytest.mark.parametrize("call, match", [
    (lambda: kl.exp_se3([1.0, 2.0, 3.0]), "shape \\(\\.\\.\\., 6\\)"),
    (lambda: kl.exp_se3([np.nan, 0, 0, 0, 0, 1]), "NaN"),
    (lambda: kl.exp_se3(np.zeros((3, 6)), [1.0, 2.0]), "do not broadcast"),
    (lambda: kl.exp_se3([0, 0, 0, 0, 0, sp.Symbol("a")], sp.Symbol("t")), "screw axis"),
    (lambda: kl.log_se3(np.eye(3)), "4×4|4, 4"),
    (lambda: kl.log_se3(2 * np.eye(4)), "rotation|transform"),
    (lambda: kl.log_se3(sp.eye(4) * sp.Symbol("a")), "numeric"),
    (lambda: kl.adjoint(np.ones((4, 4))), "rotation|transform|bottom row"),
    (lambda: kl.hat_se3("twist"), "6"),
])
def test_bad_input_is_a_kinlib_error(call, match):
    with pytest.raises(kl.KinlibError, match=match):
        call()
