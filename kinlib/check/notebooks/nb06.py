"""Notebook 06 · quaternions: the plane's rotations as complex numbers, the product,
conjugation, Euler parameters, checkpoints, composition."""

import numpy as np

from .._verdict import RIGHT, Mistake, Verdict, as_numeric, close, fmt
from ..mistakes import CONJUGATE, DEGREES, HALF_ANGLE, ORDER, XYZW
from ._make import choice, expression, judged, value

# --- 06.0 · the 2×2 matrix of z ↦ e^{iθ} z -----------------------------------------------

def _plane_rotation(half=False, rows_swapped=False):
    """The 2×2 block of kinlib's R_Z(θ) (or R_Z(θ/2)): the rotation of the x-y plane."""
    def model():
        import sympy as sp

        from ... import rotz

        theta = sp.Symbol("theta", real=True)
        M = rotz(theta / 2 if half else theta)[:2, :2]
        return M[::-1, :] if rows_swapped else M
    return model


# --- 06.1 · which term of the product changes sign when the factors are swapped ---------

_TERMS = {"a": lambda r1, v1, r2, v2: np.atleast_1d(r1 * r2 - v1 @ v2),
          "b": lambda r1, v1, r2, v2: r1 * v2 + r2 * v1,
          "c": lambda r1, v1, r2, v2: np.cross(v1, v2)}


def _flipping_term() -> str:
    """The term of (r1, v1)(r2, v2) that is odd under 1 ↔ 2, found at random numbers."""
    rng = np.random.default_rng(0)
    (r1, r2), (v1, v2) = rng.normal(size=2), rng.normal(size=(2, 3))
    odd = [k for k, f in _TERMS.items()
           if np.allclose(f(r2, v2, r1, v1), -f(r1, v1, r2, v2))
           and not np.allclose(f(r1, v1, r2, v2), 0.0)]
    return odd[0]


# --- 06.2 · the matrix of p ↦ q p q̄ for q about z --------------------------------------

def _rz_sym(factor):
    def model():
        import sympy as sp

        from ... import rotz

        return rotz(factor * sp.Symbol("theta", real=True))
    return model


_CONJUGATION_MISTAKES = (
    CONJUGATE.of(_rz_sym(-1), "that is q̄ p q, the conjugation the other way round: it turns "
                              "by −θ (the transpose Rᵀ). A rotation is p ↦ q p q̄ = q p q⁻¹"),
    HALF_ANGLE.of(_rz_sym(2), "your matrix turns by 2θ: the quaternion of θ about z is "
                              "(cos θ/2, 0, 0, sin θ/2), with the half angle"),
)


# --- 06.3 · seed 002's Euler parameters, scalar last --------------------------------------

def _R_seed():
    from ... import matrix_from_axis_angle

    return matrix_from_axis_angle([1.0, -2.0, 2.0], np.deg2rad(100))


def _q_seed():
    from ... import quat_from_matrix

    return quat_from_matrix(_R_seed())


def _eps_seed002(R, swap_differences=False):
    """Seed 002's inverse problem, as written there: (ε1, ε2, ε3, ε4)."""
    eps4 = 0.5 * np.sqrt(1.0 + np.trace(R))
    diff = np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]])
    return np.r_[(-diff if swap_differences else diff) / (4.0 * eps4), eps4]


# --- 06.4 · seed 000's checkpoints -------------------------------------------------------

_CHECKPOINTS = (("no rotation", (1.0, 0.0, 0.0), 0.0),
                ("180° about z", (0.0, 0.0, 1.0), np.pi),
                ("90° about y", (0.0, 1.0, 0.0), np.pi / 2),
                ("−90° about x", (1.0, 0.0, 0.0), -np.pi / 2))


def _checkpoint(axis, angle):
    from ... import quat_from_axis_angle

    return quat_from_axis_angle(axis, angle)


def _by_hand(axis, angle):
    return np.r_[np.cos(angle / 2), np.sin(angle / 2) * np.asarray(axis)]


_ROW_MISTAKES = (
    (HALF_ANGLE.key, lambda u, a: np.r_[np.cos(a), np.sin(a) * np.asarray(u)],
     "this is (cos θ, sin θ û): the quaternion carries the half angle, "
     "(cos θ/2, sin θ/2 û)"),
    (DEGREES.key, lambda u, a: _by_hand(u, np.rad2deg(a)),
     "you put the angle in degrees into cos and sin (np.cos(90 / 2)): they take radians"),
    (XYZW.key, lambda u, a: np.roll(_checkpoint(u, a), -1),
     "this is [x, y, z, w], the scalar last (ROS, scipy, seed 002's ε4); kinlib's "
     "order is [w, x, y, z]: the scalar cos θ/2 first"),
    (CONJUGATE.key, lambda u, a: _checkpoint(u, -a),
     "this is the rotation by −θ, the conjugate: a negative angle flips the vector part, "
     "(cos(−θ/2), sin(−θ/2) û) = (cos θ/2, −sin θ/2 û)"),
)


def _checkpoints_judge(args, got):
    a, bad = as_numeric(got, (4, 4), "four quaternions, one row each", returned=False)
    if a is None:
        return bad
    expected = np.array([_checkpoint(u, t) for _, u, t in _CHECKPOINTS])
    for row, (name, u, t), ref in zip(a, _CHECKPOINTS, expected, strict=True):
        if close(row, ref, 1e-6) or close(row, -ref, 1e-6):
            continue
        where = f"the row for {name}, {fmt(row)}"
        for key, model, message in _ROW_MISTAKES:
            wrong = model(u, t)
            if ((close(row, wrong, 1e-6) or close(row, -wrong, 1e-6))
                    and not (close(wrong, ref, 1e-6) or close(wrong, -ref, 1e-6))):
                return Verdict(False, key, f"{where}: {message}", expected)
        norm = float(np.linalg.norm(row))
        if abs(norm - 1.0) > 1e-6:
            hint = "; cos 45° = sin 45° = √0.5, not 0.5" if np.isclose(
                np.abs(row), 0.5).any() else ""
            return Verdict(False, "unit", f"{where}, has norm {norm:.4g}: a rotation is a "
                                          f"unit quaternion (cos θ/2, sin θ/2 û){hint}",
                           expected)
        return Verdict(False, "wrong", f"{where}, is not the quaternion of that rotation: "
                                       "write (cos θ/2, sin θ/2 û)", expected)
    return RIGHT


# --- 06.5 · 120° about (1, 1, 1)/√3 by hand; 06.6 · first q_perm, then 90° about z -------

_DIAG = np.ones(3) / np.sqrt(3.0)


def _q_perm():
    from ... import quat_from_axis_angle

    return quat_from_axis_angle(_DIAG, np.deg2rad(120))


def _q_z90():
    from ... import quat_from_axis_angle

    return quat_from_axis_angle([0.0, 0.0, 1.0], np.pi / 2)


def _mul(p, q):
    from ... import quat_multiply

    return quat_multiply(p, q)


def _conj(q):
    from ... import quat_conjugate

    return quat_conjugate(q)


def _then():
    return _mul(_q_z90(), _q_perm())


EXERCISES = [
    expression("06.0", "the 2×2 matrix of z ↦ e^{iθ} z", _plane_rotation(),
               Mistake("re im", "the rows are swapped: x′ is the real part of e^{iθ}(x + iy), "
                                "y′ the imaginary part", _plane_rotation(rows_swapped=True)),
               HALF_ANGLE.of(_plane_rotation(half=True),
                             "your matrix turns by θ/2: in the plane z ↦ e^{iθ} z turns by the "
                             "whole angle. The half angle belongs to the quaternion, whose "
                             "sandwich q p q̄ multiplies by q twice"),
               what="a 2×2 sympy Matrix in theta", swaps=(), diagnoses=("transposed",),
               explain="e^{iθ}(x + iy) = (x cos θ − y sin θ) + i (x sin θ + y cos θ): the matrix "
                       "is [[cos θ, −sin θ], [sin θ, cos θ]], the top-left block of R_Z(θ) in "
                       "notebook 01. Multiplying by a unit complex number turns the plane."),
    choice("06.1", "predict", "which term of q1 q2 changes sign when the factors swap",
           {"a": "the scalar part r1 r2 − v1·v2", "b": "r1 v2 + r2 v1", "c": "v1 × v2",
            "d": "none: only non-unit quaternions fail to commute"}, _flipping_term(),
           {"a": ("dot product", "r1 r2 and v1·v2 do not change when 1 and 2 swap: q1 q2 "
                                 "and q2 q1 always have the same scalar part"),
            "b": ("symmetric", "r1 v2 + r2 v1 becomes r2 v1 + r1 v2 when 1 and 2 swap: the "
                               "same vector"),
            "d": ("unit", "unit or not, i j = k but j i = −k: the vector parts of q1 q2 and "
                          "q2 q1 differ whenever v1 and v2 are not parallel")},
           explain="only the cross product cares about the order, v2 × v1 = −v1 × v2: "
                   "q1 q2 − q2 q1 = (0, 2 v1 × v2)."),
    expression("06.2", "the matrix of p ↦ q p q̄ for q about z", _rz_sym(1),
               *_CONJUGATION_MISTAKES, what="a 3×3 sympy Matrix in theta", swaps=(),
               explain="it is R_Z(θ), the rotation about z of notebook 01: its entries come "
                       "out as cos²(θ/2) − sin²(θ/2) = cos θ and 2 sin(θ/2) cos(θ/2) = sin θ. "
                       "The two half angles, one from q and one from q̄, add up to the whole "
                       "angle."),
    value("06.3", "compute", "seed 002's Euler parameters as a kinlib quaternion", _q_seed,
          XYZW.of(lambda: _eps_seed002(_R_seed()),
                  "you kept seed 002's order (ε1, ε2, ε3, ε4): ε4 = cos θ/2 is the scalar and "
                  "comes last there, [x, y, z, w] as in ROS and scipy; kinlib's [w, x, y, z] "
                  "is (ε4, ε1, ε2, ε3)"),
          Mistake("reversed", "you reversed the four numbers: (ε4, ε3, ε2, ε1) swaps x and "
                              "z; only ε4 moves to the front, (ε4, ε1, ε2, ε3)",
                  lambda: _eps_seed002(_R_seed())[::-1]),
          CONJUGATE.of(lambda: np.roll(_eps_seed002(_R_seed(), True), 1),
                       "the vector part has the wrong sign, the inverse rotation: seed 002 "
                       "takes r32 − r23, r13 − r31, r21 − r12 (row index first: r32 is "
                       "R[2, 1])"),
          accept=lambda: [-_q_seed()], what="a quaternion [w, x, y, z]",
          explain="kinlib's quaternion is (ε4, ε1, ε2, ε3): only the scalar ε4 = cos θ/2 moves "
                  "to the front. Seed 002's (ε1, ε2, ε3, ε4) typed in as written would be read "
                  "as w = ε1, another rotation."),
    judged("06.4", "predict", "seed 000's checkpoints", _checkpoints_judge,
           diagnoses=(HALF_ANGLE.key, DEGREES.key, XYZW.key, CONJUGATE.key, "unit")),
    value("06.5", "compute", "120° about (1, 1, 1)/√3 by hand", _q_perm,
          HALF_ANGLE.of(lambda: _by_hand(_DIAG, 2 * np.deg2rad(120)),
                        "this is (cos 120°, sin 120° û): the quaternion takes the half angle, "
                        "(cos 60°, sin 60° û)"),
          DEGREES.of(lambda: _by_hand(_DIAG, 120.0),
                     "you took the cosine of 60 radians (np.cos(120 / 2)): convert with "
                     "np.deg2rad first"),
          Mistake("unit axis", "the axis (1, 1, 1) is not a unit vector: divide it by √3, "
                               "or the quaternion is not a unit quaternion",
                  lambda: _by_hand(np.ones(3), np.deg2rad(120))),
          accept=lambda: [-_q_perm()], what="a quaternion [w, x, y, z]",
          explain="cos 60° = ½ and sin 60°/√3 = ½: all four numbers are ½ (or all −½). This "
                  "quaternion reads the same in [w, x, y, z] and [x, y, z, w], so it is a bad "
                  "test case for a conversion."),
    value("06.6", "compute", "first q_perm, then 90° about world z", _then,
          ORDER.of(lambda: _mul(_q_perm(), _q_z90()),
                   "this is q_perm ⊗ q_z90: first 90° about z, then q_perm. Like R2 R1, the "
                   "rotation applied first stands on the right: q_z90 ⊗ q_perm"),
          Mistake("conjugated", "q_z90 q_perm q̄_z90 is q_perm's rotation with its axis "
                                "turned by q_z90 (120° about another axis), not the two "
                                "rotations one after the other: multiply, q_z90 ⊗ q_perm",
                  lambda: _mul(_mul(_q_z90(), _q_perm()), _conj(_q_z90()))),
          accept=lambda: [-_then()], what="a quaternion [w, x, y, z]",
          explain="q_z90 ⊗ q_perm: as with matrices, R2 R1, the rotation applied first stands "
                  "on the right."),
]
