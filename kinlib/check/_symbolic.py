"""Judging a derivation: a sympy expression or matrix, decided exactly with
:func:`kinlib.symbolic.sym_equal` (trigonometric identities reduce to exactly zero), with
the near misses named: the exercise's own mistakes (each a wrong expression), right up to a
sign, transposed, two angles swapped.

Every exact comparison is screened first at random points: two expressions that differ
there are not equal, and no exact reduction is needed (that keeps a check of a wrong
answer fast); two that agree are then decided exactly.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from itertools import combinations

import numpy as np

from ._verdict import RIGHT, Mistake, Verdict, fmt
from .mistakes import SIGN, SWAPPED, TRANSPOSED

__all__ = ["expression_judge"]


def _as_sympy(got, matrix: bool):
    """``got`` as a sympy Matrix (array-like) or a scalar expression; a 1×1 matrix is a
    scalar where a scalar is expected. Raises TypeError/SympifyError for anything else."""
    import sympy as sp

    if isinstance(got, np.ndarray | list | tuple):
        got = sp.Matrix(got)
    if isinstance(got, sp.MatrixBase):
        return got[0, 0] if not matrix and got.shape == (1, 1) else sp.Matrix(got)
    return sp.sympify(got, strict=True)


def _groups(unit) -> list[list]:
    """``unit`` as a list of unit vectors (a flat list of symbols is one, as for
    :func:`~kinlib.symbolic.sym_equal`)."""
    import sympy as sp

    groups = list(unit or ())
    if groups and all(isinstance(s, sp.Symbol) for s in groups):
        return [groups]
    return [list(g) if isinstance(g, list | tuple) else [g] for g in groups]


def _points(symbols, unit, n: int = 2, seed: int = 0) -> list[dict]:
    """``n`` random points for ``symbols`` (in [0.2, 1.3]), unit vectors normalised."""
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n):
        values = {s: float(v) for s, v in zip(symbols, rng.uniform(0.2, 1.3, len(symbols)),
                                              strict=True)}
        for group in _groups(unit):
            norm = np.sqrt(sum(values.get(s, 0.0) ** 2 for s in group))
            for s in group:
                values[s] = values.get(s, 0.0) / norm
        out.append(values)
    return out


def _value(expr, at: dict):
    import sympy as sp

    try:
        return np.array(sp.Matrix([expr]).xreplace(at).evalf(), dtype=float)
    except (TypeError, ValueError):
        return None


class _Comparer:
    """Equality of sympy expressions with the answer: screened at random points, then
    decided exactly (``unit`` as for :func:`~kinlib.symbolic.sym_equal`)."""

    def __init__(self, got, unit, symbols):
        self.got, self.unit = got, unit
        self.points = _points(symbols, unit)
        self.at = [_value(got, p) for p in self.points]

    def equal(self, other) -> bool:
        from ..symbolic import sym_equal

        for p, g in zip(self.points, self.at, strict=True):
            o = _value(other, p)
            if g is not None and o is not None and (
                    g.shape != o.shape or not np.allclose(g, o, rtol=1e-7, atol=1e-9)):
                return False  # they differ at a point: not equal, no need to reduce
        try:
            return sym_equal(self.got, other, self.unit)
        except Exception:  # outside what the exact reduction handles: not shown equal
            return False

    def where(self, expected) -> str:
        """Where the answer and ``expected`` differ, for the message."""
        at, g = self.points[0], self.at[0]
        e = _value(expected, at)
        if g is None or e is None:
            return ""
        where = ", ".join(f"{s} = {v:.3g}" for s, v in at.items())
        return f" (at {where}: yours is {fmt(g.ravel())}, the right one {fmt(e.ravel())})"


def expression_judge(expected: Callable, *, unit=None, swaps: Sequence | None = None,
                     what: str = "a sympy expression", mistakes: Sequence[Mistake] = ()):
    """Judge a sympy answer against ``expected()`` (built from the notebook's own symbols;
    the student's symbols are matched by name). ``unit`` as for :func:`sym_equal`.
    ``mistakes``: the exercise's own near misses, each a :class:`Mistake` whose model
    gives the wrong expression, tried first; then the answer right up to a sign, the
    transpose, and ``swaps``: the symbols whose pairwise exchange is named (default: every
    pair of the expected expression's free symbols)."""

    def judge(args, got):
        import sympy as sp

        exp = expected(*args)
        matrix = isinstance(exp, sp.MatrixBase)
        if matrix:
            exp = sp.Matrix(exp)
        if not matrix and isinstance(got, list | tuple) and len(got) == 1:
            return Verdict(False, "type", "that is a list of one (sympy's solve returns the "
                                          "list of solutions): store its element, [0]")
        try:
            g = _as_sympy(got, matrix)
        except (TypeError, ValueError, sp.SympifyError):
            return Verdict(False, "type", f"expected {what}, got {fmt(got, 80)}")
        by_name = {s.name: s for s in exp.free_symbols}
        g = g.xreplace({s: by_name[s.name] for s in getattr(g, "free_symbols", ())
                        if s.name in by_name and by_name[s.name] != s})
        symbols = sorted(exp.free_symbols | getattr(g, "free_symbols", set()), key=str)
        same = _Comparer(g, unit, symbols)

        def like(x) -> bool:  # the same kind of object as the answer, of its shape
            return isinstance(x, sp.MatrixBase) == isinstance(g, sp.MatrixBase) and (
                not isinstance(g, sp.MatrixBase) or x.shape == g.shape)

        def named():  # the exercise's own mistakes, of the answer's kind and shape
            for m in mistakes:
                try:
                    wrong = m.model(*args)
                except Exception:  # a model that does not apply here
                    continue
                if like(wrong) and same.equal(wrong):
                    return Verdict(False, m.key, m.message, exp)
            return None

        if not like(exp):  # another kind or shape: one of the named mistakes, or said so
            mistake = named()
            if mistake is not None:
                return mistake
            if matrix != isinstance(g, sp.MatrixBase):
                return Verdict(False, "type", f"expected {what}, got {fmt(got, 80)}")
            if g.shape == exp.shape[::-1]:
                return Verdict(False, TRANSPOSED.key, f"your matrix is {g.shape[0]}×"
                                                      f"{g.shape[1]}, the transpose's shape: "
                                                      "check rows against columns")
            return Verdict(False, "shape", f"your matrix is {g.shape[0]}×{g.shape[1]}, "
                                           f"expected {exp.shape[0]}×{exp.shape[1]}")
        if same.equal(exp):
            return RIGHT
        mistake = named()
        if mistake is not None:
            return mistake
        if same.equal(-exp):
            return Verdict(False, SIGN.key, "right up to the sign: look for a reversed "
                                            "cross product, a transposed rotation or a "
                                            "minus lost in the algebra", exp)
        if matrix and exp.shape[0] == exp.shape[1] and same.equal(exp.T):
            return Verdict(False, TRANSPOSED.key, TRANSPOSED.message, exp)
        pool = list(swaps) if swaps is not None else sorted(exp.free_symbols, key=str)
        for a, b in combinations(pool, 2):
            if same.equal(exp.xreplace({a: b, b: a})):
                return Verdict(False, SWAPPED.key, f"{a} and {b} are swapped in your answer",
                               exp)
        unknown = sorted(s.name for s in getattr(g, "free_symbols", ()) if s.name not in by_name)
        if unknown:  # and they do not cancel (sin²γ + cos²γ in an unsimplified answer would)
            return Verdict(False, "symbols", f"your answer has symbols the right one does not: "
                                             f"{', '.join(unknown)}; build it from the "
                                             f"notebook's symbols ({', '.join(sorted(by_name))})")
        return Verdict(False, "wrong", "not equal to the right answer" + same.where(exp), exp)
    return judge
