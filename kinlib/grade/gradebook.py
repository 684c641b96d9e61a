"""Back to the instructor: who each submission is, and a gradebook CSV to import in Canvas.

A student is identified from the path of the submission, never from what the notebook
says about itself (:func:`identify`), in this order:

1. a file named as Canvas's "Download Submissions" names them,
   ``lastfirst_12345_6789012_original.ipynb`` (name, Canvas user id, submission id, the
   file's own name; ``late`` may follow the name): Student ``lastfirst``, ID ``12345``;
2. the file's name less the assignment's: ``01_rotations_alice.ipynb``, ``alice.ipynb``;
3. the folder of a file named only after its assignment: ``alice/01_rotations.ipynb``;
4. only when the path says nothing (``01_rotations.ipynb`` given without a folder), the
   notebook's metadata ``"kinlib": {"student": ...}``, which is the student's own claim;
5. else the file's name, flagged.

:func:`write_csv` writes one row per student in Canvas's gradebook format: the columns
``Student, ID, SIS User ID, SIS Login ID, Section`` of Canvas's export, then per assignment
its total and each function's points, and a second row ``Points Possible``. Two submissions
of one assignment that come to one student are both left out of it (their cells blank, so
an import changes nothing) and named on stderr; text cells that a spreadsheet would run as
a formula are neutralised (:func:`neutralise`).
"""

from __future__ import annotations

import csv
import json
import re
from collections import Counter, defaultdict
from dataclasses import dataclass
from pathlib import Path

from ..errors import KinlibError
from ._grader import assignment_names

__all__ = ["Identity", "canvas_identity", "identify", "student_claim", "neutralise",
           "gradebook_rows", "write_csv", "load_results", "count_sources", "CANVAS_COLUMNS"]

#: the student columns of Canvas's gradebook export, which its import reads
CANVAS_COLUMNS = ["Student", "ID", "SIS User ID", "SIS Login ID", "Section"]

# name, an optional late mark, Canvas user id, submission id, the file's original name
_CANVAS = re.compile(r"^(?P<name>[^_]+?)(?:_late)?_(?P<uid>\d+)_(?P<sid>\d+)_(?P<orig>.+)$",
                     re.IGNORECASE)
# what a download or a resubmission adds to a name: " (1)", "-1", " copy"
_COPY = re.compile(r"(?:[ _-]*\(\d+\)|[ _-]+copy|[ _-]+\d+)+$", re.IGNORECASE)
_SEP = " _-."


@dataclass(frozen=True)
class Identity:
    """Who a submission is: ``student`` (a name to show), Canvas's user ``id`` when known,
    and ``source``: ``"canvas"``, ``"file name"``, ``"folder"``, ``"metadata"`` (the
    notebook's own claim) or ``"unknown"``."""

    student: str
    id: str = ""
    source: str = "file name"

    @property
    def key(self) -> tuple[str, str]:
        """What two submissions of one student share."""
        return ("id", self.id) if self.id else ("name", self.student.casefold())


def canvas_identity(filename: str) -> Identity | None:
    """The student of a file named by Canvas's "Download Submissions", or None.

    >>> canvas_identity("smithjohn_late_12345_6789012_01_rotations-1.ipynb")
    Identity(student='smithjohn', id='12345', source='canvas')
    >>> canvas_identity("01_rotations_alice.ipynb") is None
    True
    """
    m = _CANVAS.match(filename)
    return Identity(m["name"], m["uid"], "canvas") if m else None


def _rest(stem: str, assignment: str | None) -> str:
    """``stem`` without the assignment's name (as a prefix or suffix) and the marks of a
    downloaded copy: what else the file's name says."""
    rest = stem
    if assignment:
        low = rest.casefold()
        if low.startswith(assignment.casefold()):
            rest = rest[len(assignment):]
        elif low.endswith(assignment.casefold()):
            rest = rest[:-len(assignment)]
    if rest != stem:
        rest = _COPY.sub("", rest)
    return rest.strip(_SEP)


def identify(results: list[dict], claims: list[str | None] | None = None) -> list[Identity]:
    """The :class:`Identity` of each result's submission (see the module's docstring).

    ``claims`` are the students the notebooks name in their metadata (``None`` where one
    does not), used only for a path that says nothing; by default they are read from the
    notebook (:func:`student_claim`), and only for such a path.

    >>> [i.student for i in identify([
    ...     {"submission": "in/doejane_1002_5002_01_rotations.ipynb", "assignment": "01_rotations"},
    ...     {"submission": "in/01_rotations_alice.ipynb", "assignment": "01_rotations"},
    ...     {"submission": "bob/01_rotations.ipynb", "assignment": "01_rotations"},
    ...     {"submission": "01_rotations.ipynb", "assignment": "01_rotations"}],
    ...     [None, None, "mallory", "carol"])]
    ['doejane', 'alice', 'bob', 'carol']
    """
    read = claims is None
    claims = claims if claims is not None else [None] * len(results)
    out = []
    for r, claim in zip(results, claims, strict=True):
        path = Path(str(r.get("submission", "")))
        who = canvas_identity(path.name)
        if who is None:
            rest = _rest(path.stem, r.get("assignment"))
            folder = path.parent.name
            if rest:
                who = Identity(rest, "", "file name")
            elif folder:
                who = Identity(folder, "", "folder")
            elif claim or (read and (claim := student_claim(path))):
                who = Identity(claim, "", "metadata")
            else:
                who = Identity(path.stem or str(path), "", "unknown")
        out.append(who)
    return out


def student_claim(path) -> str | None:
    """The student a notebook names in its metadata (``"kinlib": {"student": ...}``), or
    None: the student's own claim, read only when the path names nobody."""
    try:
        meta = json.loads(Path(path).read_bytes()).get("metadata", {}).get("kinlib", {})
    except (OSError, ValueError, AttributeError, RecursionError):
        return None
    claim = meta.get("student") if isinstance(meta, dict) else None
    return claim.strip()[:200] if isinstance(claim, str) and claim.strip() else None


_FORMULA = tuple("=+-@＝＋－＠")  # (and their full-width forms)


def neutralise(cell: str) -> str:
    r"""A text cell a spreadsheet shows as text, never runs: control characters (a tab, a
    carriage return, a newline) become spaces, and a cell that then starts like a formula
    (``= + - @``, after any spaces) gets a leading apostrophe, OWASP's advice on CSV
    injection.

    >>> neutralise('=HYPERLINK("http://x")'), neutralise("Smith, John"), neutralise("\t@SUM(1)")
    ('\'=HYPERLINK("http://x")', 'Smith, John', "' @SUM(1)")
    """
    cell = "".join(" " if ord(ch) < 32 or ord(ch) == 127 else ch for ch in str(cell))
    return "'" + cell if cell.lstrip().startswith(_FORMULA) else cell


def _num(x: float) -> str:
    return f"{round(float(x), 2):g}"


def gradebook_rows(results: list[dict], identities: list[Identity] | None = None, *,
                   totals_only: bool = False) -> tuple[list[list[str]], list[str]]:
    """The CSV's rows (header, ``Points Possible``, one per student, by name) and the
    problems to tell the instructor: submissions not graded or naming nobody, and two of
    one assignment that come to one student (a claim in a notebook's metadata gives way to
    a path; else both are left blank)."""
    identities = identities if identities is not None else identify(results)
    problems = []
    for r, who in zip(results, identities, strict=True):
        if not r.get("graded"):
            problems.append(f"not in the gradebook: {r.get('submission')} could not be "
                            f"graded ({r.get('error')})")
        elif who.source == "unknown":
            problems.append(f"NOBODY NAMED: {r.get('submission')} names no student (give "
                            "each student a folder or keep Canvas's file names); its row "
                            f"is called {who.student!r}")
    graded = [(r, who) for r, who in zip(results, identities, strict=True) if r.get("graded")]
    # the assignments and their functions, in the order of their checks
    functions: dict[str, dict[str, float]] = {}
    maxima: dict[str, float] = {}
    for r, _ in graded:
        maxima[r["assignment"]] = float(r["max_score"])
        fns = functions.setdefault(r["assignment"], {})
        for c in r["checks"]:
            fns.setdefault(c["function"], float(c["points"]))
    order = [a for a in assignment_names() if a in functions] + \
        sorted(a for a in functions if a not in assignment_names())
    columns = []  # (assignment, function or None for its total, points)
    for a in order:
        columns.append((a, None, maxima[a]))
        if not totals_only:
            columns += [(a, f, p) for f, p in functions[a].items()]
    # one row per student, one submission per student and assignment
    groups: dict[tuple, list] = defaultdict(list)
    for r, who in graded:
        groups[(who.key, r["assignment"])].append((r, who))
    rows_by_key: dict[tuple, dict] = {}
    for (key, a), subs in groups.items():
        named = [s for s in subs if s[1].source != "metadata"]
        if len(subs) > 1 and len(named) == 1:  # a claim never takes a path's student
            for r, who in subs:
                if who.source == "metadata":
                    problems.append(
                        f"CLAIM REFUSED: {r['submission']} says in its metadata that it is "
                        f"{who.student!r}'s, whose {a} is {named[0][0]['submission']}; "
                        "left out of the gradebook")
            subs = named
        row = rows_by_key.setdefault(key, {"who": subs[0][1], "cells": {}})
        if len(subs) > 1:
            problems.append(
                f"DUPLICATE: {len(subs)} submissions of {a} come to one student "
                f"({subs[0][1].student!r}): "
                + ", ".join(f"{r['submission']} (from its {who.source})" for r, who in subs)
                + "; both left blank in the gradebook: grade the right one alone")
            continue
        r = subs[0][0]
        row["cells"][(a, None)] = _num(r["score"])
        for c in r["checks"]:
            row["cells"][(a, c["function"])] = _num(c["score"])
    header = CANVAS_COLUMNS + [neutralise(a if f is None else f"{a}: {f}")
                               for a, f, _ in columns]
    points = ["Points Possible", "", "", "", ""] + [_num(p) for _, _, p in columns]
    rows = [header, points]
    for entry in sorted(rows_by_key.values(),
                        key=lambda e: (e["who"].student.casefold(), e["who"].id)):
        who = entry["who"]
        login = "" if who.id else who.student  # a folder's or hub's name: often the login
        rows.append([neutralise(who.student), who.id, "", neutralise(login), ""]
                    + [entry["cells"].get((a, f), "") for a, f, _ in columns])
    return rows, problems


def write_csv(results: list[dict], path, *, totals_only: bool = False) -> list[str]:
    """Write the gradebook CSV of ``results`` to ``path`` (UTF-8); the problems to tell the
    instructor, as :func:`gradebook_rows` finds them."""
    rows, problems = gradebook_rows(results, totals_only=totals_only)
    with open(path, "w", encoding="utf-8", newline="") as f:
        csv.writer(f).writerows(rows)
    return problems


def _valid(r) -> bool:
    if not isinstance(r, dict) or not isinstance(r.get("submission"), str):
        return False
    if not r.get("graded"):
        return True
    checks = r.get("checks")
    return (isinstance(r.get("assignment"), str) and isinstance(checks, list)
            and all(isinstance(r.get(k), int | float) for k in ("score", "max_score"))
            and all(isinstance(c, dict) and isinstance(c.get("function"), str)
                    and all(isinstance(c.get(k), int | float)
                            for k in ("points", "score", "passed", "total"))
                    and isinstance(c.get("diagnoses"), list)
                    and isinstance(c.get("examples"), list) for c in checks))


def load_results(paths) -> list[dict]:
    """Results written earlier by ``python -m kinlib.grade --out`` (``*.grade.json``), to
    build a gradebook or report without grading again. Read only files the grader wrote
    where students cannot write: a result file is believed as it is."""
    out = []
    for path in paths:
        try:
            r = json.loads(Path(path).read_text(encoding="utf-8"))
        except (OSError, ValueError, RecursionError) as exc:
            raise KinlibError(f"{path}: expected a result file written by the grader "
                              f"(*.grade.json), could not read it: {exc}") from None
        if not _valid(r):
            raise KinlibError(f"{path}: expected a result of kinlib.grade (a JSON object with "
                              "submission, assignment, score, max_score and checks), got "
                              "something else")
        out.append(r)
    return out


def count_sources(identities: list[Identity]) -> str:
    """How the students were told, for the instructor: "3 from Canvas's file names, ..."."""
    counts = Counter(i.source for i in identities)
    words = {"canvas": "Canvas's file names", "file name": "file names", "folder": "folders",
             "metadata": "notebook metadata (the students' own claim)",
             "unknown": "nothing (the file's name)"}
    return ", ".join(f"{n} from {words[s]}" for s, n in counts.most_common())
