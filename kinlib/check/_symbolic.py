"""Judging a derivation: a sympy expression or matrix, decided exactly with
:func:`kinlib.symbolic.sym_equal` (trigonometric identities reduce to exactly zero), with
the near misses named: right up to a sign, transposed, two angles swapped, or only right
for unit vectors."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from itertools import combinations

import numpy as np

from ._verdict import RIGHT, Verdict, fmt
from .mistakes import SIGN, SWAPPED, TRANSPOSED

__all__ = ["expression_judge"]


def _as_sympy(got, matrix: bool):
    import sympy as sp

    if isinstance(got, np.ndarray) or (matrix and isinstance(got, list | tuple)):
        got = sp.Matrix(got)
    if matrix and not isinstance(got, sp.MatrixBase):
        raise TypeError
    if not matrix and isinstance(got, sp.MatrixBase):
        if got.shape == (1, 1):
            return got[0, 0]
        raise TypeError
    return got if matrix else sp.sympify(got, strict=True)


def _equal(a, b, unit) -> bool:
    from ..symbolic import sym_equal

    try:
        return sym_equal(a, b, unit)
    except Exception:  # outside what the exact reduction handles: not shown equal
        return False


def _probe(got, expected, symbols, unit, seed: int = 0):
    """Where the two differ, at a random point (unit vectors normalised): for the message."""
    import sympy as sp

    rng = np.random.default_rng(seed)
    values = {s: float(v) for s, v in zip(symbols, rng.uniform(0.2, 1.3, len(symbols)),
                                          strict=True)}
    groups = list(unit or ())
    if groups and all(isinstance(s, sp.Symbol) for s in groups):
        groups = [groups]  # a flat sequence of symbols is one unit vector (as for sym_equal)
    for group in groups:
        group = list(group) if isinstance(group, list | tuple) else [group]
        norm = np.sqrt(sum(values.get(s, 0.0) ** 2 for s in group))
        for s in group:
            values[s] = values.get(s, 0.0) / norm
    try:
        g = np.array(sp.Matrix([got]).subs(values).evalf(), dtype=float)
        e = np.array(sp.Matrix([expected]).subs(values).evalf(), dtype=float)
    except (TypeError, ValueError):
        return ""
    at = ", ".join(f"{s} = {v:.3g}" for s, v in values.items())
    return f" (at {at}: yours is {fmt(g.ravel())}, the right one {fmt(e.ravel())})"


def expression_judge(expected: Callable, *, unit=None, swaps: Sequence | None = None,
                     what: str = "a sympy expression"):
    """Judge a sympy answer against ``expected()`` (built from the notebook's own symbols;
    the student's symbols are matched by name). ``unit`` as for :func:`sym_equal`;
    ``swaps``: the symbols whose pairwise exchange is a named mistake (default: every
    pair of the expected expression's free symbols)."""

    def judge(args, got):
        import sympy as sp

        exp = expected(*args)
        matrix = isinstance(exp, sp.MatrixBase)
        if matrix:
            exp = sp.Matrix(exp)
        try:
            g = _as_sympy(got, matrix)
        except (TypeError, ValueError, sp.SympifyError):
            return Verdict(False, "type", f"expected {what}, got {fmt(got, 80)}")
        by_name = {s.name: s for s in exp.free_symbols}
        g = g.xreplace({s: by_name[s.name] for s in getattr(g, "free_symbols", ())
                        if s.name in by_name and by_name[s.name] != s})
        unknown = sorted(s.name for s in getattr(g, "free_symbols", ()) if s.name not in by_name)
        if unknown:  # right if they cancel (sin²γ + cos²γ in an unsimplified answer)
            if _equal(g, exp, unit):
                return RIGHT
            return Verdict(False, "symbols", f"your answer has symbols the right one does not: "
                                             f"{', '.join(unknown)}; build it from the "
                                             f"notebook's symbols ({', '.join(sorted(by_name))})")
        if matrix and g.shape != exp.shape:
            if g.shape == exp.shape[::-1]:
                return Verdict(False, TRANSPOSED.key, f"your matrix is {g.shape[0]}×"
                                                      f"{g.shape[1]}, the transpose's shape: "
                                                      "check rows against columns")
            return Verdict(False, "shape", f"your matrix is {g.shape[0]}×{g.shape[1]}, "
                                           f"expected {exp.shape[0]}×{exp.shape[1]}")
        if _equal(g, exp, unit):
            return RIGHT
        if _equal(g, -exp, unit):
            return Verdict(False, SIGN.key, "right up to the sign: look for a reversed "
                                            "cross product, a transposed rotation or a "
                                            "minus lost in the algebra")
        if matrix and exp.shape[0] == exp.shape[1] and _equal(g.T, exp, unit):
            return Verdict(False, TRANSPOSED.key, TRANSPOSED.message)
        pool = list(swaps) if swaps is not None else sorted(exp.free_symbols, key=str)
        for a, b in combinations(pool, 2):
            if _equal(g.xreplace({a: b, b: a}), exp, unit):
                return Verdict(False, SWAPPED.key, f"{a} and {b} are swapped in your answer")
        symbols = sorted(exp.free_symbols, key=str)
        return Verdict(False, "wrong", "not equal to the right answer" +
                       _probe(g, exp, symbols, unit), exp)
    return judge
