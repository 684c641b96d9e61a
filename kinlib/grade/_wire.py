"""Plain-data messages between the grader and the student's process (no pickle).

One message is one line of JSON. Values are tagged so that nothing the student returns can
pass for something else: ``None``, ``bool``, ``int``, ``float`` (NaN and ±inf included) and
``str`` go as they are; everything else is a small object with a ``"t"`` tag:

=====================  ============================================================
``{"t": "nd", ...}``   a numeric array: ``dtype`` ("f8", "i8" or "b1"), ``shape``, flat ``v``
``{"t": "list", ...}`` a list (``"tuple"``: a tuple), items in ``v``
``{"t": "dict", ...}`` a dict, ``v`` a list of ``[key, value]`` pairs
``{"t": "odd", ...}``  anything else: its type name and (a short) repr, never the object
=====================  ============================================================

:func:`encode` runs in the student's process, so it must never raise or run for long on a
hostile object (a ``__repr__`` that loops is cut off by the grader's time limit).
:func:`decode` runs in the grader and accepts only well-formed data: anything else raises
:class:`WireError`, which the grader turns into a failed case.
"""

from __future__ import annotations

import json
import math

import numpy as np

__all__ = ["encode", "decode", "dumps", "loads", "WireError", "MAX_NUMBERS", "MAX_LINE"]

MAX_NUMBERS = 1_000_000  # numbers in one value: more is "too large", not sent
MAX_LINE = 32 * 1024 * 1024  # bytes in one message line
MAX_DEPTH = 20
_KINDS = {"f": "f8", "i": "i8", "u": "i8", "b": "b1"}


class WireError(ValueError):
    """A message that is not well-formed plain data."""


def _odd(obj, why: str = "") -> dict:
    try:
        text = repr(obj)
    except BaseException:  # a hostile __repr__ must not stop the worker
        text = "<repr failed>"
    return {"t": "odd", "type": type(obj).__name__[:100], "repr": text[:200], "why": why}


def encode(obj, _depth: int = 0, _budget: list | None = None):
    """``obj`` as tagged plain data (see the module docstring)."""
    budget = [MAX_NUMBERS] if _budget is None else _budget
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
    module = getattr(type(obj), "__module__", None) or ""
    if isinstance(obj, np.ndarray) or module.startswith(("sympy", "numpy")) \
            or "__array__" in dir(type(obj)):
        return _array(obj, budget)
    if type(obj) in (list, tuple):
        if len(obj) > budget[0]:
            return _odd(obj, "too large")
        budget[0] -= len(obj)
        return {"t": "list" if type(obj) is list else "tuple",
                "v": [encode(x, _depth + 1, budget) for x in obj]}
    if type(obj) is dict:
        if len(obj) > budget[0]:
            return _odd(obj, "too large")
        budget[0] -= len(obj)
        return {"t": "dict", "v": [[encode(k, _depth + 1, budget), encode(v, _depth + 1, budget)]
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


def _check(cond: bool, what: str) -> None:
    if not cond:
        raise WireError(what)


def decode(data):
    """Tagged plain data back into Python and numpy values; :class:`WireError` if malformed,
    whatever the malformation (the student's process writes these bytes: nothing it sends
    may raise anything else in the grader)."""
    try:
        return _decode(data, 0)
    except WireError:
        raise
    except Exception as exc:  # e.g. an unhashable tuple key, an absurd array
        raise WireError(f"malformed value ({type(exc).__name__})") from None


def _decode(data, _depth: int):
    _check(_depth <= MAX_DEPTH + 1, "nested too deeply")
    if data is None or type(data) in (bool, int, float, str):
        return data
    _check(type(data) is dict and type(data.get("t")) is str, f"unexpected {type(data).__name__}")
    tag, v = data["t"], data.get("v")
    if tag in ("list", "tuple"):
        _check(type(v) is list, "list without items")
        items = [_decode(x, _depth + 1) for x in v]
        return items if tag == "list" else tuple(items)
    if tag == "dict":
        _check(type(v) is list and all(type(p) is list and len(p) == 2 for p in v), "bad dict")
        out = {}
        for k, x in v:
            key = _decode(k, _depth + 1)
            _check(isinstance(key, str | int | float | bool | tuple) or key is None,
                   "unhashable dict key")
            out[key] = _decode(x, _depth + 1)
        return out
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
        return f"a {self.type} ({self.repr[:80]})"


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
