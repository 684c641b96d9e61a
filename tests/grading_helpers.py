"""Helpers of the grader tests: build submissions from a source notebook's own code."""

from pathlib import Path

import nbformat

ROOT = Path(__file__).resolve().parents[1] / "assignments"


def solution_code(name: str) -> str:
    """The source notebook's imports and function definitions (not its test cells)."""
    nb = nbformat.read(ROOT / "source" / f"{name}.ipynb", as_version=4)
    return "\n\n".join(c.source for c in nb.cells
                        if c.cell_type == "code" and not c.source.startswith("# your tests"))


def write_notebook(path: Path, *cells: str, assignment: str | None = None) -> Path:
    nb = nbformat.v4.new_notebook()
    nb.cells = [nbformat.v4.new_code_cell(c) for c in cells]
    if assignment:
        nb.metadata["kinlib"] = {"assignment": assignment}
    nbformat.write(nb, path)
    return path


def patched(code: str, *edits: tuple[str, str]) -> str:
    for old, new in edits:
        assert code.count(old) == 1, f"patch target not found once: {old!r}"
        code = code.replace(old, new)
    return code


def by_function(result: dict) -> dict:
    return {c["function"]: c for c in result["checks"]}


def top(check: dict) -> str:
    return check["diagnoses"][0]["key"] if check["diagnoses"] else ""
