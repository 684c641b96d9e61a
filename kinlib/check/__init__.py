"""Checks that tell a student what they got wrong: the notebooks' exercises and the
diagnoses they share with the grader.

In a notebook::

    from kinlib.check import check
    R_try = ...                      # the student's answer
    check("01.1", R_try)             # right / not right yet, and why / not answered yet

An exercise's id is ``"NN.k"``: exercise ``k`` of notebook ``NN``. :func:`check` never
raises because of an answer: whatever the student wrote (``...`` still there, a wrong
shape, NaN, a function that raises) becomes feedback. The result shows itself in the
notebook (HTML, plain text, and the JSON ``application/vnd.kinlib.check+json`` that the
course's tests read).

The pieces the grader uses too: :class:`Rule` (judge a value against a reference, its
accepted alternatives and the known mistakes), :class:`Verdict`, :class:`Mistake`,
:class:`MistakeKind`, the catalogue :mod:`kinlib.check.mistakes` and the judges of
:mod:`kinlib.check.judges`.
"""

from __future__ import annotations

from ._exercise import KINDS, MIME, UNANSWERED, Exercise, Feedback, results
from ._verdict import RIGHT, Mistake, MistakeKind, Rule, Verdict, as_numeric, close, fmt

__all__ = ["check", "exercise", "exercises", "results", "Exercise", "Feedback", "KINDS", "MIME",
           "UNANSWERED", "Rule", "Verdict", "RIGHT", "Mistake", "MistakeKind", "as_numeric",
           "close", "fmt"]


def exercise(exercise_id: str) -> Exercise:
    """The exercise ``"NN.k"``."""
    from .notebooks import find

    return find(exercise_id)


def exercises(notebook: str | None = None) -> list[Exercise]:
    """Every exercise of the course, in order, or of one notebook (``"03"``)."""
    from .notebooks import every, of_notebook

    return every() if notebook is None else of_notebook(notebook)


def check(exercise_id: str, answer) -> Feedback:
    """Judge ``answer`` to exercise ``exercise_id``: a :class:`Feedback` that shows itself."""
    ex = exercise(exercise_id)
    return Feedback(ex, ex.judge(answer))
