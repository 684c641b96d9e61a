"""Grade a submission: run it in a student process, call its functions, judge the answers.

The student's process (:mod:`kinlib.grade._sandbox`) only ever sends plain data; every
comparison happens here, with kinlib's reference in this process, so nothing the
submission does to numpy, kinlib or its own process can change a verdict. A cell that
hangs or ends the process is skipped on the next start; a case that hangs or ends the
process fails, the rest of that function's cases are not run, and the next function gets
a fresh process.
"""

from __future__ import annotations

import json
import os
import secrets
import time
from collections import Counter
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from ..errors import KinlibError
from ._checks import Assignment, Check, Verdict, fmt
from ._sandbox import Worker, WorkerDied, WorkerTimeout
from ._wire import WireError, decode, encode

__all__ = ["grade", "grade_many", "format_report", "load_assignment", "assignment_names"]

MAX_RESTARTS = 12
EXAMPLES = 3


def assignment_names() -> list[str]:
    from .assignments import ASSIGNMENTS

    return sorted(ASSIGNMENTS)


def load_assignment(name: str) -> Assignment:
    """The :class:`Assignment` called ``name`` (e.g. ``"01_rotations"``)."""
    from .assignments import ASSIGNMENTS

    if name not in ASSIGNMENTS:
        raise KinlibError(f"assignment: expected one of {sorted(ASSIGNMENTS)}, got {name!r}")
    return ASSIGNMENTS[name]()


def _read(path: Path):
    import nbformat

    try:
        nb = nbformat.read(path, as_version=4)
    except FileNotFoundError:
        raise KinlibError(f"{path}: no such file") from None
    except Exception as exc:  # nbformat raises many kinds
        raise KinlibError(f"{path}: expected a Jupyter notebook (.ipynb), could not read it: "
                          f"{type(exc).__name__}: {str(exc)[:200]}") from None
    return nb


def _which(nb, path: Path, assignment: str | None) -> str:
    if assignment is not None:
        return assignment
    meta = nb.metadata.get("kinlib", {}) if isinstance(nb.metadata, dict) else {}
    name = meta.get("assignment") if isinstance(meta, dict) else None
    names = assignment_names()
    if isinstance(name, str) and name in names:
        return name
    for n in names:
        if path.stem.startswith(n) or path.stem.startswith(n[:3]):
            return n
    raise KinlibError(f"{path}: cannot tell which assignment this is (no kinlib metadata and "
                      f"the file name does not start with one of {names}); pass assignment=")


class _Session:
    """The student's process for one submission, restarted when it hangs or dies."""

    def __init__(self, cells, cell_timeout: float, memory_mb: int):
        self.cells, self.cell_timeout, self.memory_mb = cells, cell_timeout, memory_mb
        self.skip: set[int] = set()
        self.reports: dict[int, dict] = {}
        self.worker: Worker | None = None
        self.restarts = 0

    def ready(self) -> Worker:
        """A process that has run every cell not known to hang or kill it."""
        while self.worker is None or not self.worker.alive:
            if self.worker is not None:
                self.worker.close()
            if self.restarts > MAX_RESTARTS:
                raise WorkerDied(f"the submission's process was restarted {MAX_RESTARTS} "
                                 "times; giving up")
            self.restarts += 1
            self.worker = Worker(memory_mb=self.memory_mb)
            self._run_cells()
        return self.worker

    def _run_cells(self) -> None:
        """Run the cells; keep one report per cell that was sent. A cell's deadline is
        fixed when it starts (messages cannot extend it), and all cells together get
        ``cell_timeout`` each plus one."""
        w = self.worker
        batch = [c for c in self.cells if c[0] not in self.skip]
        order = [c[0] for c in batch]  # a start is taken only for the next cell, an end
        sent, nxt = set(order), 0      # only for the cell that started: one report each
        current, cell_end, last = None, None, None  # last: the cell that started last
        end = time.monotonic() + self.cell_timeout * (len(batch) + 1)

        def index(m) -> int | None:
            i = m.get("i")
            return i if type(i) is int and i in sent else None  # forged or odd: ignored

        try:
            w.request({"op": "cells", "cells": batch})
            while True:
                now = time.monotonic()
                due = min(end, cell_end) if cell_end is not None else end
                if now >= due:
                    raise WorkerTimeout("the cells took too long")
                m = w.receive(min(self.cell_timeout, due - now))
                ev, i = m.get("ev"), index(m)
                if ev == "cell" and m.get("phase") == "start":
                    if current is None and nxt < len(order) and i == order[nxt]:
                        current, last, nxt = i, i, nxt + 1
                        cell_end = time.monotonic() + self.cell_timeout
                elif ev == "cell" and i is not None and i == current:
                    self.reports.setdefault(i, {
                        "cell": i, "ok": bool(m.get("ok")), "error": str(m.get("error", ""))[:600],
                        "where": str(m.get("where", ""))[:100]})
                    current, cell_end = None, None
                elif ev == "cells_done" and current is None and nxt == len(order):
                    return  # (a forged "done" before the last cell ended is ignored)
        except (WorkerTimeout, WorkerDied) as exc:
            what = (f"ran longer than {self.cell_timeout:g} s and was stopped"
                    if isinstance(exc, WorkerTimeout) else f"ended the process: {exc}")
            # the cell running, or the last one started (its end may have been forged by
            # its own code, to escape the blame)
            culprit = current if current is not None else last
            if culprit is not None:
                self.skip.add(culprit)
                self.reports[culprit] = {"cell": culprit, "ok": False,
                                         "error": f"this cell {what}; it was skipped", "where": ""}
            else:  # no cell started: the rest are skipped rather than retried for ever
                for i in order[nxt:]:
                    self.skip.add(i)
                    self.reports.setdefault(i, {"cell": i, "ok": False, "where": "",
                                                "error": f"not run: the cells {what}"})
            w.kill()

    def close(self) -> None:
        if self.worker is not None:
            self.worker.close()


def _run_check(session: _Session, check: Check, cases: list[tuple]) -> list[tuple]:
    """Call the student's function on every case: a list of (status, payload) per case."""
    out: list[tuple] = [("not run", "an earlier case hung or ended the process")] * len(cases)
    call_id = secrets.token_hex(8)  # unguessable: code running in an earlier call cannot
    # forge replies for this one (replies to earlier calls, late or forged, are dropped)
    try:
        w = session.ready()
        w.request({"op": "call", "id": call_id, "name": check.function,
                   "cases": [encode(c) for c in cases]})
    except WorkerDied as exc:
        return [("died", str(exc))] * len(cases)
    k = 0
    end = time.monotonic() + check.time_limit * (len(cases) + 1)  # a flood of replies too
    try:
        while True:
            left = end - time.monotonic()
            if left <= 0:
                w.kill()
                raise WorkerTimeout("the whole call took too long")
            m = w.receive(min(check.time_limit, left))
            if m.get("id") != call_id:
                continue  # a late reply to an earlier call (or forged): never counted here
            ev = m.get("ev")
            if ev == "missing":
                return [("missing", str(m.get("what", "not defined")))] * len(cases)
            if ev == "call_done":
                return out
            if ev != "case" or m.get("i") != k or k >= len(cases):
                w.kill()
                out[k:] = [("died", "the process sent a reply out of order")] * (len(cases) - k)
                return out
            if m.get("ok"):
                try:
                    out[k] = ("value", decode(m.get("value")))
                except WireError as exc:
                    out[k] = ("error", f"the returned value could not be read ({exc})")
            else:
                where = f" ({m['where']})" if m.get("where") else ""
                out[k] = ("error", f"raised {str(m.get('error', ''))[:400]}{where}")
            k += 1
    except WorkerTimeout:
        out[k] = ("timeout", f"took longer than {check.time_limit:g} s (stopped)")
    except WorkerDied as exc:
        out[k] = ("died", f"{exc} while running this case")
    return out


def _judge(check: Check, args: tuple, status: str, payload) -> Verdict:
    if status != "value":
        key = {"error": "raised", "timeout": "timeout", "died": "died",
               "missing": "missing", "not run": "not run"}[status]
        if status == "missing":
            payload = f"`{check.function}` is {payload} in the submission"
        elif status == "error" and check.on_error is not None:
            try:
                hint = check.on_error(args, payload)
            except Exception:  # a hint must never stop the grading
                hint = None
            if hint:
                payload = f"{payload}. {hint}"
        return Verdict(False, key, payload)
    try:
        return check.verdict(args, payload)
    except Exception as exc:  # an odd value must not stop the grading
        return Verdict(False, "unchecked", f"the answer could not be checked: "
                                           f"{type(exc).__name__}: {str(exc)[:200]}")


def _summarise(check: Check, cases, results, verdicts) -> dict:
    passed = sum(v.ok for v in verdicts)
    fails = [(c, r, v) for c, r, v in zip(cases, results, verdicts, strict=True) if not v.ok]
    counts = Counter(v.key for _, _, v in fails)
    first = {}
    for _, _, v in fails:
        first.setdefault(v.key, v.message)
    order = sorted(counts.items(), key=lambda kv: (kv[0] == "not run", -kv[1]))  # cause first
    diagnoses = [{"key": key, "count": n, "message": first[key]} for key, n in order]
    examples = []
    for c, (status, payload), v in fails[:EXAMPLES]:
        examples.append({"input": fmt(c), "message": v.message,
                         "expected": None if v.expected is None else fmt(v.expected),
                         "got": fmt(payload) if status == "value" else None})
    total = len(cases)
    score = round(check.points * passed / total, 2) if total else 0.0
    return {"function": check.function, "title": check.title, "points": check.points,
            "score": score, "passed": passed, "total": total, "diagnoses": diagnoses,
            "examples": examples}


def grade(submission, assignment: str | None = None, *, seed: int = 0,
          cell_timeout: float = 60.0, memory_mb: int = 4096) -> dict:
    """Grade one notebook; a JSON-ready dict (see :mod:`kinlib.grade`).

    Never raises for anything the submission does. If the file cannot be read or its
    assignment cannot be told, ``graded`` is False and ``error`` says why.
    """
    path = Path(submission)
    result = {"submission": str(path), "assignment": assignment, "graded": False,
              "error": None, "score": 0.0, "max_score": 0.0, "checks": [], "cells": []}
    try:
        nb = _read(path)
        name = _which(nb, path, assignment)
        spec = load_assignment(name)
    except KinlibError as exc:
        result["error"] = str(exc)
        return result
    result.update(assignment=name, title=spec.title, max_score=spec.max_score)
    cells = [[i, c.get("source")] for i, c in enumerate(nb.cells)
             if isinstance(c, dict) and c.get("cell_type") == "code"
             and isinstance(c.get("source"), str)]  # a cell without source is left out
    session = _Session(cells, cell_timeout, memory_mb)
    try:
        for check in spec.checks:
            cases = check.make_cases(seed)
            results = _run_check(session, check, cases)
            verdicts = [_judge(check, c, s, p) for c, (s, p) in zip(cases, results, strict=True)]
            result["checks"].append(_summarise(check, cases, results, verdicts))
    finally:
        session.close()
    result["cells"] = [r for _, r in sorted(session.reports.items()) if not r["ok"]]
    result["score"] = round(sum(c["score"] for c in result["checks"]), 2)
    result["graded"] = True
    return result


def grade_many(submissions, assignment: str | None = None, *, jobs: int | None = None,
               **kwargs) -> list[dict]:
    """Grade several notebooks in parallel (``jobs`` student processes at a time)."""
    paths = list(submissions)
    jobs = max(1, min(jobs or os.cpu_count() or 1, len(paths) or 1))
    def one(path):  # one submission's failure never loses another's result
        try:
            return grade(path, assignment, **kwargs)
        except Exception as exc:
            return {"submission": str(path), "assignment": assignment, "graded": False,
                    "error": f"the grader failed on this submission: {type(exc).__name__}: "
                             f"{str(exc)[:300]}", "score": 0.0, "max_score": 0.0,
                    "checks": [], "cells": []}

    with ThreadPoolExecutor(max_workers=jobs) as pool:
        return list(pool.map(one, paths))


def _printable(line: str) -> str:
    r"""``line`` with every control or format character (newlines, carriage returns,
    terminal escapes, bidirectional overrides) shown escaped: text from a student's code
    cannot start a line of its own, hide the real total, or recolour the terminal.

    >>> print(_printable("ok\x1b[2K\r  total: 38\n"))
    ok\x1b[2K\r  total: 38\n
    """
    import unicodedata

    return "".join(ch.encode("unicode_escape").decode("ascii")
                   if unicodedata.category(ch) in ("Cc", "Cf") else ch for ch in line)


def format_report(result: dict) -> str:
    """A per-function text report of one :func:`grade` result, for the student; every line
    passes through :func:`_printable`."""
    lines = [f"{result['submission']}"]
    if not result["graded"]:
        return "\n".join(map(_printable, lines + [f"  NOT GRADED: {result['error']}"]))
    lines[0] += f"  ({result['assignment']}: {result.get('title', '')})"
    for c in result["checks"]:
        mark = "ok " if c["passed"] == c["total"] else "   "
        lines.append(f"  {mark}{c['function']:<28} {c['score']:>6g} / {c['points']:<4g} "
                     f"{c['passed']}/{c['total']} cases right")
        for d in c["diagnoses"]:
            lines.append(f"       {d['count']} case(s): {d['message']}")
        for e in c["examples"][:1]:
            lines.append(f"       e.g. input {e['input']}")
            if e["got"] is not None:
                lines.append(f"            you returned {e['got']}")
            if e["expected"] is not None:
                lines.append(f"            expected     {e['expected']}")
    for cell in result["cells"]:
        where = f" ({cell['where']})" if cell["where"] else ""
        lines.append(f"  note: running cell {cell['cell']} gave {cell['error']}{where}")
    lines.append(f"  total: {result['score']:g} / {result['max_score']:g}")
    return "\n".join(map(_printable, lines))


def to_json(result: dict) -> str:
    return json.dumps(result, allow_nan=False, default=str)
