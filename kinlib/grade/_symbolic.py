"""Graded derivations: the student's function, called with sympy symbols, returns a sympy
expression or matrix, judged against kinlib's answer for the same symbols.

The answer arrives as a :class:`~kinlib.grade._wire.Sym`, a checked tree of a few node
kinds (no sympy object: see :mod:`kinlib.grade._wire`). Judging it stays bounded whatever
the tree (sympy's ``expand``, ``simplify``, ``evalf`` or even its printer can run for ever on
an expression made for it, ``sin(10**10**9)`` say):

1. the answer and the right one are evaluated at :data:`POINTS` random points (angles in
   (−π, π), positive symbols in [0.3, 2]) by the small evaluator below, with mpmath at
   128 bits; it gives up on a point rather than compute something huge (a division by
   zero, a value beyond 1e60, the sine of more than 1e6). Answers that differ at a point
   are not equal;
2. answers that agree at every point are decided exactly by :func:`kinlib.symbolic.sym_equal`
   (the notebooks' canonical form of trigonometric polynomials) when both lie in its domain
   (sums, products and small integer powers of symbols, rationals, sin, cos, tan) and would
   expand to at most :data:`EXACT_TERMS` terms, counted before anything is expanded; other
   answers are decided by the points alone (agreement to 24 digits at eight random points).

The near misses are those of the notebooks' ``expression`` exercises
(:mod:`kinlib.check._symbolic`): the check's own mistakes (each a model of the wrong
expression, tried first), right up to the sign, the transpose, two arguments swapped,
symbols that are not among the arguments, and, for a matrix, which entries are wrong.
Numbers instead of an expression are named too.

>>> import sympy as sp
>>> from kinlib.grade._wire import decode, encode
>>> t = sp.Symbol("t", real=True)
>>> judge = symbolic_judge(lambda t: sp.sin(2 * t), names=("t",))
>>> judge((t,), decode(encode(2 * sp.sin(t) * sp.cos(t)))).ok
True
>>> judge((t,), decode(encode(-sp.sin(2 * t)))).key
'sign'
>>> judge((t,), 0.5).key
'numbers'
"""

from __future__ import annotations

import hashlib
import json
import zlib
from collections.abc import Callable, Sequence

import numpy as np

from ..check import RIGHT, Mistake, Verdict, fmt
from ..check.mistakes import SIGN, TRANSPOSED
from ._checks import Check
from ._wire import Odd, Sym, build_sympy, decode, encode

__all__ = ["symbolic_check", "symbolic_judge", "symbolic_error_hint", "sym_tree", "POINTS",
           "EXACT_TERMS"]

POINTS = 8  # random points per case
NEEDED = 4  # points where both must be defined
PRECISION = 128  # bits
EXACT_TERMS = 2000
_BIG = 1e60


class _Undefined(Exception):
    """The value at this point is not computed (see the module docstring)."""


class _Outside(Exception):
    """Not in the domain of the exact reduction."""


def sym_tree(obj) -> Sym:
    """A sympy object of the grader's own (a reference, a mistake's model) as the checked
    tree the answers arrive as."""
    value = decode(encode(obj, exact=True))
    if not isinstance(value, Sym):
        raise ValueError(f"not a sympy value the wire can carry: {fmt(value, 100)}")
    return value


# -- the evaluator ----------------------------------------------------------------------------
def _value(x, env: dict, ctx):
    tag = x[0]
    if tag == "s":
        return env[x[1]]
    if tag in ("i", "f"):
        v = ctx.mpf(x[1])
    elif tag == "q":
        v = ctx.mpf(x[1]) / x[2]
    elif tag == "c":
        if x[1] not in ("pi", "E", "I"):
            raise _Undefined
        v = {"pi": +ctx.pi, "E": +ctx.e, "I": ctx.mpc(0, 1)}[x[1]]
    else:
        v = _apply(tag, [_value(a, env, ctx) for a in x[1:]], ctx)
    if not ctx.isfinite(v) or abs(v) > _BIG:
        raise _Undefined
    return v


def _apply(tag: str, a: list, ctx):
    if tag == "+":
        return ctx.fsum(a)
    if tag == "*":
        return ctx.fprod(a)
    if tag == "^":
        b, e = a
        if b == 0:
            if ctx.re(e) > 0:
                return ctx.mpf(0)
            raise _Undefined
        size = e * ctx.log(b)
        if ctx.re(size) > 138 or abs(ctx.im(size)) > 1e6:  # beyond 1e60, or spinning
            raise _Undefined
        return ctx.power(b, e)
    if tag in ("sin", "cos", "tan", "cot"):
        if abs(a[0]) > 1e6:
            raise _Undefined
        return getattr(ctx, tag)(a[0])
    if tag == "exp":
        if abs(a[0]) > 138:
            raise _Undefined
        return ctx.exp(a[0])
    if tag == "atan2":
        if ctx.im(a[0]) or ctx.im(a[1]):
            raise _Undefined
        return ctx.atan2(ctx.re(a[0]), ctx.re(a[1]))
    if tag == "log" and a[0] == 0:
        raise _Undefined
    if tag == "Abs":
        return abs(a[0])
    return getattr(ctx, tag)(a[0])  # log, asin, acos, atan


class _Points:
    """The random points of one case, and the values of trees at them."""

    def __init__(self, names: dict):
        import mpmath

        self.ctx = mpmath.MPContext()
        self.ctx.prec = PRECISION
        rng = np.random.default_rng(zlib.crc32(",".join(sorted(names)).encode()))
        self.points = []
        for _ in range(POINTS):
            env = {}
            for name in sorted(names):
                flags = names[name]
                if "integer" in flags:
                    v = float(rng.integers(1, 6) if "positive" in flags else rng.integers(-5, 6))
                elif "positive" in flags or "nonnegative" in flags:
                    v = rng.uniform(0.3, 2.0)
                elif "negative" in flags:
                    v = -rng.uniform(0.3, 2.0)
                else:
                    v = rng.uniform(-np.pi, np.pi)
                env[name] = self.ctx.mpf(float(v))
            self.points.append(env)

    def values(self, sym: Sym) -> list:
        """Per point: the entries' values, or None where the tree is not defined."""
        out = []
        for env in self.points:
            try:
                out.append([_value(e, env, self.ctx) for e in sym.entries])
            except (_Undefined, ArithmeticError, ValueError, TypeError):
                out.append(None)
        return out


# -- the exact decision -----------------------------------------------------------------------
_CAP = EXACT_TERMS + 1


def _small_numbers(x) -> None:
    """Inside a sine: only small coefficients (sin(1000 t) expands into a long polynomial)."""
    if x[0] in ("i", "q") and (abs(x[1]) > 12 or (x[0] == "q" and x[2] > 12)):
        raise _Outside
    if x[0] not in ("s", "i", "q", "c"):
        for a in x[1:]:
            _small_numbers(a)


def _terms(x) -> int:
    """At most how many terms the tree expands to (saturated at :data:`EXACT_TERMS` + 1);
    :class:`_Outside` if it is outside the exact reduction's domain."""
    tag = x[0]
    if tag in ("s", "i", "q") or (tag == "c" and x[1] == "pi"):
        return 1
    if tag == "+":
        return min(_CAP, sum(_terms(a) for a in x[1:]))
    if tag == "*":
        n = 1
        for a in x[1:]:
            n = min(_CAP, n * _terms(a))
        return n
    if tag == "^":
        base, e = x[1], x[2]
        if e[0] == "i" and base[0] not in ("i", "q") and 0 < abs(e[1]) <= 16:
            return min(_CAP, _terms(base) ** abs(e[1]))
        if e[0] == "q" and base[0] == "i" and base[1] > 0 and e[2] <= 4:
            return 1  # a surd, sqrt(3)
        raise _Outside
    if tag in ("sin", "cos", "tan"):
        _small_numbers(x[1])
        return min(_CAP, 2 ** min(_terms(x[1]), 12))
    raise _Outside


def _exact(a: Sym, b: Sym) -> bool | None:
    """``sym_equal`` of the two trees, or None outside its domain or size."""
    try:
        if sum(_terms(e) for e in a.entries + b.entries) > EXACT_TERMS:
            return None
        import sympy as sp

        from ..symbolic import sym_equal

        symbols = {n: sp.Symbol(n, **dict.fromkeys(f, True)) for n, f in
                   {**a.names, **b.names}.items()}  # one symbol per name

        def build(s: Sym):
            entries = [build_sympy(e, sp, symbols=symbols) for e in s.entries]
            return entries[0] if s.shape is None else sp.Matrix(*s.shape, entries)
        return bool(sym_equal(build(a), build(b)))
    except Exception:  # _Outside, or anything the reduction cannot do
        return None


# -- the judge --------------------------------------------------------------------------------
def _describe(shape) -> str:
    return "a sympy expression" if shape is None else f"a {shape[0]}×{shape[1]} sympy Matrix"


def _scalar(x):
    """A number of a list the student returned (sent as a 0-d array) as a Python number."""
    if isinstance(x, np.ndarray) and x.shape == () and x.dtype.kind in "iuf":
        return x.item()
    return x


def _answer(got, want: Sym):
    """``got`` as a :class:`Sym` of ``want``'s kind, or the verdict saying why not."""
    what = _describe(want.shape)
    numbers = (f"expected {what} built from the symbols your function receives, with "
               "sympy's functions (sp.cos, sp.sin, sp.Matrix): numpy's np.cos cannot take a "
               "symbol, and float() or a substitution leaves numbers without the derivation")
    if got is None:
        return Verdict(False, "none", f"returned None, expected {what}: is there a `return` "
                                      "at the end of your function?")
    if isinstance(got, list | tuple) and got:
        if want.shape is None and len(got) == 1:
            return Verdict(False, "type", "returned a list of one (sympy's solve returns the "
                                          "list of solutions): return its element, [0]")
        rows = [[_scalar(x) for x in r] if isinstance(r, list | tuple) else [_scalar(r)]
                 for r in got]
        leaves = [x for r in rows for x in r]
        if len({len(r) for r in rows}) == 1 and all(
                (isinstance(x, Sym) and x.shape is None) or type(x) in (int, float)
                for x in leaves):
            if not any(isinstance(x, Sym) for x in leaves):
                return Verdict(False, "numbers", f"returned numbers ({fmt(got, 60)}); {numbers}")
            names, tree = {}, []
            for x in leaves:
                if isinstance(x, Sym):
                    names.update(x.names)
                    tree.append(x.tree)
                elif float(x).is_integer() and abs(x) < 2**53:
                    tree.append(["i", int(x)])
                else:
                    tree.append(["f", float(x)])
            got = Sym(tree, (len(rows), len(rows[0])), names,
                      any(x.floats if isinstance(x, Sym) else tree[i][0] == "f"
                          for i, x in enumerate(leaves)))
    if isinstance(got, np.ndarray | np.generic) or type(got) in (int, float):
        return Verdict(False, "numbers", f"returned numbers ({fmt(got, 60)}); {numbers}")
    if not isinstance(got, Sym):
        text = got.kinlib_describe() if isinstance(got, Odd) else \
            f"a {type(got).__name__} ({fmt(got, 60)})"
        return Verdict(False, "type", f"returned {text}, expected {what}")
    if want.shape is None and got.shape == (1, 1):
        return Sym(got.tree[0], None, got.names, got.floats)
    if want.shape == got.shape:
        return got
    if want.shape is None or got.shape is None:
        return Verdict(False, "type", f"returned {_describe(got.shape)}, expected {what}")
    if got.shape == want.shape[::-1]:
        return Verdict(False, TRANSPOSED.key, f"returned {_describe(got.shape)}, the shape of "
                                              f"the transpose of {what}: check rows against "
                                              "columns")
    return Verdict(False, "shape", f"returned {_describe(got.shape)}, expected {what}")


class _Shown:
    """The right answer of a report, made readable (``show``) only when it is shown."""

    def __init__(self, want, show: Callable):
        self.want, self.show, self.text = want, show, None

    def __repr__(self) -> str:
        if self.text is None:
            try:
                self.text = repr(self.show(self.want))
            except Exception:  # (a report must not fail for its decoration)
                self.text = repr(self.want)
        return self.text


_VERDICTS: dict = {}  # (check, case, answer's tree) → verdict: the same answer is judged once


def symbolic_judge(expected: Callable, *, names: Sequence[str],
                   mistakes: Sequence[Mistake] = (), swaps: Sequence[tuple] = (),
                   show: Callable | None = None, cache: str | None = None):
    """``judge(args, got) -> Verdict`` for a derivation: right when ``got`` equals
    ``expected(*args)`` (a sympy expression or Matrix built by kinlib from the same
    arguments; see the module docstring). ``names``: the function's parameters, as the
    messages call them; ``mistakes``: its own near misses, each a :class:`Mistake` whose
    model gives the wrong sympy answer (tried first); ``swaps``: pairs of argument indices
    whose exchange is named; ``show``: the right answer as a wrong answer's report shows
    it (e.g. :func:`kinlib.symbolic.simplify_rotation`; made only then); ``cache``: a name
    for this judge under which a verdict on the same case and tree is remembered (a verdict
    depends on nothing else; a batch of submissions holds many equal answers)."""

    def judge(args, got):
        key = None
        if cache is not None and isinstance(got, Sym):
            tree = json.dumps([got.shape, got.tree, got.names, encode(args, exact=True)])
            key = (cache, hashlib.sha256(tree.encode()).hexdigest())
            known = _VERDICTS.get(key)  # (one lookup: another thread may clear it)
            if known is not None:
                return known
        want = expected(*args)
        verdict = _judge(args, got, sym_tree(want))
        if not verdict.ok:
            verdict = Verdict(False, verdict.key, verdict.message,
                              _Shown(want, show) if show else want)
        if key is not None:
            if len(_VERDICTS) > 1000:
                _VERDICTS.clear()
            _VERDICTS[key] = verdict
        return verdict

    def _judge(args, got, ref: Sym) -> Verdict:
        answer = _answer(got, ref)
        if isinstance(answer, Verdict):
            return answer
        given = {}
        for a in args:
            try:
                given.update(sym_tree(a).names)
            except ValueError:  # an argument that is not a sympy value
                pass
        at = _Points({**answer.names, **given, **ref.names})
        tol = 1e-9 if answer.floats else 1e-24
        mine, right = at.values(answer), at.values(ref)
        usable = [k for k in range(POINTS) if mine[k] is not None and right[k] is not None]
        if len(usable) < NEEDED:
            return Verdict(False, "undefined", "your answer could not be evaluated at enough "
                                               "of the points tried (a division by zero, a "
                                               "logarithm of 0, or numbers beyond 1e60)")

        def differ(a, b) -> list:  # entries where a and b differ at a usable point
            if any(a[k] is None or b[k] is None for k in usable):
                return list(range(len(answer.entries)))
            return [i for i in range(len(answer.entries)) if any(
                abs(a[k][i] - b[k][i]) > tol * max(1, abs(a[k][i]), abs(b[k][i]))
                for k in usable)]

        def like(tree_values) -> bool:
            return not differ(mine, tree_values) and bool(differ(right, tree_values))

        wrong = differ(mine, right)
        if not wrong:
            if _exact(answer, ref) is not False:
                return RIGHT
            return Verdict(False, "wrong", "not equal to the right answer (it agrees with it "
                                           "at the points tried, but not identically)")
        for m in mistakes:
            try:
                model = sym_tree(m.model(*args))
            except Exception:  # a model that does not apply here
                continue
            if model.shape == answer.shape and like(at.values(model)):
                return Verdict(False, m.key, m.message)
        if like([None if v is None else [-x for x in v] for v in right]):
            return Verdict(False, SIGN.key, "right up to the sign: look for a minus lost in "
                                            "the algebra, or two rows or columns swapped")
        r, c = ref.shape or (1, 0)
        if r == c and like([None if v is None else [v[(i % r) * r + i // r] for i in
                                                    range(r * r)] for v in right]):
            return Verdict(False, TRANSPOSED.key, TRANSPOSED.message)
        for i, k in swaps:
            swapped = list(args)
            swapped[i], swapped[k] = args[k], args[i]
            if like(at.values(sym_tree(expected(*swapped)))):
                return Verdict(False, "swapped", f"{names[i]} and {names[k]} are swapped in "
                                                 "your answer")
        unknown = sorted(set(answer.names) - set(given) - set(ref.names))
        if unknown:
            return Verdict(False, "symbols", f"your answer has symbols that are not among "
                                             f"your function's arguments: "
                                             f"{', '.join(unknown)}; build it from the "
                                             "arguments (the grader passes its own symbols, "
                                             "under other names too)")
        if ref.shape is not None and len(wrong) < len(answer.entries):
            cols = ref.shape[1]
            where = ", ".join(f"[{i // cols}, {i % cols}]" for i in wrong)
            return Verdict(False, "entries", f"the entries {where} are wrong (indices from "
                                             f"0), the other {len(answer.entries) - len(wrong)}"
                                             " right")
        k, i = usable[0], wrong[0]
        point = ", ".join(f"{n} = {float(v):.4g}" for n, v in sorted(at.points[k].items()))
        entry = "" if ref.shape is None else f" entry [{i // ref.shape[1]}, {i % ref.shape[1]}]:"
        return Verdict(False, "wrong", f"not equal to the right answer: at {point},{entry} "
                                       f"yours is {_number(mine[k][i])}, the right one "
                                       f"{_number(right[k][i])}")
    return judge


def _number(v) -> str:
    v = complex(v)
    return f"{v.real:.4g}" if abs(v.imag) < 1e-12 * max(1.0, abs(v)) else f"{v:.4g}"


def symbolic_error_hint(args, error: str):
    """A hint when the student's function fails on sympy symbols (numpy's functions)."""
    if any(k in error for k in ("Symbol", "ufunc", "convert expression", "sympy")):
        return ("Your function gets sympy symbols: build the answer with sympy's functions "
                "(sp.cos, sp.sin, sp.Matrix, M.jacobian), not numpy's (np.cos, np.array, "
                "np.linalg), and without float()")
    return None


def symbolic_check(function: str, points: float, title: str, cases, expected: Callable, *,
                   names: Sequence[str], mistakes: Sequence[Mistake] = (),
                   swaps: Sequence[tuple] = (), show: Callable | None = None) -> Check:
    """A :class:`~kinlib.grade._checks.Check` of a derivation: ``cases(rng)`` gives the
    argument tuples (sympy symbols and expressions), ``expected(*args)`` kinlib's sympy
    answer; the rest as for :func:`symbolic_judge`. A case may take 10 s (sympy is slow)."""
    return Check(function, points, title, cases, on_error=symbolic_error_hint,
                 judge=symbolic_judge(expected, names=names, mistakes=mistakes, swaps=swaps,
                                      show=show, cache=f"{function}: {title}"),
                 time_limit=10.0)
