"""``python -m kinlib.site [--out site] [--notebooks notebooks] [--jobs N] [--only NAME ...]
[--executed]``: build the course site.

Run from the course repository's root (``make site``), or give the folders: ``--notebooks``
(default ``notebooks/``), ``--out`` (default ``site/``) and ``--mathjax`` (default: fetched
once with npm into ``build/``), all relative to the current directory. ``--executed``
exports notebooks that have run and were saved (with JupyterLab's *Settings → Save Widget
State Automatically* ticked, for the 3-D scenes) without running them again.

Exit status 0 when every page was written, 1 when a notebook failed (its name and cell are
printed), 2 for bad arguments (a missing notebooks folder among them) or when the course's
tools are not installed (``pip install 'kinlib[course]'``).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from .._optional import COURSE_MODULES, course_import
from ..errors import KinlibError
from . import NOTEBOOKS, build_site

PROG = "python -m kinlib.site"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog=PROG, description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", default="site", help="output folder (default: site)")
    parser.add_argument("--notebooks", default=None,
                        help=f"folder of NN_name.ipynb notebooks (default: {NOTEBOOKS}/ of "
                             "the current directory)")
    parser.add_argument("--jobs", "-j", type=int, default=1,
                        help="notebooks executed at once (default 1)")
    parser.add_argument("--timeout", type=float, default=600.0,
                        help="seconds a single cell may run (default 600)")
    parser.add_argument("--only", nargs="+", metavar="NAME",
                        help="build only these notebooks (file names without .ipynb)")
    parser.add_argument("--executed", action="store_true",
                        help="the notebooks have run and were saved with their outputs and "
                             "widget state: export them without running them")
    parser.add_argument("--mathjax", help="a MathJax 3 tex-svg-full.js to use (default: "
                        "fetched once with npm into build/)")
    args = parser.parse_args(argv)
    notebooks = Path(args.notebooks) if args.notebooks is not None else NOTEBOOKS
    if not notebooks.is_dir():
        which = "--notebooks" if args.notebooks is not None else f"the default {NOTEBOOKS}/"
        parser.error(f"{which}: no folder {notebooks} in {Path.cwd()}; run from the course "
                     "repository's root or give the notebooks' folder with --notebooks")
    try:
        for name in COURSE_MODULES:
            course_import(name, PROG)
    except KinlibError as exc:
        print(f"{PROG}: {exc}", file=sys.stderr)
        return 2
    start = time.perf_counter()
    how = "exporting the saved notebooks (not run again)" if args.executed else "building"
    print(f"{how}: the course site in {Path(args.out).resolve()}")
    try:
        seconds = build_site(args.out, notebooks, jobs=args.jobs, timeout=args.timeout,
                             only=args.only, mathjax=args.mathjax, executed=args.executed)
    except KinlibError as exc:
        print(f"site build failed: {exc}", file=sys.stderr)
        return 1
    print(f"{len(seconds)} pages in {time.perf_counter() - start:.1f} s; open "
          f"{(Path(args.out) / 'index.html').resolve().as_uri()}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
