"""Assignment 05 (orientation kinematics): the grader's references agree with kinlib by
independent routes (finite differences, scipy's rotations and Slerp, Modern Robotics' SE(3)
exponential, closed forms; det E derived with sympy against −cos β and finite
differences), the cases cover the edges they must, each classic mistake gets
its diagnosis from a real wrong submission, and right alternatives are accepted.

Submissions are built from the source notebook's own code with one mistake patched in per
function; all of them are graded once, together, by a module-scoped fixture.
"""

import modern_robotics as mr
import numpy as np
import pytest
import sympy as sp
from grading_helpers import (
    by_function,
    judge_notebooks,
    misdiagnosed,
    mistake_submissions,
    patched,
    solution_code,
    top,
    write_notebook,
)
from scipy.spatial.transform import Rotation, Slerp

import kinlib as kl
from kinlib.grade import grade
from kinlib.grade._wire import decode, encode
from kinlib.grade.assignments import _euler_det as ED
from kinlib.grade.assignments import _interpolation as I
from kinlib.grade.assignments import orientation as O

NAME = "05_orientation_kinematics"


def vee(S):
    return np.array([S[2, 1], S[0, 2], S[1, 0]])


def cases_of(function, seed=0):
    return next(c for c in O.assignment().checks if c.function == function).make_cases(seed)


def same_rotation(p, q, atol=1e-9):
    return np.allclose(p, q, atol=atol) or np.allclose(p, -np.asarray(q), atol=atol)


# -- the references, by other routes --------------------------------------------------------
def test_rate_matrix_is_the_omega_of_a_finite_difference():
    """E φ̇ is vee(Ṙ Rᵀ) with Ṙ a central difference of scipy's intrinsic ZYX rotation."""
    rng = np.random.default_rng(1)
    h = 1e-6
    for phi in [np.array(c[:3]) for c in cases_of("euler_rate_matrix_zyx")]:
        rate = rng.normal(size=3)
        R = lambda p: Rotation.from_euler("ZYX", p).as_matrix()  # noqa: E731
        Rd = (R(phi + h * rate) - R(phi - h * rate)) / (2 * h)
        assert np.allclose(O.rate_matrix(*phi) @ rate, vee(Rd @ R(phi).T), atol=1e-8)
        assert np.isclose(np.linalg.det(O.rate_matrix(*phi)), -np.cos(phi[1]), atol=1e-12)


def test_rate_det_reference_is_minus_cos_beta_and_the_finite_difference_det():
    """euler_rate_det_zyx's judge takes −cos β (typed here) on every case, also the exact 0
    at the lock; det of E built from finite differences of scipy's ZYX rotation is the
    determinant of the construction the mistakes vary; the mistake models differ from it."""
    check = next(c for c in O.assignment().checks if c.function == "euler_rate_det_zyx")
    cases = check.make_cases(0)
    for a, b, g in cases:
        assert check.verdict((a, b, g), decode(encode(-sp.cos(b)))).ok
        assert check.verdict((a, b, g), decode(encode(sp.cos(b) - 2 * sp.cos(b)))).ok
    assert any(-sp.cos(c[1]) == 0 for c in cases)  # the exact lock: the number 0 is right
    A, B, G = sp.symbols("alpha beta gamma", real=True)
    rng, h = np.random.default_rng(7), 1e-6
    R = lambda p: Rotation.from_euler("ZYX", p).as_matrix()  # noqa: E731
    for phi in rng.uniform(-np.pi, np.pi, (6, 3)):
        E = np.column_stack([vee((R(phi + h * e) - R(phi - h * e)) / (2 * h) @ R(phi).T)
                             for e in np.eye(3)])
        at = dict(zip((A, B, G), phi, strict=True))
        assert np.isclose(float(ED.rate_det(A, B, G).subs(at)), np.linalg.det(E), atol=1e-8)
        assert np.isclose(np.linalg.det(E), -np.cos(phi[1]), atol=1e-8)
    for model in (lambda *a: ED.rate_det(*a, third=(0, 0, 1)),
                  lambda *a: ED.rate_det(*a, turned=False)):
        assert sp.simplify(model(A, B, G) + sp.cos(B)) != 0


def test_rates_reference_and_its_lock_test():
    """φ̇ rebuilds ω; the lock is |cos β| < tol; every case is clear of the threshold."""
    locked = near = beyond = 0
    for a, b, g, w, tol in cases_of("euler_rates_zyx"):
        cb = abs(np.cos(b))
        assert O.locked(a, b, g, tol) == (cb < tol)
        assert cb <= tol / 100 or cb >= 10 * tol, (b, tol)  # any sensible test agrees
        rates = O.euler_rates(a, b, g, w, tol)
        if cb < tol:
            locked += 1
            assert rates is None
        else:
            near += cb < 1e-3
            assert np.allclose(O.rate_matrix(a, b, g) @ rates, w, atol=1e-9)
        beyond += abs(b) > np.pi / 2 + 0.1
    assert locked >= 8 and near >= 4 and beyond >= 4


def test_angular_velocity_of_a_constant_spin():
    """R(t) = exp(t S(ω)) R0 (scipy's rotation vector): kinlib's ω from a central difference."""
    h = 1e-6
    rng = np.random.default_rng(2)
    for R0, w in zip(kl.matrix_from_quat(rng.normal(size=(20, 4))), rng.normal(size=(20, 3)),
                     strict=True):
        Rd = (Rotation.from_rotvec(h * w).as_matrix()
              - Rotation.from_rotvec(-h * w).as_matrix()) @ R0 / (2 * h)
        assert np.allclose(kl.angular_velocity(R0, kl.skew(w) @ R0), w, atol=1e-12)
        assert np.allclose(vee(Rd @ R0.T), w, atol=1e-7)
    for R, Rd in cases_of("omega_from_rdot"):  # every case is an exact derivative
        W = Rd @ R.T
        assert np.allclose(W, -W.T, atol=1e-12)


def test_chain_reference_is_the_omega_of_the_whole_product():
    """Each frame spins at a constant rate in its parent: R^{i−1}_i(t) = exp(t S(w_i)) A_i."""
    rng = np.random.default_rng(3)
    h = 1e-6
    for n in range(1, 6):
        A = kl.matrix_from_quat(rng.normal(size=(n, 4)))
        w = rng.normal(size=(n, 3))

        def whole(t, A=A, w=w):
            out = np.eye(3)
            for Ai, wi in zip(A, w, strict=True):
                out = out @ Rotation.from_rotvec(t * wi).as_matrix() @ Ai
            return out

        Rd = (whole(h) - whole(-h)) / (2 * h)
        assert np.allclose(kl.add_angular_velocities(A, w), vee(Rd @ whole(0.0).T), atol=1e-7)
    assert {len(r) for r, _ in cases_of("omega_chain")} == set(range(1, 7))


def test_slerp_reference_is_scipys_slerp():
    """The same rotation as scipy's Slerp (scalar last), and continuous from q0 at t = 0."""
    for q0, q1, t in cases_of("slerp"):
        rots = Rotation.from_quat(np.array([kl.quat_xyzw_from_wxyz(q) for q in (q0, q1)]))
        theirs = Slerp([0.0, 1.0], rots)([t]).as_matrix()[0]
        ours = kl.quat_slerp(q0, q1, t)
        assert np.allclose(kl.matrix_from_quat(ours), theirs, atol=1e-9)
        assert np.dot(ours, q0) >= -1e-12  # on the arc that starts at q0, not at −q0


def test_dual_quaternion_product_and_sclerp_by_matrices():
    """The product is T_a T_b; ScLERP is T0 exp(t log(T0⁻¹ T1)) (Modern Robotics), its ends
    are the two poses, and the mistake models keep the ends and leave the path."""
    for a, b in cases_of("dual_quat_multiply"):
        T = kl.transform_from_dual_quat(kl.dual_quat_multiply(a, b))
        assert np.allclose(T, kl.transform_from_dual_quat(a) @ kl.transform_from_dual_quat(b))
    for dq0, dq1, t in cases_of("sclerp"):
        T0, T1 = kl.transform_from_dual_quat(dq0), kl.transform_from_dual_quat(dq1)
        rel = np.linalg.solve(T0, T1)
        theirs = T0 @ mr.MatrixExp6(t * mr.MatrixLog6(rel))
        ours = kl.transform_from_dual_quat(I.sclerp_model(dq0, dq1, t))
        assert np.allclose(ours, theirs, atol=1e-8), (t, Rotation.from_matrix(rel[:3, :3]))
        for model in (I.dlb, I.dlb_plain, I.decoupled, I.long_way_sclerp):
            at0 = kl.transform_from_dual_quat(_unit_dq(model(dq0, dq1, 0.0)))
            at1 = kl.transform_from_dual_quat(_unit_dq(model(dq0, dq1, 1.0)))
            assert np.allclose(at0, T0, atol=1e-9) and np.allclose(at1, T1, atol=1e-9)
    # the two blends are one pose; the long way turns by (2π − θ)/2 halfway
    dq0, dq1 = I.random_poses(np.random.default_rng(4), 2)
    if (kl.dual_quat_multiply(kl.dual_quat_conjugate(dq0), dq1))[0] > 0:
        dq1 = -dq1
    a, b = I.dlb(dq0, dq1, 0.3), I.dlb_plain(dq0, dq1, 0.3)
    assert not np.allclose(a, b) and np.allclose(kl.transform_from_dual_quat(a),
                                                 kl.transform_from_dual_quat(_unit_dq(b)))
    theta = _angle(kl.transform_from_dual_quat(dq0), kl.transform_from_dual_quat(dq1))
    long = kl.transform_from_dual_quat(I.long_way_sclerp(dq0, dq1, 0.5))
    assert np.isclose(_angle(kl.transform_from_dual_quat(dq0), long), np.pi - theta / 2)


def _angle(T0, T1):
    return np.linalg.norm(Rotation.from_matrix(T0[:3, :3].T @ T1[:3, :3]).as_rotvec())


def _unit_dq(dq):
    """A blend divided by |b_r| only, made a unit dual quaternion (its pose unchanged)."""
    r, d = dq[:4], dq[4:]
    return np.r_[r, d - r * (r @ d)]


def test_cayley_references_are_half_angle_rotations():
    """R(s) turns by 2 arctan|s| about s/|s| (scipy), equals (I − S)⁻¹(I + S), and the
    inverse is tan(θ/2) k; half turns (None) lie far below the threshold, the rest far above."""
    for (s,) in cases_of("cayley_to_matrix"):
        n = np.linalg.norm(s)
        rv = np.zeros(3) if n == 0 else 2 * np.arctan(n) * s / n
        S = kl.skew(s)
        R = kl.matrix_from_cayley(s)
        assert np.allclose(R, Rotation.from_rotvec(rv).as_matrix(), atol=1e-9)
        assert np.allclose(R, np.linalg.inv(np.eye(3) - S) @ (np.eye(3) + S), atol=1e-9)
    half = big = 0
    for (R,) in cases_of("matrix_to_cayley"):
        gap = 1 + np.trace(R)
        assert gap < O.HALF_TURN / 1000 or gap > O.HALF_TURN * 100, gap
        if O.half_turn(R):
            half += 1
            assert O.cayley_reference(R) is None
            continue
        rv = Rotation.from_matrix(R).as_rotvec()
        theta = np.linalg.norm(rv)
        expected = np.zeros(3) if theta == 0 else np.tan(theta / 2) * rv / theta
        s = O.cayley_reference(R)
        assert np.allclose(s, expected, rtol=1e-8, atol=1e-12)
        big += np.linalg.norm(s) > 100
    assert half >= 6 and big >= 2


# -- the cases ------------------------------------------------------------------------------
def test_cases_cover_what_they_must():
    spec = O.assignment()
    cases = {c.function: c.make_cases(0) for c in spec.checks}
    assert sum(map(len, cases.values())) >= 300
    assert all(40 <= len(c) <= 60 for f, c in cases.items() if f != "euler_rate_det_zyx"), {
        k: len(v) for k, v in cases.items()}
    assert spec.max_score == 41
    # det E: symbols (other names, sums) and one exact lock β = ±π/2
    derivation = cases["euler_rate_det_zyx"]
    assert len(derivation) == 4 and all(isinstance(a, sp.Symbol) for a, _, _ in derivation[:2])
    assert sum(abs(b) == sp.pi / 2 for _, b, _ in derivation) == 1
    slerp = cases["slerp"]
    assert sum(q0 @ q1 < 0 for q0, q1, _ in slerp) >= 15
    assert {0.0, 1.0} <= {t for *_, t in slerp}
    assert sum(abs(abs(q0 @ q1) - 1) < 1e-15 for q0, q1, _ in slerp) >= 3  # q1 = ±q0, ≈ q0
    assert sum(abs(q0 @ q1) < 1e-12 for q0, q1, _ in slerp) >= 2
    rels = [(kl.dual_quat_multiply(kl.dual_quat_conjugate(a), b), t) for a, b, t in
            cases["sclerp"]]
    assert sum(r[0] < 0 for r, _ in rels) >= 10
    angles = [2 * np.arctan2(np.linalg.norm(r[1:4]), abs(r[0])) for r, _ in rels]
    assert sum(a < 1e-12 for a in angles) >= 4
    assert 1e-6 < min(a for a in angles if a > 1e-12) < 1e-4
    assert max(angles) > np.pi - 2e-3 and {0.0, 1.0} <= {t for _, t in rels}
    for a, b in cases["dual_quat_multiply"]:
        for x in (a, b):
            assert np.isclose(np.linalg.norm(x[:4]), 1) and abs(x[:4] @ x[4:]) < 1e-12


# -- the judges on hand-made answers --------------------------------------------------------
def test_judges_on_hand_made_answers():
    rates = next(c for c in O.assignment().checks if c.function == "euler_rates_zyx")
    w = np.array([0.3, -0.2, 1.0])
    lock, near = (0.2, np.pi / 2, 0.1, w, 1e-9), (0.2, np.pi / 2 - 1e-4, 0.1, w, 1e-9)
    assert rates.verdict(lock, None).ok and rates.verdict(near, O.euler_rates(*near)).ok
    assert rates.verdict(lock, [1e16, 0.0, 1e16]).key == "gimbal"
    assert rates.verdict(lock, [np.nan] * 3).key == "gimbal"
    assert rates.verdict(near, None).key == "missed"
    assert rates.verdict(near, O.euler_rates(*near)[::-1]).key == "order"
    inverse = next(c for c in O.assignment().checks if c.function == "matrix_to_cayley")
    assert inverse.verdict((kl.rotx(np.pi),), None).ok
    assert inverse.verdict((kl.rotx(np.pi),), [1e16, 0, 0]).key == "half turn"
    assert inverse.verdict((kl.rotx(3.0),), None).key == "missed"
    # a right answer to tan θ k's model where tan θ is huge (θ = 90°) is not "half angle"
    assert inverse.verdict((kl.rotz(np.pi / 2),), [0.0, 0.0, 1.0]).ok
    assert inverse.verdict((kl.rotz(np.pi / 2),), [0.0, 0.0, 3.0]).key == "wrong"
    slerp = I.slerp_check()
    q = kl.quat_from_axis_angle([0.0, 0.6, 0.8], 2.0)
    assert slerp.verdict((q, q, 0.3), [np.nan] * 4).key == "equal"
    q0, q1 = kl.quat_from_axis_angle([1.0, 0, 0], 0.5), -kl.quat_from_axis_angle([0, 1.0, 0], 2)
    long = I.SLERP_MISTAKES[0].model(q0, q1, 0.4)
    assert slerp.verdict((q0, q1, 0.4), long).key == "long way"
    assert slerp.verdict((q0, q1, 0.4), -long).key == "long way"  # either sign
    assert slerp.verdict((q0, q1, 0.4), -kl.quat_slerp(q0, q1, 0.4)).ok
    # where a model divides by sin Ω ≈ 0 (q1 = −q0 the long way; Ω = 90° doubled), it is
    # huge and would match anything: a wrong answer there is just wrong
    half = np.full(4, 0.5)
    assert slerp.verdict((q, -q, 0.3), half).key == "wrong"
    assert slerp.verdict((np.r_[1.0, 0, 0, 0], np.r_[0.0, 0, 0, 1], 0.3), half).key == "wrong"
    sclerp = I.sclerp_check()
    dq = I.random_poses(np.random.default_rng(5), 1)[0]
    shifted = kl.dual_quat_multiply(dq, kl.dual_quat_from_transform(kl.transform(p=[1., 0, 0])))
    assert sclerp.verdict((dq, shifted, 0.5), [np.nan] * 8).key == "no rotation"


# -- classic mistakes, graded for real ------------------------------------------------------
E_RET = ("    return np.array([[0.0, -sa, ca * cb],\n"
         "                     [0.0, ca, sa * cb],\n"
         "                     [1.0, 0.0, -sb]])")
BODY_E = ("np.array([[-sb, 0.0, 1.0], [cb * np.sin(gamma), np.cos(gamma), 0.0],\n"
          "                     [cb * np.cos(gamma), -np.sin(gamma), 0.0]])")
RATE_MATRIX_MISTAKES = [  # (edit or tuple of edits, diagnosis)
    ((E_RET, "    return " + BODY_E), "frame"),
    ((E_RET, "    return np.array([[0.0, 0.0, 1.0], [-sa, ca, 0.0], [ca * cb, sa * cb, -sb]])"),
     "transposed"),
    ((E_RET, "    return np.array([[ca * cb, -sa, 0.0], [sa * cb, ca, 0.0], [-sb, 0.0, 1.0]])"),
     "columns"),
    ((E_RET, "    return np.array([[0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]])"),
     "fixed axes"),
    (("    ca, sa = np.cos(alpha), np.sin(alpha)\n    cb, sb = np.cos(beta), np.sin(beta)\n"
      "    return",
      "    alpha, beta = np.deg2rad(alpha), np.deg2rad(beta)\n"
      "    ca, sa = np.cos(alpha), np.sin(alpha)\n    cb, sb = np.cos(beta), np.sin(beta)\n"
      "    return"), "degrees"),
]
RATES = ("    gamma_dot = (ca * w[0] + sa * w[1]) / cb\n"
         "    beta_dot = -sa * w[0] + ca * w[1]\n"
         "    alpha_dot = w[2] + sb * gamma_dot\n"
         "    return np.array([alpha_dot, beta_dot, gamma_dot])")
E_INLINE = "E = np.array([[0.0, -sa, ca * cb], [0.0, ca, sa * cb], [1.0, 0.0, -sb]])\n    "
RATES_MISTAKES = [
    ((RATES, "    " + E_INLINE + "return E.T @ w"), "transposed"),
    ((RATES, "    " + E_INLINE + "return E @ w"), "inverse"),
    ((RATES, "    return np.linalg.solve(" + BODY_E + ", w)"), "frame"),
    (("return np.array([alpha_dot, beta_dot, gamma_dot])",
      "return np.array([gamma_dot, beta_dot, alpha_dot])"), "order"),
    (("return np.array([alpha_dot, beta_dot, gamma_dot])",
      "return np.rad2deg([alpha_dot, beta_dot, gamma_dot])"), "degrees"),
    (("if abs(cb) < tol:", "if False:"), "gimbal"),
    (("if abs(cb) < tol:", "if abs(cb) < 1e-3:"), "missed"),
    (("if abs(cb) < tol:", "if abs(beta - np.pi / 2) < tol:"), "gimbal"),
]
DET_E = "E = sp.Matrix.hstack(e_z, Rz * e_y, Rz * Ry * e_x)"
DET_TIDY = "    return sp.simplify(E.det())"
DET_RETURN = "    return E.det()"  # the submissions' (see graded)
DET_MISTAKES = [  # det E derived with sympy
    ((DET_E, "E = sp.Matrix.hstack(Rz * Ry * e_x, Rz * e_y, e_z)  # gamma_dot first"), "sign"),
    ((DET_E, "E = sp.Matrix.hstack(e_z, Rz * e_y, Rz * Ry * e_z)"), "sin"),
    ((DET_E, "E = sp.Matrix.hstack(e_z, e_y, Rz * Ry * e_x)"), "R_z"),
    ((DET_E, "E = sp.Matrix.hstack(e_z, e_y, e_x)  # the base axes"), "constant"),
    ((DET_E, "E = sp.Matrix.hstack(e_z, Rz * e_x, Rz * Ry * e_x)"), "singular"),
    (("ca, sa, cb, sb = sp.cos(alpha), sp.sin(alpha), sp.cos(beta), sp.sin(beta)",
      "ca, sa, cb, sb = np.cos(alpha), np.sin(alpha), np.cos(beta), np.sin(beta)"), "raised"),
    ((DET_RETURN, "    return E"), "type"),
]
OMEGA_MISTAKES = [
    (("S = R_dot @ R.T", "S = R.T @ R_dot"), "frame"),
    (("S = R_dot @ R.T", "S = R @ R_dot.T"), "sign"),
    (("return np.array([S[2, 1], S[0, 2], S[1, 0]])\n    ### END SOLUTION\n\n\ndef omega_chain",
      "return np.array([S[2, 1], S[2, 0], S[1, 0]])\n    ### END SOLUTION\n\n\ndef omega_chain"),
     "vee"),
    (("S = R_dot @ R.T", "S = R_dot"), "no R"),
]
CHAIN_MISTAKES = [
    (("total = total + R0 @ w", "total = total + w"), "frames"),
    (("        total = total + R0 @ w\n        R0 = R0 @ R",
      "        R0 = R0 @ R\n        total = total + R0 @ w"), "shift"),
    (("R0 = R0 @ R", "R0 = R @ R0"), "order"),
    (("total = total + R0 @ w", "total = total + R0.T @ w"), "transposed"),
]
SLERP_FORMULA = "np.sin((1 - t) * omega) * q0 + np.sin(t * omega) * q1"
SLERP_MISTAKES = [
    (("    if c < 0:                          # the short way",
      "    if False:                          # the short way"), "long way"),
    ((f"q = ({SLERP_FORMULA}) / np.sin(omega)", "q = (1 - t) * q0 + t * q1"), "nlerp"),
    (("    return q / np.linalg.norm(q)", "    return (1 - t) * q0 + t * q1"), "linear"),
    ((SLERP_FORMULA, "np.sin(t * omega) * q0 + np.sin((1 - t) * omega) * q1"), "reversed"),
    (("omega = np.arccos(min(c, 1.0))", "omega = 2 * np.arccos(min(c, 1.0))"), "angle"),
]
DQ_MISTAKES = [
    (("real = quat_multiply(ar, br)\n    dual = quat_multiply(ar, bd) + quat_multiply(ad, br)",
      "real = quat_multiply(br, ar)\n    dual = quat_multiply(br, ad) + quat_multiply(bd, ar)"),
     "order"),
    (("dual = quat_multiply(ar, bd) + quat_multiply(ad, br)",
      "dual = quat_multiply(ar, bd) + quat_multiply(br, ad)"), "dual terms"),
    (("real = quat_multiply(ar, br)\n", "real = quat_multiply(ar, br) + quat_multiply(ad, bd)\n"),
     "epsilon"),
    (("return np.concatenate([real, dual])", "return np.concatenate([dual, real])"), "halves"),
]
SCLERP_START = "    def mul(a, b):\n"
SCLERP_MISTAKES = [
    (("    if rel[0] < 0:                     # the short way",
      "    if False:                          # the short way"), "long way"),
    ((SCLERP_START, "    if dq0[:4] @ dq1[:4] < 0:\n        dq1 = -dq1\n"
                    "    b = (1 - t) * dq0 + t * dq1\n    return b / np.linalg.norm(b[:4])\n"
                    + SCLERP_START), "blend"),
    ((SCLERP_START, "    p0, p1 = (2 * quat_multiply(q[4:], quat_conjugate(q[:4]))[1:] "
                    "for q in (dq0, dq1))\n    qr = _slerp(dq0[:4], dq1[:4], t)\n"
                    "    p = (1 - t) * p0 + t * p1\n"
                    "    return np.concatenate([qr, 0.5 * quat_multiply(np.r_[0.0, p], qr)])\n"
                    + SCLERP_START), "decoupled"),
    ((SCLERP_START, "    dq0, dq1 = dq1, dq0\n" + SCLERP_START), "reversed"),
    (("    return mul(dq0, step)", "    return mul(step, dq0)"), "order"),
    (("    if s < 1e-12:", "    if False:"), "no rotation"),
]
CAYLEY_MISTAKES = [
    (("np.linalg.solve(np.eye(3) - S, np.eye(3) + S)",
      "np.linalg.solve(np.eye(3) + S, np.eye(3) - S)"), "transposed"),
    (("    S = skew(s)\n    return",
      "    S = np.array([[0.0, -s[0], s[1]], [s[0], 0.0, -s[2]], [-s[1], s[2], 0.0]])\n"
      "    return"), "swapped"),
    (("    S = skew(s)\n    return",
      "    theta = np.linalg.norm(s)\n    K = skew(s / theta) if theta > 0 else np.zeros((3, 3))\n"
      "    return np.eye(3) + np.sin(theta) * K + (1 - np.cos(theta)) * K @ K\n"
      "    S = skew(s)\n    return"), "rotation vector"),
    (("    S = skew(s)\n    return",
      "    theta = np.arctan(np.linalg.norm(s))\n"
      "    K = skew(s / np.linalg.norm(s)) if theta > 0 else np.zeros((3, 3))\n"
      "    return np.eye(3) + np.sin(theta) * K + (1 - np.cos(theta)) * K @ K\n"
      "    S = skew(s)\n    return"), "half angle"),
]
CAYLEY_SOLVE = "    S = np.linalg.solve(np.eye(3) + R, R - np.eye(3))"
SKEW_PART = "np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]])"
INVERSE_MISTAKES = [
    (("solve(np.eye(3) + R, R - np.eye(3))", "solve(np.eye(3) + R, np.eye(3) - R)"),
     "transposed"),
    (("(R - I)\n    return np.array([S[2, 1], S[0, 2], S[1, 0]])",
      "(R - I)\n    return np.array([S[1, 0], S[0, 2], S[2, 1]])"), "swapped"),
    ((CAYLEY_SOLVE, "    theta = np.arccos(np.clip((np.trace(R) - 1) / 2, -1, 1))\n"
                    f"    return np.tan(theta) * {SKEW_PART} / (2 * np.sin(theta))\n"
                    + CAYLEY_SOLVE), "half angle"),
    ((CAYLEY_SOLVE, f"    return {SKEW_PART} / (4 * np.sqrt(1 + np.trace(R)) / 2)\n"
                    + CAYLEY_SOLVE), "quaternion"),
    ((CAYLEY_SOLVE, f"    return {SKEW_PART} / 2\n" + CAYLEY_SOLVE), "skew part"),
    (("if 1 + np.trace(R) < 1e-9:", "if False:"), "half turn"),
    (("if 1 + np.trace(R) < 1e-9:", "if 1 + np.trace(R) < 1e-3:"), "missed"),
]
TABLE = (("euler_rate_matrix_zyx", RATE_MATRIX_MISTAKES), ("euler_rate_det_zyx", DET_MISTAKES),
         ("euler_rates_zyx", RATES_MISTAKES),
         ("omega_from_rdot", OMEGA_MISTAKES), ("omega_chain", CHAIN_MISTAKES),
         ("slerp", SLERP_MISTAKES), ("dual_quat_multiply", DQ_MISTAKES),
         ("sclerp", SCLERP_MISTAKES), ("cayley_to_matrix", CAYLEY_MISTAKES),
         ("matrix_to_cayley", INVERSE_MISTAKES))


def alternatives(code: str) -> str:
    """Right answers written another way: E from its columns (nested lists); det E of the
    body-frame matrix Rᵀ E, unsimplified; the rates by
    np.linalg.solve and det E; ω from the skew part (a list); the chain from the far end;
    slerp as q0 (q0* q1)^t with the flip at ≤ 0 and −q; the product as −â b̂; ScLERP as
    −(q̂1 q̂0*)^t q̂0; both Cayley maps in closed form."""
    return patched(
        code,
        (E_RET, "    return np.column_stack([[0.0, 0.0, 1.0], rotz(alpha) @ [0.0, 1.0, 0.0],\n"
                "                            rotz(alpha) @ roty(beta) @ [1, 0, 0]]).tolist()"),
        (DET_RETURN,
         "    Rx = sp.Matrix([[1, 0, 0], [0, sp.cos(gamma), -sp.sin(gamma)],\n"
         "                    [0, sp.sin(gamma), sp.cos(gamma)]])\n"
         "    return ((Rz * Ry * Rx).T * E).det()  # the body frame: the same determinant"),
        ("    if abs(cb) < tol:  # det E = -cos(beta)\n        return None\n" + RATES,
         "    E = np.array(euler_rate_matrix_zyx(alpha, beta, gamma))\n"
         "    if abs(np.linalg.det(E)) < tol:\n        return None\n"
         "    return np.linalg.solve(E, w)"),
        ("    S = R_dot @ R.T\n    return np.array([S[2, 1], S[0, 2], S[1, 0]])",
         "    S = (R_dot @ R.T - R @ R_dot.T) / 2\n    return [S[2, 1], S[0, 2], S[1, 0]]"),
        ("    total = np.zeros(3)\n",
         "    total = np.zeros(3)\n    for R, w in zip(rotations[::-1], omegas[::-1]):\n"
         "        total = w + R @ total\n    return total\n"),
        ("    c = q0 @ q1\n",
         "    if q0 @ q1 <= 0:\n        q1 = -q1\n"
         "    rel = quat_multiply(quat_conjugate(q0), q1)\n"
         "    half = np.arctan2(np.linalg.norm(rel[1:]), rel[0])\n"
         "    u = rel[1:] / np.linalg.norm(rel[1:]) if half > 0 else np.zeros(3)\n"
         "    power = np.concatenate([[np.cos(t * half)], np.sin(t * half) * u])\n"
         "    return -quat_multiply(q0, power)\n    c = q0 @ q1\n"),
        ("return np.concatenate([real, dual])", "return -np.concatenate([real, dual])"),
        ("    conj0 = np.concatenate([quat_conjugate(dq0[:4]), quat_conjugate(dq0[4:])])\n"
         "    rel = mul(conj0, dq1)\n",
         "    conj0 = np.concatenate([quat_conjugate(dq0[:4]), quat_conjugate(dq0[4:])])\n"
         "    rel = mul(dq1, conj0)\n"),
        ("    return mul(dq0, step)", "    return -mul(step, dq0)"),
        ("    S = skew(s)\n    return np.linalg.solve(np.eye(3) - S, np.eye(3) + S)",
         "    S = skew(s)\n    return np.eye(3) + 2 / (1 + s @ s) * (S + S @ S)"),
        (CAYLEY_SOLVE, f"    return {SKEW_PART} / (1 + np.trace(R))\n" + CAYLEY_SOLVE))


@pytest.fixture(scope="module")
def graded(tmp_path_factory):
    """Every submission of this file, graded in one run: the mistake submissions, then the
    alternatives."""
    tmp = tmp_path_factory.mktemp("orientation")
    # det E's final simplification is left out (any form is right, and it costs 0.1 s a
    # submission; the solution as written is graded in test_grader.py)
    code = patched(solution_code(NAME), (DET_TIDY, DET_RETURN))
    right = code + "\n\n_slerp = slerp\n"  # the decoupled ScLERP's slerp is a right copy
    subs = mistake_submissions(tmp, NAME, code, TABLE, right)
    subs.append(write_notebook(tmp / "alt.ipynb", alternatives(code), assignment=NAME))
    results = judge_notebooks(subs)
    return results[:-1], results[-1], subs


def _verdicts(result: dict) -> list:
    return [(c["function"], c["score"], c["passed"], c["total"],
             [(d["key"], d["count"], d["message"]) for d in c["diagnoses"]],
             c["examples"]) for c in result["checks"]]


def test_judged_in_process_is_what_the_sandbox_gives(graded):
    """The mistake tables are judged in this process (grading_helpers.judge_notebooks);
    two of their submissions, graded for real in the sandbox, get the very same result:
    every score, count, diagnosis, message and example."""
    mistakes, _, subs = graded
    for k in (0, 5):
        sandboxed = grade(subs[k])
        assert sandboxed["sandbox"] and mistakes[k]["sandbox"] is None
        assert sandboxed["score"] == mistakes[k]["score"] < sandboxed["max_score"]
        assert _verdicts(sandboxed) == _verdicts(mistakes[k])


def test_orientation_mistakes_are_diagnosed(graded):
    mistakes, _, _ = graded
    wrong = misdiagnosed(mistakes, TABLE)
    assert not wrong, wrong
    results = [by_function(r) for r in mistakes]
    numpy_cos = results[5]["euler_rate_det_zyx"]["diagnoses"][0]["message"]
    assert "Symbol" in numpy_cos and "sympy's functions (sp.cos" in numpy_cos, numpy_cos
    # at the exact lock det E is the number 0: right there for the sign and the singular E,
    # "lock" for the constant one
    for n, key in ((0, "sign"), (4, "singular")):
        det = results[n]["euler_rate_det_zyx"]
        assert det["total"] - det["passed"] == 3 and top(det) == key
    constant = results[3]["euler_rate_det_zyx"]["diagnoses"]
    assert [(d["key"], d["count"]) for d in constant] == [("constant", 3), ("lock", 1)]
    # the rare mistakes fail only where they matter
    lock = results[5]["euler_rates_zyx"]  # no lock test: only the locked cases fail
    locked = sum(O.locked(*c[:3], c[4]) for c in cases_of("euler_rates_zyx"))
    assert lock["total"] - lock["passed"] == locked
    plus_only = results[7]["euler_rates_zyx"]  # β = +π/2 only: the other locks fail
    assert 0 < plus_only["total"] - plus_only["passed"] < locked
    nan = results[5]["sclerp"]["diagnoses"][0]
    assert nan["key"] == "no rotation" and nan["count"] == 4
    long = results[0]["slerp"]
    assert long["total"] - long["passed"] >= 15


def test_other_right_answers_are_accepted(graded):
    _, alt, _ = graded
    assert alt["score"] == alt["max_score"], [(c["function"], c["diagnoses"])
                                              for c in alt["checks"] if c["diagnoses"]]
