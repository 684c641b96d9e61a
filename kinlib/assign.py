"""Make the student versions of the assignment notebooks: ``python -m kinlib.assign``.

Each ``assignments/source/NN_name.ipynb`` holds the instructor's solution between
``### BEGIN SOLUTION`` and ``### END SOLUTION`` lines (the nbgrader convention). The student
version ``assignments/release/NN_name.ipynb`` is the same notebook with every such block
replaced by ``raise NotImplementedError`` (indented like the ``BEGIN`` line), and no outputs
or execution counts. ``--check`` writes nothing and exits 1 if a release is missing or stale.

>>> print(release_source('''def f(x):
...     \"\"\"Twice x.\"\"\"
...     ### BEGIN SOLUTION
...     return 2 * x
...     ### END SOLUTION'''))
def f(x):
    \"\"\"Twice x.\"\"\"
    raise NotImplementedError
"""

from __future__ import annotations

import argparse
import re
import sys
from pathlib import Path

from .errors import KinlibError

__all__ = ["release_source", "release_notebook", "main", "BEGIN", "END"]

BEGIN = "### BEGIN SOLUTION"
END = "### END SOLUTION"
_ROOT = Path(__file__).resolve().parents[1] / "assignments"


def release_source(source: str, where: str = "cell") -> str:
    """``source`` with each solution block replaced by ``raise NotImplementedError``."""
    out, inside = [], False
    for n, line in enumerate(source.split("\n"), 1):
        stripped = line.strip()
        if stripped == BEGIN:
            if inside:
                raise KinlibError(f"{where}, line {n}: {BEGIN} inside another solution block")
            inside = True
            out.append(line[:len(line) - len(line.lstrip())] + "raise NotImplementedError")
        elif stripped == END:
            if not inside:
                raise KinlibError(f"{where}, line {n}: {END} without a {BEGIN}")
            inside = False
        elif not inside:
            out.append(line)
    if inside:
        raise KinlibError(f"{where}: {BEGIN} without an {END}")
    return "\n".join(out)


def release_notebook(nb):
    """The student version of a source notebook (a new nbformat node)."""
    import copy

    student = copy.deepcopy(nb)
    for i, cell in enumerate(student.cells):
        if cell.cell_type == "code":
            cell.source = release_source(cell.source, f"cell {i}")
            cell.outputs = []
            cell.execution_count = None
        elif re.search(r"^\s*" + re.escape(BEGIN), cell.source, re.M):
            raise KinlibError(f"cell {i}: solution markers belong in code cells")
    return student


def _pairs(root: Path):
    sources = sorted((root / "source").glob("*.ipynb"))
    if not sources:
        raise KinlibError(f"no source notebooks in {root / 'source'}")
    return [(s, root / "release" / s.name) for s in sources]


def main(argv=None) -> int:
    import nbformat

    p = argparse.ArgumentParser(prog="python -m kinlib.assign", description=__doc__.split(
        "\n\n")[0])
    p.add_argument("--root", type=Path, default=_ROOT, help="the assignments folder")
    p.add_argument("--check", action="store_true",
                   help="write nothing; exit 1 if a release is missing or out of date")
    args = p.parse_args(argv)
    stale = []
    for src, dst in _pairs(args.root):
        text = nbformat.writes(release_notebook(nbformat.read(src, as_version=4))) + "\n"
        if dst.exists() and dst.read_text(encoding="utf-8") == text:
            continue
        stale.append(dst)
        if not args.check:
            dst.parent.mkdir(parents=True, exist_ok=True)
            dst.write_text(text, encoding="utf-8")
            print(f"wrote {dst}")
    if args.check and stale:
        print("out of date (run `python -m kinlib.assign`): "
              + ", ".join(str(s) for s in stale), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
