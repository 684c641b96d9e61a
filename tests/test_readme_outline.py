"""The README's course outline lists every notebook and each of its exercises, as the
notebooks and kinlib.check have them. ``python tests/test_readme_outline.py`` rewrites
the outline in the README (between its two marker comments) after a change."""

from __future__ import annotations

import re
import sys
from pathlib import Path

import nbformat

from kinlib.check import exercises

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
BEGIN, END = "<!-- outline: begin -->", "<!-- outline: end -->"
PARTS = {"01": "**Part 1 · Spatial descriptions and orientation**",
         "08": "**Part 2 · Kinematic models, inverse and differential kinematics, planning**"}


def outline() -> str:
    lines = []
    for path in sorted((ROOT / "instructor").glob("[0-9][0-9]_*.ipynb")):
        nb = nbformat.read(path, as_version=4)
        title = nb.cells[0].source.splitlines()[0].lstrip("# ").strip()
        number = path.stem[:2]
        if number in PARTS:
            lines += ["", PARTS[number], ""]
        lines.append(f"- [{title}](notebooks/{path.name})")
        lines += [f"  - {e.id} *{e.kind}*: {e.title}" for e in exercises(number)]
    return "\n".join(lines[1:])


def _block(text: str) -> re.Match:
    m = re.search(re.escape(BEGIN) + r"\n(.*?)" + re.escape(END), text, re.S)
    assert m, f"the README has no outline between {BEGIN} and {END}"
    return m


def readme_outline(text: str) -> str:
    return _block(text).group(1).rstrip("\n")


def test_readme_outline_lists_every_notebook_and_exercise():
    expected = outline()
    assert readme_outline(README.read_text()) == expected, \
        "the README's outline is stale: run `python tests/test_readme_outline.py`"
    every = exercises()
    assert sum(line.startswith("  - ") for line in expected.splitlines()) == len(every)


if __name__ == "__main__":
    text = README.read_text()
    new = text.replace(_block(text).group(0), f"{BEGIN}\n{outline()}\n{END}")
    README.write_text(new)
    print("README outline:", "updated" if new != text else "current", file=sys.stderr)
