"""The instructor's solution text, and a search for it in a tree of files.

A *block* is what a student must not receive: the body of each ``### BEGIN SOLUTION`` …
``### END SOLUTION`` block of both sources (``instructor/*.ipynb``,
``assignments/source/*.ipynb``), and each cell tagged ``solution`` (the instructor's
discussion of an answer), with every line stripped and blank lines dropped.

A block is searched for as a whole, line-aligned (``"\\nline1\\nline2\\n"`` in a file's text
normalised the same way), in every file, and each of its lines of at least
:data:`MIN_CHARS` characters on its own (a partial copy). What may legitimately appear in
a student's files is left out of those searches, decided from the sources alone, so the
search is deterministic: the lines of kinlib's own files (the wheel ships the library,
which implements the same mathematics: ``c, s = np.cos(theta), np.sin(theta)`` is in both)
and of the sources outside their solutions (the givens, which the student edition keeps).
A block that is shorter than :data:`MIN_CHARS` or that appears whole in that legitimate
text is *generic*: searching for it everywhere would find its innocent twins. It is checked
in its context instead (:func:`absent_in_context`): the released cell with the same id
must not hold it unless the source cell holds it outside its solution, and a tagged cell's
id must be gone.
"""

from __future__ import annotations

import json
import zipfile
from dataclasses import dataclass
from pathlib import Path

BEGIN, END = "### BEGIN SOLUTION", "### END SOLUTION"
MIN_CHARS = 12  # shorter lines (`else:`, `x = 1`, `return q`) are too common to search for
SOURCES = (("instructor", "notebooks"), ("assignments/source", "assignments"))


def normal(text: str) -> str:
    """Each line stripped, blank lines dropped."""
    return "\n".join(line.strip() for line in text.splitlines() if line.strip())


def _strings(obj):
    """Every string of a JSON document (a notebook's list of source lines as one)."""
    if isinstance(obj, str):
        yield obj
    elif isinstance(obj, list) and obj and all(isinstance(x, str) for x in obj):
        yield "".join(obj)
    elif isinstance(obj, list):
        for x in obj:
            yield from _strings(x)
    elif isinstance(obj, dict):
        for key, value in obj.items():
            yield key
            yield from _strings(value)


def readable(name: str, data: bytes) -> str:
    """A file's text for the search: a notebook's strings (its JSON escapes undone)."""
    text = data.decode("utf-8", errors="replace")
    if name.endswith(".ipynb"):
        try:
            return "\n".join(_strings(json.loads(text)))
        except ValueError:
            return text
    return text


@dataclass(frozen=True)
class Block:
    source: str        # e.g. "instructor/03_euler_and_fixed_angles.ipynb"
    released: str      # the same notebook in the student repository
    cell_id: str
    text: str          # normalised
    outside: str       # the cell's text outside its solution blocks, normalised
    tagged: bool       # a whole cell tagged "solution"


def blocks(root: Path) -> tuple[list[Block], list[str]]:
    """Every solution block of the sources under ``root``, and the legitimate text (each
    source cell outside its blocks, untagged cells only)."""
    found, legit = [], []
    for src, dst in SOURCES:
        for path in sorted((root / src).glob("*.ipynb")):
            nb = json.loads(path.read_text(encoding="utf-8"))
            where, released = f"{src}/{path.name}", f"{dst}/{path.name}"
            for cell in nb["cells"]:
                text = "".join(cell["source"])
                if "solution" in cell.get("metadata", {}).get("tags", ()):
                    found.append(Block(where, released, cell["id"], normal(text), "", True))
                    continue
                outside, bodies, body, inside = [], [], [], False
                for line in text.split("\n"):
                    if line.strip() == BEGIN:
                        inside, body = True, []
                    elif line.strip() == END:
                        inside = False
                        bodies.append(body)
                    else:
                        (body if inside else outside).append(line)
                kept = normal("\n".join(outside))
                legit.append(kept)
                found += [Block(where, released, cell["id"], normal("\n".join(b)), kept, False)
                          for b in bodies]
    return found, legit


def library_text(root: Path) -> list[str]:
    """The text of kinlib's files in the checkout (what its wheel ships)."""
    return [normal(p.read_text(encoding="utf-8", errors="replace"))
            for p in sorted((root / "kinlib").rglob("*"))
            if p.is_file() and "__pycache__" not in p.parts and p.suffix != ".pyc"]


def tree_text(folder: Path) -> dict[str, str]:
    """Every file under ``folder`` but ``.git``, and every member of each wheel
    (``wheels/x.whl!kinlib/...``): name -> normalised text."""
    out = {}
    for path in sorted(p for p in folder.rglob("*") if p.is_file()):
        rel = path.relative_to(folder).as_posix()
        if rel.split("/")[0] == ".git":
            continue
        data = path.read_bytes()
        if path.suffix == ".whl":
            with zipfile.ZipFile(path) as whl:
                for member in whl.namelist():
                    out[f"{rel}!{member}"] = normal(readable(member, whl.read(member)))
        else:
            out[rel] = normal(readable(rel, data))
    return out


def is_generic(block: Block, legit: list[str]) -> bool:
    needle = f"\n{block.text}\n"
    return len(block.text) < MIN_CHARS or any(needle in f"\n{doc}\n" for doc in legit)


def found_in(block: Block, texts: dict[str, str], legit_lines: set[str]) -> list[str]:
    """Where ``block`` (whole, or one of its searchable lines) is in ``texts``."""
    needle = f"\n{block.text}\n"
    lines = [line for line in block.text.split("\n")
             if len(line) >= MIN_CHARS and line not in legit_lines]
    hits = []
    for name, text in texts.items():
        if needle in f"\n{text}\n":
            hits.append(f"{name} (the whole block)")
        elif lines:
            have = set(text.split("\n"))
            hits += [f"{name}: {line!r}" for line in lines if line in have]
    return hits


def absent_in_context(block: Block, released: dict) -> str | None:
    """None if the released notebook (``released``: parsed JSON) does not hold ``block``
    where the source had it; else what is wrong."""
    cells = {c["id"]: normal("".join(c["source"])) for c in released["cells"]}
    if block.tagged:
        return f"cell {block.cell_id} is there" if block.cell_id in cells else None
    if block.cell_id not in cells:
        return None
    if f"\n{block.text}\n" in f"\n{cells[block.cell_id]}\n" \
            and f"\n{block.text}\n" not in f"\n{block.outside}\n":
        return f"cell {block.cell_id} holds it"
    return None
