"""``python -m kinlib.grade``: grade submissions, print reports, write JSON results."""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from ._grader import assignment_names, format_report, grade_many, to_json


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="python -m kinlib.grade",
        description="Grade assignment notebooks against kinlib. Exit status 0 when every "
                    "submission could be graded (whatever its score), 2 otherwise.")
    p.add_argument("submissions", nargs="+", type=Path, help="notebooks (.ipynb) to grade")
    p.add_argument("--assignment", choices=assignment_names(),
                   help="which assignment (default: the notebook's metadata or file name)")
    p.add_argument("--json", action="store_true",
                   help="print one JSON object per submission (one per line) instead of "
                        "the text report")
    p.add_argument("--out", type=Path, default=None,
                   help="write each result as OUT/<name>.grade.json (default: next to "
                        "each submission)")
    p.add_argument("--no-write", action="store_true", help="write no result files")
    p.add_argument("--jobs", "-j", type=int, default=None,
                   help="submissions graded at once (default: the number of CPUs)")
    p.add_argument("--seed", type=int, default=0, help="seed of the random cases")
    p.add_argument("--cell-timeout", type=float, default=60.0,
                   help="seconds each notebook cell may run (default 60)")
    p.add_argument("--memory-mb", type=int, default=4096,
                   help="address-space limit of a student process in MiB (default 4096)")
    return p


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
    args = _parser().parse_args(argv)
    if args.jobs is not None and args.jobs < 1:
        _parser().error("--jobs must be at least 1")
    results = grade_many(args.submissions, args.assignment, jobs=args.jobs, seed=args.seed,
                         cell_timeout=args.cell_timeout, memory_mb=args.memory_mb)
    taken: set = set()
    if args.out is not None:
        args.out.mkdir(parents=True, exist_ok=True)
    for r in results:
        if args.json:
            print(to_json(r), flush=True)
        else:
            print(format_report(r), flush=True)
        if not args.no_write and r["graded"]:
            path = _result_path(r, args.out, taken)
            try:
                path.write_text(json.dumps(r, indent=1, allow_nan=False, default=str) + "\n",
                                encoding="utf-8")
            except OSError as exc:
                print(f"could not write {path}: {exc}", file=sys.stderr)
    return 0 if all(r["graded"] for r in results) else 2


if __name__ == "__main__":
    sys.exit(main())
