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

SECRET_ENV = "KINLIB_GRADE_SECRET"


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="python -m kinlib.grade",
        description="Grade assignment notebooks against kinlib, each in its own sandbox. "
                    "Exit status 0 when every submission could be graded (whatever its "
                    "score), 2 otherwise.")
    p.add_argument("submissions", nargs="+", type=Path, help="notebooks (.ipynb) to grade")
    p.add_argument("--assignment", choices=assignment_names(),
                   help="which assignment (default: the notebook's metadata or file name)")
    p.add_argument("--json", action="store_true",
                   help="print one JSON object per submission (one per line, as each is "
                        "graded) instead of the text report; the summary goes to stderr")
    p.add_argument("--out", type=Path, default=None,
                   help="write each result as OUT/<name>.grade.json (default: next to "
                        "each submission)")
    p.add_argument("--no-write", action="store_true", help="write no result files")
    p.add_argument("--jobs", "-j", type=int, default=None,
                   help="submissions graded at once (default: the number of CPUs)")
    p.add_argument("--seed", type=int, default=0,
                   help="seed of the random cases (public: default 0, the cases a student "
                        "can run locally)")
    p.add_argument("--secret-file", type=Path, default=None,
                   help="grade on hidden cases made from the secret in this file (or set "
                        f"{SECRET_ENV}); keep it out of what students can see")
    p.add_argument("--cell-timeout", type=float, default=60.0,
                   help="seconds each notebook cell may run (default 60)")
    p.add_argument("--submission-timeout", type=float, default=SUBMISSION_TIMEOUT,
                   help="seconds one submission may take in all, cells and cases "
                        f"(default {SUBMISSION_TIMEOUT:g})")
    p.add_argument("--memory-mb", type=int, default=4096,
                   help="address-space limit of a student process in MiB (default 4096)")
    p.add_argument("--unsandboxed", action="store_true",
                   help="run submissions WITHOUT the sandbox (where bubblewrap cannot run); "
                        "their code then has your rights, and every report says so")
    return p


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
    secret = _secret(args, parser)
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

    def done(r: dict) -> None:  # each result is printed and written as soon as it is known
        print(to_json(r) if args.json else format_report(r), flush=True)
        if not args.no_write and r["graded"]:
            path = _result_path(r, args.out, taken)
            try:
                path.write_text(json.dumps(r, indent=1, allow_nan=False, default=str) + "\n",
                                encoding="utf-8")
            except OSError as exc:
                print(f"could not write {path}: {exc}", file=sys.stderr)

    try:
        results = grade_many(args.submissions, args.assignment, jobs=args.jobs, seed=args.seed,
                             secret=secret, cell_timeout=args.cell_timeout,
                             submission_timeout=args.submission_timeout,
                             memory_mb=args.memory_mb, unsandboxed=args.unsandboxed,
                             on_result=done)
    except SandboxUnavailable as exc:  # no sandbox here: nothing was run
        print(f"not grading: {exc}", file=sys.stderr)
        return 2
    print(summary(results), file=sys.stderr if args.json else sys.stdout, flush=True)
    return 0 if all(r["graded"] for r in results) else 2


if __name__ == "__main__":
    sys.exit(main())
