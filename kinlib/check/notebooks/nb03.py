"""Notebook 03 · Euler angles and fixed angles: the order of two turns, building ᴬR_B for
moving and fixed axes, the Z-Y-X inverse problem, its singularity and the two gimbal-lock
branches."""

import numpy as np

from .._verdict import Mistake, Verdict, as_numeric, close
from ..judges import euler_angles_judge
from ..mistakes import ORDER
from ._make import choice, expression, judged, value


def _abg():
    import sympy as sp

    return sp.symbols("alpha beta gamma", real=True)


def _rot(axis: str, angle):
    from ... import rotx, roty, rotz

    return {"x": rotx, "y": roty, "z": rotz}[axis](angle)


def _product(*turns):
    """The product of elementary rotations, e.g. ``_product(("z", a), ("y", b))``."""
    out = _rot(*turns[0])
    for t in turns[1:]:
        out = out * _rot(*t)
    return out


def _zyx():
    """ᴬR_B of the Z-Y-X Euler angles (α, β, γ), from kinlib's sequence convention."""
    from ... import matrix_from_euler

    return matrix_from_euler(list(_abg()), "ZYX")


def _xyz_fixed():
    """ᴬR_B of the X-Y-Z fixed angles (γ, β, α), from kinlib's sequence convention."""
    from ... import matrix_from_euler

    a, b, g = _abg()
    return matrix_from_euler([g, b, a], "xyz")


def _reversed():
    a, b, g = _abg()
    return _product(("x", g), ("y", b), ("z", a))


def _letters_as_xyz():
    a, b, g = _abg()
    return _product(("x", a), ("y", b), ("z", g))


def _roty_sign():
    a, b, g = _abg()
    return _rot("z", a) * _rot("y", b).T * _rot("x", g)


def _similarity_backwards():
    """Seed 002's fixed-angle derivation with N = R M Rᵀ instead of Rᵀ M R."""
    a, b, g = _abg()
    first = _rot("x", g)
    second = first * (first * _rot("y", b) * first.T)
    return second * (second * _rot("z", a) * second.T)


# ---- 03.1: two quarter turns in both orders -------------------------------------------

P_TURNED = np.array([1.0, 0.0, 1.0])


def _two_turns(angle=np.pi / 2, first_only=False):
    """Rows: the point P_TURNED turned about x, then about y (both fixed); and about y,
    then about x. ``first_only``: the second turn forgotten."""
    from ... import rotx, roty

    Rx, Ry = rotx(angle), roty(angle)
    if first_only:
        return np.array([Rx @ P_TURNED, Ry @ P_TURNED])
    return np.array([Ry @ Rx @ P_TURNED, Rx @ Ry @ P_TURNED])


_EXTRINSIC_EULER = ("this is Rx(γ) Ry(β) Rz(α): the turns multiplied right to left, as for "
                   "fixed axes. About the moving axes each new turn is described in the frame "
                   "before it and multiplies on the right, as in ᴬR_B = ᴬR_B′ ᴮ′R_B″ ᴮ″R_B")
_RY_SIGN = ("the sines of R_Y(β) have swapped signs: R_Y(β) = [[cβ, 0, sβ], [0, 1, 0], "
            "[−sβ, 0, cβ]] (turning about y takes z towards x)")
_EXTRINSIC_FIXED = ("this is Rx(γ) Ry(β) Rz(α): you multiplied the turns left to right, as for "
                   "moving axes. A turn about a fixed axis multiplies on the left: the "
                   "similarity transform gives ᴬR_B″ = ᴬR_B′ (ᴬR_B′)ᵀ Ry(β) ᴬR_B′ = Ry(β) Rx(γ)")


def _R_try():
    """The notebook's R_try: 1 rad about (1, -1, 2), its angles not in sight."""
    from ... import matrix_from_axis_angle

    return matrix_from_axis_angle([1.0, -1.0, 2.0], 1.0)


_FIXED_MESSAGES = {
    "sequence": "your angles come in the wrong order: x-y-z fixed angles are listed in the "
                "order of the letters, (γ, β, α) — the angle about x first — with "
                "R = Rz(α) Ry(β) Rx(γ); you gave (α, β, γ), the Z-Y-X order",
    "extrinsic": "your angles rebuild R as Rx(γ) Ry(β) Rz(α), the X-Y-Z Euler matrix (moving "
                 "axes, 'XYZ'); the fixed angles 'xyz' mean R = Rz(α) Ry(β) Rx(γ)",
}


def _fixed_angles_judge():
    """euler_angles_judge("xyz") on R_try, its messages in the notebook's names: the angle
    about x is γ, about z α."""
    base = euler_angles_judge("xyz")

    def judge(args, got):
        v = base((_R_try(),), got)
        if v.key in _FIXED_MESSAGES:
            return Verdict(False, v.key, _FIXED_MESSAGES[v.key], v.expected)
        return v
    return judge


def _singularity_answer() -> str:
    """Option a when, at β = ±90°, the third turn's axis Rz(α) Ry(β) x̂ is parallel to the
    first (ẑ) while det R stays 1 (so b, c, d are the misconceptions)."""
    from ... import matrix_from_euler, roty, rotz

    aligned = all(abs(abs((rotz(0.7) @ roty(beta))[:, 0] @ [0.0, 0.0, 1.0]) - 1.0) < 1e-12
                  for beta in (np.pi / 2, -np.pi / 2))
    unit_det = np.isclose(np.linalg.det(matrix_from_euler([0.7, np.pi / 2, 0.2], "ZYX")), 1.0)
    return "a" if aligned and unit_det else "b"


def _lock_case(alpha, beta, gamma):
    """A Z-Y-X matrix with its structural zeros exact (as a matrix typed in or read from a
    pose would have them): at gimbal lock cos β is exactly 0."""
    from ... import matrix_from_euler

    R = matrix_from_euler([alpha, beta, gamma], "ZYX")
    return np.where(np.abs(R) < 1e-12, 0.0, R)


def _zyx_cases():
    from ... import matrix_from_euler

    rng = np.random.default_rng(33)
    generic = rng.uniform([-np.pi, -1.4, -np.pi], [np.pi, 1.4, np.pi], (6, 3))
    generic = np.vstack([generic, [3.0, 0.3, -2.9], [-2.5, -1.2, 2.8]])
    locks = [(0.7, np.pi / 2, 0.2), (-1.2, np.pi / 2, 2.5), (0.4, -np.pi / 2, 1.1),
             (2.0, -np.pi / 2, -0.6), (0.0, -np.pi / 2, 0.9)]
    return ([(matrix_from_euler(x, "ZYX"),) for x in generic]
            + [(_lock_case(*x),) for x in locks])


def _zyx_judge():
    """Angles that rebuild R are right (euler_angles_judge); at gimbal lock, angles right
    but for the sign of γ are the +90° formula used at −90° (or the reverse)."""
    from ...spatial.euler import euler_gimbal_lock, matrix_from_euler

    base = euler_angles_judge("ZYX")

    def judge(args, got):
        v = base(args, got)
        (R,) = args
        if v.ok or not euler_gimbal_lock(R, "ZYX"):
            return v
        x, _ = as_numeric(got, (3,))
        if x is not None and close(matrix_from_euler([x[0], x[1], -x[2]], "ZYX"), R, 1e-6):
            at = "−90°" if R[2, 0] > 0 else "+90°"
            return Verdict(False, "sign", f"γ has the wrong sign at β = {at}: there (r12, r22) "
                                          + ("= (−sin γ, cos γ), so γ = −atan2(r12, r22); "
                                             "atan2(r12, r22) is the +90° formula"
                                             if at == "−90°" else
                                             "= (sin γ, cos γ), so γ = +atan2(r12, r22)"),
                           v.expected)
        return v
    return judge


EXERCISES = [
    value("03.1", "predict", "one point, two quarter turns, two orders", _two_turns,
          ORDER.of(lambda: _two_turns()[::-1],
                   "the rows are swapped: the turn applied first stands on the right, so "
                   "'about x, then about y' is R_Y(90°) R_X(90°) p"),
          Mistake("sense", "both turns go the wrong way: a positive turn about x takes y to "
                           "z and z to −y, about y it takes z to x and x to −z (the "
                           "right-hand rule: thumb along the axis, the fingers curl the "
                           "positive way)", lambda: _two_turns(-np.pi / 2)),
          Mistake("commute", "the two rows are the same: two turns about different axes do "
                             "not commute, R_Y R_X ≠ R_X R_Y — work out each order step by step",
                  lambda: _two_turns()[[0, 0]]),
          Mistake("commute", "the two rows are the same: two turns about different axes do "
                             "not commute, R_Y R_X ≠ R_X R_Y — work out each order step by step",
                  lambda: _two_turns()[[1, 1]]),
          Mistake("one turn", "that is where the first turn alone takes p: turn the result "
                              "once more, about the other axis",
                  lambda: _two_turns(first_only=True)),
          what="a 2×3 array",
          explain="about x, then y: (1, 0, 1) → (1, −1, 0) → (0, −1, −1); about y, then x: "
                  "(1, 0, 1) → (1, 0, −1) → (1, 1, 0). Linearity helps: p = x̂ + ẑ, so turn "
                  "the two axes and add."),
    expression("03.2", "ᴬR_B for Z-Y-X Euler angles", _zyx,
               Mistake("extrinsic", _EXTRINSIC_EULER, _reversed),
               Mistake("sequence", "this is Rx(α) Ry(β) Rz(γ), the X-Y-Z Euler sequence: in "
                                   "Z-Y-X, α turns about z, β about the new y, γ about the "
                                   "newest x", _letters_as_xyz),
               Mistake("R_Y sign", _RY_SIGN, _roty_sign),
               what="a 3×3 sympy Matrix", diagnoses=("swapped", "transposed"),
               explain="each turn is about an axis of the moving frame, an elementary rotation "
                    "described in the frame before it, so it multiplies on the right: "
                    "ᴬR_B = Rz(α) Ry(β) Rx(γ). Seed 001 prints this product entry by entry "
                    "as its eq. 4.66 (the roll–pitch–yaw matrix)."),
    expression("03.3", "ᴬR_B for X-Y-Z fixed angles", _xyz_fixed,
               Mistake("extrinsic", _EXTRINSIC_FIXED, _reversed),
               Mistake("similarity", "the similarity transform is the wrong way round: a "
                                     "rotation M about a fixed axis, described in the current "
                                     "frame {B′}, is N = (ᴬR_B′)⁻¹ M ᴬR_B′, the inverse on the "
                                     "left", _similarity_backwards),
               Mistake("sequence", "this is Rx(α) Ry(β) Rz(γ): the angle about the fixed x is "
                                   "γ, about the fixed z α (the angles (γ, β, α) go with x, y, "
                                   "z), and a turn about a fixed axis multiplies on the left",
                       _letters_as_xyz),
               Mistake("R_Y sign", _RY_SIGN, _roty_sign),
               what="a 3×3 sympy Matrix", diagnoses=("swapped",),
               explain="a turn about a fixed axis multiplies on the left: the similarity "
                    "transforms collapse, ᴬR_B″ = ᴬR_B′ (ᴬR_B′)⁻¹ Ry(β) ᴬR_B′ = Ry(β) Rx(γ), "
                    "then ᴬR_B = Rz(α) Ry(β) Rx(γ) — the matrix of the Z-Y-X Euler angles of "
                    "03.2."),
    judged("03.4", "compute", "the X-Y-Z fixed angles of R_try", _fixed_angles_judge(),
           diagnoses=("sequence", "extrinsic", "degrees"),
           explain="x-y-z fixed angles and Z-Y-X Euler angles both build Rz(α) Ry(β) Rx(γ): "
                   "the fixed angles (γ, β, α) are the Euler angles (α, β, γ) in reverse "
                   "order."),
    choice("03.5", "predict", "the physical interpretation of the Z-Y-X singularity",
           {"a": "the first and third rotation axes line up: a degree of freedom is lost",
            "b": "R becomes singular (det R = 0)",
            "c": "orientations with β = ±90° cannot be reached",
            "d": "only a numerical problem of dividing by cos β"}, _singularity_answer(),
           {"b": ("det", "R is still a rotation, det R = 1 for every β: what is lost is not R "
                         "but the uniqueness of the angles that build it"),
            "c": ("unreachable", "they are reached — by infinitely many (α, γ) pairs, not by "
                                 "none: at β = +90° any pair with the same γ − α gives R"),
            "d": ("numerical", "no formula can help: at cos β = 0 the entries r11, r21, r32, "
                               "r33 that carry α and γ all vanish, and R depends on γ − α (or "
                               "γ + α) only — the information is not in R")},
           explain="at β = ±90° the newest x lies along ∓Ẑ_A: the first and third turns are "
                   "about one line. R is still a rotation, reached by infinitely many (α, γ); "
                   "the demonstration below shows it."),
    judged("03.6", "implement", "Z-Y-X Euler angles with both gimbal-lock branches",
           _zyx_judge(), cases=_zyx_cases(),
           diagnoses=("sign", "gimbal", "sequence", "degrees"),
           explain="at the lock R holds only γ − α (β = +90°) or γ + α (β = −90°): with α = 0 "
                   "your γ carries the whole turn about the aligned axis, Craig's convention "
                   "and kinlib's."),
]
