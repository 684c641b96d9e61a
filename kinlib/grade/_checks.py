"""What a check is: a student function, its cases, kinlib's reference and the mistakes
the grader recognises.

A :class:`Check` names a function the student writes, builds its cases (fixed ones and
seeded random ones), and judges each returned value in the grader's own process:

1. the value must be the right kind of thing (an array of the expected shape, finite);
2. it is right if it is close to the reference's answer or to an accepted alternative
   (``accept``: e.g. ``-q`` for a quaternion, the other elbow of an IK solution);
3. otherwise each :class:`Mistake` model (the answer a classic mistake would give: the
   transpose, degrees, the other Euler sequence, ``[x, y, z, w]``...) is tried in order,
   and the first that matches names the mistake and tells the student what to look at.

A check may instead give its own ``judge(args, got) -> Verdict`` (e.g. an IK answer is
right when its forward kinematics reaches the target).
"""

from __future__ import annotations

import zlib
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import numpy as np

from ._wire import Odd

__all__ = ["Mistake", "Verdict", "Check", "Assignment", "as_numeric", "close", "fmt"]


@dataclass(frozen=True)
class Mistake:
    """A classic mistake: ``model(*args)`` is what an implementation with it returns."""

    key: str
    message: str
    model: Callable


@dataclass(frozen=True)
class Verdict:
    """One case judged: ``ok``; else a ``key`` ("wrong", "shape", a mistake's key...) and
    a ``message`` for the student."""

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


def as_numeric(got, shape: tuple, what: str = "an array") -> tuple[np.ndarray | None, Verdict]:
    """``got`` as a float array of ``shape``, or ``None`` and the verdict saying why not."""
    want = f"{what} of shape {shape}" if shape else "a number"
    if got is None:
        return None, Verdict(False, "none", f"returned None, expected {want}: is there a "
                                            "`return` at the end of your function?")
    if isinstance(got, Odd):
        return None, Verdict(False, "type", f"returned a {got.type} ({got.repr[:80]}), "
                                            f"expected {want}")
    if isinstance(got, str | bool | dict):
        return None, Verdict(False, "type", f"returned a {type(got).__name__}, expected {want}")
    try:
        a = np.asarray(got, dtype=float)
    except (TypeError, ValueError):
        return None, Verdict(False, "type", f"returned {fmt(got, 80)}, which is not {want}")
    if a.shape != tuple(shape):
        if a.ndim == 2 and a.shape == tuple(shape)[::-1]:
            hint = "; that is the shape of the transpose: check rows against columns"
        elif a.size == int(np.prod(shape)) and a.size > 1:
            hint = f"; it has the right number of entries: reshape it to {shape}"
        else:
            hint = ""
        return None, Verdict(False, "shape", f"returned shape {a.shape}, expected {want}{hint}")
    if not np.isfinite(a).all():
        return None, Verdict(False, "nan", "returned NaN or infinity: look for a division "
                                           "by zero or the square root / arccos of a number "
                                           "just outside its domain")
    return a, RIGHT


def close(a, b, atol: float) -> bool:
    """``|a − b| ≤ atol·(1 + |b|)`` entry-wise, with matching shapes."""
    try:
        a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    except (TypeError, ValueError):
        return False
    return a.shape == b.shape and bool(np.all(np.abs(a - b) <= atol * (1.0 + np.abs(b))))


@dataclass
class Check:
    """One student function, its cases and how a returned value is judged."""

    function: str
    points: float
    title: str
    cases: Callable[[np.random.Generator], list[tuple]]
    reference: Callable | None = None
    mistakes: Sequence[Mistake] = ()
    accept: Callable | None = None  # args -> list of other right answers
    judge: Callable | None = None  # (args, got) -> Verdict, instead of the default
    atol: float = 1e-6
    time_limit: float = 5.0  # seconds per case
    on_error: Callable | None = None  # (args, error text) -> a hint for the student, or None

    def make_cases(self, seed: int) -> list[tuple]:
        rng = np.random.default_rng([seed, zlib.crc32(self.function.encode())])
        return [tuple(c) for c in self.cases(rng)]

    def verdict(self, args: tuple, got) -> Verdict:
        if self.judge is not None:
            return self.judge(args, got)
        expected = np.asarray(self.reference(*args), dtype=float)
        a, bad = as_numeric(got, expected.shape)
        if a is None:
            return Verdict(bad.ok, bad.key, bad.message, expected)
        right = [expected] + (list(self.accept(*args)) if self.accept else [])
        if any(close(a, r, self.atol) for r in right):
            return RIGHT
        for m in self.mistakes:
            try:
                wrong = m.model(*args)
            except Exception:  # a model that does not apply to this case
                continue
            if close(a, wrong, self.atol) and not close(wrong, expected, self.atol):
                return Verdict(False, m.key, m.message, expected)
        err = float(np.max(np.abs(a - expected)))
        return Verdict(False, "wrong", f"differs from the right answer by up to {err:.3g}",
                       expected)


@dataclass
class Assignment:
    """An assignment: its name (the notebook's stem), title and checks."""

    name: str
    title: str
    checks: list[Check] = field(default_factory=list)

    @property
    def max_score(self) -> float:
        return float(sum(c.points for c in self.checks))
