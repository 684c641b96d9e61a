"""Notebook 13 · differential kinematics II: singularities and manipulability of the planar
2R arm (and the PUMA 560)."""

from functools import cache

import numpy as np

from .._verdict import Mistake
from ..judges import choice_judge
from ..mistakes import DEGREES, SIGN, SWAPPED, TRANSPOSED
from ._make import expression, judged, value

L1, L2 = 1.0, 0.8   # the notebook's arm


def _J(theta1, theta2, rows=2):
    """The arm's Jacobian from kinlib: rows ẋ, ẏ (and φ̇ for rows=3)."""
    from ... import planar_2r_jacobian

    return planar_2r_jacobian(theta1, theta2, L1, L2)[:rows]


# -- 13.1 · det J of the 2R arm --------------------------------------------------------------
def _det_2r():
    """det of the position Jacobian, from the tip built with kinlib's rotz (not from x, y)."""
    import sympy as sp

    from ... import rotz

    t1, t2 = sp.symbols("theta_1 theta_2", real=True)
    l1, l2 = sp.symbols("l_1 l_2", positive=True)
    tip = rotz(t1) * (sp.Matrix([l1, 0, 0]) + rotz(t2) * sp.Matrix([l2, 0, 0]))
    return sp.Matrix(tip[:2]).jacobian([t1, t2]).det()


def _det_swapped():
    import sympy as sp

    t1, t2 = sp.symbols("theta_1 theta_2", real=True)
    return _det_2r().xreplace({t1: t2, t2: t1})


_DET_MISTAKES = (
    SIGN.of(lambda: -_det_2r(),
            "right up to the sign: are your columns in the order (θ2, θ1)? Swapping two "
            "columns flips a determinant; column j is the tip velocity ∂(x, y)/∂θj"),
    SWAPPED.of(_det_swapped,
               "θ1 and θ2 are swapped: det J cannot depend on θ1, since turning joint 1 "
               "turns the whole arm without changing its shape; it depends on the elbow "
               "angle θ2"),
)


# -- 13.2 · the lost direction at θ2 = 0 -----------------------------------------------------
LOST_OPTIONS = {"a": "along the arm: towards the base or away from it",
                "b": "across the arm, perpendicular to it",
                "c": "none: two joints still make every planar velocity, only more slowly"}
_LOST_WRONG = {
    "b": ("across", "across the arm is the one direction the tip can still move in: each "
                    "joint swings the tip on a circle about itself, and at θ2 = 0 both centres "
                    "lie on the arm's line, so both columns of J point across the arm"),
    "c": ("rank", "at θ2 = 0, det J = 0: the two columns are parallel and J q̇ covers only "
                  "one line of tip velocities, however fast the joints turn")}


@cache
def _lost_right() -> str:
    """The option the SVD of J at θ2 = 0 gives: the left null vector against the arm's line."""
    theta1 = 0.3
    U, s, _ = np.linalg.svd(_J(theta1, 0.0))
    if s[1] > 1e-9 * s[0]:
        return "c"
    along = abs(U[:, 1] @ [np.cos(theta1), np.sin(theta1)])
    return "a" if np.isclose(along, 1.0) else "b"


def _judge_lost(args, got):
    return choice_judge(LOST_OPTIONS, _lost_right(), _LOST_WRONG)(args, got)


# -- 13.3 · joint velocities for a tip velocity ----------------------------------------------
V_TIP = np.array([-1.0, 0.0])
Q_TIP = (0.0, np.pi / 2)


def _qdot():
    return np.linalg.solve(_J(*Q_TIP), V_TIP)


# -- 13.4 · manipulability at θ2 = π/2 --------------------------------------------------------
Q_W = (0.3, np.pi / 2)


def _w(q=Q_W):
    from ... import manipulability

    return float(manipulability(_J(*q)))


def _w_with_phi_row():
    J3 = _J(*Q_W, rows=3)
    return float(np.sqrt(np.linalg.det(J3.T @ J3)))


EXERCISES = [
    expression("13.1", "det J of the planar 2R arm", _det_2r, *_DET_MISTAKES,
               explain="det J = l1 l2 sin θ2 (seed 001 gets there through c1 s12 − s1 c12 = "
                   "sin θ2). It does not depend on θ1, and it vanishes exactly at θ2 = 0 and "
                   "θ2 = π: the arm stretched out or folded back"),
    judged("13.2", "predict", "the tip direction lost at θ2 = 0", _judge_lost,
           diagnoses=("across", "rank"),
           explain="each joint swings the tip on a circle about itself, and at θ2 = 0 both "
                   "centres lie on the arm's line: both columns of J point across the arm, "
                   "and no joint velocity moves the tip along it"),
    value("13.3", "compute", "joint velocities for the tip velocity (−1, 0) at θ = (0, π/2)",
          _qdot,
          TRANSPOSED.of(lambda: _J(*Q_TIP).T @ V_TIP,
                        "you computed Jᵀ v: the transpose of J is not its inverse (J is not a "
                        "rotation). Solve J q̇ = v, q̇ = J⁻¹ v (Jᵀ maps tip forces to joint "
                        "torques instead)"),
          SWAPPED.of(lambda: _qdot()[::-1],
                     "your two joint rates are swapped: q̇ = (θ̇1, θ̇2), and the second row "
                     "of J, ẏ = (l1 c1 + l2 c12) θ̇1 + l2 c12 θ̇2, is ẏ = θ̇1 here"),
          Mistake("phi row", "the three rows of kl.planar_2r_jacobian include φ̇ = θ̇1 + θ̇2: "
                             "solving with v = (−1, 0, 0) also asks for φ̇ = 0, which the arm "
                             "cannot do at the same time. Use the two position rows, [:2]",
                  lambda: np.linalg.lstsq(_J(*Q_TIP, rows=3), [*V_TIP, 0.0], rcond=None)[0]),
          what="a 2-vector (θ̇1, θ̇2)",
          explain="J(0, π/2) = [[−l2, −l2], [l1, 0]]: its second row gives θ̇1 = 0, the first "
                  "then θ̇2 = 1/l2 = 1.25 rad/s. Only the elbow turns: the forearm points "
                  "straight up, and turning it swings the tip to the left"),
    value("13.4", "compute", "the manipulability w at θ = (0.3, π/2)", _w,
          Mistake("squared", "that is w² = det(J Jᵀ): the manipulability is its square root, "
                             "w = √det(J Jᵀ) = σ1 σ2", lambda: _w() ** 2),
          Mistake("phi row", "you used the 3×2 Jacobian with its φ̇ row: √det(JᵀJ) of it is "
                             "not the tip's manipulability; take the position rows, J[:2]",
                  _w_with_phi_row),
          Mistake("phi row", "J Jᵀ of the 3×2 Jacobian (with its φ̇ row) is 3×3 of rank 2, so "
                             "its determinant is 0: take the 2×2 position rows, J[:2]",
                  lambda: 0.0),
          DEGREES.of(lambda: _w((0.3, 90.0)), "you put in θ2 = 90, in degrees: kinlib's "
                                             "angles are radians, θ2 = π/2"),
          what="a number",
          explain="w = l1 l2 = 0.8, the largest w the arm has: for a square J, w = |det J| "
                  "= l1 l2 |sin θ2|, largest when the links are perpendicular. The ellipse is "
                  "fattest there and thins as the arm stretches out or folds back"),
]
