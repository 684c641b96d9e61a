"""kinlib.grade._trusted.judge_functions: the assignments' own mistake tables judged in
this process (test_grader_orientation.py shows it gives what the sandbox gives)."""

import pytest
from grading_helpers import _sandbox_legal

from kinlib.grade import load_assignment
from kinlib.grade._trusted import judge_functions


def test_nothing_defined_is_missing_everywhere_and_marked():
    result = judge_functions({"rotz": 3}, "01_rotations")
    spec = load_assignment("01_rotations")
    assert result["graded"] and result["score"] == 0 and result["max_score"] == spec.max_score
    assert result["sandbox"] is None and "without the sandbox" in result["warning"]
    assert [c["function"] for c in result["checks"]] == [c.function for c in spec.checks]
    keys = {d["key"] for c in result["checks"] for d in c["diagnoses"]}
    assert keys == {"missing"}, keys
    rotz = next(c for c in result["checks"] if c["function"] == "rotz")
    assert "a int, not a function" in rotz["diagnoses"][0]["message"]


def test_an_exception_is_reported_like_the_student_process_does():
    def rotz(theta):
        raise ValueError("no")
    rotz_check = next(c for c in judge_functions({"rotz": rotz}, "01_rotations")["checks"]
                      if c["function"] == "rotz")
    assert rotz_check["passed"] == 0
    assert rotz_check["diagnoses"][0]["message"].startswith("raised ValueError: no")


@pytest.mark.parametrize("source", ["import scipy.linalg", "from kinlib import rotz",
                                    "import numpy as np\nfrom roboticstoolbox import ETS"])
def test_a_test_submission_may_not_import_what_the_sandbox_blocks(source):
    with pytest.raises(AssertionError, match="the sandbox blocks"):
        _sandbox_legal(source, "m0.ipynb, cell 0")
    _sandbox_legal("import numpy as np\nimport sympy as sp", "m0.ipynb, cell 0")


def test_a_class_shares_its_cases_and_each_case_is_worked_out_once():
    """Submissions judged on the same seed share the cases (read-only) and, per case, the
    reference's answer and each mistake's: counted here with a check of our own."""
    import numpy as np

    from kinlib.grade._checks import Check, Mistake, shared_cases
    from kinlib.grade._grader import _judge

    calls = {"reference": 0, "transposed": 0}

    def reference(R):
        calls["reference"] += 1
        return R @ R

    def transposed(R):
        calls["transposed"] += 1
        return (R @ R).T

    check = Check("square", 1, "R²", lambda rng: [(rng.normal(size=(3, 3)),) for _ in range(5)],
                  reference, [Mistake("transposed", "transposed", transposed)])
    cases, memos = shared_cases("test_shared", check, 7)
    assert shared_cases("test_shared", check, 7)[0] is cases
    assert not cases[0][0].flags.writeable  # no submission's judging can change a case
    answers = [lambda R: R @ R, lambda R: (R @ R).T, lambda R: R, lambda R: R @ R]
    verdicts = [[_judge(check, c, "value", f(*c), m).key or "right"
                 for c, m in zip(cases, memos, strict=True)] for f in answers]
    assert verdicts == [["right"] * 5, ["transposed"] * 5, ["wrong"] * 5, ["right"] * 5]
    assert calls == {"reference": 5, "transposed": 5}  # not once per answer judged
    assert not memos[0]["expected"].flags.writeable
    fresh = [_judge(check, c, "value", (c[0] @ c[0]).T).key for c in cases]  # no memo
    assert fresh == ["transposed"] * 5 and calls == {"reference": 10, "transposed": 10}
    assert np.allclose(memos[0]["expected"], cases[0][0] @ cases[0][0])
