"""Assignment 05 · orientation kinematics: the ZYX Euler-rate matrix, its determinant
derived with sympy (:mod:`._euler_det`), the Euler rates of an angular velocity (None at
gimbal lock), ω from Ṙ, angular velocities added along a chain, slerp, the dual-quaternion
product, ScLERP, and Cayley's formula both ways (None for a half turn).

The references are kinlib's: :func:`~kinlib.euler_rate_matrix` (on sympy symbols too, for
det E) and :func:`~kinlib.euler_rates_singular` (``"ZYX"``), :func:`~kinlib.angular_velocity`,
:func:`~kinlib.add_angular_velocities`, :func:`~kinlib.quat_slerp`,
:func:`~kinlib.dual_quat_multiply`, :func:`~kinlib.dual_quat_sclerp`,
:func:`~kinlib.matrix_from_cayley` and :func:`~kinlib.cayley_from_matrix`.
"""

from __future__ import annotations

import numpy as np

import kinlib as kl

from ...check import Rule
from ...check.mistakes import FRAME, HALF_ANGLE, SIGN, SWAPPED
from .._checks import RIGHT, Assignment, Check, Mistake, Verdict, as_numeric
from ._euler_det import rate_det_check
from ._interpolation import dual_quat_multiply_check, finite_model, sclerp_check, slerp_check
from .common import DEGREES, TRANSPOSED, random_rotations, random_unit_vectors

#: a rotation with 1 + tr R below this is a half turn: no Cayley parameters
HALF_TURN = 1e-9


def _R(a, b, g):
    return kl.matrix_from_euler([a, b, g], "ZYX")


# -- the Euler-rate matrix ------------------------------------------------------------------
def rate_matrix(alpha, beta, gamma):
    """E(φ) with ω = E(φ) φ̇, ω in the fixed frame (kinlib's, for "ZYX")."""
    return kl.euler_rate_matrix([alpha, beta, gamma], "ZYX")


FIXED_AXES = np.array([[0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]])

RATE_MATRIX_MISTAKES = [
    FRAME.of(lambda a, b, g: _R(a, b, g).T @ rate_matrix(a, b, g),
             "these columns are the rate axes in the moving (body) frame, Rᵀ E: ω = E φ̇ is "
             "in the fixed frame, where α̇ turns about e_z, β̇ about R_z(α) e_y and γ̇ about "
             "R_z(α) R_y(β) e_x"),
    TRANSPOSED.of(lambda a, b, g: rate_matrix(a, b, g).T,
                  "you returned Eᵀ: the axis of each rate is a column of E (ω = E φ̇ is "
                  "α̇ times column 1 plus β̇ times column 2 plus γ̇ times column 3)"),
    Mistake("columns", "your columns are in the order γ̇, β̇, α̇: column k of E is the axis "
                       "of the k-th rate of φ̇ = (α̇, β̇, γ̇), so column 1 is e_z (α turns "
                       "about the base z axis)", lambda a, b, g: rate_matrix(a, b, g)[:, ::-1]),
    Mistake("fixed axes", "you used the base axes e_z, e_y, e_x for all three rates: each "
                          "rate turns about its axis as it stands after the rotations before "
                          "it, β̇ about R_z(α) e_y and γ̇ about R_z(α) R_y(β) e_x",
            lambda a, b, g: FIXED_AXES),
    DEGREES.of(lambda a, b, g: rate_matrix(*np.deg2rad([a, b, g]))),
]


def _rate_matrix_cases(rng):
    h = np.pi / 2
    fixed = [(0.0, 0.0, 0.0), (0.0, h, 0.0), (0.3, -h, 1.0), (1.0, 0.4, -0.7), (np.pi, 0.2, 0.1),
             (-2.0, 1.2, 3.0), (h, 0.0, 0.0)]
    rand = rng.uniform([-np.pi, -h, -np.pi], [np.pi, h, np.pi], (45, 3))
    return fixed + [tuple(map(float, r)) for r in rand]


# -- Euler rates of ω, None at gimbal lock --------------------------------------------------
def locked(alpha, beta, gamma, tol) -> bool:
    """Whether |det E| < tol (kinlib's euler_rates_singular): gimbal lock."""
    return bool(kl.euler_rates_singular([alpha, beta, gamma], "ZYX", tol))


def euler_rates(alpha, beta, gamma, omega, tol):
    """φ̇ = E(φ)⁻¹ ω, or None at gimbal lock."""
    if locked(alpha, beta, gamma, tol):
        return None
    return np.linalg.solve(rate_matrix(alpha, beta, gamma), np.asarray(omega, dtype=float))


def _solve(E, w):
    return np.linalg.solve(E, np.asarray(w, dtype=float))


RATES_MISTAKES = [
    TRANSPOSED.of(lambda a, b, g, w, tol: rate_matrix(a, b, g).T @ w,
                  "you multiplied ω by Eᵀ: E is not a rotation matrix (its columns are unit "
                  "vectors, but not perpendicular), so its inverse is not its transpose; "
                  "solve E φ̇ = ω"),
    Mistake("inverse", "you returned E ω; the rates solve E φ̇ = ω, so φ̇ = E⁻¹ ω",
            lambda a, b, g, w, tol: rate_matrix(a, b, g) @ w),
    FRAME.of(lambda a, b, g, w, tol: _solve(_R(a, b, g).T @ rate_matrix(a, b, g), w),
             "you solved with the body-frame matrix Rᵀ E, as if ω were given in the moving "
             "frame; ω is in the fixed frame: solve E φ̇ = ω"),
    Mistake("order", "your rates come in the order (γ̇, β̇, α̇): return (α̇, β̇, γ̇), the "
                     "order of the angles",
            lambda a, b, g, w, tol: euler_rates(a, b, g, w, tol)[::-1]),
    DEGREES.of(lambda a, b, g, w, tol: _solve(rate_matrix(*np.deg2rad([a, b, g])), w)),
    DEGREES.of(lambda a, b, g, w, tol: np.rad2deg(euler_rates(a, b, g, w, tol)),
               "you returned degrees per second: the rates are in radians per second, like ω"),
]
_RATES_RULE = Rule(euler_rates, RATES_MISTAKES)
LOCK = "|det E| = |cos β| < tol"


def _judge_rates(args, got):
    a, b, g, _, tol = args
    cb = abs(np.cos(b))
    if locked(a, b, g, tol):
        if got is None:
            return RIGHT
        arr, bad = as_numeric(got, (3,), "three rates (α̇, β̇, γ̇)")
        why = ("NaN or infinity" if bad.key == "nan" else
               "rates" if arr is not None else f"something else ({bad.message})")
        return Verdict(False, "gimbal", f"this is gimbal lock, {LOCK} (|cos β| = {cb:.3g}, tol "
                                        f"= {tol:g}): E is singular and no rates give every "
                                        f"ω, so return None; you returned {why}")
    if got is None:
        return Verdict(False, "missed", f"you returned None, but here |cos β| = {cb:.3g} is not "
                                        f"below tol = {tol:g}: E is invertible (the rates are "
                                        "large near the lock, but they exist). Return None "
                                        f"only when {LOCK}", euler_rates(*args))
    return _RATES_RULE.verdict(args, got)


def _rates_cases(rng):
    h = np.pi / 2
    tols = (1e-9, 1e-6, 1e-3)
    out = []
    for n in range(34):  # ordinary orientations
        a, g = rng.uniform(-np.pi, np.pi, 2)
        b = rng.uniform(-h + 0.05, h - 0.05)
        out.append((a, b, g, rng.normal(size=3), tols[n % 3]))
    for n, d in enumerate((1e-4, 3e-5, 1e-3, 1e-2, 0.05, 1e-4)):  # near the lock, not at it
        a, g = rng.uniform(-np.pi, np.pi, 2)
        tol = (1e-9, 1e-9, 1e-6, 1e-6, 1e-3, 1e-6)[n]
        out.append((a, (-1) ** n * (h - d), g, rng.normal(size=3), tol))
    locks = [(h, 1e-9), (-h, 1e-9), (h + 1e-12, 1e-9), (-h - 1e-12, 1e-9), (h - 1e-6, 1e-3),
             (-h + 1e-6, 1e-3), (3 * h, 1e-9), (-3 * h, 1e-6), (h, 1e-6), (-h, 1e-3)]
    for b, tol in locks:  # gimbal lock (|cos β| far below tol)
        a, g = rng.uniform(-np.pi, np.pi, 2)
        out.append((a, b, g, rng.normal(size=3), tol))
    out += [(0.4, 2.0, -1.0, rng.normal(size=3), 1e-9),  # β beyond ±π/2: not locked
            (-1.2, np.pi, 0.3, rng.normal(size=3), 1e-6),
            (0.7, -2.5, 2.2, rng.normal(size=3), 1e-3),
            (0.3, 0.2, 0.1, np.zeros(3), 1e-9), (0.0, 0.0, 0.0, np.array([0.0, 0.0, 1.0]), 1e-9),
            (0.0, 0.0, 0.0, np.array([1.0, 2.0, 3.0]), 1e-9)]
    return [(float(a), float(b), float(g), np.asarray(w, dtype=float), float(t))
            for a, b, g, w, t in out]


# -- ω from Ṙ -------------------------------------------------------------------------------
def _w(S):
    return np.array([S[2, 1], S[0, 2], S[1, 0]])


OMEGA_MISTAKES = [
    FRAME.of(lambda R, Rd: kl.vee(R.T @ Rd),
             "Rᵀ Ṙ = S(Rᵀ ω) gives ω in the moving (body) frame; the course's ω is in the "
             "fixed frame: S(ω) = Ṙ Rᵀ"),
    SIGN.of(lambda R, Rd: -kl.angular_velocity(R, Rd),
            "you returned −ω: S(ω) = Ṙ Rᵀ, not R Ṙᵀ (its transpose), and ω is read off as "
            "(S₃₂, S₁₃, S₂₁) = (S[2, 1], S[0, 2], S[1, 0])"),
    Mistake("vee", "one component has the wrong sign: read ω off S(ω) as (S₃₂, S₁₃, S₂₁), "
                   "i.e. S[2, 1], S[0, 2], S[1, 0] (S₃₁ = −ω_y)",
            lambda R, Rd: _w(Rd @ R.T) * [1.0, -1.0, 1.0]),
    Mistake("no R", "you read ω off Ṙ itself: Ṙ = S(ω) R, so S(ω) = Ṙ Rᵀ (Ṙ alone is skew "
                    "only where R = I)", lambda R, Rd: _w(Rd)),
    Mistake("no R", "you read ω off Ṙ itself: Ṙ = S(ω) R, so S(ω) = Ṙ Rᵀ (Ṙ alone is skew "
                    "only where R = I)", lambda R, Rd: kl.vee((Rd - Rd.T) / 2)),
]


def _omega_cases(rng):
    Rs = random_rotations(rng, 40)
    ws = random_unit_vectors(rng, 40) * rng.uniform(0.1, 5.0, (40, 1))
    out = [(R, kl.skew(w) @ R) for R, w in zip(Rs, ws, strict=True)]
    t, rate = 0.3, 2.0  # Rz(rate t) and its derivative, by hand
    Rd = rate * np.array([[-np.sin(rate * t), -np.cos(rate * t), 0.0],
                          [np.cos(rate * t), -np.sin(rate * t), 0.0], [0.0, 0.0, 0.0]])
    out += [(np.eye(3), kl.skew([0.0, 0.0, 2.0])), (Rs[0], np.zeros((3, 3))),
            (kl.rotz(rate * t), Rd), (kl.rotx(np.pi), kl.skew([0.5, -1.0, 0.2]) @ kl.rotx(np.pi))]
    return out


# -- angular velocities along a chain -------------------------------------------------------
def _chain(rotations, omegas, *, shift=0, reverse=False, transpose=False):
    """Σ R⁰_{i−1} ω_i, or the mistakes: R⁰_i (shift=1), the product reversed, R⁰_{i−1}ᵀ."""
    total, R0 = np.zeros(3), np.eye(3)
    for R, w in zip(rotations, omegas, strict=True):
        after = R0 @ R if not reverse else R @ R0
        A = after if shift else R0
        total = total + (A.T if transpose else A) @ w
        R0 = after
    return total


CHAIN_MISTAKES = [
    Mistake("frames", "you added the vectors as they are: each ω^{i−1}_{i−1,i} is expressed in "
                      "frame i − 1, so turn it into frame 0 first, with R⁰_{i−1}",
            lambda Rs, ws: np.sum(ws, axis=0)),
    Mistake("shift", "you turned ω^{i−1}_{i−1,i} with R⁰_i, one rotation too many: it is "
                     "expressed in frame i − 1, so it needs R⁰_{i−1} = R⁰_1 ⋯ R^{i−2}_{i−1} "
                     "(the identity for i = 1)", lambda Rs, ws: _chain(Rs, ws, shift=1)),
    Mistake("order", "you built R⁰_{i−1} in the wrong order: R⁰_{i−1} = R⁰_1 R¹_2 ⋯ "
                     "R^{i−2}_{i−1}, the first rotation leftmost",
            lambda Rs, ws: _chain(Rs, ws, reverse=True)),
    TRANSPOSED.of(lambda Rs, ws: _chain(Rs, ws, transpose=True),
                  "you turned each ω with R⁰_{i−1}ᵀ (from frame 0 into frame i − 1); from "
                  "frame i − 1 into frame 0 it is R⁰_{i−1}"),
]


def _chain_cases(rng):
    out = []
    for n in range(42):
        k = 1 + n % 6
        out.append((random_rotations(rng, k), rng.normal(size=(k, 3))))
    out.append((np.array([kl.rotz(np.pi / 2), kl.rotx(0.7)]),  # a wheel on a turntable
                np.array([[0.0, 0.0, 2.0], [5.0, 0.0, 0.0]])))
    thetas = rng.uniform(-np.pi, np.pi, 4)  # joints turning about their own z axes
    out.append((np.array([kl.rotz(t) @ kl.rotx(a) for t, a in
                          zip(thetas, (0.5, -1.0, 1.3, 0.2), strict=True)]),
                np.array([[0.0, 0.0, r] for r in rng.normal(size=4)])))
    out.append((np.array([np.eye(3)] * 3), rng.normal(size=(3, 3))))
    return out


# -- Cayley's formula -----------------------------------------------------------------------
def _aa(s, angle_of_norm):
    s = np.asarray(s, dtype=float)
    n = np.linalg.norm(s)
    return np.eye(3) if n == 0 else kl.matrix_from_axis_angle(s / n, angle_of_norm(n))


CAYLEY_MISTAKES = [
    TRANSPOSED.of(lambda s: kl.matrix_from_cayley(s).T,
                  "this is Rᵀ, the matrix of −s: R = (I − S)⁻¹(I + S), not (I + S)⁻¹(I − S); "
                  "or the signs of your S are swapped: S = [s]× has S₃₂ = s_x, S₁₃ = s_y, "
                  "S₂₁ = s_z"),
    SWAPPED.of(lambda s: kl.matrix_from_cayley(np.asarray(s)[::-1]),
               "s_x and s_z are swapped: that is S written the way seed 002 prints it "
               "(S₂₁ = s_x, S₃₂ = s_z); the course's S = [s]× has S₃₂ = s_x, S₁₃ = s_y, "
               "S₂₁ = s_z, the skew matrix of the cross product s × ·"),
    Mistake("rotation vector", "you turned by |s| about s/|s|, as if s were the rotation "
                               "vector θk: Cayley's s = tan(θ/2) k, and R = (I − S)⁻¹(I + S)",
            lambda s: _aa(s, lambda n: n)),
    HALF_ANGLE.of(lambda s: _aa(s, np.arctan),
                  "you turned by arctan|s|, as if s = tan θ k: Cayley's s = tan(θ/2) k, so "
                  "(I − S)⁻¹(I + S) turns by 2 arctan|s|"),
]


def _cayley_cases(rng):
    dirs = random_unit_vectors(rng, 36)
    norms = np.concatenate([rng.uniform(0.05, 1.0, 18), rng.uniform(1.0, 8.0, 14),
                            [20.0, 150.0, 1e3, 1e-4]])
    out = [(d * n,) for d, n in zip(dirs, norms, strict=True)]
    out += [(np.zeros(3),), (np.array([0.0, 0.0, 1.0]),), (np.array([1.0, 0.0, 0.0]),),
            (np.array([0.1, -0.2, 0.3]),), (np.array([2.0, 0.0, -1.0]),)]
    return out


def half_turn(R) -> bool:
    return bool(1.0 + np.trace(R) < HALF_TURN)


def cayley_reference(R):
    """kinlib's Cayley parameters, or None for a half turn (1 + tr R < HALF_TURN)."""
    return None if half_turn(R) else kl.cayley_from_matrix(R)


def _axis_angle(R):
    return kl.axis_angle_from_matrix(R)


INVERSE_MISTAKES = [
    TRANSPOSED.of(lambda R: -kl.cayley_from_matrix(R),
                  "that is −s, the parameters of Rᵀ (the opposite turn): (I − S) R = I + S "
                  "gives R − I = S (I + R), so S = (R − I)(I + R)⁻¹, not (I − R)(I + R)⁻¹"),
    SWAPPED.of(lambda R: kl.cayley_from_matrix(R)[::-1],
               "s_x and s_z are swapped: that is S read the way seed 002 prints it "
               "(S₂₁ = s_x); the course's S = [s]× has S₃₂ = s_x, S₁₃ = s_y, S₂₁ = s_z"),
    HALF_ANGLE.of(finite_model(lambda R: np.tan(_axis_angle(R)[1]) * _axis_angle(R)[0]),
                  "that is tan θ k: Cayley's parameters use the half angle, s = tan(θ/2) k"),
    Mistake("quaternion", "sin(θ/2) k is the vector part of the unit quaternion; Cayley's "
                          "parameters divide it by the scalar part cos(θ/2): s = tan(θ/2) k",
            lambda R: np.sin(_axis_angle(R)[1] / 2) * _axis_angle(R)[0]),
    Mistake("skew part", "that is sin θ k, the skew part (R − Rᵀ)/2 read as a vector: "
                         "Cayley's S is not the skew part of R. Solve (I − S) R = I + S for S",
            lambda R: kl.vee(R - R.T) / 2),
]
_INVERSE_RULE = Rule(cayley_reference, INVERSE_MISTAKES)


def _judge_inverse(args, got):
    (R,) = args
    if half_turn(R):
        if got is None:
            return RIGHT
        return Verdict(False, "half turn", f"R is a half turn (1 + tr R = {1 + np.trace(R):.2g}"
                                           f" < {HALF_TURN:g}): I + R is singular and "
                                           "tan(θ/2) infinite, so there are no Cayley "
                                           "parameters; return None")
    if got is None:
        return Verdict(False, "missed", f"you returned None, but R turns by "
                                        f"{np.rad2deg(_axis_angle(R)[1]):.6g}°, not a half "
                                        f"turn (1 + tr R = {1 + np.trace(R):.3g}): its "
                                        "parameters exist, large as they are near 180°",
                       cayley_reference(R))
    return _INVERSE_RULE.verdict(args, got)


def _inverse_cases(rng):
    out = [(R,) for R in random_rotations(rng, 34)]
    out += [(kl.matrix_from_axis_angle(k, a),) for k, a in
            zip(random_unit_vectors(rng, 6), (np.pi - 1e-3, np.pi - 1e-2, 3.0, np.pi - 1e-3,
                                              1e-7, 0.5), strict=True)]
    out += [(np.eye(3),), (kl.rotz(np.pi / 2),), (kl.rotx(-np.pi / 2),)]
    half = [kl.rotx(np.pi), kl.roty(np.pi), kl.rotz(np.pi)]  # half turns: no parameters
    half += [kl.matrix_from_axis_angle(k, np.pi) for k in random_unit_vectors(rng, 5)]
    return out + [(R,) for R in half]


def assignment() -> Assignment:
    checks = [Check("euler_rate_matrix_zyx", 4, "E(α, β, γ) with ω = E φ̇ (fixed frame)",
                    _rate_matrix_cases, rate_matrix, RATE_MATRIX_MISTAKES),
              rate_det_check(),
              Check("euler_rates_zyx", 6, "φ̇ = E⁻¹ ω, or None at gimbal lock", _rates_cases,
                    judge=_judge_rates, is_trivial=lambda c: locked(*c[:3], c[4]),
                    trivial="of None at gimbal lock"),
              Check("omega_from_rdot", 3, "ω with S(ω) = Ṙ Rᵀ", _omega_cases,
                    kl.angular_velocity, OMEGA_MISTAKES),
              Check("omega_chain", 4, "ω⁰_{0,n} = Σ R⁰_{i−1} ω^{i−1}_{i−1,i}", _chain_cases,
                    kl.add_angular_velocities, CHAIN_MISTAKES),
              slerp_check(), dual_quat_multiply_check(), sclerp_check(),
              Check("cayley_to_matrix", 3, "R = (I − S)⁻¹(I + S)", _cayley_cases,
                    kl.matrix_from_cayley, CAYLEY_MISTAKES),
              Check("matrix_to_cayley", 4, "s = tan(θ/2) k of R, or None for a half turn",
                    _inverse_cases, judge=_judge_inverse, is_trivial=lambda c: half_turn(c[0]),
                    trivial="of None for half turns")]
    return Assignment("05_orientation_kinematics", "Orientation kinematics", checks)
