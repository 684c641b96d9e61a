"""The course's two editions: ``instructor/`` (the notebooks with every exercise's solution
between solution markers) and ``notebooks/`` (the student edition, generated from it).

Read statically here: the student edition is current and holds no solution; every
exercise of ``kinlib.check`` has its heading, its answer cell and its check cell, in order;
each notebook has at least three exercises of at least two kinds, the course at least 40;
and no cell depends on a student's answer, so the student edition with every exercise blank
runs top to bottom. (That the instructor edition's checks all say "right" is checked as
nbval runs it, in ../conftest.py; that the student edition runs and every check says "not
answered yet" is checked in JupyterLab, in test_lab.py.)
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

import nbformat
import pytest

from kinlib.assign import BEGIN, END, SOLUTION_TAG, assigned_names, used_names
from kinlib.assign import main as assign_main
from kinlib.check import KINDS, exercises

ROOT = Path(__file__).resolve().parents[1]
INSTRUCTOR, STUDENT = ROOT / "instructor", ROOT / "notebooks"
NAMES = sorted(p.stem for p in INSTRUCTOR.glob("[0-9][0-9]_*.ipynb"))
HEADING = re.compile(r"^###\s+Exercise\s+(\d\d\.\d+)\s+·\s+(\w+)\s*$", re.M)


def read(folder: Path, name: str):
    return nbformat.read(folder / f"{name}.ipynb", as_version=4)


def check_call(source: str):
    """``(id, answer name)`` if the cell is exactly ``check("NN.k", name)``, else None."""
    try:
        body = ast.parse(source).body
    except SyntaxError:
        return None
    if len(body) != 1 or not isinstance(body[0], ast.Expr):
        return None
    call = body[0].value
    if not (isinstance(call, ast.Call) and isinstance(call.func, ast.Name)
            and call.func.id == "check"):
        return None
    args = call.args
    assert len(args) == 2 and isinstance(args[0], ast.Constant) and isinstance(
        args[1], ast.Name) and not call.keywords, f"a check cell is check('NN.k', name): {source}"
    return args[0].value, args[1].id


def exercise_cells(nb) -> list[tuple[str, str, int, int]]:
    """``(id, answer name, answer cell, check cell)`` for each check cell, in order."""
    code = [i for i, c in enumerate(nb.cells) if c.cell_type == "code"]
    out = []
    for k, i in enumerate(code):
        found = check_call(nb.cells[i].source)
        if found:
            assert k > 0, "a check cell needs an answer cell before it"
            out.append((*found, code[k - 1], i))
    return out


def solution_blocks(source: str) -> list[str]:
    """The code between the solution markers of a cell, dedented."""
    out, inside, cur, indent = [], False, [], 0
    for line in source.split("\n"):
        if line.strip() == BEGIN:
            inside, cur, indent = True, [], len(line) - len(line.lstrip())
        elif line.strip() == END:
            inside = False
            out.append("\n".join(x[indent:] for x in cur))
        elif inside:
            cur.append(line)
    return out


def expressions(code: str, least: int = 1) -> set[str]:
    """The expressions of ``code`` (as ``ast.dump``) made of at least ``least`` nodes."""
    try:
        tree = ast.parse(re.sub(r"^(\s*)[%!].*$", r"\1pass", code, flags=re.M))
    except SyntaxError:
        return set()
    found = set()

    def size(node) -> int:  # nodes below and at ``node``, each counted once
        n = 1 + sum(size(child) for child in ast.iter_child_nodes(node))
        if isinstance(node, ast.expr) and n >= least:
            found.add(ast.dump(node))
        return n

    size(tree)
    return found


def test_both_editions_hold_the_same_notebooks():
    assert len(NAMES) == 15, NAMES
    assert sorted(p.stem for p in STUDENT.glob("*.ipynb")) == NAMES


def test_student_edition_is_generated_and_current():
    assert assign_main(["--root", str(ROOT), "--check"]) == 0, \
        "run `python -m kinlib.assign` (make release)"


@pytest.mark.parametrize("name", NAMES)
def test_student_edition_has_no_solution(name):
    student = read(STUDENT, name)
    for i, cell in enumerate(student.cells):
        assert BEGIN not in cell.source and END not in cell.source, (name, i)
    for ex_id, answer, a, _ in exercise_cells(student):
        src = student.cells[a].source
        blank = (re.search(rf"^{answer}\s*=\s*\.\.\.", src, re.M)
                 or "raise NotImplementedError" in src)
        assert blank, f"{name}: the answer cell of {ex_id} is not blank:\n{src}"


@pytest.mark.parametrize("name", NAMES)
def test_every_exercise_has_a_heading_an_answer_and_a_check_in_order(name):
    nb = read(INSTRUCTOR, name)
    registered = exercises(name[:2])
    found = exercise_cells(nb)
    assert [f[0] for f in found] == [e.id for e in registered], name
    headings = [m for c in nb.cells if c.cell_type == "markdown" for m in HEADING.findall(c.source)]
    assert headings == [(e.id, e.kind) for e in registered], f"{name}: headings {headings}"
    for (ex_id, answer, a, _), ex in zip(found, registered, strict=True):
        src = nb.cells[a].source
        assert BEGIN in src and END in src, f"{name}: the answer cell of {ex_id} has no solution"
        assert answer in assigned_names(src), f"{name}: {ex_id}'s answer cell does not set {answer}"
        md = [c.source for c in nb.cells[:a] if c.cell_type == "markdown"][-3:]
        assert any(f"Exercise {ex_id}" in m for m in md), f"{name}: {ex_id} has no heading nearby"
        assert ex.title, ex_id


def test_the_course_has_enough_exercises_of_every_kind():
    by_notebook = {name: exercises(name[:2]) for name in NAMES}
    for name, exs in by_notebook.items():
        assert len(exs) >= 3, f"{name}: {len(exs)} exercises"
        assert len({e.kind for e in exs}) >= 2, f"{name}: only {exs[0].kind} exercises"
    every = [e for exs in by_notebook.values() for e in exs]
    assert len(every) >= 40 and {e.kind for e in every} == set(KINDS), len(every)


@pytest.mark.parametrize("name", NAMES)
def test_no_cell_depends_on_a_students_answer(name):
    """The names an exercise's solution sets are read only by that exercise's own cells."""
    nb = read(INSTRUCTOR, name)
    code = {i: c.source for i, c in enumerate(nb.cells) if c.cell_type == "code"
            and SOLUTION_TAG not in c.metadata.get("tags", ())}  # instructor-only cells may
    reads = {i: used_names(src) - assigned_names(src) for i, src in code.items()}
    for ex_id, answer, a, c in exercise_cells(nb):
        solution = "\n".join(block for block in re.findall(
            rf"^{re.escape(BEGIN)}\n(.*?)^{re.escape(END)}", code[a], re.M | re.S))
        names = assigned_names(solution) | {answer}
        for i in code:
            if i in (a, c):
                continue
            leaked = names & reads[i]
            assert not leaked, f"{name}: cell {i} reads {sorted(leaked)}, set by exercise {ex_id}"


#: how many AST nodes an expression of a solution needs to count as giving it away
SOLUTION_SIZE = 8


@pytest.mark.parametrize("name", NAMES)
def test_no_solution_code_in_the_student_edition(name):
    """An exercise's answer is not shown elsewhere in the student edition: no expression of
    a solution (of some size) appears in a student cell, unless the lesson had it already
    before the exercise (a given)."""
    inst, student = read(INSTRUCTOR, name), read(STUDENT, name)
    shown = set().union(*(expressions(c.source) for c in student.cells if c.cell_type == "code"))
    before = set()  # the expressions of the cells so far that hold no solution: givens
    for i, cell in enumerate(inst.cells):
        if cell.cell_type != "code":
            continue
        if BEGIN not in cell.source:
            before |= expressions(cell.source)
            continue
        for block in solution_blocks(cell.source):
            leaked = (expressions(block, SOLUTION_SIZE) & shown) - before
            assert not leaked, f"{name}: cell {i}'s solution is shown in the student edition: " \
                               + "; ".join(ast.unparse(eval(x, vars(ast))) for x in leaked)
