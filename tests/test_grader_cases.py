"""Which cases are graded and what a right answer earns: hidden cases from the instructor's
secret, and no credit for "no path" said everywhere."""

import json
import subprocess
import sys

import numpy as np
import pytest
from grading_helpers import ROOT, by_function, solution_code, write_notebook

from kinlib.errors import KinlibError
from kinlib.grade import grade, load_assignment
from kinlib.grade._grader import cases_seed
from kinlib.grade.assignments import planning as P


# -- hidden cases ---------------------------------------------------------------------------
def test_a_secret_gives_other_cases_than_the_public_seed():
    spec = load_assignment("02_forward_kinematics")
    for check in spec.checks:
        public = check.make_cases(0)
        hidden = check.make_cases(cases_seed("instructor's secret", spec.name))
        again = check.make_cases(cases_seed("instructor's secret\n", spec.name))  # a file's
        assert len(public) == len(hidden)                                          # newline
        assert repr(hidden) == repr(again)
        assert repr(public) != repr(hidden), check.function
    assert cases_seed("a", "01_rotations") != cases_seed("b", "01_rotations")
    with pytest.raises(KinlibError, match="non-empty secret"):
        cases_seed("  \n", "01_rotations")


def test_the_secret_from_a_file_or_the_environment(tmp_path):
    sub = tmp_path / "01_rotations.ipynb"
    sub.write_text((ROOT / "source" / "01_rotations.ipynb").read_text())
    secret = tmp_path / "secret.txt"
    secret.write_text("s3cret\n")
    base = [sys.executable, "-m", "kinlib.grade", "--json", "--no-write", str(sub)]

    def run(*extra, env=None):
        import os

        return subprocess.run(base + list(extra), capture_output=True, text=True, timeout=300,
                              env={**os.environ, **(env or {})})

    by_file = run("--secret-file", str(secret))
    by_env = run(env={"KINLIB_GRADE_SECRET": "s3cret"})
    for out in (by_file, by_env):
        assert out.returncode == 0, out.stderr
        row = json.loads(out.stdout)
        assert row["cases"] == "secret" and row["score"] == row["max_score"]
        assert "s3cret" not in out.stdout
    both = run("--secret-file", str(secret), env={"KINLIB_GRADE_SECRET": "x"})
    assert both.returncode == 2 and "not both" in both.stderr
    seed_too = run("--secret-file", str(secret), "--seed", "3")
    assert seed_too.returncode == 2 and "give one of them" in seed_too.stderr


# -- credit that means something ------------------------------------------------------------
def no_path_cases():
    """How many of assignment 04's A* cases have no path, by the grader's plain Dijkstra
    (not the A* the reference uses)."""
    check = next(c for c in load_assignment("04_planning").checks if c.function == "astar_2r")
    cases = check.make_cases(0)
    count = 0
    for free, start, goal, l1, l2, metric in cases:
        costs = P._costs(*P._key(free.shape, l1, l2, metric))
        if not (free[start] and free[goal]) or np.isinf(P._dijkstra(free, costs, start, goal)):
            count += 1
    return count, len(cases)


def test_saying_no_path_everywhere_earns_nothing(tmp_path):
    trivial, total = no_path_cases()
    assert 4 <= trivial < total / 2
    sub = write_notebook(tmp_path / "04_planning.ipynb",
                         "def astar_2r(free, start, goal, l1, l2, metric):\n    return None",
                         assignment="04_planning")
    astar = by_function(grade(sub))["astar_2r"]
    assert astar["passed"] == trivial  # the right answers are still counted as right ...
    assert astar["score"] == 0  # ... but earn nothing (it was 20 * 9 / 56 = 3.21 before)
    (note,) = [d for d in astar["diagnoses"] if d["key"] == "trivial"]
    assert note["count"] == trivial and "0%" in note["message"]


def test_right_paths_earn_the_no_path_cases_back(tmp_path):
    trivial, total = no_path_cases()
    code = solution_code("04_planning")
    right = write_notebook(tmp_path / "right.ipynb", code, assignment="04_planning")
    assert by_function(grade(right))["astar_2r"]["score"] == 20
    # every third path is lost (None): between 50 % and 75 % of the paths right
    lossy = write_notebook(tmp_path / "lossy.ipynb", code, "_right, _calls = astar_2r, [0]\n"
                           "def astar_2r(*args):\n    path = _right(*args)\n"
                           "    _calls[0] += 1\n"
                           "    return None if path is not None and _calls[0] % 3 == 0 else path",
                           assignment="04_planning")
    astar = by_function(grade(lossy))["astar_2r"]
    paths_right = astar["passed"] - trivial
    rate = paths_right / (total - trivial)
    assert 0.5 < rate < 0.75, rate
    weight = (rate - 0.5) / 0.25  # the rule the report states
    assert astar["score"] == pytest.approx(20 * (paths_right + weight * trivial) / total, abs=0.01)
    assert paths_right * 20 / total < astar["score"] < astar["passed"] * 20 / total
