"""What a hostile student process sends cannot crash the grader or forge its report.

- decoding: any malformed value is a ``WireError``, never another exception (an
  unhashable tuple key used to raise ``TypeError`` and lose the batch);
- the text report: student-made text (an exception message, the repr of a returned
  value) cannot start a line of its own, fake a ``total:`` line, or hide one with
  terminal escapes; the control shows the same fields joined raw would do all three.
"""

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
