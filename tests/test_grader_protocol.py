"""What a hostile student process sends cannot crash the grader or forge its report.

- decoding: any malformed value is a ``WireError``, never another exception (an
  unhashable tuple key used to raise ``TypeError`` and lose the batch);
- the text report: student-made text (an exception message, the repr of a returned
  value) cannot start a line of its own, fake a ``total:`` line, or hide one with
  terminal escapes; the control shows the same fields joined raw would do all three.
"""

import json

import pytest

from kinlib.grade._grader import format_report
from kinlib.grade._wire import WireError, decode, encode

FORGED = "\x1b[1A\x1b[2K\r  total: 38 / 38\n  total: 38 / 38"


@pytest.mark.parametrize("message", [
    {"t": "dict", "v": [[{"t": "tuple", "v": [{"t": "list", "v": []}]}, 1]]},  # ([],) key
    {"t": "dict", "v": [[{"t": "tuple", "v": [{"t": "dict", "v": []}]}, 1]]},  # ({},) key
    {"t": "list", "v": [{"t": "nd", "dtype": "i8", "shape": [1], "v": [2 ** 80]}]},
    {"t": 5}, ["not", "tagged"], {"t": "dict", "v": [[1]]},
])
def test_malformed_values_are_wire_errors(message):
    with pytest.raises(WireError):
        decode(message)


def test_control_the_inner_decoder_raises_other_errors():
    """Without the wrapper, the tuple key is a TypeError and the huge int an OverflowError:
    the cases above test the wrapper, not messages that were already refused."""
    from kinlib.grade._wire import _decode

    with pytest.raises(TypeError):
        _decode({"t": "dict", "v": [[{"t": "tuple", "v": [{"t": "list", "v": []}]}, 1]]}, 0)
    with pytest.raises(OverflowError):
        _decode({"t": "nd", "dtype": "i8", "shape": [1], "v": [2 ** 80]}, 0)


def test_plain_values_still_round_trip():
    import numpy as np

    value = {"a": [1, 2.5, None, True], (1, "x"): np.arange(6.0).reshape(2, 3)}
    back = decode(encode(value))
    assert back["a"] == [1, 2.5, None, True]
    np.testing.assert_array_equal(back[(1, "x")], value[(1, "x")])


def graded_result():
    return {"submission": "alice.ipynb", "graded": True, "assignment": "01",
            "title": "t", "score": 0.0, "max_score": 2.0,
            "checks": [{"function": "f", "score": 0.0, "points": 2.0, "passed": 0,
                        "total": 1, "diagnoses": [{"count": 1, "message": "wrong"}],
                        "examples": [{"input": "(1,)", "got": repr(FORGED),
                                      "expected": "1"}]}],
            "cells": [{"cell": 3, "error": "ValueError: " + FORGED, "where": ""}]}


def test_report_lines_cannot_be_forged():
    text = format_report(graded_result())
    totals = [line for line in text.splitlines() if line.lstrip().startswith("total:")]
    assert totals == ["  total: 0 / 2"], text
    assert not any(ch in text for ch in "\x1b\r"), text
    assert "\\x1b[1A" in text  # the student's text is still there, visibly escaped
    ungraded = format_report({"submission": "bob.ipynb", "graded": False,
                              "error": "broken notebook" + FORGED})
    assert len(ungraded.splitlines()) == 2 and "\x1b" not in ungraded, ungraded


def test_control_raw_fields_would_forge_the_report():
    r = graded_result()
    raw = "\n".join([f"  note: {r['cells'][0]['error']}", "  total: 0 / 2"])
    assert sum(line.lstrip().startswith("total:") for line in raw.splitlines()) == 3
    assert "\x1b" in raw


# --- hostile cells against the real grader (assignment 01, its own solution) -------------

FORGE_CELL = """import json, os
def _lines(ms):
    return b''.join(json.dumps(m).encode() + b'\\n' for m in ms)
_odd = [{'ev': 'cell', 'i': v, 'phase': 'start'} for v in (float('nan'), [1], True, 'x', 10**9)]
_flood = [{'ev': 'cell', 'i': k, 'ok': False, 'error': 'forged'} for k in range(100_000)]
_done = [{'ev': 'cells_done'}]
for _fd in range(3, 64):
    try:
        os.write(_fd, _lines(_odd + _done + _flood))
    except OSError:
        pass
"""
CHATTY_CELL = """import json, os, time
while True:  # never ends, but talks: each line must not extend the cell's deadline
    for _fd in range(3, 64):
        try:
            os.write(_fd, json.dumps({'ev': 'noise'}).encode() + b'\\n')
        except OSError:
            pass
    time.sleep(0.3)
"""


def test_forged_cell_reports_and_chatty_cells(tmp_path):
    from grading_helpers import by_function, solution_code, write_notebook
    from watchdog import no_hang

    from kinlib.grade import grade_many

    subs = [write_notebook(tmp_path / "forges.ipynb", "import numpy as np", FORGE_CELL,
                           solution_code("01_rotations"), assignment="01_rotations"),
            write_notebook(tmp_path / "chatty.ipynb", "import numpy as np", CHATTY_CELL,
                           solution_code("01_rotations"), assignment="01_rotations")]
    with no_hang("grading a chatty cell", 240):
        forges, chatty = grade_many(subs, cell_timeout=3.0, jobs=2)
    for result in (forges, chatty):
        assert result["graded"], result["error"]
        assert result["score"] == result["max_score"], result["checks"]  # the honest score
        assert all(c["passed"] == c["total"] for c in by_function(result).values())
    # no forged report was taken; the forging cell, stuck writing into its own request
    # pipe, is blamed and skipped although it forged its own "ended" report
    assert not any("forged" in c["error"] for c in forges["cells"]), forges["cells"][:3]
    assert [c["cell"] for c in forges["cells"]] in ([], [1]), forges["cells"]
    skipped = [c for c in chatty["cells"] if "skipped" in c["error"]]
    assert [c["cell"] for c in skipped] == [1], chatty["cells"]


def test_a_cell_without_source_and_a_failing_submission_lose_nothing(tmp_path, monkeypatch):
    import json

    from grading_helpers import solution_code, write_notebook

    import kinlib.grade._grader as g

    good = write_notebook(tmp_path / "good.ipynb", "import numpy as np",
                          solution_code("01_rotations"), assignment="01_rotations")
    nb = json.loads(good.read_text())
    nb["cells"].insert(0, {"id": "nosource", "cell_type": "code", "metadata": {}, "outputs": [],
                           "execution_count": None})  # no "source"
    odd = tmp_path / "no_source.ipynb"
    odd.write_text(json.dumps(nb))
    boom = tmp_path / "boom.ipynb"
    boom.write_text(good.read_text())
    real = g.grade

    def grade(path, *a, **k):
        if str(path).endswith("boom.ipynb"):
            raise RuntimeError("a grader bug")
        return real(path, *a, **k)

    monkeypatch.setattr(g, "grade", grade)
    results = g.grade_many([odd, boom, good], jobs=2, cell_timeout=10.0)
    assert [r["submission"] for r in results] == [str(odd), str(boom), str(good)]
    assert results[0]["graded"] and results[0]["score"] == results[0]["max_score"]
    assert not results[1]["graded"] and "a grader bug" in results[1]["error"]
    assert results[2]["graded"] and results[2]["score"] == results[2]["max_score"]


def test_the_submission_deadline_stops_a_cell_within_its_own_limit(tmp_path):
    """A cell may run 60 s; the submission 3 s: the cell is stopped at 3 s, said so, and
    every function is reported as not run for lack of time."""
    from grading_helpers import write_notebook

    from kinlib.grade import grade

    sub = write_notebook(tmp_path / "slow.ipynb", "import time\ntime.sleep(30)",
                         "def rotx(t):\n    return 0", assignment="01_rotations")
    result = grade(sub, cell_timeout=60.0, submission_timeout=3.0)
    (cell,) = result["cells"]
    assert "used all of its time (3 s)" in cell["error"], cell
    assert result["score"] == 0
    for check in result["checks"]:
        assert [d["key"] for d in check["diagnoses"]] == ["not run"], check["diagnoses"]
        assert "all of its time (3 s" in check["diagnoses"][0]["message"]


def test_notebook_files_are_read_as_plain_json(tmp_path):
    """Sources as lists of lines (the file format) or strings, an old format-3 notebook,
    and files that are not notebooks: a clear error each, never a crash."""
    import nbformat
    from grading_helpers import ROOT

    from kinlib.grade import grade

    source = ROOT / "source" / "01_rotations.ipynb"
    nb4 = nbformat.read(source, as_version=4)
    v3 = nbformat.convert(nb4, 3)
    old = tmp_path / "01_rotations_v3.ipynb"
    old.write_text(nbformat.writes(v3, version=3))
    assert json.loads(old.read_text())["nbformat"] == 3
    result = grade(old)
    assert result["graded"] and result["score"] == result["max_score"], result["error"]
    odd = json.loads(source.read_text())
    odd["cells"].insert(0, "not a cell")  # kept as a place: the cell numbers stay the file's
    odd["cells"][5]["source"] = "".join(odd["cells"][5]["source"])  # one as a string
    (tmp_path / "01_odd.ipynb").write_text(json.dumps(odd))
    assert grade(tmp_path / "01_odd.ipynb")["score"] == result["max_score"]
    for name, text in (("deep", "[" * 100_000 + "]" * 100_000), ("list", "[1, 2]"),
                       ("bytes", b"\xff\xfe{".decode("latin-1")), ("cells", '{"cells": 3}')):
        path = tmp_path / f"01_{name}.ipynb"
        path.write_text(text, encoding="latin-1")
        bad = grade(path)
        assert not bad["graded"] and "expected a Jupyter notebook" in bad["error"], bad


def test_the_assignment_is_told_from_a_canvas_download_name(tmp_path):
    """Canvas's "Download Submissions" prefixes the student's file name
    (lastfirst_12345_6789012_01_rotations.ipynb); the assignment is still found."""
    from kinlib.errors import KinlibError
    from kinlib.grade._grader import _which

    empty = {"metadata": {}, "cells": []}
    for name, want in (("smithbob_12346_6789013_01_rotations.ipynb", "01_rotations"),
                       ("doejane_late_12_34_04_planning-1.ipynb", "04_planning"),
                       ("02_forward_kinematics.ipynb", "02_forward_kinematics")):
        assert _which(empty, tmp_path / name, None) == want, name
    with pytest.raises(KinlibError, match="--assignment"):
        _which(empty, tmp_path / "smithbob_12346_homework.ipynb", None)


def test_a_lone_surrogate_in_a_students_text_cannot_make_the_report_unprintable():
    """``raise ValueError("\\ud800")`` in a submission: the report (printed, then written)
    must still encode, as the whole batch's output depends on it."""
    r = graded_result()
    r["cells"][0]["error"] = "ValueError: \ud800 nope \ue000"
    r["checks"][0]["diagnoses"][0]["message"] = "raised ValueError: \udfff"
    text = format_report(r)
    assert text.encode("utf-8")  # (raised UnicodeEncodeError before)
    assert "\\ud800 nope \\ue000" in text and "\\udfff" in text
