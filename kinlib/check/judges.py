"""Judges for answers that have more than one right form: Euler angles (any angles that
rebuild the matrix, also at gimbal lock), axis-angle pairs, and multiple choice.

Each returns ``judge(args, got) -> Verdict`` for a :class:`~kinlib.check.Rule`. They serve
the notebooks' exercises and the grader's checks alike.
"""

from __future__ import annotations

import numpy as np

from ._verdict import RIGHT, Verdict, as_numeric, close, fmt
from .mistakes import DEGREES, EXTRINSIC, SEQUENCE

__all__ = ["euler_angles_judge", "axis_angle_judge", "choice_judge", "product_text"]

_GREEK = ("α", "β", "γ")


def product_text(seq: str) -> str:
    """The matrix product of a sequence with angles α, β, γ in letter order, e.g.
    ``"Rz(α) Ry(β) Rx(γ)"`` for ``"ZYX"`` and ``"Rz(γ) Ry(β) Rx(α)"`` for ``"xyz"``."""
    parts = [f"R{c.lower()}({g})" for c, g in zip(seq, _GREEK, strict=True)]
    return " ".join(parts if seq.isupper() else parts[::-1])


def euler_angles_judge(seq: str = "ZYX", atol: float = 1e-6):
    """Three angles (in letter order) are right when they rebuild the matrix ``args[0]``:
    at gimbal lock every pair that does is right. Diagnoses degrees, angles in the wrong
    order, the other kind of axes, NaN at the lock and a wrong lock branch."""
    from ..spatial.euler import euler_from_matrix, euler_gimbal_lock, matrix_from_euler

    names = ", ".join(_GREEK)
    build = product_text(seq)

    def judge(args, got):
        (R_in,) = args
        a, bad = as_numeric(got, (3,), f"three angles ({names})")
        if a is None:
            if bad.key == "nan" and euler_gimbal_lock(R_in, seq, atol):
                return Verdict(False, "gimbal", "NaN at gimbal lock (the middle angle makes "
                                                "cos or sin zero): there only a sum or "
                                                "difference of the outer angles is "
                                                "determined; set the first angle to 0 and "
                                                "get the last from the entries that remain")
            return bad
        if close(matrix_from_euler(a, seq), R_in, atol):
            return RIGHT
        if close(matrix_from_euler(np.deg2rad(a), seq), R_in, atol):
            return Verdict(False, DEGREES.key, DEGREES.message)
        if close(matrix_from_euler(a[::-1], seq), R_in, atol):
            return Verdict(False, SEQUENCE.key, f"your angles come in the wrong order: return "
                                                f"({names}) with R = {build}")
        if close(matrix_from_euler(a, seq.swapcase()), R_in, atol):
            return Verdict(False, EXTRINSIC.key, f"your angles rebuild R as "
                                                 f"{product_text(seq.swapcase())}; "
                                                 f"{seq!r} means R = {build}")
        if euler_gimbal_lock(R_in, seq, atol):
            return Verdict(False, "gimbal", f"wrong at gimbal lock: with {_GREEK[0]} = 0, "
                                            f"{build} must equal R; solve {_GREEK[2]} from "
                                            "the entries that do not vanish (their signs "
                                            "differ at the two lock angles)")
        err = float(np.abs(matrix_from_euler(a, seq) - R_in).max())
        return Verdict(False, "wrong", f"{build} of your angles misses R by up to {err:.3g}",
                       euler_from_matrix(R_in, seq))
    return judge


def axis_angle_judge(args, got):
    """An ``(axis, angle)`` pair is right when Rodrigues' matrix of it is ``args[0]``, with
    the angle in [0, π] and a unit axis."""
    from ..spatial.axis_angle import axis_angle_from_matrix, matrix_from_axis_angle

    (R_in,) = args
    if not isinstance(got, tuple | list) or len(got) != 2:
        return Verdict(False, "type", f"returned {fmt(got, 80)}; expected a pair "
                                      "(axis, angle): axis a unit 3-vector, angle in [0, π]")
    k, bad = as_numeric(got[0], (3,), "a unit axis")
    if k is None:
        return bad
    t, bad = as_numeric(got[1], ())
    if t is None:
        return bad
    t = float(t)
    if abs(np.linalg.norm(k) - 1.0) > 1e-6:
        return Verdict(False, "unit", f"the axis has length {np.linalg.norm(k):.4g}; it must "
                                      "be a unit vector (at θ = 0 any unit axis will do)")
    if t > np.pi + 1e-6 and close(matrix_from_axis_angle(k, np.deg2rad(t)), R_in, 1e-6):
        return Verdict(False, DEGREES.key, DEGREES.message)
    if not -1e-9 <= t <= np.pi + 1e-9:
        return Verdict(False, "range", f"angle {t:.4g} is outside [0, π]: arccos((tr R − 1)/2) "
                                       "gives the angle in [0, π]")
    rebuilt = matrix_from_axis_angle(k, t)
    if close(rebuilt, R_in, 1e-6):
        return RIGHT
    if close(rebuilt.T, R_in, 1e-6):
        return Verdict(False, "axis sign", "your axis points the wrong way (you get Rᵀ back): "
                                           "the skew part (R − Rᵀ)/2 is sin θ [k]×, so "
                                           "k = (R32 − R23, R13 − R31, R21 − R12) / (2 sin θ)")
    near_pi = abs(np.trace(R_in) + 1.0) < 1e-6
    hint = (" Near θ = π, sin θ ≈ 0: get k from the symmetric part, R + I = 2 k kᵀ"
            if near_pi else "")
    return Verdict(False, "wrong", "Rodrigues' matrix of your (axis, angle) is not R." + hint,
                   axis_angle_from_matrix(R_in))


def choice_judge(options: dict, right, wrong: dict | None = None):
    """Multiple choice: ``got`` must be one of ``options`` (keys, e.g. ``"a"``; compared
    case- and space-insensitively for text). ``right`` is the key of the right option;
    ``wrong`` maps other keys to ``(mistake key, diagnosis)``."""
    wrong = wrong or {}

    def norm(x):
        return x.strip().lower() if isinstance(x, str) else x

    keys = {norm(k): k for k in options}
    listing = ", ".join(repr(k) for k in options)

    def judge(args, got):
        key = keys.get(norm(got)) if isinstance(got, str | int) and not isinstance(
            got, bool) else None
        if key is None:
            return Verdict(False, "type", f"answer with one of {listing} (got {fmt(got, 60)})")
        if key == right:
            return RIGHT
        mistake, message = wrong.get(key, ("wrong", f"not {key!r}: read the options again"))
        return Verdict(False, mistake, message, right)
    return judge
