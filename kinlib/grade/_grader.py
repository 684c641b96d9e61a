"""Grade a submission: run it in a student process, call its functions, judge the answers.

The student's process (:mod:`kinlib.grade._sandbox`, inside the sandbox of
:mod:`kinlib.grade._bwrap`) only ever sends plain data; every comparison happens here, with
kinlib's reference in this process, so nothing the submission does to numpy, kinlib or its
own process can change a verdict. A cell that hangs or ends the process is skipped on the
next start; a case that hangs or ends the process fails, the rest of that function's cases
are not run, and the next function gets a fresh process. Every wait has a deadline that
messages cannot extend: per cell, per case, per check, and for the whole submission.
"""

from __future__ import annotations

import hashlib
import json
import os
import secrets
import time
from collections import Counter
from concurrent.futures import ThreadPoolExecutor, as_completed
from pathlib import Path

from ..errors import KinlibError
from ._bwrap import Sandbox
from ._checks import Assignment, Check, Verdict, fmt, once_per_case, shared_cases
from ._container import Container
from ._sandbox import BLOCKED, Worker, WorkerDied, WorkerTimeout
from ._tiers import find_isolation
from ._wire import WireError, decode, encode

__all__ = ["grade", "grade_many", "format_report", "load_assignment", "assignment_names",
           "summary", "cases_seed", "GradeResult"]

MAX_RESTARTS = 12
EXAMPLES = 3
#: seconds one submission may take in all, whatever its cells and cases do
SUBMISSION_TIMEOUT = 300.0
UNSANDBOXED = ("graded WITHOUT the sandbox (--unsandboxed): the submission's code ran with "
               "the grader's own rights and could have read or changed anything they reach, "
               "this result included")


class OutOfTime(RuntimeError):
    """The submission used all of its time (:data:`SUBMISSION_TIMEOUT`)."""


def cases_seed(secret: str | bytes, assignment: str) -> int:
    """The seed of the graded cases, from the instructor's secret (one per assignment).

    >>> cases_seed("correct horse", "01_rotations") == cases_seed(b"correct horse", "01_rotations")
    True
    >>> cases_seed("correct horse", "01_rotations") != cases_seed("correct horse", "04_planning")
    True
    """
    key = secret.encode() if isinstance(secret, str) else bytes(secret)
    if not key.strip():
        raise KinlibError("secret: expected a non-empty secret (a file's contents or "
                          "KINLIB_GRADE_SECRET), got an empty one")
    digest = hashlib.sha256(b"kinlib-grade\0" + key.strip() + b"\0" + assignment.encode())
    return int.from_bytes(digest.digest()[:8], "little")


def assignment_names() -> list[str]:
    from .assignments import ASSIGNMENTS

    return sorted(ASSIGNMENTS)


def load_assignment(name: str) -> Assignment:
    """The :class:`Assignment` called ``name`` (e.g. ``"01_rotations"``)."""
    from .assignments import ASSIGNMENTS

    if name not in ASSIGNMENTS:
        raise KinlibError(f"assignment: expected one of {sorted(ASSIGNMENTS)}, got {name!r}")
    return ASSIGNMENTS[name]()


#: the largest notebook file read (a hand-in with big images stays well below it)
MAX_NOTEBOOK_BYTES = 100 * 1024 * 1024


def _read(path: Path) -> dict:
    """The notebook at ``path`` as plain JSON: ``{"metadata": dict, "cells": [{"cell_type",
    "source": str}, ...]}`` (sources joined). Read with :mod:`json`, not nbformat, whose
    schema validation costs about 2 s per grader process to import and is not needed to
    find the code cells; notebooks older than format 4 go through nbformat's converter."""
    try:
        size = path.stat().st_size
        if size > MAX_NOTEBOOK_BYTES:
            raise KinlibError(f"{path}: expected a notebook of at most "
                              f"{MAX_NOTEBOOK_BYTES >> 20} MiB, the file has {size >> 20} MiB")
        data = json.loads(path.read_bytes())
    except FileNotFoundError:
        raise KinlibError(f"{path}: no such file") from None
    except KinlibError:
        raise
    except Exception as exc:  # not UTF-8, not JSON, too deep, a directory...
        raise KinlibError(f"{path}: expected a Jupyter notebook (.ipynb), could not read it: "
                          f"{type(exc).__name__}: {str(exc)[:200]}") from None
    if isinstance(data, dict) and isinstance(data.get("nbformat"), int) \
            and data["nbformat"] < 4 and "worksheets" in data:
        from .._optional import course_import  # an old notebook: nbformat's converter

        nbformat = course_import("nbformat", f"{path}: an old notebook (format "
                                             f"{data['nbformat']}), to be converted,")
        try:
            data = json.loads(nbformat.writes(nbformat.reads(json.dumps(data), as_version=4)))
        except Exception as exc:
            raise KinlibError(f"{path}: an old notebook (format {data['nbformat']}) that could "
                              f"not be converted: {str(exc)[:200]}") from None
    if not isinstance(data, dict) or not isinstance(data.get("cells"), list):
        raise KinlibError(f"{path}: expected a Jupyter notebook (a JSON object with a list of "
                          "cells), got something else")
    cells = []
    for c in data["cells"]:
        if not isinstance(c, dict):  # (kept as a place, so that cell numbers stay the file's)
            c = {}
        source = c.get("source")
        if isinstance(source, list) and all(isinstance(x, str) for x in source):
            source = "".join(source)
        cells.append({"cell_type": c.get("cell_type"),
                      "source": source if isinstance(source, str) else None})
    meta = data.get("metadata")
    return {"metadata": meta if isinstance(meta, dict) else {}, "cells": cells}


def _which(nb, path: Path, assignment: str | None) -> str:
    if assignment is not None:
        return assignment
    meta = nb["metadata"].get("kinlib", {})
    name = meta.get("assignment") if isinstance(meta, dict) else None
    names = assignment_names()
    if isinstance(name, str) and name in names:
        return name
    for n in names:
        if path.stem.startswith(n) or path.stem.startswith(n[:3]):
            return n
    for n in names:  # a name with a prefix: Canvas's lastfirst_12345_6789012_01_rotations
        if f"_{n}" in path.stem:
            return n
    raise KinlibError(f"{path}: cannot tell which assignment this is (no kinlib metadata and "
                      f"the file name does not start with or hold one of {names}); give it "
                      "(--assignment, or assignment=)")


class _Session:
    """The student's process for one submission, restarted when it hangs or dies."""

    def __init__(self, cells, cell_timeout: float, memory_mb: int,
                 sandbox: Sandbox | Container | None,
                 budget: float):
        self.cells, self.cell_timeout, self.memory_mb = cells, cell_timeout, memory_mb
        self.sandbox, self.budget = sandbox, budget
        self.deadline = time.monotonic() + budget  # for all cells and cases together
        self.skip: set[int] = set()
        self.reports: dict[int, dict] = {}
        self.worker: Worker | None = None
        self.restarts = 0

    def ready(self) -> Worker:
        """A process that has run every cell not known to hang or kill it."""
        while self.worker is None or not self.worker.alive:
            if self.worker is not None:
                self.worker.close()
            if time.monotonic() >= self.deadline:
                raise OutOfTime("the submission used all of its time")
            if self.restarts > MAX_RESTARTS:
                raise WorkerDied(f"the submission's process was restarted {MAX_RESTARTS} "
                                 "times; giving up")
            self.restarts += 1
            self.worker = Worker(sandbox=self.sandbox, memory_mb=self.memory_mb)
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
        end = min(time.monotonic() + self.cell_timeout * (len(batch) + 1), self.deadline)

        def index(m) -> int | None:
            i = m.get("i")
            return i if type(i) is int and i in sent else None  # forged or odd: ignored

        try:
            w.request({"op": "cells", "cells": batch},  # (read in time, or the process dies)
                      timeout=max(0.05, min(self.cell_timeout, end - time.monotonic())))
            while True:
                now = time.monotonic()
                due = min(end, cell_end) if cell_end is not None else end
                if now >= due:
                    raise WorkerTimeout("the cells took too long")  # (or all its time)
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
            if isinstance(exc, WorkerDied):
                what = f"ended the process: {exc}"
            elif time.monotonic() >= self.deadline:
                what = (f"was running when the submission used all of its time "
                        f"({self.budget:g} s) and was stopped")
            else:
                what = f"ran longer than {self.cell_timeout:g} s and was stopped"
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
        # the whole call (its request, a flood of replies too), and the submission's deadline
        end = min(time.monotonic() + check.time_limit * (len(cases) + 1), session.deadline)
        w.request({"op": "call", "id": call_id, "name": check.function,
                   "cases": [encode(c, exact=True) for c in cases]},  # (pi/2 stays pi/2)
                  timeout=max(0.05, min(check.time_limit, end - time.monotonic())))
    except WorkerDied as exc:
        return [("died", str(exc))] * len(cases)
    except OutOfTime:
        return [("not run", _out_of_time(session))] * len(cases)
    k = 0
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
        if time.monotonic() >= session.deadline:
            out[k:] = [("not run", _out_of_time(session))] * (len(cases) - k)
        else:
            out[k] = ("timeout", f"took longer than {check.time_limit:g} s (stopped)")
    except WorkerDied as exc:
        out[k] = ("died", f"{exc} while running this case")
    return out


def _out_of_time(session: _Session) -> str:
    return (f"not run: the submission used all of its time ({session.budget:g} s for all "
            "cells and cases together)")


def _judge(check: Check, args: tuple, status: str, payload, memo: dict | None = None) -> Verdict:
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
        return check.verdict(args, payload, memo)
    except Exception as exc:  # an odd value must not stop the grading
        return Verdict(False, "unchecked", f"the answer could not be checked: "
                                           f"{type(exc).__name__}: {str(exc)[:200]}")


def _is_trivial(check: Check, case, memo: dict | None = None) -> bool:
    def trivial() -> bool:
        try:
            return bool(check.is_trivial(case))
        except Exception:  # a reference that fails on a case: judge that case like any other
            return False

    return once_per_case(memo, "trivial", trivial)


def _judged(check: Check, cases, memos, results) -> dict:
    """The check's part of a result: each case's answer (``results``: (status, payload)
    per case) judged with the case's memo (:func:`shared_cases`), and summarised."""
    verdicts = [_judge(check, c, s, p, m)
                for c, (s, p), m in zip(cases, results, memos, strict=True)]
    return _summarise(check, cases, results, verdicts, memos)


def _summarise(check: Check, cases, results, verdicts, memos) -> dict:
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
    credit = passed
    if check.is_trivial is not None:  # right "trivial" answers count only beside right others
        trivial = [_is_trivial(check, c, m) for c, m in zip(cases, memos, strict=True)]
        main = [v.ok for v, t in zip(verdicts, trivial, strict=True) if not t]
        easy = sum(v.ok for v, t in zip(verdicts, trivial, strict=True) if t)
        rate = sum(main) / len(main) if main else 1.0
        weight = min(1.0, max(0.0, (rate - 0.5) / 0.25))
        credit = sum(main) + weight * easy
        if easy and weight < 1:
            diagnoses.append({"key": "trivial", "count": easy, "message": (
                f"{easy} right answer(s) {check.trivial} count {weight:.0%}: they earn credit "
                f"only when most other cases are right (here {sum(main)} of {len(main)}; "
                "none below 50 %, in full from 75 %)")})
    score = round(check.points * credit / total, 2) if total else 0.0
    return {"function": check.function, "title": check.title, "points": check.points,
            "score": score, "passed": passed, "total": total, "diagnoses": diagnoses,
            "examples": examples}


class GradeResult(dict):
    """The result of :func:`grade`: the JSON-ready dict of :mod:`kinlib.grade` (every key
    reads as before: ``r["score"]``, ``r["checks"]``), with the flag every kinlib result
    carries and its JSON text.

    ``success`` is ``r["graded"]``: whether the submission could be graded at all (not
    whether it scored well). It is a property, not a key, so the JSON is unchanged.

    >>> r = GradeResult(submission="a.ipynb", graded=False, error="not a notebook")
    >>> r.success, r["error"]
    (False, 'not a notebook')
    >>> r.to_json()
    '{"submission": "a.ipynb", "graded": false, "error": "not a notebook"}'
    """

    __slots__ = ()

    @property
    def success(self) -> bool:
        """Whether the submission was graded (``self["graded"]``)."""
        return bool(self.get("graded", False))

    def to_json(self) -> str:
        """One line of JSON (NaN/inf refused; anything else unusual as its ``str``): what
        ``python -m kinlib.grade --json`` prints."""
        return json.dumps(self, allow_nan=False, default=str)


def not_graded(submission, assignment: str | None, error: str | None,
               max_score: float = 0.0) -> GradeResult:
    """A result with nothing graded (yet): ``error`` says why."""
    return GradeResult(submission=str(submission), assignment=assignment, graded=False,
                       error=error, score=0.0, max_score=max_score, checks=[], cells=[])


def grade(submission, assignment: str | None = None, *, seed: int = 0,
          secret: str | bytes | None = None, cell_timeout: float = 60.0,
          memory_mb: int = 4096, submission_timeout: float = SUBMISSION_TIMEOUT,
          unsandboxed: bool = False, sandbox: str = "auto", unreadable=(),
          unwritable=()) -> GradeResult:
    """Grade one notebook: a :class:`GradeResult`, the JSON-ready dict of
    :mod:`kinlib.grade` with ``.success`` (graded) and ``.to_json()``.

    The cases come from ``seed`` (public: a student can run the same ones), or, if
    ``secret`` is given, from the instructor's secret (:func:`cases_seed`). The submission's
    code runs isolated (:mod:`kinlib.grade._tiers`): in the bubblewrap sandbox where bwrap
    can run, else, for a root grader in a container, in the container tier (``sandbox``:
    ``"auto"``, ``"bubblewrap"`` or ``"container"``; ``unreadable`` and ``unwritable``: the
    paths the container tier must prove hidden, besides kinlib). The result names the tier
    (``"tier"``) and what it did (``"sandbox"``). With neither this raises
    :class:`~kinlib.grade._bwrap.SandboxUnavailable` (naming the fix) unless
    ``unsandboxed=True``, which marks the result (``"sandbox": null``, ``"tier": null`` and a
    ``warning``).

    Never raises for anything the submission does. If the file cannot be read or its
    assignment cannot be told, ``graded`` is False and ``error`` says why.
    """
    isolation = None if unsandboxed else find_isolation(BLOCKED, sandbox, unreadable,
                                                         unwritable)
    path = Path(submission)
    result = not_graded(path, assignment, None)
    result["sandbox"] = None if isolation is None else isolation.describe()
    result["tier"] = None if isolation is None else isolation.tier
    if isolation is None:
        result["warning"] = UNSANDBOXED
    try:
        nb = _read(path)
        name = _which(nb, path, assignment)
        spec = load_assignment(name)
        seed = cases_seed(secret, name) if secret is not None else int(seed)
    except KinlibError as exc:
        result["error"] = str(exc)
        return result
    result.update(assignment=name, title=spec.title, max_score=spec.max_score,
                  cases="secret" if secret is not None else f"public (seed {seed})")
    cells = [[i, c["source"]] for i, c in enumerate(nb["cells"])
             if c["cell_type"] == "code" and c["source"] is not None]  # (no source: left out)
    session = _Session(cells, cell_timeout, memory_mb, isolation, submission_timeout)
    try:
        for check in spec.checks:
            cases, memos = shared_cases(name, check, seed)
            result["checks"].append(_judged(check, cases, memos,
                                            _run_check(session, check, cases)))
    finally:
        session.close()
    result["cells"] = [r for _, r in sorted(session.reports.items()) if not r["ok"]]
    result["score"] = round(sum(c["score"] for c in result["checks"]), 2)
    result["graded"] = True
    return result


def grade_many(submissions, assignment: str | None = None, *, jobs: int | None = None,
               on_result=None, **kwargs) -> list[GradeResult]:
    """Grade several notebooks in parallel (``jobs`` student processes at a time); the
    results in the order of ``submissions``. ``on_result(result)`` is called (in this
    thread) for each one as soon as it is known. Keyword arguments go to :func:`grade`.

    The sandbox is looked for once, first: without one this raises
    :class:`~kinlib.grade._bwrap.SandboxUnavailable` before anything runs (unless
    ``unsandboxed=True``).
    """
    paths = list(submissions)
    if not kwargs.get("unsandboxed"):
        find_isolation(BLOCKED, kwargs.get("sandbox", "auto"), kwargs.get("unreadable", ()),
                       kwargs.get("unwritable", ()))
    jobs = max(1, min(jobs or os.cpu_count() or 1, len(paths) or 1))

    def one(path):  # one submission's failure never loses another's result
        try:
            return grade(path, assignment, **kwargs)
        except Exception as exc:
            return not_graded(path, assignment, "the grader failed on this submission: "
                                                f"{type(exc).__name__}: {str(exc)[:300]}")

    out: list = [None] * len(paths)
    with ThreadPoolExecutor(max_workers=jobs) as pool:
        futures = {pool.submit(one, p): k for k, p in enumerate(paths)}
        for future in as_completed(futures):
            out[futures[future]] = result = future.result()
            if on_result is not None:
                on_result(result)
    return out


def summary(results: list[dict]) -> str:
    """One line on a batch: how many were graded, the mean score, and any warnings."""
    graded = [r for r in results if r["graded"]]
    line = f"graded {len(graded)} of {len(results)} submission(s)"
    if len(graded) < len(results):
        line += f" ({len(results) - len(graded)} could not be graded)"
    if graded:
        line += f"; mean score {sum(r['score'] for r in graded) / len(graded):.4g}"
        maxima = {r["max_score"] for r in graded}
        if len(maxima) == 1:  # one assignment: out of its maximum
            line += f" / {maxima.pop():g}"
    if any(r.get("warning") for r in results):
        line += "; WITHOUT the sandbox"
    # a class graded on the public cases (not a student's self-check): they could be
    # answered from a table of them, with no code (kinlib.grade.__main__ says more)
    public = [r for r in graded if str(r.get("cases", "")).startswith("public")
              and not r.get("practice")]
    if len(results) > 1 and public:
        line += (f"; WARNING: {len(public)} graded on the PUBLIC cases, which students can "
                 "run and answer from a table: give --secret-file for hidden cases")
    return line


def _printable(line: str) -> str:
    r"""``line`` with every control or format character (newlines, carriage returns,
    terminal escapes, bidirectional overrides), lone surrogate, private-use or unassigned
    one shown escaped: text from a student's code cannot start a line of its own, hide the
    real total, recolour the terminal, or make the report unprintable.

    >>> print(_printable("ok\x1b[2K\r  total: 38\n"))
    ok\x1b[2K\r  total: 38\n
    >>> _printable("\ud800 nope").encode("utf-8")
    b'\\ud800 nope'
    """
    import unicodedata

    return "".join(ch.encode("unicode_escape").decode("ascii")
                   if unicodedata.category(ch) in ("Cc", "Cf", "Cs", "Co", "Cn") else ch
                   for ch in line)


def check_lines(check: dict) -> list[str]:
    """What went wrong in one function's check: its diagnoses, then one example."""
    lines = [f"{d['count']} case(s): {d['message']}" for d in check["diagnoses"]]
    for e in check["examples"][:1]:
        lines.append(f"e.g. input {e['input']}")
        if e["got"] is not None:
            lines.append(f"     you returned {e['got']}")
        if e["expected"] is not None:
            lines.append(f"     expected     {e['expected']}")
    return lines


def format_report(result: dict) -> str:
    """A per-function text report of one :func:`grade` result, for the student; every line
    passes through :func:`_printable`."""
    # a self-check (kinlib.grade._practice) says so first
    first = [f"PRACTICE: {result.get('note', '')}"] if result.get("practice") else []
    lines = [f"{result['submission']}"]
    if result.get("warning"):
        lines.append(f"  WARNING: {result['warning']}")
    if not result["graded"]:
        return "\n".join(map(_printable, first + lines + [f"  NOT GRADED: {result['error']}"]))
    lines[0] += f"  ({result['assignment']}: {result.get('title', '')})"
    for c in result["checks"]:
        mark = "ok " if c["passed"] == c["total"] else "   "
        lines.append(f"  {mark}{c['function']:<28} {c['score']:>6g} / {c['points']:<4g} "
                     f"{c['passed']}/{c['total']} cases right")
        lines += ["       " + line for line in check_lines(c)]
    for cell in result["cells"]:
        where = f" ({cell['where']})" if cell["where"] else ""
        lines.append(f"  note: running cell {cell['cell']} gave {cell['error']}{where}")
    lines.append(f"  total: {result['score']:g} / {result['max_score']:g}")
    if result.get("sandbox"):  # the isolation tier it ran in
        lines.append(f"  graded in: {result['sandbox']}")
    return "\n".join(map(_printable, first + lines))


def to_json(result: dict) -> str:
    """``result`` as one line of JSON (:meth:`GradeResult.to_json`, for any dict)."""
    return GradeResult.to_json(result)
