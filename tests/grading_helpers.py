"""Helpers of the grader tests: build submissions from a source notebook's own code, and
judge the instructor's wrong versions of it in this process (:func:`judge_notebooks`)."""

import ast
import json
import os
import shutil
import zipfile
from pathlib import Path

import nbformat

from kinlib.grade._sandbox import BLOCKED
from kinlib.grade._trusted import judge_functions

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


def _edits(mistake) -> list:
    """A mistake's edit: one (old, new) pair, or a tuple of them."""
    edit = mistake[0]
    return [edit] if isinstance(edit[0], str) else list(edit)


def mistake_submissions(tmp_path: Path, name: str, code: str, table, *before: str) -> list:
    """Submission n carries the n-th mistake of every function in ``table`` (pairs
    ``(function, [(edit, key), ...])``) patched into ``code``, after the cells ``before``."""
    subs = []
    for n in range(max(len(m) for _, m in table)):
        edits = [e for _, m in table if n < len(m) for e in _edits(m[n])]
        subs.append(write_notebook(tmp_path / f"m{n}.ipynb", *before, patched(code, *edits),
                                   assignment=name))
    return subs


def misdiagnosed(results: list, table, unaffected=None) -> list:
    """The mistakes of ``table`` not diagnosed with their key in ``results`` (graded
    :func:`mistake_submissions`). Functions in ``unaffected`` (default: all) must score
    full marks in the submissions without a mistake of their own."""
    wrong = []
    for fn, mistakes in table:
        for n, (edit, key) in enumerate(mistakes):
            check = by_function(results[n])[fn]
            if check["passed"] == check["total"] or top(check) != key:
                wrong.append((fn, key, str(edit)[:80], check["passed"], check["diagnoses"]))
        if unaffected is None or fn in unaffected:
            for r in results[len(mistakes):]:
                check = by_function(r)[fn]
                assert check["passed"] == check["total"], (fn, check["diagnoses"])
    return wrong


def _sandbox_legal(source: str, where: str) -> None:
    """The code of a test's submission imports nothing the sandbox would refuse (judged in
    process it could, and a mistake could then pass here that fails in the sandbox)."""
    for node in ast.walk(ast.parse(source)):
        names = ([a.name for a in node.names] if isinstance(node, ast.Import)
                 else [node.module or ""] if isinstance(node, ast.ImportFrom) else [])
        bad = [n for n in names if n.split(".")[0] in BLOCKED]
        assert not bad, f"{where}: imports {bad}, which the sandbox blocks"


def judge_notebooks(paths) -> list:
    """What ``grade_many(paths)`` gives these notebooks (written by this file's helpers from
    the solution and its known mistakes: the instructor's code, never a student's), judged
    in this process by :func:`kinlib.grade._trusted.judge_functions`: the same cases, wire
    format, judges and summary, without a student process per submission. The sandboxed
    path is tested end to end for every assignment in test_grader.py."""
    results = []
    for path in paths:
        nb = json.loads(Path(path).read_text())
        namespace = {"__name__": "__main__", "display": lambda *a, **k: None}
        for i, cell in enumerate(nb["cells"]):
            if cell["cell_type"] != "code":
                continue
            source = "".join(cell["source"]) if isinstance(cell["source"], list) \
                else cell["source"]
            _sandbox_legal(source, f"{Path(path).name}, cell {i}")
            exec(compile(source, f"<cell {i}>", "exec"), namespace)  # the tests' own code
        results.append(judge_functions(namespace, nb["metadata"]["kinlib"]["assignment"]))
    return results


# -- Gradescope: its /autograder layout and its results.json format ---------------------------
#: what a grader does not need, and Gradescope's image must not get (it got 55 packages,
#: 343 MB, with Jupyter, zmq, tornado, pyngrok)
NOT_NEEDED = {"jupyterlab", "notebook", "jupyter-server", "ipykernel", "ipywidgets",
              "anywidget", "meshcat", "pyzmq", "tornado", "pyngrok", "u-msgpack-python",
              "scipy", "numba", "nbconvert", "nbclient"}
# Gradescope's autograder specification (gradescope-autograders.readthedocs.io, "specs"),
# written down here as a JSON Schema: the fields it documents, their types and values
_FORMATS = {"enum": ["text", "html", "simple_format", "md", "ansi"]}
_SEEN = {"enum": ["hidden", "after_due_date", "after_published", "visible"]}
GRADESCOPE_SCHEMA = {
    "type": "object", "additionalProperties": False,
    "properties": {
        "score": {"type": "number", "minimum": 0}, "execution_time": {"type": "number"},
        "output": {"type": "string"}, "output_format": _FORMATS,
        "test_output_format": _FORMATS, "test_name_format": _FORMATS,
        "visibility": _SEEN, "stdout_visibility": _SEEN, "extra_data": {"type": "object"},
        "leaderboard": {"type": "array"},
        "tests": {"type": "array", "items": {
            "type": "object", "additionalProperties": False,
            "properties": {
                "score": {"type": "number", "minimum": 0},
                "max_score": {"type": "number", "minimum": 0},
                "status": {"enum": ["passed", "failed"]}, "name": {"type": "string"},
                "name_format": _FORMATS, "number": {"type": "string"},
                "output": {"type": "string"}, "output_format": _FORMATS,
                "tags": {"type": "array", "items": {"type": "string"}},
                "visibility": _SEEN, "extra_data": {"type": "object"}}}}},
    "anyOf": [{"required": ["score"]}, {"required": ["tests"]}],
}


def check_results(data: dict) -> None:
    """results.json as Gradescope documents it (raises otherwise): the schema, every test
    named and within its maximum, the score their sum."""
    import jsonschema

    jsonschema.validate(data, GRADESCOPE_SCHEMA)
    for t in data["tests"]:
        assert t["name"] and 0 <= t["score"] <= t["max_score"], t
    assert abs(sum(t["score"] for t in data["tests"]) - data["score"]) < 0.05


def extract(zip_path: Path, source: Path) -> Path:
    """The zip's contents in ``source``, with their permission bits (as unzip restores
    them; extractall drops them)."""
    with zipfile.ZipFile(zip_path) as z:
        z.extractall(source)
        for info in z.infolist():
            mode = info.external_attr >> 16
            if mode:
                os.chmod(source / info.filename, mode)
    return source


def unpack(zip_path: Path, root: Path) -> Path:
    """Gradescope's layout: the zip's contents in root/source, the submission, results."""
    source = extract(zip_path, root / "source")
    (root / "submission").mkdir()
    (root / "results").mkdir()
    return source


def hand_in(root: Path, notebook: Path, name: str = "homework.ipynb") -> None:
    for d in ("submission", "results"):
        shutil.rmtree(root / d)
        (root / d).mkdir()
    shutil.copy(notebook, root / "submission" / name)
