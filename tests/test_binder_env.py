"""binder/ (the environment repo2docker builds for Binder and JupyterHub images) says what
pyproject.toml says: binder/requirements.txt lists exactly kinlib's runtime dependencies
and its ``lab`` extra (what ``make lab`` adds for the notebook server), with the same
version specifiers; binder/runtime.txt names a Python that ``requires-python`` allows; and
binder/postBuild installs kinlib itself without re-resolving its dependencies."""

from __future__ import annotations

import os
import re
import shutil
import stat
import subprocess
from pathlib import Path

from packaging.requirements import InvalidRequirement, Requirement
from packaging.specifiers import SpecifierSet
from packaging.utils import canonicalize_name

try:
    import tomllib
except ModuleNotFoundError:  # Python 3.10: tomli, the same parser, comes with pytest there
    import tomli as tomllib

ROOT = Path(__file__).resolve().parents[1]
BINDER = ROOT / "binder"
#: the optional-dependency groups the course's image needs besides the runtime: the
#: notebook server and a kernel (``dev``, ``fast`` and ``bench`` stay out of it)
EXTRAS = ("lab",)


def _key(req: Requirement) -> tuple[str, tuple[str, ...], str]:
    """What must agree between the two files for one package: its version specifiers (as
    a set, so ``>=1,<2`` equals ``<2,>=1``), its extras and its environment marker."""
    spec = ",".join(sorted(str(s) for s in req.specifier)) or "any version"
    return spec, tuple(sorted(req.extras)), str(req.marker or "")


def _show(key: tuple[str, tuple[str, ...], str]) -> str:
    spec, extras, marker = key
    return (f"[{','.join(extras)}]" if extras else "") + spec + (f"; {marker}" if marker else "")


def _collect(lines, where: str, problems: list[str]) -> dict[str, tuple]:
    found: dict[str, tuple] = {}
    for line in lines:
        try:
            req = Requirement(line)
        except InvalidRequirement as exc:
            problems.append(f"{where}: cannot parse {line!r}: {exc}")
            continue
        name = canonicalize_name(req.name)
        if name in found:
            problems.append(f"{where}: {name} is listed twice")
        found[name] = _key(req)
    return found


def requirement_lines(requirements_text: str) -> list[str]:
    """The requirement lines of a requirements file: comments and blank lines dropped."""
    lines = []
    for raw in requirements_text.splitlines():
        line = re.sub(r"(^|\s)#.*", "", raw).strip()
        if line:
            lines.append(line)
    return lines


def drift(pyproject_text: str, requirements_text: str, extras=EXTRAS) -> list[str]:
    """How ``requirements_text`` differs from ``pyproject_text``'s ``[project].dependencies``
    plus the optional dependencies ``extras``: one sentence per package missing, extra or
    with other specifiers (an empty list when the two agree).

    >>> drift('[project]\\ndependencies = ["numpy>=1.24"]', "numpy>=1.24  # arrays\\n", ())
    []
    >>> drift('[project]\\ndependencies = ["numpy>=1.24"]', "NumPy>=1.20\\nscipy\\n", ())
    ['numpy: pyproject.toml has >=1.24, binder/requirements.txt has >=1.20', \
'scipy: in binder/requirements.txt (any version) but not in pyproject.toml']
    """
    problems: list[str] = []
    project = tomllib.loads(pyproject_text)["project"]
    wanted = list(project.get("dependencies", []))
    groups = project.get("optional-dependencies", {})
    for extra in extras:
        if extra not in groups:
            problems.append(f"pyproject.toml has no optional-dependency group {extra!r}")
        wanted += groups.get(extra, [])
    lines = requirement_lines(requirements_text)
    options = [line for line in lines if line.startswith("-")]
    problems += [f"binder/requirements.txt: {line!r} is not a plain requirement (kinlib is "
                 "installed by binder/postBuild)" for line in options]
    expected = _collect(wanted, "pyproject.toml", problems)
    listed = _collect([line for line in lines if line not in options],
                      "binder/requirements.txt", problems)
    for name in sorted(expected.keys() | listed.keys()):
        if name not in listed:
            problems.append(f"{name}: in pyproject.toml ({_show(expected[name])}) "
                            "but not in binder/requirements.txt")
        elif name not in expected:
            problems.append(f"{name}: in binder/requirements.txt ({_show(listed[name])}) "
                            "but not in pyproject.toml")
        elif expected[name] != listed[name]:
            problems.append(f"{name}: pyproject.toml has {_show(expected[name])}, "
                            f"binder/requirements.txt has {_show(listed[name])}")
    return problems


def runtime_python(runtime_text: str) -> str:
    """The Python version a repo2docker runtime.txt asks for: ``python-3.11`` -> ``3.11``."""
    m = re.fullmatch(r"python-(\d+\.\d+)", runtime_text.strip())
    assert m, f"binder/runtime.txt should read python-X.Y, not {runtime_text.strip()!r}"
    return m.group(1)


def runtime_allowed(runtime_text: str, requires_python: str) -> bool:
    return SpecifierSet(requires_python).contains(runtime_python(runtime_text))


def install_commands(script_text: str) -> list[str]:
    """The ``pip install`` commands of a shell script (comments dropped)."""
    lines = (re.sub(r"(^|\s)#.*", "", line).strip() for line in script_text.splitlines())
    return [line for line in lines if re.search(r"\bpip\s+install\b", line)]


def installs_without_deps(script_text: str) -> bool:
    """Every ``pip install`` in the script has ``--no-deps``, and one installs ``.``."""
    commands = install_commands(script_text)
    return (bool(commands) and all("--no-deps" in c.split() for c in commands)
            and any("." in c.split() for c in commands))


# --- the repository's files -----------------------------------------------------------

def test_binder_requirements_match_pyproject():
    problems = drift((ROOT / "pyproject.toml").read_text(),
                     (BINDER / "requirements.txt").read_text())
    assert not problems, ("binder/requirements.txt and pyproject.toml have drifted apart "
                          "(dependencies + extras " + ", ".join(EXTRAS) + "):\n  "
                          + "\n  ".join(problems))


def test_runtime_is_a_python_pyproject_allows():
    requires = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["requires-python"]
    runtime = (BINDER / "runtime.txt").read_text()
    assert runtime_allowed(runtime, requires), \
        f"binder/runtime.txt asks for Python {runtime_python(runtime)}, " \
        f"pyproject.toml requires-python is {requires!r}"


def test_postbuild_is_an_executable_strict_bash_script_installing_kinlib_without_deps():
    path = BINDER / "postBuild"
    text = path.read_text()
    assert path.stat().st_mode & stat.S_IXUSR, "binder/postBuild is not executable"
    lines = text.splitlines()
    assert lines and re.fullmatch(r"#!\s*(/usr/bin/env\s+bash|/bin/bash)", lines[0]), \
        f"binder/postBuild should start with a bash shebang, not {lines[:1]}"
    assert "set -euo pipefail" in lines, "binder/postBuild should `set -euo pipefail`"
    assert installs_without_deps(text), \
        f"binder/postBuild should install kinlib with `pip install --no-deps .`: " \
        f"its pip commands are {install_commands(text)}"
    # The mode git records is the one a clone (and so repo2docker) gets.
    git = shutil.which("git")
    if git and (ROOT / ".git").exists():
        out = subprocess.run([git, "ls-files", "-s", "binder/postBuild"], cwd=ROOT,
                             capture_output=True, text=True, env={**os.environ, "LC_ALL": "C"})
        if out.returncode == 0 and out.stdout:
            assert out.stdout.startswith("100755"), \
                f"git records binder/postBuild without its executable bit: {out.stdout.strip()}"


# --- controls: the checks above can fail ----------------------------------------------

def test_drift_reports_each_kind_of_difference():
    pyproject = (ROOT / "pyproject.toml").read_text()
    requirements = (BINDER / "requirements.txt").read_text()
    lines = requirement_lines(requirements)
    assert {canonicalize_name(Requirement(line).name) for line in lines} >= {"numpy",
                                                                             "jupyterlab"}
    assert not drift(pyproject, requirements)

    dropped = requirements.replace("jupyterlab>=4\n", "")
    assert drift(pyproject, dropped) == [
        "jupyterlab: in pyproject.toml (>=4) but not in binder/requirements.txt"]

    loosened = requirements.replace("numpy>=1.24", "numpy>=1.20")
    assert drift(pyproject, loosened) == [
        "numpy: pyproject.toml has >=1.24, binder/requirements.txt has >=1.20"]

    added = requirements + "pytest>=8\n-e .\n"
    assert drift(pyproject, added) == [
        "binder/requirements.txt: '-e .' is not a plain requirement "
        "(kinlib is installed by binder/postBuild)",
        "pytest: in binder/requirements.txt (>=8) but not in pyproject.toml"]

    twice = requirements + "JupyterLab>=4\n"
    assert drift(pyproject, twice) == ["binder/requirements.txt: jupyterlab is listed twice"]

    # and the other way: a dependency added to pyproject.toml alone
    grown = pyproject.replace('    "numpy>=1.24",\n', '    "numpy>=1.24",\n    "pyyaml>=6",\n')
    assert grown != pyproject
    assert drift(grown, requirements) == [
        "pyyaml: in pyproject.toml (>=6) but not in binder/requirements.txt"]

    assert drift(pyproject, requirements, extras=("lab", "labs")) == [
        "pyproject.toml has no optional-dependency group 'labs'"]


def test_runtime_and_postbuild_checks_can_fail():
    assert runtime_allowed("python-3.11\n", ">=3.10")
    assert not runtime_allowed("python-3.9\n", ">=3.10")
    assert installs_without_deps("set -euo pipefail\npython -m pip install --no-deps .\n")
    assert not installs_without_deps("python -m pip install .\n")
    assert not installs_without_deps("pip install --no-deps .\npip install -r x.txt\n")
    assert not installs_without_deps("# pip install --no-deps .\n")
