r"""Symbolic helpers for the derivations: canonical trigonometric reduction and batched lambdify.

Rotation products are polynomials in the sines and cosines of the joint/Euler angles (and
in the components of unit axes or quaternions). :func:`trig_reduce` writes such an
expression in a canonical form:

1. every angle is rescaled so that its trigonometric arguments are integer combinations
   (``θ/2`` inside ``sin(θ/2)`` and ``θ`` inside ``sin θ`` both become multiples of one
   half-angle), and ``sin``/``cos`` of sums and multiples are expanded (``expand_trig``);
2. the result is a polynomial in :math:`c_i = \cos\theta_i`, :math:`s_i = \sin\theta_i`
   and the other symbols; every power :math:`s_i^2` is replaced by :math:`1 - c_i^2` and, for
   each unit vector :math:`(u_1, \dots, u_n)` named in ``unit``, every :math:`u_n^2` by
   :math:`1 - u_1^2 - \dots - u_{n-1}^2`.

These replacement rules form a Gröbner basis (their leading terms share no variable), so the
remainder is unique: an identity between rotation products reduces to exactly ``0``. No
heuristics, no random choices, no ``simplify()`` search: the same input always takes the
same steps. :func:`simplify_rotation` then makes the canonical form readable
(``l1 cos θ1 + l2 cos(θ1 + θ2)``) with one ``trigsimp`` per entry, and :func:`sym_equal`
decides identities.

:func:`lambdify_batched` turns a sympy expression or matrix into a numpy function that
takes arrays with any leading batch shape and returns ``batch + expr.shape``.

>>> import sympy as sp
>>> from kinlib import rotx, rotz
>>> a, b = sp.symbols("alpha beta", real=True)
>>> simplify_rotation(rotz(a) * rotz(b))[0, :]
Matrix([[cos(alpha + beta), -sin(alpha + beta), 0]])
>>> sym_equal((rotx(a) * rotz(b)).T * (rotx(a) * rotz(b)), sp.eye(3))
True
"""

from __future__ import annotations

import math
from collections.abc import Iterable

import numpy as np
import sympy as sp

from .._validate import as_array, fmt_index
from ..errors import KinlibError
from ._trig_fold import combine_sums as _combine_sums
from ._trig_fold import lower_half_angles as _lower_half_angles

__all__ = ["trig_reduce", "simplify_rotation", "sym_equal", "lambdify_batched"]


def _as_sympy(expr, name: str = "expr"):
    if isinstance(expr, sp.MatrixBase | sp.Expr):
        return expr
    if isinstance(expr, str | bytes) or expr is None:
        raise KinlibError(f"{name}: expected a sympy expression or Matrix, got {expr!r}")
    try:
        out = sp.sympify(expr, strict=True)
    except (sp.SympifyError, TypeError, ValueError):
        out = None
    if isinstance(out, sp.MatrixBase | sp.Expr):
        return out
    if isinstance(expr, list | tuple | np.ndarray):
        try:
            return sp.Matrix(expr)
        except (sp.SympifyError, TypeError, ValueError):
            pass
    raise KinlibError(
        f"{name}: expected a sympy expression or Matrix, got {type(expr).__name__}"
    )


def _unit_groups(unit) -> list[tuple[sp.Symbol, ...]]:
    """``unit`` as a list of symbol tuples: one flat sequence or a sequence of sequences."""
    if unit is None:
        return []
    if isinstance(unit, sp.MatrixBase):
        unit = list(unit)
    if isinstance(unit, str | bytes) or not isinstance(unit, Iterable):
        raise KinlibError(
            f"unit: expected symbols of a unit vector, e.g. [kx, ky, kz], got {unit!r}"
        )
    items = list(unit)
    if not items:
        return []
    groups = [items] if all(isinstance(u, sp.Symbol) for u in items) else items
    out = []
    for i, g in enumerate(groups):
        g = list(g) if isinstance(g, Iterable | sp.MatrixBase) and not isinstance(g, str) else [g]
        if len(g) < 2 or not all(isinstance(s, sp.Symbol) for s in g):
            raise KinlibError(
                f"unit[{i}]: expected two or more sympy Symbols (the components of one unit "
                f"vector), got {g!r}"
            )
        out.append(tuple(g))
    seen = [s for g in out for s in g]
    if len(set(seen)) != len(seen):
        raise KinlibError(f"unit: a symbol appears in two unit vectors: {out!r}")
    return out


def _angle_scales(e: sp.Expr) -> dict[sp.Symbol, int]:
    """For each symbol inside a sin/cos/tan, the LCM of the denominators of its coefficients."""
    scales: dict[sp.Symbol, int] = {}
    for f in e.atoms(sp.sin, sp.cos, sp.tan, sp.cot):
        arg = sp.expand(f.args[0])
        for s in arg.free_symbols:
            coeff = arg.coeff(s)
            den = int(sp.fraction(coeff)[1]) if coeff.is_Rational else 1
            scales[s] = math.lcm(scales.get(s, 1), den)
    return scales


def _reduce_poly(e: sp.Expr, rules: dict[sp.Symbol, sp.Expr]) -> sp.Expr:
    """Replace every ``x**n`` (n ≥ 2, x a key of ``rules``) by ``x**(n % 2) * rules[x]**(n // 2)``.

    One pass is complete: no right-hand side contains a key (``1 - c**2`` for ``s``; for the
    last component of a unit vector, the other components, and unit vectors share no
    symbol), so expanding the result makes no new power of a key. Rules that break this
    would need more passes, in a loop that might not end: they are refused.
    """
    if not rules:
        return e
    keys = set(rules)
    tangled = sorted((str(x) for x, r in rules.items() if r.free_symbols & keys))
    if tangled:
        raise KinlibError(
            f"trig_reduce: the replacement for {', '.join(tangled)} contains a symbol that is "
            "itself replaced; one pass would leave powers behind"
        )
    powers = {
        p: p.base ** (int(p.exp) % 2) * rules[p.base] ** (int(p.exp) // 2)
        for p in e.atoms(sp.Pow) if p.base in rules and p.exp.is_Integer and p.exp >= 2
    }
    return sp.expand(e.xreplace(powers)) if powers else e


def _reduce_scalar(e: sp.Expr, groups) -> sp.Expr:
    if not e.free_symbols:
        return sp.nsimplify(e) if e.is_Float else sp.expand(e)
    e = e.rewrite(sp.tan, sp.sin) if e.has(sp.tan, sp.cot) else e
    e = e.rewrite(sp.cot, sp.cos) if e.has(sp.cot) else e
    scales = {s: k for s, k in _angle_scales(e).items() if k > 1}
    fine = {s: sp.Dummy(f"{s.name}_{k}", real=True) for s, k in scales.items()}
    e = e.xreplace({s: k * fine[s] for s, k in scales.items()}) if scales else e
    num, den = sp.fraction(sp.together(sp.expand_trig(e)))
    rules: dict[sp.Symbol, sp.Expr] = {}
    back: dict[sp.Symbol, sp.Expr] = {}
    trig = sorted(
        {f for f in (num.atoms(sp.sin, sp.cos) | den.atoms(sp.sin, sp.cos))},
        key=sp.default_sort_key,
    )
    args = sorted({f.args[0] for f in trig}, key=sp.default_sort_key)
    sub = {}
    for i, a in enumerate(args):
        c, s = sp.Dummy(f"c{i}", real=True), sp.Dummy(f"s{i}", real=True)
        sub[sp.cos(a)], sub[sp.sin(a)] = c, s
        back[c], back[s] = sp.cos(a), sp.sin(a)
        rules[s] = 1 - c**2
    for g in groups:
        rules[g[-1]] = 1 - sum(x**2 for x in g[:-1])

    def canon(p):
        return _reduce_poly(sp.expand(p.xreplace(sub)), rules).xreplace(back)

    num = canon(num)
    if num == 0:
        return sp.S.Zero
    den = canon(den)
    out = num if den == 1 else sp.cancel(num / den)
    return out.xreplace({d: s / scales[s] for s, d in fine.items()}) if scales else out


def trig_reduce(expr, unit=None):
    r"""The canonical polynomial form of a trigonometric expression or matrix.

    Parameters
    ----------
    expr : sympy expression or Matrix
        Built from sums, products and integer powers of sin/cos (tan/cot are rewritten)
        of linear combinations of symbols, with rational coefficients.
    unit : sequence of Symbols, or a sequence of such sequences, optional
        Components of unit vectors (``[kx, ky, kz]``, a quaternion ``[w, x, y, z]``):
        the square of the last one is replaced by one minus the squares of the others.

    Returns
    -------
    The same kind of object, every entry reduced: exactly ``0`` for an identity.

    >>> import sympy as sp
    >>> t = sp.symbols("theta", real=True)
    >>> trig_reduce(sp.sin(t)**2 + sp.cos(t)**2)
    1
    >>> trig_reduce(sp.sin(t) - 2 * sp.sin(t / 2) * sp.cos(t / 2))
    0
    >>> kx, ky, kz = sp.symbols("k_x k_y k_z", real=True)
    >>> trig_reduce(kx**2 + ky**2 + kz**2, unit=[kx, ky, kz])
    1
    """
    e = _as_sympy(expr)
    groups = _unit_groups(unit)
    if isinstance(e, sp.MatrixBase):
        return sp.Matrix(e).applyfunc(lambda x: _reduce_scalar(x, groups))
    return _reduce_scalar(e, groups)


def simplify_rotation(expr, unit=None):
    r"""A readable, deterministic simplification of a rotation/transform product.

    :func:`trig_reduce` first (so identities vanish and equal inputs give equal outputs),
    then an exact, term-by-term folding of :math:`c_1 c_2 - s_1 s_2` into
    :math:`\cos(\theta_1 + \theta_2)` (and the three other sum/difference patterns),
    repeated so that chains give ``cos(θ1 + θ2 + θ3)``. Only entries left with squares of
    sines/cosines (half-angle forms) go on to ``sympy.trigsimp``. Much faster than
    ``sympy.simplify`` on long chains (a PUMA 560's whole 6-joint transform in about a
    second), and deterministic.

    >>> import sympy as sp
    >>> from kinlib import dh_transform
    >>> t1, t2, l1, l2 = sp.symbols("theta1 theta2 l1 l2", real=True)
    >>> T = dh_transform(theta=t1, d=0, a=l1, alpha=0) * dh_transform(theta=t2, d=0, a=l2, alpha=0)
    >>> simplify_rotation(T[0, 3])
    l1*cos(theta1) + l2*cos(theta1 + theta2)
    """
    e = trig_reduce(expr, unit)

    def tidy(x):
        if not x.has(sp.sin, sp.cos):
            return sp.factor_terms(x)
        x = _combine_sums(x)
        squares = any(p.base.func in (sp.sin, sp.cos) for p in x.atoms(sp.Pow))
        if squares:
            x = _combine_sums(sp.expand(_lower_half_angles(sp.trigsimp(x))))
        return sp.factor_terms(x)

    if isinstance(e, sp.MatrixBase):
        return e.applyfunc(tidy)
    return tidy(e)


def sym_equal(a, b, unit=None) -> bool:
    """True when ``a − b`` reduces to exactly zero (see :func:`trig_reduce`).

    >>> import sympy as sp
    >>> t = sp.symbols("theta", real=True)
    >>> sym_equal(sp.cos(2 * t), 1 - 2 * sp.sin(t)**2), sym_equal(sp.cos(t), sp.sin(t))
    (True, False)
    """
    ea, eb = _as_sympy(a, "a"), _as_sympy(b, "b")
    ma, mb = isinstance(ea, sp.MatrixBase), isinstance(eb, sp.MatrixBase)
    if ma != mb or (ma and ea.shape != eb.shape):
        what = lambda x, m: f"a {x.shape[0]}×{x.shape[1]} Matrix" if m else "a scalar"  # noqa: E731
        raise KinlibError(f"sym_equal: cannot compare {what(ea, ma)} with {what(eb, mb)}")
    d = trig_reduce(ea - eb, unit)
    return bool(d.is_zero_matrix) if ma else d == 0


def lambdify_batched(args, expr):
    r"""A numpy function of ``args`` evaluating ``expr`` over any batch of inputs.

    Parameters
    ----------
    args : sequence
        Each item is a Symbol (its input: an array of any shape) or a sequence of Symbols
        (its input: an array of shape ``(..., len)``, e.g. a joint vector q).
    expr : sympy expression or Matrix
        Its free symbols must all appear in ``args``.

    Returns
    -------
    f : callable
        ``f(*arrays)`` broadcasts the batch shapes of its inputs and returns a float array
        of shape ``batch + expr.shape`` (``batch`` for a scalar expression, ``batch + (n,)``
        for an n×1 column vector, like kinlib's vectors). Constant entries
        are broadcast too, so a 4×4 transform keeps its ``[0, 0, 0, 1]`` row.

    >>> import numpy as np, sympy as sp
    >>> from kinlib import rotz
    >>> t = sp.symbols("theta", real=True)
    >>> f = lambdify_batched([t], rotz(t))
    >>> f(np.linspace(0, np.pi, 5)).shape
    (5, 3, 3)
    >>> f(np.pi / 2).round(12) + 0.0
    array([[ 0., -1.,  0.],
           [ 1.,  0.,  0.],
           [ 0.,  0.,  1.]])
    """
    e = _as_sympy(expr)
    if isinstance(args, sp.Symbol) or not isinstance(args, Iterable) or isinstance(args, str):
        raise KinlibError(
            f"args: expected a list of Symbols (or of lists of Symbols), got {args!r}"
        )
    specs: list[tuple[str, list[sp.Symbol] | sp.Symbol]] = []
    flat: list[sp.Symbol] = []
    for i, a in enumerate(list(args)):
        if isinstance(a, sp.Symbol):
            specs.append(("scalar", a))
            flat.append(a)
            continue
        seq = isinstance(a, Iterable | sp.MatrixBase) and not isinstance(a, str)
        items = list(a) if seq else []
        if not items or not all(isinstance(s, sp.Symbol) for s in items):
            raise KinlibError(f"args[{i}]: expected a Symbol or a list of Symbols, got {a!r}")
        specs.append(("vector", items))
        flat.extend(items)
    if len(set(flat)) != len(flat):
        raise KinlibError(f"args: a symbol is listed twice: {flat!r}")
    missing = sorted(e.free_symbols - set(flat), key=sp.default_sort_key)
    if missing:
        raise KinlibError(
            f"expr: has free symbols {', '.join(map(str, missing))} that are not in args; "
            "list them in args or give them values with expr.subs(...)"
        )
    shape = tuple(e.shape) if isinstance(e, sp.MatrixBase) else ()
    if len(shape) == 2 and shape[1] == 1:
        shape = (shape[0],)  # a column vector gives (..., n), like kinlib's vectors
    entries = list(e) if shape else [e]
    fn = sp.lambdify(flat, entries, modules="numpy", cse=True)
    names = [
        str(s) if kind == "scalar" else "[" + ", ".join(map(str, s)) + "]" for kind, s in specs
    ]

    def f(*values):
        if len(values) != len(specs):
            raise KinlibError(
                f"expected {len(specs)} input(s) ({', '.join(names)}), got {len(values)}"
            )
        cols, batches = [], []
        for (kind, s), v, name in zip(specs, values, names, strict=False):
            if kind == "scalar":
                a = as_array(v, name)
                cols.append(a)
                batches.append(a.shape)
            else:
                a = as_array(v, name, (len(s),))
                cols.extend(a[..., j] for j in range(len(s)))
                batches.append(a.shape[:-1])
        try:
            batch = np.broadcast_shapes(*batches) if batches else ()
        except ValueError:
            raise KinlibError(
                "inputs: batch shapes "
                + ", ".join(f"{n} {b}" for n, b in zip(names, batches, strict=False))
                + " do not broadcast"
            ) from None
        with np.errstate(all="ignore"):
            vals = fn(*cols)
        out = np.empty(batch + (len(entries),))
        for j, val in enumerate(vals):
            a = np.asarray(val)
            if a.dtype.kind == "c":
                raise KinlibError(f"expr: entry {j} is complex for these inputs")
            out[..., j] = np.broadcast_to(a.astype(np.float64, copy=False), batch)
        bad = ~np.isfinite(out).all(axis=-1)
        if np.any(bad):
            j = int(np.argwhere(~np.isfinite(out.reshape(-1, len(entries))))[0][1])
            raise KinlibError(
                f"expr: entry {j} ({entries[j]}) is not finite at input"
                f"{fmt_index(batch, bad) or ''} (outside its domain, e.g. a division by zero "
                "or the square root of a negative number)"
            )
        return out.reshape(batch + shape)

    f.__doc__ = f"Batched numpy evaluation of {len(entries)} entries in ({', '.join(names)})."
    return f
