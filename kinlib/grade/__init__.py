"""Grade students' assignment notebooks against kinlib's reference implementations.

Command line::

    python -m kinlib.grade SUBMISSION.ipynb [MORE.ipynb ...] [--json] [--jobs N]

Python::

    from kinlib.grade import grade, grade_many, format_report
    result = grade("alice/01_rotations.ipynb")
    print(format_report(result))

Each submission runs in its own process (a separate Python with memory, CPU-time and
file-size limits and a time limit on every cell and every case; see
:mod:`kinlib.grade._sandbox`). Its functions are found by name and called on fixed and
seeded random cases; the answers come back as plain JSON data and are judged here, against
kinlib, with diagnoses of the classic mistakes (:mod:`kinlib.grade._checks`).

A result is a JSON-ready dict::

    {"submission": path, "assignment": "01_rotations", "graded": true, "error": null,
     "score": 35.5, "max_score": 38.0,
     "checks": [{"function": "rotx", "points": 2, "score": 2.0, "passed": 30, "total": 30,
                 "diagnoses": [{"key": "transposed", "count": 12, "message": "..."}],
                 "examples": [{"input": "...", "expected": "...", "got": "...",
                               "message": "..."}]}, ...],
     "cells": [{"cell": 7, "ok": false, "error": "NotImplementedError", "where": "..."}]}

``graded`` is False (and ``error`` says why) only when the file could not be graded at all:
not a notebook, or not one of the assignments.
"""

from __future__ import annotations

from ._grader import assignment_names, format_report, grade, grade_many, load_assignment

__all__ = ["grade", "grade_many", "format_report", "load_assignment", "assignment_names"]
