"""Grade students' assignment notebooks against kinlib's reference implementations.

Command line::

    python -m kinlib.grade SUBMISSION.ipynb [MORE.ipynb ...] [--json] [--jobs N]
    python -m kinlib.grade --csv grades.csv --report class.html --secret-file S hand-ins/*/*.ipynb
    python -m kinlib.grade --self-check my_notebook.ipynb     # a student, as practice

Python::

    from kinlib.grade import grade, grade_many, format_report
    result = grade("alice/01_rotations.ipynb")
    print(format_report(result))
    print(format_report(self_check("01_rotations.ipynb")))  # a student's practice run

Each submission runs in its own process inside a bubblewrap sandbox (no kinlib, no network,
no other files, its own PID namespace, never root: :mod:`kinlib.grade._bwrap`), with memory,
CPU-time, file-size and process limits and deadlines per cell, case, function and
submission (:mod:`kinlib.grade._sandbox`). Without a sandbox the grader refuses unless
``unsandboxed=True`` (``--unsandboxed``), which marks the result. Its functions are found by
name and called on fixed and seeded random cases (public, ``seed``, or hidden, from the
instructor's ``secret``); the answers come back as plain JSON data and are judged here,
against kinlib, with diagnoses of the classic mistakes (:mod:`kinlib.grade._checks`).
:mod:`kinlib.grade.gradescope` exports an assignment as a Gradescope autograder;
:mod:`kinlib.grade.gradebook` writes a class's scores as a CSV for Canvas's gradebook and
:mod:`kinlib.grade.class_report` an HTML page of its most common mistakes.

A result (:class:`GradeResult`: a dict with ``.success`` and ``.to_json()``) is a JSON-ready
dict::

    {"submission": path, "assignment": "01_rotations", "graded": true, "error": null,
     "score": 35.5, "max_score": 38.0, "cases": "secret", "sandbox": "bubblewrap 0.11.0",
     "checks": [{"function": "rotx", "points": 2, "score": 2.0, "passed": 30, "total": 30,
                 "diagnoses": [{"key": "transposed", "count": 12, "message": "..."}],
                 "examples": [{"input": "...", "expected": "...", "got": "...",
                               "message": "..."}]}, ...],
     "cells": [{"cell": 7, "ok": false, "error": "NotImplementedError", "where": "..."}]}

``graded`` is False (and ``error`` says why) only when the file could not be graded at all:
not a notebook, or not one of the assignments. An unsandboxed result has ``"sandbox": null``
and a ``"warning"``.
"""

from __future__ import annotations

from ._bwrap import SandboxUnavailable
from ._grader import (
    GradeResult,
    assignment_names,
    cases_seed,
    format_report,
    grade,
    grade_many,
    load_assignment,
    summary,
)
from ._practice import self_check

__all__ = ["GradeResult", "grade", "grade_many", "format_report", "load_assignment",
           "assignment_names", "summary", "cases_seed", "SandboxUnavailable", "self_check"]
