"""Notebook 01 · spatial descriptions: positions, rotation matrices, which matrices keep
lengths, frames, mappings."""

import numpy as np

from .._verdict import Mistake
from ..mistakes import DEGREES, TRANSPOSED
from ._make import choice, expression, value


def _R_AB():
    from ... import matrix_from_euler

    return matrix_from_euler([0.4, -0.3, 1.1], "ZYX")


def _rx45():
    from ... import rotx

    return rotx(np.deg2rad(-45))


P_B, P_BORG = np.array([0.0, 1.0, 1.0]), np.array([0.0, 0.0, 2.0])


def _turned():
    from ... import rotz

    return rotz(np.deg2rad(30)).T @ np.array([1.0, 0.0, 0.0])


def _roty_sym():
    import sympy as sp

    from ... import roty

    return roty(sp.Symbol("theta", real=True))


def _candidates():
    """The four matrices of exercise 01.5, as the notebook gives them: a rotation, the swap
    of x and y, a shear, and unit columns at 45° to each other."""
    from ... import matrix_from_axis_angle

    s = np.sqrt(0.5)
    return [matrix_from_axis_angle([1.0, 2.0, 2.0], 0.9),
            np.array([[0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]),
            np.array([[1.0, 0.5, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]),
            np.array([[1.0, s, 0.0], [0.0, s, 0.0], [0.0, 0.0, 1.0]])]


def _keeps_length():
    """Which candidates keep the length of every vector: tried on random vectors (the
    definition, not the theorem MᵀM = I)."""
    P = np.random.default_rng(1).normal(size=(3, 200))
    return np.array([np.allclose(np.linalg.norm(M @ P, axis=0), np.linalg.norm(P, axis=0))
                     for M in _candidates()], dtype=float)


def _det_one():
    return np.array([np.isclose(np.linalg.det(M), 1.0) for M in _candidates()], dtype=float)


def _rotations_only():
    from ... import is_rotation

    return np.array([is_rotation(M) for M in _candidates()], dtype=float)


def _unit_columns():
    return np.array([np.allclose(np.linalg.norm(M, axis=0), 1.0) for M in _candidates()],
                    dtype=float)


EXERCISES = [
    choice("01.1", "predict", "when a position vector keeps its length",
           {"a": "for any two frames", "b": "when {A} and {B} share their origin",
            "c": "only when {B} is turned about Z_A"}, "b",
           {"a": ("translation", "a translation changes the vector from the origin to the "
                                 "point, and so its length: ‖ᴬP‖ = ‖ᴮP‖ for every P needs "
                                 "ᴬP_BORG = 0, a pure rotation"),
            "c": ("rotation axis", "every rotation keeps lengths, whatever its axis: "
                                   "‖R p‖² = pᵀRᵀR p = pᵀp")},
           explain="a rotation keeps every length, ‖R p‖² = pᵀRᵀR p = pᵀp; a translation "
                   "moves the origin the vector is measured from, so the lengths change"),
    expression("01.2", "R_Y(θ) from the dot products of the axes", _roty_sym,
               what="a 3×3 sympy Matrix", diagnoses=("transposed", "sign"),
               explain="R_Y(θ) = [[cos θ, 0, sin θ], [0, 1, 0], [−sin θ, 0, cos θ]]. Unlike "
                       "R_X and R_Z, its −sin θ sits below the diagonal: about Y the positive "
                       "turn takes Z to X (not X to Z), so ᴬX̂_B = (cos θ, 0, −sin θ)"),
    value("01.3", "predict", "independent constraints in RᵀR = I", lambda: 6,
          Mistake("symmetric", "RᵀR is symmetric: the equation for entry (i, j) is the one "
                               "for (j, i), so of its nine entries only six are independent",
                  lambda: 9),
          Mistake("right angles", "3 is what remains, 9 − 6 free parameters (or only the "
                                  "three unit lengths): the constraints are three unit "
                                  "lengths and also three right angles between the columns",
                  lambda: 3), what="a number"),
    choice("01.4", "predict", "what RᵀR = I allows for det R",
           {"a": "only +1", "b": "+1 or −1", "c": "any number except 0"}, "b",
           {"a": ("handedness", "RᵀR = I alone gives det(R)² = det(RᵀR) = det(I) = 1, so ±1: "
                                "a mirror diag(1, 1, −1) has orthonormal columns and det −1. "
                                "What picks +1 is that the frame is right-handed"),
            "c": ("orthonormal", "RᵀR = I says more than 'R has an inverse': det(Rᵀ) det(R) "
                                 "= det(R)² = det(I) = 1, so det R is +1 or −1")},
           explain="det(R)² = det(Rᵀ) det(R) = det(RᵀR) = det(I) = 1. Which of the two signs "
                   "a rotation has: the demonstration"),
    value("01.5", "predict", "which matrices keep every length", _keeps_length,
          Mistake("determinant", "det M = +1 is not what keeps lengths: the shear c has det 1 "
                                 "and takes (0, 1, 0) to (0.5, 1, 0), of length 1.118, while b "
                                 "has det −1 and keeps every length. ‖Mp‖ = ‖p‖ for all p "
                                 "exactly when MᵀM = I", _det_one),
          Mistake("reflection", "b keeps every length too: it swaps x and y, a reflection in "
                                "the plane x = y. Its columns are orthonormal, MᵀM = I, which "
                                "is all ‖Mp‖ = ‖p‖ needs; det = −1 only flips the handedness",
                  _rotations_only),
          Mistake("unit columns", "unit columns are not enough: d's columns have length 1 but "
                                  "meet at 45°. ‖Mp‖² = Σᵢⱼ pᵢpⱼ (colᵢ · colⱼ) keeps the cross "
                                  "terms unless the columns are also perpendicular",
                  _unit_columns),
          what="four answers, True or False",
          explain="a (a rotation) and b (the swap of x and y: a reflection, det −1) keep every "
                  "length; c (a shear, det +1) and d (unit columns at 45°) do not. "
                  "‖Mp‖ = ‖p‖ for every p exactly when MᵀM = I, whatever det M."),
    value("01.6", "compute", "ᴮŶ_A: a row of ᴬR_B", lambda: _R_AB()[1, :],
          TRANSPOSED.of(lambda: _R_AB()[:, 1], "that is a column: ᴬŶ_B, the Y axis of {B} "
                                               "in {A}. The axes of {A} written in {B} are "
                                               "the rows of ᴬR_B (ᴮR_A = ᴬR_Bᵀ)"),
          explain="ᴮŶ_A is the second column of ᴮR_A = ᴬR_Bᵀ, i.e. the second row of ᴬR_B: "
                  "`R_AB[1, :]`"),
    value("01.7", "compute", "ᴬP = ᴬR_B ᴮP + ᴬP_BORG", lambda: _rx45() @ P_B + P_BORG,
          Mistake("translation", "the translation is missing: add ᴬP_BORG = (0, 0, 2), the "
                                 "origin of {B} in {A}", lambda: _rx45() @ P_B),
          TRANSPOSED.of(lambda: _rx45().T @ P_B + P_BORG,
                        "you rotated with ᴮR_A = ᴬR_Bᵀ (or by +45°): ᴬP = ᴬR_B ᴮP + ᴬP_BORG"),
          Mistake("order", "you added the offset before rotating: ᴬP_BORG is already in {A}, "
                           "so it is added after the rotation", lambda: _rx45() @ (P_B + P_BORG)),
          DEGREES.of(lambda: np.array([[1, 0, 0], [0, np.cos(-45), -np.sin(-45)],
                                       [0, np.sin(-45), np.cos(-45)]]) @ P_B + P_BORG),
          explain="ᴬP = ᴬR_B ᴮP + ᴬP_BORG ≈ (0, 1.414, 2): rotate ᴮP into the orientation "
                  "of {A} (the intermediate frame {C}), then add the origin of {B}"),
    value("01.8", "compute", "a fixed point described in a frame turned +30°", _turned,
          TRANSPOSED.of(lambda: _turned() * [1, -1, 1],
                        "that is the operator Rz(+30°) ᴬP, which moves the point forward; "
                        "describing the fixed point in the turned frame uses ᴮR_A = ᴬR_Bᵀ "
                        "= Rz(−30°)"),
          DEGREES.of(lambda: np.array([np.cos(30), -np.sin(30), 0.0])),
          explain="ᴮP = ᴬR_Bᵀ ᴬP = Rz(−30°)(1, 0, 0) = (cos 30°, −sin 30°, 0) ≈ (0.866, −0.5, 0): "
                  "seen from the frame turned forward, the fixed point appears turned "
                  "backward"),
]
