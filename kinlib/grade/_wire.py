"""Plain-data messages between the grader and the student's process (no pickle).

One message is one line of JSON. Values are tagged so that nothing the student returns can
pass for something else: ``None``, ``bool``, ``int``, ``float`` (NaN and ±inf included) and
``str`` go as they are; everything else is a small object with a ``"t"`` tag:

=====================  ============================================================
``{"t": "nd", ...}``   a numeric array: ``dtype`` ("f8", "i8" or "b1"), ``shape``, flat ``v``
``{"t": "list", ...}`` a list (``"tuple"``: a tuple), items in ``v``
``{"t": "dict", ...}`` a dict, ``v`` a list of ``[key, value]`` pairs
``{"t": "sym", ...}``  a sympy expression (``v``: one node) or matrix (``shape`` [r, c],
                       ``v``: its r·c entries row by row), as a tree of nodes (below)
``{"t": "odd", ...}``  anything else: its type name and (a short) repr, never the object
=====================  ============================================================

A sympy value is a tree of plain lists of a few kinds only, never text to parse (sympify,
``eval`` and ``parse_expr`` on a student's text run code):

- ``["s", name, flags]`` a Symbol (a name of 1 to 64 printable characters; ``flags``: the
  assumptions of :data:`SYM_FLAGS` that hold), ``["i", n]`` an Integer, ``["q", p, q]`` a
  Rational, ``["f", x]`` a Float (a finite double), ``["c", name]`` one of
  :data:`SYM_CONSTANTS`;
- ``["+", a, b, ...]``, ``["*", a, b, ...]``, ``["^", base, exponent]`` (``sqrt`` is a
  power), ``[f, x, ...]`` for the functions of :data:`SYM_FUNCTIONS`.

Bounds (the ``MAX_SYM_*`` constants): the nodes of one message, counted as written out
(a sympy expression sharing subexpressions, a "node bomb", is too large), the depth, the
entries of a matrix, integers below ``10**60``, a number as an exponent. A sympy value with
no symbols goes as numbers (``nd``) unless ``encode(..., exact=True)`` (the grader's exact
arguments, ``pi/2``); so does a matrix of more than :data:`MAX_SYM_ENTRIES` entries.

:func:`encode` runs in the student's process, so it must never raise or run for long on a
hostile object (a ``__repr__`` that loops is cut off by the grader's time limit; a sympy
object is never repr'd: only sympy's own classes are read, by exact type, so a subclass with
a hostile ``__repr__`` or ``args`` is refused by name). :func:`decode` runs in the grader
and accepts only well-formed data: anything else raises :class:`WireError`, which the grader
turns into a failed case. A sympy value comes back as a :class:`Sym` (the checked tree and a
short text, no sympy object: building one could evaluate ``10**10**9``), or, with
``sympy=True`` (the worker, reading the grader's arguments), as sympy objects.
"""

from __future__ import annotations

import functools
import json
import math
import sys

import numpy as np

__all__ = ["encode", "decode", "dumps", "loads", "WireError", "Odd", "Sym", "build_sympy",
           "MAX_NUMBERS", "MAX_LINE", "MAX_SYM_NODES", "MAX_SYM_DEPTH", "MAX_SYM_ENTRIES",
           "MAX_SYM_POWER", "SYM_FLAGS", "SYM_FUNCTIONS", "SYM_CONSTANTS"]

MAX_NUMBERS = 1_000_000  # numbers in one value: more is "too large", not sent
MAX_LINE = 32 * 1024 * 1024  # bytes in one message line
MAX_DEPTH = 20
_KINDS = {"f": "f8", "i": "i8", "u": "i8", "b": "b1"}
MAX_SYM_NODES = 5_000  # nodes of the sympy values in one message
MAX_SYM_DEPTH = 60
MAX_SYM_ENTRIES = 256  # entries of one sympy matrix
MAX_SYM_POWER = 1000  # a number as an exponent: |value| (and a Rational's denominator)
_MAX_INT = 10**60  # integers in a sympy value: |n| below this
SYM_FLAGS = ("real", "positive", "negative", "nonnegative", "nonzero", "integer")
SYM_FUNCTIONS = {"sin": 1, "cos": 1, "tan": 1, "cot": 1, "asin": 1, "acos": 1, "atan": 1,
                 "atan2": 2, "exp": 1, "log": 1, "Abs": 1}
SYM_CONSTANTS = ("pi", "E", "I", "oo", "-oo", "zoo", "nan")


class WireError(ValueError):
    """A message that is not well-formed plain data."""


def _odd(obj, why: str = "", show: bool = True) -> dict:
    try:
        text = repr(obj) if show else ""
    except BaseException:  # a hostile __repr__ must not stop the worker
        text = "<repr failed>"
    return {"t": "odd", "type": type(obj).__name__[:100], "repr": text[:200], "why": why}


def encode(obj, _depth: int = 0, _budget: list | None = None, *, exact: bool = False):
    """``obj`` as tagged plain data (see the module docstring); ``exact``: sympy numbers as
    sympy values too (else as numbers)."""
    budget = [MAX_NUMBERS, MAX_SYM_NODES] if _budget is None else _budget
    if _depth > MAX_DEPTH:
        return _odd(obj, "nested too deeply")
    if obj is None or type(obj) in (bool, str):
        return obj if type(obj) is not str else obj[:100_000]
    if type(obj) is int:
        return obj if abs(obj) < 2**63 else float(obj)
    if type(obj) is float:
        return obj
    if isinstance(obj, np.generic) and obj.dtype.kind in _KINDS:
        return encode(obj.item(), _depth, budget)
    try:
        why, symbolic = "", _symbolic(obj)
    except BaseException:  # e.g. a __class__ that raises
        why, symbolic = "", False
    if symbolic:
        try:
            value = _sym_value(obj, budget, exact)
        except _Unreadable as exc:
            value, why = None, str(exc)
        except BaseException:  # anything the student's object does
            value, why = None, "it could not be read"
        if value is not None:
            return value
        if why:  # (not turned into numbers either: float() of it could take for ever)
            return _odd(obj, f"a sympy value the grader cannot read: {why}",
                        show=isinstance(obj, np.ndarray))
    module = getattr(type(obj), "__module__", None) or ""
    if symbolic or isinstance(obj, np.ndarray) or module.startswith(("sympy", "numpy")) \
            or "__array__" in dir(type(obj)):
        return _array(obj, budget)
    if type(obj) in (list, tuple):
        if len(obj) > budget[0]:
            return _odd(obj, "too large")
        budget[0] -= len(obj)
        return {"t": "list" if type(obj) is list else "tuple",
                "v": [encode(x, _depth + 1, budget, exact=exact) for x in obj]}
    if type(obj) is dict:
        if len(obj) > budget[0]:
            return _odd(obj, "too large")
        budget[0] -= len(obj)
        return {"t": "dict", "v": [[encode(k, _depth + 1, budget, exact=exact),
                                    encode(v, _depth + 1, budget, exact=exact)]
                                   for k, v in obj.items()]}
    return _odd(obj)


def _array(obj, budget: list):
    try:
        a = np.asarray(obj)
        if a.dtype.kind not in _KINDS:
            a = np.asarray(obj, dtype=float)  # e.g. a numeric sympy Matrix
    except BaseException:  # anything the student's object does
        return _odd(obj, "not a numeric array")
    if a.dtype.kind not in _KINDS:
        return _odd(obj, "not a numeric array")
    if a.size > budget[0]:
        return _odd(obj, "too large")
    budget[0] -= a.size
    kind = _KINDS[a.dtype.kind]
    flat = a.astype({"f8": float, "i8": np.int64, "b1": bool}[kind]).ravel().tolist()
    return {"t": "nd", "dtype": kind, "shape": list(a.shape), "v": flat,
            "from": type(obj).__name__[:100]}


# -- sympy values, in the student's process ------------------------------------------------
class _Unreadable(Exception):
    """Why a sympy value cannot go as a tree."""


@functools.lru_cache(maxsize=1)
def _sympy_kinds():
    """sympy's own classes (by exact type) → node kind, its constants, its dense matrices."""
    import sympy as sp
    from sympy.core import numbers as n

    kinds = {sp.Symbol: "s", sp.Integer: "i", n.One: "i", n.Zero: "i", n.NegativeOne: "i",
             sp.Rational: "q", n.Half: "q", sp.Float: "f", sp.Add: "+", sp.Mul: "*",
             sp.Pow: "^", **{getattr(sp, f): f for f in SYM_FUNCTIONS}}
    constants = dict(zip(map(type, (sp.pi, sp.E, sp.I, sp.oo, -sp.oo, sp.zoo, sp.nan)),
                         SYM_CONSTANTS, strict=True))
    return {**kinds, **dict.fromkeys(constants, "c")}, constants, \
        (sp.MutableDenseMatrix, sp.ImmutableDenseMatrix)


def _symbolic(obj) -> bool:
    """A sympy object (sympy already imported by the student's code), or an object array."""
    if isinstance(obj, np.ndarray):
        return obj.dtype == object and 0 < obj.size <= MAX_SYM_ENTRIES and any(
            _symbolic(x) for x in obj.flat)
    sp = sys.modules.get("sympy")
    kinds = getattr(sp, "Basic", None), getattr(sp, "MatrixBase", None)  # (None: sympy is
    return None not in kinds and isinstance(obj, kinds)  # being imported, obj is not one)


def _name_ok(name) -> bool:
    return type(name) is str and 0 < len(name) <= 64 and name.isprintable()


def _int_ok(n) -> bool:
    return type(n) is int and -_MAX_INT < n < _MAX_INT


def _power_ok(e: list) -> bool:
    """A number as an exponent is small (no ``10**10**9`` to evaluate)."""
    return e[0] not in ("i", "q", "f") or (abs(e[1]) <= MAX_SYM_POWER
                                           and (e[0] != "q" or e[2] <= MAX_SYM_POWER))


def _number_node(x) -> list:
    if type(x) is int and not _int_ok(x):
        raise _Unreadable("an integer of more than 60 digits")
    if type(x) is int or math.isfinite(x):
        return ["i" if type(x) is int else "f", x]
    return ["c", "nan" if x != x else "oo" if x > 0 else "-oo"]


def _tree(obj, budget: list, depth: int, seen: list) -> list:
    """``obj`` as a node; ``seen[0]`` is set when a Symbol is met."""
    budget[1] -= 1
    if budget[1] < 0:
        raise _Unreadable(f"too large (more than {MAX_SYM_NODES} nodes written out)")
    if depth > MAX_SYM_DEPTH:
        raise _Unreadable(f"nested more than {MAX_SYM_DEPTH} levels deep")
    if isinstance(obj, np.generic) and obj.dtype.kind in "iuf":
        obj = obj.item()
    if type(obj) in (int, float):
        return _number_node(obj)
    kinds, constants, _ = _sympy_kinds()
    kind = kinds.get(type(obj))
    if kind is None:
        raise _Unreadable(f"it contains a {type(obj).__name__[:60]}, which is not one of the "
                          "kinds of sympy object the grader reads")
    if kind == "s":
        if not _name_ok(obj.name):
            raise _Unreadable("a Symbol's name must be 1 to 64 printable characters")
        seen[0] = True
        return ["s", obj.name, [f for f in SYM_FLAGS if getattr(obj, "is_" + f) is True]]
    if kind in ("i", "q"):
        node = ["i", obj.p] if kind == "i" else ["q", obj.p, obj.q]
        if not all(map(_int_ok, node[1:])):
            raise _Unreadable("an integer of more than 60 digits")
        return node
    if kind == "f":
        return _number_node(float(obj))
    if kind == "c":
        return ["c", constants[type(obj)]]
    args = obj.args
    arity = 2 if kind == "^" else SYM_FUNCTIONS.get(kind)
    if type(args) is not tuple or (len(args) != arity if arity else len(args) < 2):
        raise _Unreadable(f"a {type(obj).__name__} with odd arguments")
    if len(args) > budget[1]:
        raise _Unreadable(f"too large (more than {MAX_SYM_NODES} nodes written out)")
    node = [kind, *(_tree(a, budget, depth + 1, seen) for a in args)]
    if kind == "^" and not _power_ok(node[2]):
        raise _Unreadable(f"a number larger than {MAX_SYM_POWER} as an exponent")
    return node


def _sym_value(obj, budget: list, exact: bool) -> dict | None:
    """``obj`` as a ``sym`` value; None when it has no symbols (unless ``exact``)."""
    seen = [False]
    if isinstance(obj, np.ndarray) or type(obj) in _sympy_kinds()[2]:
        shape = tuple(obj.shape)
        if len(shape) not in (1, 2) or not all(type(n) is int for n in shape):
            raise _Unreadable("a matrix must have one or two dimensions")
        r, c = shape if len(shape) == 2 else (shape[0], 1)
        if r * c > MAX_SYM_ENTRIES or r * c == 0:
            return None  # numbers, if anything (too large for a derivation)
        rows = obj.reshape(-1).tolist() if isinstance(obj, np.ndarray) else obj.tolist()
        flat = rows if isinstance(obj, np.ndarray) else [x for row in rows for x in row]
        if len(flat) != r * c:
            raise _Unreadable("a matrix whose entries do not match its shape")
        value = {"t": "sym", "shape": [r, c], "v": [_tree(x, budget, 1, seen) for x in flat]}
    else:
        value = {"t": "sym", "v": _tree(obj, budget, 0, seen)}
    return value if seen[0] or exact else None


def _check(cond: bool, what: str) -> None:
    if not cond:
        raise WireError(what)


def decode(data, *, sympy: bool = False):
    """Tagged plain data back into Python and numpy values; :class:`WireError` if malformed,
    whatever the malformation (the student's process writes these bytes: nothing it sends
    may raise anything else in the grader). A sympy value becomes a :class:`Sym`, or with
    ``sympy=True`` the sympy object itself (built by sympy's constructors, evaluated)."""
    try:
        return _decode(data, 0, [MAX_SYM_NODES, sympy])
    except WireError:
        raise
    except Exception as exc:  # e.g. an unhashable tuple key, an absurd array
        raise WireError(f"malformed value ({type(exc).__name__})") from None


def _decode(data, _depth: int, _state: list | None = None):
    state = [MAX_SYM_NODES, False] if _state is None else _state
    _check(_depth <= MAX_DEPTH + 1, "nested too deeply")
    if data is None or type(data) in (bool, int, float, str):
        return data
    _check(type(data) is dict and type(data.get("t")) is str, f"unexpected {type(data).__name__}")
    tag, v = data["t"], data.get("v")
    if tag in ("list", "tuple"):
        _check(type(v) is list, "list without items")
        items = [_decode(x, _depth + 1, state) for x in v]
        return items if tag == "list" else tuple(items)
    if tag == "dict":
        _check(type(v) is list and all(type(p) is list and len(p) == 2 for p in v), "bad dict")
        out = {}
        for k, x in v:
            key = _decode(k, _depth + 1, state)
            _check(isinstance(key, str | int | float | bool | tuple) or key is None,
                   "unhashable dict key")
            out[key] = _decode(x, _depth + 1, state)
        return out
    if tag == "sym":
        return _decode_sym(data, state)
    if tag == "nd":
        shape, kind = data.get("shape"), data.get("dtype")
        _check(kind in ("f8", "i8", "b1"), "bad dtype")
        _check(type(shape) is list and all(type(n) is int and n >= 0 for n in shape)
               and len(shape) <= 32, "bad shape")
        _check(type(v) is list and len(v) == math.prod(shape), "array size does not match")
        ok = {"f8": (int, float), "i8": (int,), "b1": (bool,)}[kind]
        _check(all(type(x) in ok for x in v), "array items of the wrong type")
        return np.array(v, dtype={"f8": float, "i8": np.int64, "b1": bool}[kind]).reshape(shape)
    if tag == "odd":
        return Odd(str(data.get("type", "?"))[:100], str(data.get("repr", ""))[:200],
                   str(data.get("why", ""))[:100])
    raise WireError(f"unknown tag {tag!r}")


class Odd:
    """Stands for an object the student returned that is not plain data."""

    __slots__ = ("repr", "type", "why")

    def __init__(self, type_: str, text: str, why: str = ""):
        self.type, self.repr, self.why = type_, text, why

    def __repr__(self) -> str:
        return f"<{self.type} {self.repr}>"

    def kinlib_describe(self) -> str:
        """How a check names it (:func:`kinlib.check.as_numeric`)."""
        if not self.repr:  # (a sympy value that could not be read: why not)
            return f"a {self.type} ({self.why[:160]})"
        return f"a {self.type} ({self.repr[:80]})"


# -- sympy values, in the grader -------------------------------------------------------------
def _decode_sym(data: dict, state: list):
    shape, v = data.get("shape"), data.get("v")
    if shape is None:
        entries = [v]
    else:
        _check(type(shape) is list and len(shape) == 2 and all(type(n) is int and n > 0
                                                                for n in shape)
               and shape[0] * shape[1] <= MAX_SYM_ENTRIES,
               f"a sympy matrix must be r×c with at most {MAX_SYM_ENTRIES} entries")
        _check(type(v) is list and len(v) == shape[0] * shape[1],
               "a sympy matrix whose entries do not match its shape")
        entries = v
    names: dict = {}
    floats = [False]
    for x in entries:
        _valid(x, 0, state, names, floats)
    if not state[1]:
        return Sym(v, None if shape is None else tuple(shape), names, floats[0])
    import sympy as sp  # (the worker: the grader's own arguments)

    if shape is None:
        return build_sympy(v, sp)
    return sp.Matrix(*shape, [build_sympy(x, sp) for x in entries])


def _valid(x, depth: int, state: list, names: dict, floats: list) -> None:
    """Check one node (see the module docstring) and count it; collect the Symbols."""
    state[0] -= 1
    _check(state[0] >= 0, f"a sympy value of more than {MAX_SYM_NODES} nodes")
    _check(depth <= MAX_SYM_DEPTH, f"a sympy value nested more than {MAX_SYM_DEPTH} deep")
    _check(type(x) is list and len(x) > 0 and type(x[0]) is str, "a malformed sympy node")
    tag, n = x[0], len(x)
    if tag == "s":
        _check(n == 3 and _name_ok(x[1]), "a Symbol's name must be 1 to 64 printable "
                                          "characters")
        _check(type(x[2]) is list and all(type(f) is str and f in SYM_FLAGS for f in x[2])
               and len(set(x[2])) == len(x[2]), "a Symbol with unknown assumptions")
        names.setdefault(x[1], tuple(x[2]))
    elif tag in ("i", "q"):
        _check(n == (2 if tag == "i" else 3) and all(map(_int_ok, x[1:]))
               and (tag == "i" or x[2] > 0), "an integer of more than 60 digits, or malformed")
    elif tag == "f":
        _check(n == 2 and type(x[1]) is float and math.isfinite(x[1]), "a bad Float")
        floats[0] = True
    elif tag == "c":
        _check(n == 2 and type(x[1]) is str and x[1] in SYM_CONSTANTS, "an unknown constant")
    elif tag in ("+", "*", "^") or tag in SYM_FUNCTIONS:
        arity = 2 if tag == "^" else SYM_FUNCTIONS.get(tag)
        _check(n - 1 == arity if arity else n >= 3, f"{tag} with a wrong number of arguments")
        for a in x[1:]:
            _valid(a, depth + 1, state, names, floats)
        _check(tag != "^" or _power_ok(x[2]), f"a number larger than {MAX_SYM_POWER} as an "
                                              "exponent")
    else:
        raise WireError(f"an unknown kind of sympy node {tag[:20]!r}")


def build_sympy(x: list, sp, evaluate: bool = True, symbols: dict | None = None):
    """The sympy object of a checked node (``sp``: the sympy module; ``symbols``: the
    Symbol to use for a name, if given)."""
    tag = x[0]
    if tag == "s":
        return (symbols or {}).get(x[1]) or sp.Symbol(x[1], **dict.fromkeys(x[2], True))
    if tag in ("i", "q", "f"):
        return {"i": sp.Integer, "q": sp.Rational, "f": sp.Float}[tag](*x[1:])
    if tag == "c":
        return dict(zip(SYM_CONSTANTS, (sp.pi, sp.E, sp.I, sp.oo, -sp.oo, sp.zoo, sp.nan),
                        strict=True))[x[1]]
    args = [build_sympy(a, sp, evaluate, symbols) for a in x[1:]]
    f = {"+": sp.Add, "*": sp.Mul, "^": sp.Pow}.get(tag) or getattr(sp, tag)
    return f(*args, evaluate=evaluate)


def _show(x, need: int = 0) -> str:
    """A node as text (never through sympy's printer, which may evaluate); ``need``: the
    precedence the context needs (0 a sum's term, 1 a factor, 3 a power's base or exponent)."""
    tag = x[0]
    if tag in ("s", "c", "i", "f"):
        text = repr(float(x[1])) if tag == "f" else str(x[1])
        level = 0 if text.startswith("-") else 3
    elif tag == "q":
        text, level = f"{x[1]}/{x[2]}", 0 if x[1] < 0 else 1
    elif tag == "+":
        parts = [_show(a) for a in x[1:]]
        text = parts[0] + "".join(f" - {t[1:]}" if t.startswith("-") else f" + {t}"
                                  for t in parts[1:])
        level = 0
    elif tag == "*":
        args, sign = x[1:], ""
        if args[0][0] in ("i", "q", "f") and args[0][1] < 0:  # -2*x, not (-2)*x
            sign, first = "-", [args[0][0], -args[0][1], *args[0][2:]]
            args = args[1:] if first[1:] == [1] else [first, *args[1:]]
        text, level = sign + "*".join(_show(a, 1) for a in args), 0 if sign else 1
    elif tag == "^":
        text, level = f"{_show(x[1], 3)}**{_show(x[2], 3)}", 2
    else:
        text, level = f"{tag}({', '.join(_show(a) for a in x[1:])})", 3
    return f"({text})" if level < need else text


class Sym(Odd):
    """A sympy expression (``shape`` None, ``tree`` one node) or matrix (``shape`` (r, c),
    ``tree`` its entries row by row) the student returned, as a checked tree; ``names``:
    its Symbols' names → assumptions, ``floats``: whether it holds a Float. Judges that
    want numbers see an object that is not one (an :class:`Odd`)."""

    __slots__ = ("floats", "names", "shape", "tree")

    def __init__(self, tree, shape, names: dict, floats: bool):
        self.tree, self.shape, self.names, self.floats = tree, shape, names, floats
        if shape is None:
            text, what = _show(tree), "sympy expression"
        else:
            r, c = shape
            rows = [", ".join(_show(e) for e in tree[i * c:(i + 1) * c]) for i in range(r)]
            text, what = "Matrix([" + ", ".join(f"[{row}]" for row in rows) + "])", \
                f"sympy {r}×{c} Matrix"
        super().__init__(what, text[:300])

    @property
    def entries(self) -> list:
        """The entries' nodes (one for an expression)."""
        return [self.tree] if self.shape is None else list(self.tree)


def dumps(message: dict) -> bytes:
    """One message as a line of JSON (NaN and inf allowed)."""
    return json.dumps(message, allow_nan=True, separators=(",", ":")).encode() + b"\n"


def loads(line: bytes) -> dict:
    """Parse one message line; :class:`WireError` unless it is a JSON object."""
    try:
        msg = json.loads(line)
    except (ValueError, UnicodeDecodeError, RecursionError) as exc:
        raise WireError(f"not JSON: {exc}") from None
    _check(type(msg) is dict, "a message must be a JSON object")
    return msg
