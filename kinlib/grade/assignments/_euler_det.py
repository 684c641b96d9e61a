"""Assignment 05's derivation: det E of the ZYX Euler-rate matrix, with sympy.

The student's ``euler_rate_det_zyx(alpha, beta, gamma)`` gets sympy symbols (other names,
sums of symbols, and an exact β = ±π/2 too) and returns det E(φ) as a sympy expression; the
reference is the determinant of kinlib's :func:`~kinlib.euler_rate_matrix` of the same
symbols, −cos β, judged by :func:`kinlib.grade._symbolic.symbolic_judge`. The mistakes are
the determinants of wrong rate matrices (:func:`rate_det`). The body-frame matrix Rᵀ E and
Eᵀ have the same determinant: they are right here.

A sympy number arrives as a number, and det E may be one: at the exact lock the right
answer is 0 (any other number there is "lock"), and a wrong E can have a constant
determinant (the base axes: −1), named by value; any other number is "numbers" (no
derivation).

>>> import sympy as sp
>>> a, b, g = sp.symbols("alpha beta gamma", real=True)
>>> sp.simplify(rate_det(a, b, g)), sp.simplify(rate_det(a, b, g, third=(0, 0, 1)))
(-cos(beta), -sin(beta))
"""

from __future__ import annotations

import numpy as np

import kinlib as kl

from .._checks import RIGHT, Check, Mistake, Verdict
from .._symbolic import symbolic_error_hint, symbolic_judge

__all__ = ["rate_det", "rate_det_check", "det_symbols"]


def rate_det(alpha, beta, gamma, third=(1, 0, 0), turned=True):
    """det [e_z, R_z(α) e_y, R_z(α) R_y(β) e_x] of sympy angles; the keywords make the
    mistakes: ``third``, the unit vector R_z(α) R_y(β) turns into the γ̇ axis (e_x);
    ``turned=False``, β̇ about e_y instead of R_z(α) e_y."""
    import sympy as sp

    Rz = kl.rotz(alpha)
    second = Rz[:, 1] if turned else sp.Matrix([0, 1, 0])
    return sp.Matrix.hstack(sp.Matrix([0, 0, 1]), second,
                            Rz * kl.roty(beta) * sp.Matrix(third)).det()


def _reference(alpha, beta, gamma):
    return kl.euler_rate_matrix([alpha, beta, gamma], "ZYX").det()


def det_symbols(rng):
    """Plain symbols, other names without assumptions, sums of symbols, and gimbal lock
    with an exact β = ±π/2 (where det E is exactly 0)."""
    import sympy as sp

    k = int(rng.integers(1, 10))
    q, s = sp.symbols(f"q{k} s{k}", real=True)
    alpha, beta, gamma = sp.symbols("alpha beta gamma", real=True)
    return [(alpha, beta, gamma), sp.symbols(f"a{k} b{k} c{k}"), (q + s, 2 * s, -q),
            (alpha, int(rng.choice([1, -1])) * sp.pi / 2, gamma)]


LOCK = ("β = ±π/2 (gimbal lock), where the γ̇ axis R_z(α) R_y(β) e_x = (cos α cos β, "
        "sin α cos β, −sin β) lines up with e_z, the α̇ axis")


def _mistakes() -> list[Mistake]:
    """Three wrong determinants, then three constant ones."""
    import sympy as sp

    return [
        Mistake("sign", "right up to the sign: the columns of E are the axes of α̇, β̇, γ̇ in "
                        "that order (the order of φ̇); exchanging two columns flips the sign "
                        "of a determinant", lambda *a: -rate_det(*a)),
        Mistake("sin", "sin β where cos β belongs: the γ̇ axis is R_z(α) R_y(β) e_x, R_y(β)'s "
                       "first column (cos β, 0, −sin β) turned by R_z(α); you used its last "
                       "column, R_y(β) e_z", lambda *a: rate_det(*a, third=(0, 0, 1))),
        Mistake("R_z", "cos α should not appear: a column lacks R_z(α). β̇ turns about "
                       "R_z(α) e_y and γ̇ about R_z(α) R_y(β) e_x, both after the first turn",
                lambda *a: rate_det(*a, turned=False)),
        Mistake("constant", f"your det E is −1 at every angle, but E must lose rank at {LOCK}: "
                            "with the base axes e_z, e_y, e_x, or without R_y(β) in the γ̇ "
                            "axis, it never does", lambda *a: sp.Integer(-1)),
        Mistake("constant", "your det E is 1 at every angle, the determinant of a rotation; E "
                            f"is no rotation, and it loses rank at {LOCK}",
                lambda *a: sp.Integer(1)),
        Mistake("singular", "your det E is 0 at every angle: two of your columns are parallel "
                            "(β̇ turns about R_z(α) e_y, not R_z(α) e_x); E loses rank only at "
                            f"{LOCK}", lambda *a: sp.Integer(0))]


def _constant(got) -> float | None:
    """The real number the student's function returned (a sympy number arrives as one)."""
    if type(got) in (int, float) or (isinstance(got, np.ndarray) and got.size == 1
                                     and got.dtype.kind in "iuf"):
        return float(np.asarray(got).ravel()[0])
    return None


def rate_det_check() -> Check:
    """``euler_rate_det_zyx(alpha, beta, gamma)``: det E(φ), a sympy expression (3 points)."""
    from kinlib.symbolic import simplify_rotation

    mistakes = _mistakes()
    symbolic = symbolic_judge(_reference, names=("alpha", "beta", "gamma"), mistakes=mistakes,
                              swaps=[(0, 1), (1, 2)], show=simplify_rotation)

    def judge(args, got):
        value = _constant(got)
        if value is None:
            return symbolic(args, got)
        want = simplify_rotation(_reference(*args))
        if want.is_number:  # the exact lock, where every answer is a number
            if abs(value - float(want)) < 1e-12:
                return RIGHT
            return Verdict(False, "lock", f"at β = ±π/2 exactly (gimbal lock) det E = {want}, "
                                          f"yours is {value:.6g}: E must lose rank there", want)
        for m in mistakes[3:]:  # constant at every angle
            if abs(value - float(m.model(*args))) < 1e-12:
                return Verdict(False, m.key, m.message, want)
        return symbolic(args, got)  # a number where an expression belongs
    return Check("euler_rate_det_zyx", 3, "det E of the ZYX Euler rates derived with sympy",
                 det_symbols, judge=judge, on_error=symbolic_error_hint, time_limit=10.0)
