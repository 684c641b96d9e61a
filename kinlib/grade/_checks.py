"""What a grader check is: a student function, its cases, kinlib's reference and the
mistakes it recognises.

A :class:`Check` names a function the student writes, builds its cases (fixed ones and
seeded random ones), and judges each returned value in the grader's own process with its
:class:`~kinlib.check.Rule` (the same judging, mistakes and diagnoses as the notebooks'
exercises: :mod:`kinlib.check`).
"""

from __future__ import annotations

import threading
import zlib
from collections import OrderedDict
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import numpy as np

from ..check import RIGHT, Mistake, Rule, Verdict, as_numeric, close, fmt
from ..check._verdict import once_per_case, read_only

__all__ = ["Mistake", "Verdict", "Check", "Assignment", "RIGHT", "as_numeric", "close", "fmt",
           "once_per_case", "shared_cases"]


@dataclass
class Check:
    """One student function, its cases and how a returned value is judged: by the
    :class:`~kinlib.check.Rule` made of ``reference``, ``mistakes``, ``accept``, ``judge``
    and ``atol``."""

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
    # cases whose right answer a function that does nothing could give ("no path"): args ->
    # bool. Right answers to them earn credit only when the other cases are mostly right
    # (none below 50 % of those right, in full from 75 %); ``trivial`` names them.
    is_trivial: Callable | None = None
    trivial: str = "to the trivial cases"

    @property
    def rule(self) -> Rule:
        return Rule(self.reference, self.mistakes, self.accept, self.judge, self.atol)

    def make_cases(self, seed: int) -> list[tuple]:
        rng = np.random.default_rng([seed, zlib.crc32(self.function.encode())])
        return [tuple(c) for c in self.cases(rng)]

    def verdict(self, args: tuple, got, memo: dict | None = None) -> Verdict:
        return self.rule.verdict(args, got, memo)


@dataclass
class Assignment:
    """An assignment: its name (the notebook's stem), title and checks."""

    name: str
    title: str
    checks: list[Check] = field(default_factory=list)

    @property
    def max_score(self) -> float:
        return float(sum(c.points for c in self.checks))


#: (assignment, function, seed) → the check's cases and a memo per case, most recent last
_SHARED: OrderedDict[tuple, tuple[list[tuple], list[dict]]] = OrderedDict()
_SHARED_MAX = 64
_shared_lock = threading.Lock()


def shared_cases(assignment: str, check: Check, seed: int) -> tuple[list[tuple], list[dict]]:
    """``check.make_cases(seed)`` made once in this process for every submission judged on
    them (a class's submissions share the cases of their seed), their arrays read-only, and
    a memo per case in which the check's rule keeps what does not depend on the answer
    (the reference's answer, the accepted ones, each mistake's): judging a class then costs
    one reference and one run of each mistake per case, not one per submission."""
    key = (assignment, check.function, seed)
    with _shared_lock:
        found = _SHARED.get(key)
        if found is not None:
            _SHARED.move_to_end(key)
            return found
    cases = check.make_cases(seed)
    read_only(cases)
    made = (cases, [{} for _ in cases])
    with _shared_lock:
        found = _SHARED.setdefault(key, made)
        while len(_SHARED) > _SHARED_MAX:
            _SHARED.popitem(last=False)
    return found
