"""kinlib's layers (pyproject.toml's import-linter contract, checked by ``make lint``):
spatial maths → models → kinematics → robots and planning → plot and viz → the course's
tools. Here: the contract catches an import that goes up a layer (on a copy of the
package), and no module of the library's layers reaches the ``kinlib`` package itself,
which would import every layer at once and slip past the contract."""

from __future__ import annotations

import ast
import shutil
import subprocess
import sys
import tomllib
from pathlib import Path

import kinlib

PACKAGE = Path(kinlib.__file__).resolve().parent
PYPROJECT = PACKAGE.parent / "pyproject.toml"
LINT_IMPORTS = Path(sys.executable).with_name("lint-imports")
COURSE = {"check", "grade", "assign", "site"}  # the top layer, above the library


def _layers() -> list[list[str]]:
    config = tomllib.loads(PYPROJECT.read_text())["tool"]["importlinter"]
    (contract,) = config["contracts"]
    return [[m.strip() for m in layer.replace(":", "|").split("|")]
            for layer in contract["layers"]]


def _lint(root: Path) -> subprocess.CompletedProcess:
    return subprocess.run([str(LINT_IMPORTS), "--no-cache", str(root / "pyproject.toml")],
                          cwd=root, capture_output=True, text=True, timeout=120,
                          env={"PATH": "/usr/bin:/bin", "PYTHONPATH": str(root)})


def test_every_module_of_kinlib_is_in_a_layer():
    layered = {m for layer in _layers() for m in layer}
    tops = {f"kinlib.{p.stem if p.is_file() else p.name}" for p in PACKAGE.iterdir()
            if (p.suffix == ".py" and p.stem != "__init__")
            or (p.is_dir() and (p / "__init__.py").exists())}
    assert tops == layered, (sorted(tops - layered), sorted(layered - tops))


def test_the_contract_catches_an_upward_import(tmp_path):
    shutil.copytree(PACKAGE, tmp_path / "kinlib",
                    ignore=shutil.ignore_patterns("__pycache__", "*.nbi", "*.nbc"))
    shutil.copy(PYPROJECT, tmp_path / "pyproject.toml")
    kept = _lint(tmp_path)
    assert kept.returncode == 0, kept.stdout[-2000:] + kept.stderr[-2000:]
    # spatial maths that reaches up into the kinematics layer
    rotations = tmp_path / "kinlib" / "spatial" / "rotations.py"
    rotations.write_text(rotations.read_text() + "\nfrom ..kinematics import robot  # noqa\n")
    broken = _lint(tmp_path)
    assert broken.returncode != 0
    assert "kinlib.spatial is not allowed to import kinlib.kinematics" in broken.stdout, \
        broken.stdout[-2000:]


def _imports_of_package_root(path: Path) -> list[str]:
    """Imports in ``path`` (a module of kinlib) that take names from ``kinlib`` itself."""
    rel = path.relative_to(PACKAGE.parent).with_suffix("")
    package = list(rel.parts[:-1])  # a module's package; an __init__'s own
    found = []
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            found += [a.name for a in node.names if a.name == "kinlib"]
        elif isinstance(node, ast.ImportFrom):
            if node.level == 0:
                target = node.module or ""
            else:
                base = package[:len(package) - node.level + 1]
                target = ".".join(base + ([node.module] if node.module else []))
            if target == "kinlib":
                names = [a.name for a in node.names
                         if not (PACKAGE / a.name).is_dir()
                         and not (PACKAGE / f"{a.name}.py").exists()]
                found += [f"{path.name}:{node.lineno}: from kinlib import {n}" for n in names]
    return found


def test_the_library_layers_never_import_the_package_root():
    library = [p for p in PACKAGE.rglob("*.py")
               if p.relative_to(PACKAGE).parts[0].removesuffix(".py") not in COURSE
               and p != PACKAGE / "__init__.py"]
    assert len(library) > 40
    found = [hit for p in library for hit in _imports_of_package_root(p)]
    assert not found, found
    # the control: the course's tools do take names from the package root
    check = [hit for p in (PACKAGE / "check").rglob("*.py")
             for hit in _imports_of_package_root(p)]
    assert check, "the scan found no import of the package root anywhere"
