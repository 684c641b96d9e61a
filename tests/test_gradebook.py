"""Back to the instructor, and a student's self-check: a class graded once on the command
line (in the sandbox, two at a time) with --csv and --report, the gradebook and the class
report checked against what the test planted; the warning for a class graded on public
cases; --self-check without a sandbox or a secret.

The class is assignment 01: the solution, and the solution with mistakes from the
assignment's own table (a transposed rotx, a roty that raises), under Canvas's file names,
in a folder per student, and named only by the notebook's metadata (once rightly, once
claiming a classmate's row). Expected points are computed here from the assignment's points
and cases, never read from the grader.
"""

import csv
import json
import os
import re
import subprocess
import sys
from html.parser import HTMLParser

import nbformat
import numpy as np
import pytest
from grading_helpers import ROOT, patched, solution_code

import kinlib as kl
from kinlib.grade import (
    SandboxUnavailable,
    format_report,
    grade_many,
    load_assignment,
    self_check,
    summary,
)
from kinlib.grade.__main__ import main
from kinlib.grade.class_report import class_report, class_stats
from kinlib.grade.gradebook import (
    CANVAS_COLUMNS,
    canvas_identity,
    gradebook_rows,
    identify,
    neutralise,
)

A = "01_rotations"
POINTS = {c.function: c.points for c in load_assignment(A).checks}
MAX = sum(POINTS.values())
SCRIPT = "<script>alert('x')</script>&"


def _transposed_rotx_score() -> float:
    """rotx's points for a transposed rotx: right only where R(θ) = R(θ)ᵀ (sin θ = 0)."""
    (check,) = [c for c in load_assignment(A).checks if c.function == "rotx"]
    cases = check.make_cases(0)
    right = sum(np.allclose(kl.rotx(t), kl.rotx(t).T, atol=1e-6) for (t,) in cases)
    assert 0 < right < len(cases)
    return round(POINTS["rotx"] * right / len(cases), 2)


def _code(*mistakes: str) -> list[str]:
    """Cells: the right solution (with right copies of the rotations), then the solution
    with ``mistakes`` planted; the Euler matrix calls the right copies, so that each
    planted mistake costs its own function only."""
    right = solution_code(A) + "\n\n_rx, _ry, _rz = rotx, roty, rotz\n"
    code = patched(solution_code(A), ("return rotz(alpha) @ roty(beta) @ rotx(gamma)",
                                      "return _rz(alpha) @ _ry(beta) @ _rx(gamma)"))
    edits = {"transposed": ("[0.0, c, -s], [0.0, s, c]]", "[0.0, c, s], [0.0, -s, c]]"),
             "raises": ("c, s = np.cos(theta), np.sin(theta)\n    return np.array([[c, 0.0, s]",
                        f"raise ValueError({SCRIPT!r})\n"
                        "    return np.array([[c, 0.0, s]")}
    return [right, patched(code, *(edits[m] for m in mistakes))]


def _notebook(path, cells, student=None):
    nb = nbformat.v4.new_notebook()
    nb.cells = [nbformat.v4.new_code_cell(c) for c in cells]
    nb.metadata["kinlib"] = {"assignment": A, **({"student": student} if student else {})}
    path.parent.mkdir(parents=True, exist_ok=True)
    nbformat.write(nb, path)
    return path


# submission (relative to the hand-in folder): (cells, metadata claim, Student, ID, lost)
# where lost maps a function to the score it keeps
ROTX = _transposed_rotx_score()
CLASS = {
    "smithjohn_1001_5001_01_rotations.ipynb": (_code(), None, "smithjohn", "1001", {}),
    "doejane_LATE_1002_5002_01_rotations-1.ipynb": (_code("transposed"), None, "doejane",
                                                    "1002", {"rotx": ROTX}),
    "alice/01_rotations.ipynb": (_code(), None, "alice", "", {}),
    "bob/01_rotations.ipynb": (_code("transposed", "raises"), None, "bob", "",
                               {"rotx": ROTX, "roty": 0.0}),
    # a folder names mallory: her claim to be alice is never read
    "mallory/01_rotations.ipynb": (_code("transposed"), "alice", "mallory", "",
                                   {"rotx": ROTX}),
    # the path names nobody: the metadata does, rightly for carol...
    "01_rotations.ipynb": (_code(), "carol", "carol", "", {}),
    # ...and wrongly here, claiming alice's row, which her folder already holds
    "01_rotations (1).ipynb": (_code("transposed"), "alice", None, "", {"rotx": ROTX}),
    # a student-chosen folder name that a spreadsheet would run as a formula
    "=1+2/01_rotations.ipynb": (None, None, "'=1+2", "", {f: 0.0 for f in POINTS}),
}


@pytest.fixture(scope="module")
def graded(tmp_path_factory):
    """The class graded once: ``python -m kinlib.grade -j 2 --out --csv --report``, run in
    the hand-in folder on relative paths (as an instructor would)."""
    root = tmp_path_factory.mktemp("class")
    hand_ins = root / "hand-ins"
    for name, (cells, claim, *_) in CLASS.items():
        if cells is None:  # the student version, as released: nothing done
            (hand_ins / name).parent.mkdir(parents=True, exist_ok=True)
            (hand_ins / name).write_text((ROOT / "release" / f"{A}.ipynb").read_text())
        else:
            _notebook(hand_ins / name, cells, claim)
    out = subprocess.run(
        [sys.executable, "-m", "kinlib.grade", "-j", "2", "--json", "--out", str(root / "out"),
         "--csv", str(root / "grades.csv"), "--report", str(root / "class.html"), *CLASS],
        cwd=hand_ins, capture_output=True, text=True, timeout=600)
    assert out.returncode == 0, out.stderr
    results = [json.loads(line) for line in out.stdout.splitlines()]
    return {"root": root, "hand_ins": hand_ins, "stderr": out.stderr, "results": results,
            "csv": (root / "grades.csv").read_text(encoding="utf-8"),
            "html": (root / "class.html").read_text(encoding="utf-8")}


def _expected_row(keeps: dict) -> dict:
    cells = {f"{A}: {f}": keeps.get(f, p) for f, p in POINTS.items()}
    cells[A] = round(MAX - sum(POINTS[f] - s for f, s in keeps.items()), 2)
    return cells


def test_gradebook_csv_is_canvas_shaped_with_the_right_points(graded):
    rows = list(csv.reader(graded["csv"].splitlines()))
    assert rows[0][:5] == CANVAS_COLUMNS == ["Student", "ID", "SIS User ID", "SIS Login ID",
                                             "Section"]
    assert rows[0][5:] == [A] + [f"{A}: {f}" for f in POINTS]
    assert rows[1][0] == "Points Possible"
    assert [float(x) for x in rows[1][5:]] == [MAX, *POINTS.values()]
    body = {r[0]: dict(zip(rows[0], r, strict=True)) for r in rows[2:]}
    expected = {student: (sid, keeps) for _, _, student, sid, keeps in CLASS.values()
                if student is not None}
    assert sorted(body) == sorted(expected)  # one row per student; the forged claim has none
    for student, (sid, keeps) in expected.items():
        row = body[student]
        assert row["ID"] == sid, student
        assert row["SIS Login ID"] == ("" if sid else student), student
        for column, value in _expected_row(keeps).items():
            assert float(row[column]) == pytest.approx(value, abs=0.011), (student, column)
    assert body["smithjohn"][A] == body["alice"][A] == f"{MAX:g}"
    assert float(body["'=1+2"][A]) == 0


def test_identities_and_claims_are_reported(graded):
    err = graded["stderr"]
    assert "CLAIM REFUSED" in err and "01_rotations (1).ipynb" in err
    assert "'alice'" in err.split("CLAIM REFUSED")[1].splitlines()[0]
    assert "2 from Canvas's file names" in err and "4 from folders" in err
    assert "2 from notebook metadata" in err
    assert "DUPLICATE" not in err


def test_public_batch_warns(graded):
    err = graded["stderr"]
    assert "WARNING: grading 8 submissions on the PUBLIC cases" in err
    assert "--secret-file" in err.split("PUBLIC")[1]
    last = err.strip().splitlines()
    assert any(line.startswith("graded 8 of 8") and "PUBLIC" in line for line in last)


class _Page(HTMLParser):
    def __init__(self):
        super().__init__()
        self.tags, self.attrs, self.text = [], [], []

    def handle_starttag(self, tag, attrs):
        self.tags.append(tag)
        self.attrs += attrs

    def handle_data(self, data):
        self.text.append(data)


def test_class_report_names_the_planted_mistakes(graded):
    page = graded["html"]
    parser = _Page()
    parser.feed(page)
    text = " ".join(" ".join(parser.text).split())
    # the planted transposed rotx: 4 of the 8 students, with its message and an example
    n = len(CLASS)
    transposed = sum(cells is not None and "rotx" in keeps
                     for cells, *_, keeps in CLASS.values())
    assert transposed == 4
    assert f"{A} · rotx: transposed" in text
    assert f"{transposed} of {n} students (50 %)" in text
    assert "the sign of sin is on the wrong side" in text
    glance = text.split("At a glance: the most common mistakes")[1]
    assert glance.split("assignment ", 1)[1].startswith(
        f"{A} · rotx: transposed 4 of 8 students (50 %)")  # the first
    chart = glance.split("Not done yet")[0]  # the blank notebook: not done, not a mistake
    assert "NotImplementedError" not in chart and "Not done yet" in glance
    roty_row = text.split("roty rotation about y by θ")[1].split("rotz")[0]
    assert f"raised ValueError : 1 of 8 (12 %) — raised ValueError: {SCRIPT}" in roty_row
    rotx_row = text.split("rotx rotation about x by θ")[1].split("roty")[0]
    assert re.search(r"^ 2 3 of 8 \(38 %\) [0-9.]+ / 2 transposed : 4 of 8 \(50 %\)", rotx_row)
    assert "e.g. input" in rotx_row and "returned" in rotx_row and "expected" in rotx_row
    # right and mean, per function: rotz right for all but the blank notebook
    assert "rotz rotation about z by θ 2 7 of 8 (88 %) 1.75 / 2" in text
    assert "svg" in parser.tags and "rect" in parser.tags
    # the student's text is escaped, and nothing is loaded from anywhere
    assert "<script" not in page and "&lt;script&gt;alert(&#x27;x&#x27;)&lt;/script&gt;&amp;" \
        in page
    assert SCRIPT in text  # (shown as text)
    assert not {"script", "img", "link", "iframe", "object", "embed"} & set(parser.tags)
    assert not [(k, v) for k, v in parser.attrs if k in ("src", "href") and
                not (k == "href" and v.startswith("#"))]
    assert "url(" not in page and "@import" not in page and "http" not in page.replace(
        "http-equiv", "")


def test_result_files_make_the_same_gradebook_without_grading(graded, monkeypatch, capsys):
    files = sorted((graded["root"] / "out").glob("*.grade.json"))
    assert len(files) == len(CLASS)
    monkeypatch.chdir(graded["hand_ins"])  # the paths in the results are relative to it
    again = graded["root"] / "again.csv"
    assert main(["--csv", str(again), *map(str, files)]) == 0
    assert again.read_text(encoding="utf-8") == graded["csv"]
    err = capsys.readouterr().err
    assert "CLAIM REFUSED" in err and "WARNING" not in err.split("graded")[0]


def test_duplicates_are_left_blank_and_named(graded):
    results = [dict(r) for r in graded["results"]]
    alice = next(r for r in results if r["submission"] == "alice/01_rotations.ipynb")
    results.append({**alice, "submission": "late/01_rotations_alice.ipynb"})  # also alice
    rows, problems = gradebook_rows(results)
    body = {r[0]: r for r in rows[2:]}
    assert all(cell == "" for cell in body["alice"][5:])
    assert any(p.startswith("DUPLICATE: 2 submissions of 01_rotations") and
               "late/01_rotations_alice.ipynb" in p for p in problems)


def test_identities_from_paths():
    assert canvas_identity("doejane_late_1002_5002_01_rotations-1.ipynb").id == "1002"
    assert canvas_identity("alice/01_rotations.ipynb") is None
    who = identify([{"submission": p, "assignment": A} for p in (
        "x/smithjohn_1001_5001_hw.ipynb", "x/01_rotations_alice.ipynb",
        "x/bob_01_rotations.ipynb", "carol.ipynb", "dave/01_rotations-2.ipynb",
        "01_rotations.ipynb", "01_rotations copy.ipynb")],
        [None, None, None, None, "eve", "frank", None])
    assert [(i.student, i.source) for i in who] == [
        ("smithjohn", "canvas"), ("alice", "file name"), ("bob", "file name"),
        ("carol", "file name"), ("dave", "folder"), ("frank", "metadata"),
        ("01_rotations copy", "unknown")]


def test_formula_cells_are_neutralised():
    for bad in ("=1+2", "+1", "-1+1", "@SUM(A1)", "\t=1", "\r=1", " =1", "＝1"):
        cell = neutralise(bad)
        assert cell.startswith("'") and not re.search(r"[\t\r\n]", cell), bad
    assert neutralise("O'Brien, Ann") == "O'Brien, Ann"


def test_self_check_of_the_release_without_sandbox_or_secret(tmp_path):
    sub = tmp_path / f"{A}.ipynb"
    sub.write_text((ROOT / "release" / f"{A}.ipynb").read_text())
    env = {"KINLIB_BWRAP": "/nonexistent", "KINLIB_GRADE_SECRET": "not to be used"}
    out = subprocess.run([sys.executable, "-m", "kinlib.grade", "--self-check", "--json",
                          str(sub)], capture_output=True, text=True, timeout=300,
                         env={**os.environ, **env})
    assert out.returncode == 0, out.stderr
    (r,) = [json.loads(line) for line in out.stdout.splitlines()]
    assert r["practice"] is True and r["note"].startswith("your own code")
    assert r["graded"] and r["score"] == 0 and r["max_score"] == MAX
    assert r["cases"] == "public (seed 0)" and "warning" not in r
    assert "KINLIB_GRADE_SECRET is set but not used" in out.stderr
    assert "WITHOUT" not in out.stderr and "PUBLIC" not in out.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == [sub.name]  # no result file


def test_self_check_from_python_needs_no_sandbox(tmp_path, monkeypatch):
    monkeypatch.setenv("KINLIB_BWRAP", "/nonexistent")
    sub = tmp_path / f"{A}.ipynb"
    sub.write_text((ROOT / "source" / f"{A}.ipynb").read_text())
    with pytest.raises(SandboxUnavailable):  # no sandbox here: an instructor's grading stops
        grade_many([sub])
    result = self_check(sub)
    assert result["practice"] and result["score"] == result["max_score"] == MAX
    report = format_report(result)
    assert report.splitlines()[0] == ("PRACTICE: your own code, run on this machine without "
                                      "a sandbox, on the public cases; your instructor grades "
                                      "on hidden cases")
    assert "WARNING" not in report and f"total: {MAX:g} / {MAX:g}" in report


def test_self_check_refuses_a_secret(tmp_path, capsys):
    secret = tmp_path / "secret"
    secret.write_text("s3cret")
    for extra in (["--secret-file", str(secret)], ["--seed", "3"],
                  ["--csv", str(tmp_path / "g.csv")]):
        with pytest.raises(SystemExit) as exc:
            main(["--self-check", *extra, str(tmp_path / "a.ipynb")])
        assert exc.value.code == 2
        assert "--self-check runs the public cases" in capsys.readouterr().err


def test_public_warning_only_for_a_class_without_secret(tmp_path, monkeypatch, capsys):
    monkeypatch.delenv("KINLIB_GRADE_SECRET", raising=False)
    bad = [str(tmp_path / f"{k}.ipynb") for k in "ab"]
    for p in bad:
        open(p, "w").write("not a notebook")
    secret = tmp_path / "secret"
    secret.write_text("s3cret")
    warned = {}
    for name, env, args in (("public", None, bad), ("one", None, bad[:1]),
                            ("file", None, ["--secret-file", str(secret), *bad]),
                            ("env", "s3cret", bad)):
        if env:
            monkeypatch.setenv("KINLIB_GRADE_SECRET", env)
        assert main(["--no-write", *args]) == 2  # (not notebooks: not graded)
        warned[name] = "PUBLIC cases" in capsys.readouterr().err
    assert warned == {"public": True, "one": False, "file": False, "env": False}
    # the summary line says it from the results alone
    public = {"graded": True, "score": 1.0, "max_score": 2.0, "cases": "public (seed 0)"}
    assert "PUBLIC" in summary([public, public])
    assert "PUBLIC" not in summary([public])
    assert "PUBLIC" not in summary([{**public, "cases": "secret"}] * 2)
    assert "PUBLIC" not in summary([{**public, "practice": True}] * 2)


def test_class_report_of_trusted_results_escapes_and_counts():
    """The writers on hand-made results (no grading): two assignments, an ungraded one."""
    def check(fn, passed, key=None, msg=""):
        return {"function": fn, "title": "<t>", "points": 2, "score": 2.0 * passed / 4,
                "passed": passed, "total": 4,
                "diagnoses": [{"key": key, "count": 4 - passed, "message": msg}] if key else [],
                "examples": [{"input": "(1)", "got": "<del>", "expected": "1", "message": msg}]
                if key else []}
    rs = [{"submission": f"{s}/01_rotations.ipynb", "assignment": A, "graded": True,
           "title": "R", "score": 2.0, "max_score": 4.0, "cases": "secret",
           "checks": [check("rotx", 4 if s != "b" else 0, None if s != "b" else "transposed",
                            "<em>m</em>"), check("roty", 2, "degrees", "d")]}
          for s in "abcd"]
    rs.append({"submission": "e/x.ipynb", "assignment": None, "graded": False, "error": "<x>"})
    stats = class_stats(rs)
    (f_rotx, f_roty) = stats[0]["functions"]
    assert (f_rotx["right"], f_rotx["students"], f_rotx["mistakes"][0]["students"]) == (3, 4, 1)
    assert f_roty["mistakes"][0]["students"] == 4 and f_roty["mean"] == 1.0
    page = class_report(rs)
    assert "<em>" not in page and "&lt;em&gt;m&lt;/em&gt;" in page and "<del>" not in page
    assert "4 of 4 students (100 %)" in page and "1 of 4 students (25 %)" in page
