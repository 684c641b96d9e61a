"""Notebook 01 · spatial descriptions: positions, rotation matrices, frames, mappings."""

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


EXERCISES = [
    choice("01.1", "predict", "when a position vector keeps its length",
           {"a": "for any two frames", "b": "when {A} and {B} share their origin",
            "c": "only when {B} is turned about Z_A"}, "b",
           {"a": ("translation", "a translation changes the vector from the origin to the "
                                 "point, and so its length: ‖ᴬP‖ = ‖ᴮP‖ for every P needs "
                                 "ᴬP_BORG = 0, a pure rotation"),
            "c": ("rotation axis", "every rotation keeps lengths, whatever its axis: "
                                   "‖R p‖² = pᵀRᵀR p = pᵀp")}),
    expression("01.2", "R_Y(θ) from the dot products of the axes", _roty_sym,
               what="a 3×3 sympy Matrix", diagnoses=("transposed", "sign")),
    value("01.3", "predict", "independent constraints in RᵀR = I", lambda: 6,
          Mistake("symmetric", "RᵀR is symmetric: the equation for entry (i, j) is the one "
                               "for (j, i), so of its nine entries only six are independent",
                  lambda: 9),
          Mistake("right angles", "three unit lengths, yes, but also three right angles "
                                  "between the columns", lambda: 3), what="a number"),
    value("01.4", "compute", "ᴮŶ_A: a row of ᴬR_B", lambda: _R_AB()[1, :],
          TRANSPOSED.of(lambda: _R_AB()[:, 1], "that is a column: ᴬŶ_B, the Y axis of {B} "
                                               "in {A}. The axes of {A} written in {B} are "
                                               "the rows of ᴬR_B (ᴮR_A = ᴬR_Bᵀ)")),
    value("01.5", "compute", "ᴬP = ᴬR_B ᴮP + ᴬP_BORG", lambda: _rx45() @ P_B + P_BORG,
          Mistake("translation", "the translation is missing: add ᴬP_BORG = (0, 0, 2), the "
                                 "origin of {B} in {A}", lambda: _rx45() @ P_B),
          TRANSPOSED.of(lambda: _rx45().T @ P_B + P_BORG,
                        "you rotated with ᴮR_A = ᴬR_Bᵀ (or by +45°): ᴬP = ᴬR_B ᴮP + ᴬP_BORG"),
          Mistake("order", "you added the offset before rotating: ᴬP_BORG is already in {A}, "
                           "so it is added after the rotation", lambda: _rx45() @ (P_B + P_BORG)),
          DEGREES.of(lambda: np.array([[1, 0, 0], [0, np.cos(-45), -np.sin(-45)],
                                       [0, np.sin(-45), np.cos(-45)]]) @ P_B + P_BORG)),
    value("01.6", "compute", "a fixed point described in a frame turned +30°", _turned,
          TRANSPOSED.of(lambda: _turned() * [1, -1, 1],
                        "that is the operator Rz(+30°) ᴬP, which moves the point forward; "
                        "describing the fixed point in the turned frame uses ᴮR_A = ᴬR_Bᵀ "
                        "= Rz(−30°)"),
          DEGREES.of(lambda: np.array([np.cos(30), -np.sin(30), 0.0]))),
]
