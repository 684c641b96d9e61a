"""The notebooks' exercise checks tell a student what is probably wrong.

For every exercise, real wrong answers (tests/wrong_answers/: what a student would write,
not the mistake models of kinlib.check) get the diagnosis they must get; every mistake an
exercise names is produced by one of them, and so is every kind of the catalogue
(kinlib.check.mistakes). Whatever a student writes, a check never raises: ``...`` is "not
answered yet", odd values and functions that raise are "not right yet"."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from wrong_answers import WRONG

from kinlib import KinlibError
from kinlib.check import check, exercise, exercises
from kinlib.check.mistakes import CATALOGUE

CASES = [(ex_id, k, answer, key) for ex_id, pairs in WRONG.items()
         for k, (answer, key) in enumerate(pairs)]


@pytest.mark.parametrize("ex_id, k, answer, key", CASES,
                         ids=[f"{c[0]}-{c[3]}-{c[1]}" for c in CASES])
def test_a_wrong_answer_gets_its_diagnosis(ex_id, k, answer, key):
    feedback = check(ex_id, answer)
    assert feedback.status == "wrong" and feedback.key == key, str(feedback)
    assert feedback.message and "Exercise " + ex_id in str(feedback)


def test_every_exercise_has_wrong_answers_for_every_mistake_it_names():
    for ex in exercises():
        tested = {key for _, key in WRONG.get(ex.id, ())}
        assert tested, f"{ex.id}: no wrong answer is tested"
        missing = set(ex.diagnoses) - tested
        assert not missing, f"{ex.id}: no real wrong answer produces {sorted(missing)}"


def test_every_kind_of_mistake_is_produced_by_a_real_wrong_answer():
    tested = {key for pairs in WRONG.values() for _, key in pairs}
    assert set(CATALOGUE) <= tested, sorted(set(CATALOGUE) - tested)


ODD = [None, "x", 3.5, np.nan, [1, 2], {"a": 1}, object(), sp.Symbol("zeta"), np.eye(7)]


@pytest.mark.parametrize("ex_id", [e.id for e in exercises()])
def test_a_check_never_raises(ex_id):
    ex = exercise(ex_id)
    assert check(ex_id, ...).status == "unanswered"
    for odd in ODD:
        assert check(ex_id, odd).status == "wrong", (ex_id, odd)
    if ex.cases:  # a function: still blank, raising, returning nothing
        def blank(*args):
            raise NotImplementedError

        def broken(*args):
            return 1 / 0

        assert check(ex_id, blank).status == "unanswered"
        feedback = check(ex_id, broken)
        assert feedback.key == "raised" and "ZeroDivisionError" in feedback.message
        assert check(ex_id, lambda *args: None).status == "wrong"


def test_the_feedback_shows_itself_in_three_forms():
    from kinlib.check import MIME

    right = check("01.3", 6)
    bundle = right._repr_mimebundle_()
    assert set(bundle) == {"text/plain", "text/html", MIME}
    assert bundle[MIME] == {"exercise": "01.3", "kind": "predict", "status": "right",
                            "key": "", "message": ""}
    assert "✔" in bundle["text/html"] and str(right) == "Exercise 01.3 (predict): right."
    blank = check("01.3", ...)._repr_mimebundle_()
    assert blank[MIME]["status"] == "unanswered" and "<code>...</code>" in blank["text/html"]
    wrong = check("01.3", 9)
    assert "&lt;" not in wrong._repr_html_() or "<" in wrong.message


def test_unknown_exercises_are_a_clear_error():
    with pytest.raises(KinlibError, match=r"notebook 01 has no exercise 01\.99; its exercises"):
        check("01.99", 1)
    with pytest.raises(KinlibError, match=r"expected an exercise id like '03\.2'"):
        check("1.1", 1)
