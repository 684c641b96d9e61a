"""Notebook 04 · gimbal lock: the Z-Y-X sequence at β = ±90°, the Euler-rate map losing
rank, seed 000's questions and arm experiment, and where the X-Y-X sequence locks."""

import numpy as np

from .._verdict import RIGHT, Mistake, Verdict, fmt
from ..mistakes import DEGREES, EXTRINSIC, SIGN
from ._make import choice, judged, value

# 04.1: the locked orientation (α, β, γ) = (20°, 90°, −30°), and a new first angle of 60°
LOCKED = np.deg2rad([20.0, 90.0, -30.0])
ALPHA_NEW = np.deg2rad(60.0)


def _gamma_new():
    """γ' with (α', 90°, γ') = the locked R: kinlib's angles at the lock are (0, 90°, γ0)
    and the family they stand for is (t, 90°, γ0 + t)."""
    from ...spatial.euler import euler_from_matrix, matrix_from_euler

    _, _, gamma0 = euler_from_matrix(matrix_from_euler(LOCKED, "ZYX"), "ZYX")
    return gamma0 + ALPHA_NEW


def _gamma_sum_kept():
    """γ' if α + γ (the rule of β = −90°) were kept: α' + γ' = α + γ."""
    return LOCKED[0] + LOCKED[2] - ALPHA_NEW


def _turns():
    t = _gamma_new()
    return [t - 2 * np.pi, t + 2 * np.pi]


def _lock_rank():
    from ...spatial.velocity import euler_rate_matrix

    return np.linalg.matrix_rank(euler_rate_matrix(LOCKED, "ZYX"))


# 04.4: seed 000's arm experiment, 90° about x, then the new y, then the new z
ARM_ENDS = {"a": np.array([1.0, 0.0, 0.0]), "b": np.array([0.0, 0.0, 1.0]),
            "c": np.array([0.0, 0.0, -1.0])}


def _arm_end(seq):
    from ...spatial.euler import matrix_from_euler

    return matrix_from_euler(np.deg2rad([90.0, 90.0, 90.0]), seq) @ [1.0, 0.0, 0.0]


def _option(direction) -> str:
    return next(k for k, v in ARM_ENDS.items() if np.allclose(v, direction, atol=1e-12))


# 04.5: the middle angles at which X-Y-X locks, in [0, π]
def _xyx_locks():
    """The middle angles among multiples of π/8 in [0, π] where E of X-Y-X is singular."""
    from ...spatial.velocity import euler_rates_singular

    grid = np.linspace(0.0, np.pi, 9)
    return grid[[bool(euler_rates_singular([0.3, m, -0.8], "XYX")) for m in grid]]


def _same_set(a, b, atol=1e-6) -> bool:
    return (all(np.isclose(b, x, atol=atol).any() for x in a)
            and all(np.isclose(a, y, atol=atol).any() for y in b))


def _locks_judge(args, got):
    if got is None or isinstance(got, str | bool | dict):
        return Verdict(False, "type", f"your answer is {fmt(got, 60)}; expected a list of "
                                      "angles in radians, e.g. [0.5, 1.0]")
    try:
        a = np.atleast_1d(np.asarray(got, dtype=float)).ravel()
    except (TypeError, ValueError):
        return Verdict(False, "type", f"your answer is {fmt(got, 60)}, which is not a list "
                                      "of angles in radians")
    right = _xyx_locks()
    if a.size == 0:
        return Verdict(False, "empty", "your list is empty: X-Y-X does lock somewhere in "
                                       "[0, π]", right)
    if not np.isfinite(a).all():
        return Verdict(False, "nan", "your list holds NaN or infinity", right)
    if _same_set(a, right):
        return RIGHT
    if _same_set(a, right, atol=0.01):
        return Verdict(False, "rounded", "close, but rounded: write π as np.pi, not 3.14",
                       right)
    if _same_set(a, np.rad2deg(right)):
        return Verdict(False, DEGREES.key, "these are degrees: give the angles in radians "
                                           "(np.pi, not 180)", right)
    if np.isclose(np.abs(a), np.pi / 2, atol=1e-6).any():
        return Verdict(False, "tait-bryan", "±π/2 is where a sequence of three different "
                                            "axes (Z-Y-X) locks; in X-Y-X the first and "
                                            "last axes are both x, and they line up when "
                                            "R_Y(β) turns e_x into ±e_x", right)
    if all(np.isclose(right, x, atol=1e-6).any() for x in a):
        return Verdict(False, "missing", "right so far, but there is another one in [0, π]: "
                                         "the first and last axes line up pointing the same "
                                         "way and pointing opposite ways", right)
    return Verdict(False, "wrong", f"det E of X-Y-X is not zero at every angle of "
                                   f"{fmt(a, 80)}, or one of its zeros in [0, π] is missing",
                   right)


EXERCISES = [
    value("04.1", "compute", "another (α, γ) for the same orientation at β = 90°",
          _gamma_new,
          SIGN.of(_gamma_sum_kept, "you kept α + γ; at β = +90° the matrix depends on "
                                   "γ − α alone (α + γ is the rule at β = −90°): raise γ by "
                                   "as much as you raised α"),
          DEGREES.of(lambda: np.rad2deg(_gamma_new()), "that is the angle in degrees: "
                                                       "give γ' in radians"),
          Mistake("unchanged", "γ cannot stay as it was: with α raised by 40°, the same "
                               "orientation needs γ − α unchanged, so γ changes too",
                  lambda: LOCKED[2]),
          accept=_turns, what="a number",
          explain="at β = +90° the matrix depends on γ − α alone: raising α by 40° needs γ "
                  "raised by 40° too, γ' = −30° + 40° = 10° (give or take a whole turn)"),
    value("04.2", "predict", "independent axes at gimbal lock", _lock_rank,
          Mistake("coincide", "two axes line up, but the third (the middle one, β's) is "
                              "still perpendicular to them: the line they share and the "
                              "middle axis are two independent directions", lambda: 1),
          Mistake("three", "there are still three axes, but axis 1 and axis 3 are parallel, "
                           "so together they span only a plane: E has rank 2",
                  lambda: 3), what="a number"),
    choice("04.3", "predict", "why gimbal lock is a problem",
           {"a": "the body cannot turn about one direction in that orientation",
            "b": "the angles lose a degree of freedom: near the lock a small turn needs "
                 "huge angle rates, and at the lock the angles are not unique",
            "c": "the matrix Rz(α) Ry(β) Rx(γ) is no longer a rotation at β = 90°"}, "b",
           {"a": ("orientation", "the orientation is an ordinary one and the body can turn "
                                 "every way from it: another sequence (or a quaternion) "
                                 "describes the same orientation and its neighbours "
                                 "smoothly. Only the three angles lose a degree of freedom"),
            "c": ("matrix", "a product of rotations is a rotation for every angle "
                            "(RᵀR = I, det R = 1, also at β = 90°); what breaks is the map "
                            "from the angles to the orientation, not the matrix")}),
    choice("04.4", "predict", "where the arm points after seed 000's three turns",
           {"a": "along +x: back to (about) the original pose, as the slide says",
            "b": "along +z", "c": "along −z"}, _option(_arm_end("XYZ")),
           {_option(np.array([1.0, 0.0, 0.0])): (
                "slide", "the slide's claim is wrong: R = Rx(90°) Ry(90°) Rz(90°) is a half "
                         "turn, not the identity, and the arm ends along +z"),
            _option(_arm_end("xyz")): (
                EXTRINSIC.key, "−z is where the fixed-axes product Rz(90°) Ry(90°) Rx(90°) "
                               "takes the arm. Seed 000 turns about the new y and the new z "
                               "(moving axes), so the matrices multiply left to right: "
                               "R = Rx Ry Rz")}),
    judged("04.5", "predict", "the middle angles at which X-Y-X locks", _locks_judge,
           diagnoses=("tait-bryan", DEGREES.key, "missing", "rounded"),
           explain="n3 = R_X(α) R_Y(β) e_x = R_X(α) (cos β, 0, −sin β) is ±e_x exactly where "
                   "sin β = 0: at β = 0 the last axis is the first, at β = π it points the "
                   "other way along the same line"),
]
