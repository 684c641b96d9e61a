"""Make the student editions: ``python -m kinlib.assign`` (``make release``).

Two pairs of folders, each a source holding the instructor's solutions between
``### BEGIN SOLUTION`` and ``### END SOLUTION`` lines (the nbgrader convention) and the
student edition generated from it:

- ``assignments/source/`` → ``assignments/release/`` (graded assignments);
- ``instructor/`` → ``notebooks/`` (the course's notebooks and their exercises).

In the student edition each solution block is gone:

- inside a function (an indented block) it becomes ``raise NotImplementedError``, so the
  function exists and a check says "not answered yet" when it calls it;
- at the top level of a cell the block is removed, and the placeholder written before it
  stays: ``R_try = ...  # your answer``. A name the block assigns that the notebook uses
  anywhere else (the check cell) must have such a placeholder in its cell, else this tool
  refuses: so the student edition runs top to bottom with every exercise blank.

A cell tagged ``"solution"`` (in its metadata) is the instructor's only: the discussion of
an answer, a derivation that is an exercise's solution. It is left out of the student
edition, and no other cell may read a name it sets.

Outputs and execution counts are dropped. ``--check`` writes nothing and exits 1 if an
edition is missing or stale. ``--student-repo DIR`` writes what students receive, a
repository of its own (:mod:`kinlib.student`): the student editions (which must be the
committed ones: it refuses while they are stale), a README for students, kinlib's wheel and
the environment repo2docker builds for Binder or a JupyterHub. The folders are found
under ``--root`` (default: the current directory, so ``make release`` runs it from the
repository's root); exit status 2 when there is nothing to release there, a notebook or a
student repository's folder is refused, or the course's tools are not installed (``pip
install 'kinlib[course]'``: nbformat, nbclient, nbconvert; see
:func:`kinlib._optional.course_import`).

>>> print(release_source('''def f(x):
...     \"\"\"Twice x.\"\"\"
...     ### BEGIN SOLUTION
...     return 2 * x
...     ### END SOLUTION'''))
def f(x):
    \"\"\"Twice x.\"\"\"
    raise NotImplementedError
>>> print(release_source('''R = ...  # your answer
... ### BEGIN SOLUTION
... R = rotx(0.5)
... ### END SOLUTION'''))
R = ...  # your answer
"""

from __future__ import annotations

import argparse
import ast
import re
import sys
from pathlib import Path

from ._optional import course_import
from .errors import KinlibError
from .student import ASSIGNMENTS, NOTEBOOKS, check_destination, write_student_repo

__all__ = ["release_source", "release_notebook", "assigned_names", "used_names", "main",
           "student_repo", "BEGIN", "END", "EDITIONS", "STUDENT_FOLDERS", "SOLUTION_TAG"]

BEGIN = "### BEGIN SOLUTION"
END = "### END SOLUTION"
SOLUTION_TAG = "solution"  # a cell with this tag is in the instructor edition only
#: (source folder, student edition folder), relative to the repository (``--root``)
EDITIONS = (("assignments/source", "assignments/release"), ("instructor", "notebooks"))
#: (source folder, the student repository's folder it is released into)
STUDENT_FOLDERS = (("assignments/source", ASSIGNMENTS), ("instructor", NOTEBOOKS))
#: what installs the course's tools (kinlib.assign, kinlib.grade, kinlib.site) beside kinlib
#: the distributions of the course's tools, as pyproject.toml's ``course`` extra lists them


def _tree(code: str, where: str) -> ast.Module:
    try:
        return ast.parse(re.sub(r"^(\s*)[%!].*$", r"\1pass", code, flags=re.M))
    except SyntaxError as exc:
        raise KinlibError(f"{where}: not valid Python ({exc.msg}, line {exc.lineno})") from None


def assigned_names(code: str, where: str = "cell") -> set[str]:
    """The names ``code`` binds at its top level (assignments, functions, classes)."""
    names = set()
    for node in _tree(code, where).body:
        if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef):
            names.add(node.name)
        targets = {ast.Assign: lambda n: n.targets, ast.AugAssign: lambda n: [n.target],
                   ast.AnnAssign: lambda n: [n.target]}.get(type(node))
        for t in targets(node) if targets else ():
            names.update(x.id for x in ast.walk(t) if isinstance(x, ast.Name))
    return names


def used_names(code: str, where: str = "cell") -> set[str]:
    """The names ``code`` reads."""
    return {x.id for x in ast.walk(_tree(code, where))
            if isinstance(x, ast.Name) and isinstance(x.ctx, ast.Load)}


def release_source(source: str, where: str = "cell") -> str:
    """``source`` with each solution block replaced (see the module's docstring)."""
    return _release(source, where)[0]


def _release(source: str, where: str) -> tuple[str, list[str]]:
    """The released source and the top-level solution blocks it dropped."""
    out, inside, top, block = [], False, False, []
    removed = []
    for n, line in enumerate(source.split("\n"), 1):
        stripped = line.strip()
        if stripped == BEGIN:
            if inside:
                raise KinlibError(f"{where}, line {n}: {BEGIN} inside another solution block")
            inside, block = True, []
            indent = line[:len(line) - len(line.lstrip())]
            top = indent == ""
            if not top:
                out.append(indent + "raise NotImplementedError")
        elif stripped == END:
            if not inside:
                raise KinlibError(f"{where}, line {n}: {END} without a {BEGIN}")
            inside = False
            if top:
                removed.append("\n".join(block))
        elif inside:
            block.append(line)
        else:
            out.append(line)
    if inside:
        raise KinlibError(f"{where}: {BEGIN} without an {END}")
    while out and not out[-1].strip() and removed:
        out.pop()
    return "\n".join(out), removed


def release_notebook(nb):
    """The student edition of a source notebook (a new nbformat node)."""
    import copy

    student = copy.deepcopy(nb)
    hidden = [i for i, c in enumerate(student.cells)
              if SOLUTION_TAG in c.metadata.get("tags", ())]
    kept = [c for i, c in enumerate(student.cells) if i not in hidden]
    read = set().union(set(), *(used_names(c.source, "cell") for c in kept
                                if c.cell_type == "code"))
    for i in hidden:
        cell = student.cells[i]
        if cell.cell_type == "code":
            needed = (assigned_names(cell.source, f"cell {i}") & read)
            if needed:
                raise KinlibError(f"cell {i} is for the instructor only (tagged "
                                  f"{SOLUTION_TAG!r}) but the student edition reads "
                                  f"{', '.join(sorted(needed))}, which it sets")
    student.cells = kept
    dropped = {}  # cell -> names its top-level solution blocks assigned
    for i, cell in enumerate(student.cells):
        if cell.cell_type == "code":
            cell.source, removed = _release(cell.source, f"cell {i}")
            if removed:
                dropped[i] = set().union(*(assigned_names(b, f"cell {i}") for b in removed))
            cell.outputs = []
            cell.execution_count = None
        elif re.search(r"^\s*" + re.escape(BEGIN), cell.source, re.M):
            raise KinlibError(f"cell {i}: solution markers belong in code cells")
    code = {i: c.source for i, c in enumerate(student.cells) if c.cell_type == "code"}
    used = set().union(*(used_names(src, f"cell {j}") for j, src in code.items())) \
        if dropped else set()
    for i, names in dropped.items():
        missing = (names & used) - assigned_names(code[i], f"cell {i}")
        if missing:
            raise KinlibError(f"cell {i}: the solution assigns {', '.join(sorted(missing))}, "
                              f"which the notebook uses but the student edition would not "
                              f"define: write a placeholder such as "
                              f"`{sorted(missing)[0]} = ...` before {BEGIN}")
    return student


def _pairs(root: Path):
    pairs = []
    for src, dst in EDITIONS:
        for s in sorted((root / src).glob("*.ipynb")):
            pairs.append((s, root / dst / s.name))
    if not pairs:
        raise KinlibError(f"no source notebooks in {root.resolve()} (expected them in "
                          f"{' or '.join(src + '/' for src, _ in EDITIONS)}): run it from the "
                          "course repository's root or give that folder as --root")
    return pairs


def _released(pairs, nbformat) -> list[tuple[Path, Path, str]]:
    """(source, student edition, the student edition's text) of each pair."""
    out = []
    for src, dst in pairs:
        try:
            text = nbformat.writes(release_notebook(nbformat.read(src, as_version=4))) + "\n"
        except KinlibError as exc:
            raise KinlibError(f"{src}: {exc}") from None
        out.append((src, dst, text))
    return out


def _stale(released) -> list[Path]:
    return [dst for _, dst, text in released
            if not (dst.exists() and dst.read_text(encoding="utf-8") == text)]


def student_repo(root: Path, dest: Path, repo_url: str | None = None):
    """Write the student repository (:func:`kinlib.student.write_student_repo`) into
    ``dest`` from the course repository ``root``: the student editions as
    :func:`release_notebook` makes them, which must be the ones committed in ``root``
    (else a :class:`KinlibError`: the release publishes what the tests ran)."""
    check_destination(root, dest, BEGIN)  # refused before any work (and again on writing)
    pairs = _pairs(root)
    released = _released(pairs, course_import("nbformat", "python -m kinlib.assign"))
    stale = _stale(released)
    if stale:
        raise KinlibError("the student editions in the course repository are missing or out "
                          "of date (" + ", ".join(str(s) for s in stale) + "): run `make "
                          "release` (python -m kinlib.assign) and commit them first, so that "
                          "the student repository gets the notebooks the tests ran")
    into, folders = dict(STUDENT_FOLDERS), {NOTEBOOKS: {}, ASSIGNMENTS: {}}
    for src, _, text in released:
        folders[into[src.parent.relative_to(root).as_posix()]][src.name] = text
    return write_student_repo(root, dest, notebooks=folders[NOTEBOOKS],
                              assignments=folders[ASSIGNMENTS], solution_marker=BEGIN,
                              repo_url=repo_url)


def main(argv=None) -> int:
    """The command line (see the module's text); 0 done, 1 stale (``--check``). Bad input
    (nothing to release, a notebook refused, nbformat missing, a student repository
    refused) raises :class:`KinlibError`; ``python -m kinlib.assign`` prints it and exits
    2."""
    p = argparse.ArgumentParser(prog="python -m kinlib.assign", description=__doc__.split(
        "\n\n")[0])
    p.add_argument("--root", type=Path, default=Path("."),
                   help="the course repository holding instructor/ and assignments/source/ "
                        "(default: the current directory)")
    mode = p.add_mutually_exclusive_group()
    mode.add_argument("--check", action="store_true",
                      help="write nothing; exit 1 if a student edition is missing or out of "
                           "date")
    mode.add_argument("--student-repo", type=Path, metavar="DIR",
                      help="write what students receive into DIR, a repository of its own "
                           "(new, empty, or a clone of the one published before): the "
                           "student editions, a README, kinlib's wheel and the Binder "
                           "environment (see kinlib.student)")
    p.add_argument("--repo-url", metavar="URL",
                   help="with --student-repo: the student repository's https address, for "
                        "its README's Binder link (default: the previous release's)")
    args = p.parse_args(argv)
    if args.repo_url and not args.student_repo:
        p.error("--repo-url goes with --student-repo")
    if args.student_repo:
        done = student_repo(args.root, args.student_repo, args.repo_url)
        print(f"student repository {done.dest}: {len(done.files)} files, "
              f"{len(done.changed)} written, {len(done.removed)} removed"
              + "".join(f"\n  wrote {rel}" for rel in done.changed)
              + "".join(f"\n  removed {rel}" for rel in done.removed))
        return 0
    pairs = _pairs(args.root)
    released = _released(pairs, course_import("nbformat", "python -m kinlib.assign"))
    stale = _stale(released)
    if args.check:
        if stale:
            print("out of date (run `python -m kinlib.assign`): "
                  + ", ".join(str(s) for s in stale), file=sys.stderr)
            return 1
        return 0
    for _, dst, text in released:
        if dst in stale:
            dst.parent.mkdir(parents=True, exist_ok=True)
            dst.write_text(text, encoding="utf-8")
            print(f"wrote {dst}")
    return 0


def _cli() -> int:
    try:
        return main()
    except KinlibError as exc:
        print(f"python -m kinlib.assign: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(_cli())
