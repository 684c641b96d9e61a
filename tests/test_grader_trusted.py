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
