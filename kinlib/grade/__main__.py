"""``python -m kinlib.grade``: grade submissions, print reports, write JSON results."""

from __future__ import annotations

import argparse
import json
import os
import sys
from pathlib import Path

from ..errors import KinlibError
from ._bwrap import SandboxUnavailable
from ._grader import (
    SUBMISSION_TIMEOUT,
    assignment_names,
    cases_seed,
    format_report,
    grade_many,
    summary,
    to_json,
)
from ._practice import as_practice
from ._tiers import TIER_ENV, TIERS
from .class_report import write_report
from .gradebook import count_sources, identify, load_results, write_csv

SECRET_ENV = "KINLIB_GRADE_SECRET"
RESULT_SUFFIX = ".grade.json"
PUBLIC_BATCH = (
    "WARNING: grading {n} submissions on the PUBLIC cases (seed {seed}), which every student "
    "can run with `python -m kinlib.grade --self-check`: a notebook that only looks its "
    "answers up in a table of them, with no code, scores full marks (38/38 on assignment "
    "01). Give --secret-file FILE (or set KINLIB_GRADE_SECRET) to grade on hidden cases.")


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="python -m kinlib.grade",
        description="Grade assignment notebooks against kinlib, each in its own sandbox. "
                    "Exit status 0 when every submission could be graded (whatever its "
                    "score), 2 otherwise. Students: --self-check NOTEBOOK grades your own "
                    "notebook here, as practice.")
    p.add_argument("submissions", nargs="+", type=Path,
                   help="notebooks (.ipynb) to grade; result files written earlier by --out "
                        f"(*{RESULT_SUFFIX}) are read instead, for --csv and --report "
                        "without grading again")
    p.add_argument("--self-check", action="store_true",
                   help="for a student: grade your own notebook on this machine as practice, "
                        "on the public cases, without a sandbox (your code still runs in a "
                        "process of its own, with time limits) and without a secret; every "
                        "report says PRACTICE; writes no result file unless --out is given")
    p.add_argument("--csv", type=Path, default=None, metavar="FILE",
                   help="write a gradebook CSV for Canvas's import: a row per student (told "
                        "from Canvas's Download Submissions file names, a folder per student "
                        "or the file name; the notebook's own claim only when the path names "
                        "nobody), the columns Student, ID, SIS User ID, SIS Login ID, Section, "
                        "then each assignment's total and its functions' points, and a Points "
                        "Possible row; two submissions for one student are left blank and "
                        "named on stderr")
    p.add_argument("--csv-totals-only", action="store_true",
                   help="in --csv, one column per assignment (its total), no functions")
    p.add_argument("--report", type=Path, default=None, metavar="FILE.html",
                   help="write the class report: per assignment and function, how many are "
                        "right, the mean score and the most common mistakes with an example; "
                        "one self-contained HTML page")
    p.add_argument("--assignment", choices=assignment_names(),
                   help="which assignment (default: the notebook's metadata or file name)")
    p.add_argument("--json", action="store_true",
                   help="print one JSON object per submission (one per line, as each is "
                        "graded) instead of the text report; the summary goes to stderr")
    p.add_argument("--out", type=Path, default=None,
                   help="write each result as OUT/<name>.grade.json (default: next to "
                        "each submission; with --self-check, none unless --out is given)")
    p.add_argument("--no-write", action="store_true", help="write no result files")
    p.add_argument("--jobs", "-j", type=int, default=None,
                   help="submissions graded at once (default: the number of CPUs)")
    p.add_argument("--seed", type=int, default=0,
                   help="seed of the random cases (public: default 0, the cases a student "
                        "can run locally)")
    p.add_argument("--secret-file", type=Path, default=None,
                   help="grade on hidden cases made from the secret in this file (or set "
                        f"{SECRET_ENV}); keep it out of what students can see. Grading more "
                        "than one submission without a secret warns: the public cases can be "
                        "answered from a table")
    p.add_argument("--cell-timeout", type=float, default=60.0,
                   help="seconds each notebook cell may run (default 60)")
    p.add_argument("--submission-timeout", type=float, default=SUBMISSION_TIMEOUT,
                   help="seconds one submission may take in all, cells and cases "
                        f"(default {SUBMISSION_TIMEOUT:g})")
    p.add_argument("--memory-mb", type=int, default=4096,
                   help="address-space limit of a student process in MiB (default 4096)")
    p.add_argument("--sandbox", choices=TIERS, default="auto",
                   help="where submissions run: bubblewrap's sandbox where it can run, else, "
                        "for a grader run as root in a container that refuses namespaces "
                        "(Docker's default profile), the container tier (an unprivileged uid "
                        "of its own, Landlock, seccomp); or insist on one (default: auto, or "
                        f"{TIER_ENV})")
    p.add_argument("--unsandboxed", action="store_true",
                   help="run submissions WITHOUT the sandbox (where neither can run); "
                        "their code then has your rights, and every report says so")
    return p


def _protected(args, notebooks: list) -> dict:
    """What a submission must neither read nor write, for the container tier's probe: the
    secret's file, the other hand-ins, and wherever results and reports are written."""
    unreadable = [p for p in (args.secret_file,) if p is not None]
    if len(notebooks) > 1:
        unreadable += notebooks
    out = [args.out] if args.out is not None else sorted({p.parent for p in notebooks})
    unwritable = out + [p.parent for p in (args.csv, args.report) if p is not None]
    return {"unreadable": unreadable + unwritable, "unwritable": unwritable}


def _secret(args, parser) -> str | None:
    env = os.environ.get(SECRET_ENV)
    if args.secret_file is not None:
        if env:
            parser.error(f"give the secret once: --secret-file or {SECRET_ENV}, not both")
        try:
            return args.secret_file.read_text(encoding="utf-8")
        except (OSError, UnicodeDecodeError) as exc:
            parser.error(f"--secret-file: cannot read {args.secret_file}: {exc}")
    return env or None


def _self_check_options(args, parser) -> None:
    """A self-check is a student's practice: refuse what only an instructor's grading has."""
    given = [name for name, on in (("--secret-file", args.secret_file is not None),
                                   ("--seed", args.seed != 0), ("--csv", args.csv),
                                   ("--report", args.report)) if on]
    if given:
        parser.error(f"--self-check runs the public cases as practice, for a student: not "
                     f"with {', '.join(given)} (those are for grading a class)")
    if any(p.name.endswith(RESULT_SUFFIX) for p in args.submissions):
        parser.error(f"--self-check grades notebooks, not result files (*{RESULT_SUFFIX})")
    if os.environ.get(SECRET_ENV):
        print(f"note: {SECRET_ENV} is set but not used: a self-check runs the public cases",
              file=sys.stderr)
    if args.out is None:
        args.no_write = True  # a student needs no result file


def _instructor_files(args, results: list) -> bool:
    """Write --csv and --report; whether everything could be written."""
    ok = True
    if args.csv is not None:
        try:
            problems = write_csv(results, args.csv, totals_only=args.csv_totals_only)
        except OSError as exc:
            print(f"could not write {args.csv}: {exc}", file=sys.stderr)
            return False
        for line in problems:
            print(line, file=sys.stderr)
        print(f"gradebook: {args.csv} (students told from "
              f"{count_sources(identify(results)) or 'no submission'})", file=sys.stderr)
    if args.report is not None:
        try:
            write_report(results, args.report)
        except OSError as exc:
            print(f"could not write {args.report}: {exc}", file=sys.stderr)
            ok = False
        else:
            print(f"class report: {args.report}", file=sys.stderr)
    return ok


def _result_path(result: dict, out: Path | None, taken: set) -> Path:
    sub = Path(result["submission"])
    folder = out if out is not None else sub.parent
    path = folder / f"{sub.stem}.grade.json"
    k = 1
    while path in taken:
        k += 1
        path = folder / f"{sub.stem}.{k}.grade.json"
    taken.add(path)
    return path


def main(argv=None) -> int:
    parser = _parser()
    args = parser.parse_args(argv)
    if args.jobs is not None and args.jobs < 1:
        parser.error("--jobs must be at least 1")
    if args.submission_timeout <= 0 or args.cell_timeout <= 0:
        parser.error("--cell-timeout and --submission-timeout must be positive")
    if args.self_check:
        _self_check_options(args, parser)
    secret = None if args.self_check else _secret(args, parser)  # (a student has none)
    notebooks = [p for p in args.submissions if not p.name.endswith(RESULT_SUFFIX)]
    try:
        earlier = load_results(p for p in args.submissions if p.name.endswith(RESULT_SUFFIX))
    except KinlibError as exc:
        parser.error(str(exc))
    if secret is not None:
        if args.seed != 0:
            parser.error("--seed and a secret both choose the cases: give one of them")
        try:
            cases_seed(secret, "")
        except KinlibError as exc:
            parser.error(str(exc))
    taken: set = set()
    if args.out is not None:
        args.out.mkdir(parents=True, exist_ok=True)

    if secret is None and not args.self_check and len(notebooks) > 1:
        print(PUBLIC_BATCH.format(n=len(notebooks), seed=args.seed), file=sys.stderr,
              flush=True)

    def done(r: dict) -> None:  # each result is printed and written as soon as it is known
        if args.self_check:
            as_practice(r)
        print(to_json(r) if args.json else format_report(r), flush=True)
        if not args.no_write and r["graded"]:
            path = _result_path(r, args.out, taken)
            try:
                path.write_text(json.dumps(r, indent=1, allow_nan=False, default=str) + "\n",
                                encoding="utf-8")
            except OSError as exc:
                print(f"could not write {path}: {exc}", file=sys.stderr)

    try:
        results = grade_many(notebooks, args.assignment, jobs=args.jobs, seed=args.seed,
                             secret=secret, cell_timeout=args.cell_timeout,
                             submission_timeout=args.submission_timeout,
                             memory_mb=args.memory_mb,
                             unsandboxed=args.unsandboxed or args.self_check,
                             sandbox=args.sandbox, **_protected(args, notebooks),
                             on_result=done) if notebooks else []
    except SandboxUnavailable as exc:  # no sandbox here: nothing was run
        print(f"not grading: {exc}", file=sys.stderr)
        return 2
    results += earlier
    print(summary(results), file=sys.stderr if args.json else sys.stdout, flush=True)
    written = _instructor_files(args, results)
    return 0 if written and all(r["graded"] for r in results) else 2


if __name__ == "__main__":
    sys.exit(main())
