"""An exercise of a notebook and what its check cell shows.

An :class:`Exercise` knows its answer's :class:`~kinlib.check.Rule`. A value answer (a
number, a matrix, a sympy expression, a choice) is judged once; a function answer is called
on every case and each return value judged. Nothing the student writes makes the check
raise: a missing answer (``...``, or a function still raising ``NotImplementedError``) is
"not answered yet", and a function that raises is a wrong answer naming the error.
"""

from __future__ import annotations

import html
import re
from collections import Counter
from dataclasses import dataclass, field

from ._verdict import Rule, Verdict, fmt

__all__ = ["Exercise", "Feedback", "KINDS", "MIME", "UNANSWERED", "results"]

#: the kinds of exercise: predict (then watch), derive (with sympy), compute, implement
KINDS = ("predict", "derive", "compute", "implement")
MIME = "application/vnd.kinlib.check+json"
UNANSWERED = "unanswered"


@dataclass(frozen=True)
class Exercise:
    """Exercise ``id`` (``"03.2"``: notebook 03, exercise 2) of kind ``kind``.

    ``rule`` judges an answer; for a function (``cases`` not empty) it judges the return
    value of each case ``answer(*case)``. ``on_error(case, error text)`` may add a hint
    when the student's function raises. ``diagnoses``: the keys of the mistakes this
    exercise names (each is produced by a real wrong answer in the course's tests).
    ``explain``: what the check adds once the answer is right (the discussion of the
    answer, which the student edition does not show before)."""

    id: str
    kind: str
    title: str
    rule: Rule
    cases: tuple = ()
    placeholder: str = "the `...` in the cell above"
    on_error: object = None
    diagnoses: tuple = ()
    explain: str = ""

    def __post_init__(self):
        if self.kind not in KINDS:
            raise ValueError(f"exercise {self.id}: kind must be one of {KINDS}, got {self.kind!r}")
        object.__setattr__(self, "cases", tuple(tuple(c) for c in self.cases))

    @property
    def notebook(self) -> str:
        return self.id.split(".")[0]

    def judge(self, answer) -> Verdict:
        verdict = self._judge(answer)
        if verdict.ok and self.explain and not verdict.message:
            return Verdict(True, "", self.explain)
        return verdict

    def _judge(self, answer) -> Verdict:
        if answer is Ellipsis:
            return Verdict(False, UNANSWERED, f"write your answer in place of {self.placeholder}, "
                                              "run that cell, then this one")
        if not self.cases:
            return _safe(self.rule, (), answer)
        if not callable(answer):
            return Verdict(False, "type", f"expected your function, got {fmt(answer, 60)}")
        verdicts = []
        for case in self.cases:
            try:
                got = answer(*case)
            except NotImplementedError:
                return Verdict(False, UNANSWERED, "replace `raise NotImplementedError` in "
                                                  "your function by your code, run that "
                                                  "cell, then this one")
            except Exception as exc:  # the student's code: any error is feedback
                text = f"{type(exc).__name__}: {exc}"[:300]
                hint = self.on_error(case, text) if callable(self.on_error) else None
                return Verdict(False, "raised", f"your function raised {text} for the input "
                                                f"{fmt(case, 160)}" + (f". {hint}" if hint else ""))
            v = _safe(self.rule, case, got)
            if not v.ok:
                verdicts.append((case, got, v))
        if not verdicts:
            return Verdict(True)
        key = Counter(v.key for _, _, v in verdicts).most_common(1)[0][0]
        case, got, v = next(x for x in verdicts if x[2].key == key)
        return Verdict(False, key, f"{v.message} — wrong in {len(verdicts)} of "
                                   f"{len(self.cases)} cases, e.g. for the input "
                                   f"{fmt(case, 160)} you returned {fmt(got, 120)}"
                                   + ("" if v.expected is None else
                                      f", the right answer is {fmt(v.expected, 120)}"),
                       v.expected)


def _safe(rule: Rule, args: tuple, got) -> Verdict:
    try:
        return rule.verdict(args, got)
    except Exception as exc:  # an odd value must not break the check
        return Verdict(False, "type", f"your answer could not be checked "
                                      f"({type(exc).__name__}: {str(exc)[:120]}): is it "
                                      "the kind of thing the exercise asks for?")


_STYLE = {True: ("#2e7d32", "#e8f5e9", "✔", "right"),
          False: ("#c62828", "#ffebee", "✘", "not right yet"),
          UNANSWERED: ("#616161", "#f5f5f5", "○", "not answered yet")}


@dataclass(frozen=True)
class Feedback:
    """What a check cell shows: right / not right yet (and the likely mistake) / not
    answered yet. ``status`` is ``"right"``, ``"wrong"`` or ``"unanswered"``."""

    exercise: Exercise
    verdict: Verdict = field(repr=False)

    @property
    def status(self) -> str:
        if self.verdict.ok:
            return "right"
        return UNANSWERED if self.verdict.key == UNANSWERED else "wrong"

    @property
    def key(self) -> str:
        """The diagnosis: a mistake's key, ``"wrong"``, ``"unanswered"``; ``""`` if right."""
        return self.verdict.key

    @property
    def message(self) -> str:
        return self.verdict.message

    def _parts(self):
        style = _STYLE[UNANSWERED if self.status == UNANSWERED else self.verdict.ok]
        head = f"Exercise {self.exercise.id} ({self.exercise.kind}): {style[3]}"
        return style, head

    def __str__(self) -> str:
        _, head = self._parts()
        return head + (f": {self.message}" if self.message else ".")

    def __repr__(self) -> str:
        return str(self)

    def _repr_html_(self) -> str:
        (color, background, icon, _), head = self._parts()
        text = re.sub(r"`([^`]+)`", r"<code>\1</code>", html.escape(self.message))
        body = f" — {text}" if self.message else ""
        return (f'<div class="kl-check kl-check-{self.status}" style="border-left: 4px solid '
                f'{color}; background: {background}; padding: 0.4em 0.8em; margin: 0.2em 0;">'
                f'<b style="color: {color}">{icon} {html.escape(head)}</b>{body}</div>')

    def to_json(self) -> dict:
        return {"exercise": self.exercise.id, "kind": self.exercise.kind,
                "status": self.status, "key": self.key, "message": self.message}

    def _repr_mimebundle_(self, include=None, exclude=None):
        return {"text/plain": str(self), "text/html": self._repr_html_(),
                MIME: self.to_json()}


def results(notebook) -> list[dict]:
    """The check results saved in an executed notebook (a dict or nbformat node), or among
    a list of cell outputs, in order: ``{"exercise", "kind", "status", "key", "message"}``."""
    if isinstance(notebook, list | tuple):
        outputs = notebook
    else:
        outputs = [o for c in notebook["cells"] for o in c.get("outputs", ())]
    return [o["data"][MIME] for o in outputs if MIME in (o.get("data") or {})]
