"""The notebooks are committed without outputs (students run them; diffs stay readable),
and each one states its learning goals, ends with what the student can now do, and then the
instructor's checks of its own results, labelled as such."""

import json
from pathlib import Path

import pytest

ROOT = Path(__file__).parent.parent
INSTRUCTOR = sorted((ROOT / "instructor").glob("*.ipynb"))
STUDENT = sorted((ROOT / "notebooks").glob("*.ipynb"))
ASSIGNMENTS = sorted((ROOT / "assignments").glob("*/*.ipynb"))


def test_there_are_notebooks():
    assert INSTRUCTOR and STUDENT, "instructor/ and notebooks/ hold the course"


@pytest.mark.parametrize("path", INSTRUCTOR + STUDENT + ASSIGNMENTS,
                         ids=lambda p: f"{p.parent.name}/{p.name}")
def test_committed_without_outputs(path):
    nb = json.loads(path.read_text())
    for i, cell in enumerate(nb["cells"]):
        if cell["cell_type"] == "code":
            assert not cell.get("outputs"), f"{path.name} cell {i} has outputs"
            assert cell.get("execution_count") is None, f"{path.name} cell {i} was run"


@pytest.mark.parametrize("path", INSTRUCTOR, ids=lambda p: p.name)
def test_goals_what_you_can_do_and_the_instructors_checks(path):
    nb = json.loads(path.read_text())
    cells = [("".join(c["source"]), c["cell_type"]) for c in nb["cells"]]
    text = "".join(s for s, kind in cells if kind == "markdown")
    assert "Learning goals" in text
    assert cells[-1][1] == "code" and "assert" in cells[-1][0], "the last cell holds the checks"
    assert cells[-2][1] == "markdown" and cells[-2][0].startswith(
        "## Checks of this notebook's results (for instructors)"), cells[-2][0][:80]
    assert cells[-3][1] == "markdown" and cells[-3][0].startswith("## What you can do now")
