"""What a judged answer is, and how an answer is judged against a reference and the
mistakes a check recognises. Shared by the notebooks' exercises and the grader.

A :class:`Rule` judges one returned value:

1. it must be the right kind of thing (an array of the expected shape, finite);
2. it is right if it is close to the reference's answer or to an accepted alternative
   (``accept``: e.g. ``-q`` for a quaternion, the other elbow of an IK solution);
3. otherwise each :class:`Mistake` (the answer a classic mistake would give: the transpose,
   degrees, the other Euler sequence, ``[x, y, z, w]``...) is tried in order, and the first
   that matches names the mistake and tells the student what to look at.

A rule may instead give its own ``judge(args, got) -> Verdict`` (e.g. an IK answer is right
when its forward kinematics reaches the target).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

__all__ = ["Mistake", "MistakeKind", "Verdict", "RIGHT", "Rule", "as_numeric", "close", "fmt"]


@dataclass(frozen=True)
class Mistake:
    """A classic mistake: ``model(*args)`` is what an answer with it comes out as."""

    key: str
    message: str
    model: Callable


@dataclass(frozen=True)
class MistakeKind:
    """A mistake whose diagnosis reads the same wherever it is made; ``of(model)`` makes the
    :class:`Mistake` of one exercise or check."""

    key: str
    message: str

    def of(self, model, message: str | None = None) -> Mistake:
        """The mistake with this model; ``message`` replaces the usual diagnosis."""
        return Mistake(self.key, message or self.message, model)


@dataclass(frozen=True)
class Verdict:
    """One answer judged: ``ok``; else a ``key`` (``"wrong"``, ``"shape"``, a mistake's
    key, ``"unanswered"``...) and a ``message`` for the student."""

    ok: bool
    key: str = ""
    message: str = ""
    expected: object = None


RIGHT = Verdict(True)


def fmt(value, limit: int = 300) -> str:
    """A short, readable rendering of a case input or a value."""
    if isinstance(value, np.ndarray):
        text = np.array2string(value, precision=4, suppress_small=True, separator=", ",
                               max_line_width=200)
    elif isinstance(value, tuple | list):
        inner = ", ".join(fmt(v, limit) for v in value)
        text = f"({inner})" if isinstance(value, tuple) else f"[{inner}]"
    elif isinstance(value, float):
        text = f"{value:.6g}"
    elif isinstance(value, dict):
        text = "{" + ", ".join(f"{k!r}: {fmt(v, limit)}" for k, v in value.items()) + "}"
    else:
        text = repr(value)
    text = " ".join(text.split())
    return text if len(text) <= limit else text[:limit - 3] + "..."


def as_numeric(got, shape: tuple, what: str = "an array", *,
               returned: bool = True) -> tuple[np.ndarray | None, Verdict]:
    """``got`` as a float array of ``shape``, or ``None`` and the verdict saying why not.

    ``returned``: ``got`` is what a function returned (else: a value the student wrote).
    A value that describes itself (``kinlib_describe()``: the grader's stand-in for an
    object that is not plain data) is named by that description."""
    want = f"{what} of shape {shape}" if shape else "a number"
    was, has = ("returned", "returned") if returned else ("your answer is", "your answer has")
    if got is None:
        hint = ": is there a `return` at the end of your function?" if returned else ""
        return None, Verdict(False, "none", f"{was} None, expected {want}{hint}")
    describe = getattr(got, "kinlib_describe", None)
    if callable(describe):
        return None, Verdict(False, "type", f"{was} {describe()}, expected {want}")
    if isinstance(got, str | bool | dict):
        return None, Verdict(False, "type", f"{was} a {type(got).__name__}, expected {want}")
    try:
        a = np.asarray(got, dtype=float)
    except (TypeError, ValueError):
        return None, Verdict(False, "type", f"{was} {fmt(got, 80)}, which is not {want}")
    if a.shape != tuple(shape):
        if a.ndim == 2 and a.shape == tuple(shape)[::-1]:
            hint = "; that is the shape of the transpose: check rows against columns"
        elif a.size == int(np.prod(shape)) and a.size > 1:
            hint = f"; it has the right number of entries: reshape it to {shape}"
        else:
            hint = ""
        return None, Verdict(False, "shape", f"{has} shape {a.shape}, expected {want}{hint}")
    if not np.isfinite(a).all():
        return None, Verdict(False, "nan", f"{was.replace(' is', ' has')} NaN or infinity: "
                                           "look for a division by zero or the square root "
                                           "/ arccos of a number just outside its domain")
    return a, RIGHT


def close(a, b, atol: float) -> bool:
    """``|a − b| ≤ atol·(1 + |b|)`` entry-wise, with matching shapes."""
    try:
        a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    except (TypeError, ValueError):
        return False
    return a.shape == b.shape and bool(np.all(np.abs(a - b) <= atol * (1.0 + np.abs(b))))


_NOT_APPLICABLE = object()  # a mistake's model that raised on the case


def _model(m: Mistake, args: tuple):
    try:
        return m.model(*args)
    except Exception:  # a model that does not apply to this case
        return _NOT_APPLICABLE


def read_only(value):
    """``value`` with its arrays (nested in lists and tuples too) made read-only: what is
    shared by every answer judged on a case."""
    if isinstance(value, np.ndarray):
        value.setflags(write=False)
    elif isinstance(value, list | tuple):
        for v in value:
            read_only(v)
    return value


def once_per_case(memo: dict | None, key, compute):
    """``compute()``, or what it gave before for this case (``memo``: None, no memo)."""
    if memo is None:
        return compute()
    if key not in memo:
        memo[key] = read_only(compute())
    return memo[key]


@dataclass
class Rule:
    """How one returned value is judged: against ``reference(*args)`` and ``accept``, then
    the ``mistakes``; or by ``judge(args, got)`` alone."""

    reference: Callable | None = None
    mistakes: Sequence[Mistake] = ()
    accept: Callable | None = None  # args -> list of other right answers
    judge: Callable | None = None  # (args, got) -> Verdict, instead of the default
    atol: float = 1e-6
    what: str = "an array"  # how the expected value is named in a shape message
    returned: bool = True  # the value a function returned (else: a value written down)

    def verdict(self, args: tuple, got, memo: dict | None = None) -> Verdict:
        """``got`` judged for the case ``args``. ``memo``: a dict kept with the case (the
        grader's, shared by every submission judged on it): what does not depend on the
        answer (the reference's answer, the accepted ones, each mistake's) is computed
        once per case instead of once per answer, and kept read-only."""
        if self.judge is not None:
            return self.judge(args, got)
        expected = once_per_case(memo, "expected",
                         lambda: np.asarray(self.reference(*args), dtype=float))
        a, bad = as_numeric(got, expected.shape, self.what, returned=self.returned)
        if a is None:
            return Verdict(bad.ok, bad.key, bad.message, expected)
        right = [expected] + (once_per_case(memo, "accept",
                                            lambda: list(self.accept(*args)))
                              if self.accept else [])
        if any(close(a, r, self.atol) for r in right):
            return RIGHT
        for k, m in enumerate(self.mistakes):
            wrong = once_per_case(memo, ("mistake", k), lambda m=m: _model(m, args))
            if wrong is _NOT_APPLICABLE:
                continue
            if close(a, wrong, self.atol) and not close(wrong, expected, self.atol):
                return Verdict(False, m.key, m.message, expected)
        err = float(np.max(np.abs(a - expected)))
        who = "" if self.returned else "your answer "
        return Verdict(False, "wrong", f"{who}differs from the right answer by up to "
                                       f"{err:.3g}", expected)
