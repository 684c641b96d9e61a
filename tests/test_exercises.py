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
    explain = exercise("01.3").explain
    assert bundle[MIME] == {"exercise": "01.3", "kind": "predict", "status": "right",
                            "key": "", "message": explain}
    assert "✔" in bundle["text/html"]
    assert str(right) == "Exercise 01.3 (predict): right" + (f": {explain}" if explain else ".")
    blank = check("01.3", ...)._repr_mimebundle_()
    assert blank[MIME]["status"] == "unanswered" and "<code>...</code>" in blank["text/html"]
    wrong = check("01.3", 9)
    assert "&lt;" not in wrong._repr_html_() or "<" in wrong.message


def test_unknown_exercises_are_a_clear_error():
    with pytest.raises(KinlibError, match=r"notebook 01 has no exercise 01\.99; its exercises"):
        check("01.99", 1)
    with pytest.raises(KinlibError, match=r"expected an exercise id like '03\.2'"):
        check("1.1", 1)


def test_a_derivation_is_decided_exactly_whatever_its_form():
    """Symbols are matched by name (assumptions aside); an unsimplified answer whose extra
    symbol cancels is right; a foreign symbol that stays is named."""
    import kinlib as kl

    theta, gamma = sp.Symbol("theta", real=True), sp.Symbol("gamma", real=True)
    plain = sp.Symbol("theta")  # no real=True: another sympy symbol of the same name
    assert check("01.2", kl.roty(plain)).status == "right"
    assert check("01.2", kl.roty(theta) * (sp.sin(gamma) ** 2 + sp.cos(gamma) ** 2)).status \
        == "right"
    stays = check("01.2", kl.roty(theta) * sp.cos(gamma))
    assert stays.key == "symbols" and "gamma" in stays.message
    half = kl.roty(theta).subs(sp.cos(theta), 1 - 2 * sp.sin(theta / 2) ** 2)  # half angles
    assert half != kl.roty(theta) and check("01.2", half).status == "right"


def test_a_wrong_derivation_is_shown_at_a_point_on_the_unit_sphere():
    """With unit=[kx, ky, kz] (one unit vector, as sym_equal reads it), the message's point
    has |k| = 1, where the right answer is defined."""
    import re

    from kinlib.check import Rule
    from kinlib.check._symbolic import expression_judge

    k = sp.Matrix(sp.symbols("k_x k_y k_z", real=True))
    b = sp.Matrix(sp.symbols("b_x b_y b_z", real=True))
    judge = Rule(judge=expression_judge(lambda: -k.cross(k.cross(b)), unit=list(k)))
    verdict = judge.verdict((), b)  # b, not b⊥
    assert verdict.key == "wrong"
    values = dict(re.findall(r"(k_[xyz]) = (-?[0-9.e-]+)", verdict.message))
    assert abs(sum(float(v) ** 2 for v in values.values()) - 1) < 1e-2, verdict.message
