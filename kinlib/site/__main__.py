"""``python -m kinlib.site [--out site] [--jobs N] [--only NAME ...]``: build the course site.

Exit status 0 when every page was written, 1 when a notebook failed (its name and cell are
printed), 2 for bad arguments.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from ..errors import KinlibError
from . import ROOT, build_site


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="python -m kinlib.site", description=__doc__)
    parser.add_argument("--out", default="site", help="output folder (default: site)")
    parser.add_argument("--notebooks", default=str(ROOT / "notebooks"),
                        help="folder of NN_name.ipynb notebooks (default: the course's)")
    parser.add_argument("--jobs", "-j", type=int, default=1,
                        help="notebooks executed at once (default 1)")
    parser.add_argument("--timeout", type=float, default=600.0,
                        help="seconds a single cell may run (default 600)")
    parser.add_argument("--only", nargs="+", metavar="NAME",
                        help="build only these notebooks (file names without .ipynb)")
    parser.add_argument("--mathjax", help="a MathJax 3 tex-svg-full.js to use (default: "
                        "fetched once with npm into build/)")
    args = parser.parse_args(argv)
    start = time.perf_counter()
    print(f"building the course site in {Path(args.out).resolve()}")
    try:
        seconds = build_site(args.out, args.notebooks, jobs=args.jobs, timeout=args.timeout,
                             only=args.only, mathjax=args.mathjax)
    except KinlibError as exc:
        print(f"site build failed: {exc}", file=sys.stderr)
        return 1
    print(f"{len(seconds)} pages in {time.perf_counter() - start:.1f} s; open "
          f"{(Path(args.out) / 'index.html').resolve().as_uri()}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
