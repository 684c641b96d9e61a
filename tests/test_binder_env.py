"""The student repository's environment (``binder/``, what repo2docker builds for Binder
and a JupyterHub's image; written by ``python -m kinlib.assign --student-repo`` from the
templates in ``kinlib/student/templates``) says what pyproject.toml says:
binder/requirements.txt lists exactly kinlib's runtime dependencies, its ``lab`` extra
(the notebook server and a kernel) and nbformat (which the self-check reads notebooks
with), with the same version specifiers; binder/runtime.txt names a Python that
``requires-python`` allows; and binder/postBuild installs the wheel shipped in the
repository without re-resolving its dependencies.

The course repository itself has no ``binder/``: students are pointed at the student
repository, never at the instructor's. These tests check the files as kinlib makes them
(no wheel is built: ``tests/test_student_release.py`` checks a real release with the same
helpers)."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from packaging.requirements import InvalidRequirement, Requirement
from packaging.specifiers import SpecifierSet
from packaging.utils import canonicalize_name

try:
    import tomllib
except ModuleNotFoundError:  # Python 3.10: tomli, the same parser, comes with pytest there
    import tomli as tomllib

from kinlib.student import environment, project

ROOT = Path(__file__).resolve().parents[1]
WHEEL = "kinlib-0.1.0-py3-none-any.whl"  # any name: the files are made for it
#: the optional-dependency groups the course's image needs besides the runtime: the
#: notebook server and a kernel (``dev``, ``fast`` and ``bench`` stay out of it)
EXTRAS = ("lab",)
#: and single packages of other groups: nbformat of ``grade``, for the self-check
PICKED = (("grade", "nbformat"),)


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


def drift(pyproject_text: str, requirements_text: str, extras=EXTRAS,
          picked=PICKED) -> list[str]:
    """How ``requirements_text`` differs from ``pyproject_text``'s ``[project].dependencies``
    plus the optional dependencies ``extras`` and the packages ``picked`` ((group, name)
    pairs): one sentence per package missing, extra or with other specifiers (an empty list
    when the two agree).

    >>> drift('[project]\\ndependencies = ["numpy>=1.24"]', "numpy>=1.24  # arrays\\n", (), ())
    []
    >>> drift('[project]\\ndependencies = ["numpy>=1.24"]', "NumPy>=1.20\\nscipy\\n", (), ())
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
    for extra, name in picked:
        found = [r for r in groups.get(extra, []) if canonicalize_name(Requirement(r).name)
                 == canonicalize_name(name)]
        if not found:
            problems.append(f"pyproject.toml's {extra!r} group has no {name}")
        wanted += found
    lines = requirement_lines(requirements_text)
    options = [line for line in lines if line.startswith("-")]
    problems += [f"binder/requirements.txt: {line!r} is not a plain requirement (kinlib is "
                 "installed by binder/postBuild)" for line in options]
    # the student environment installs kinlib from its wheel, never from an index
    problems += [f"binder/requirements.txt: {line!r} is kinlib itself (binder/postBuild "
                 "installs the shipped wheel)" for line in lines if line not in options
                 and canonicalize_name(Requirement(line).name) == "kinlib"]
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


def installs_wheel_without_deps(script_text: str, wheel: str) -> bool:
    """The script has one ``pip install`` command (a line continued with ``\\`` is one
    line): of the wheel ``wheels/<wheel>``, with ``--no-deps`` and ``--no-index``."""
    commands = install_commands(script_text.replace("\\\n", " "))
    return (len(commands) == 1 and {"--no-deps", "--no-index"} <= set(commands[0].split())
            and any(arg.strip("'\"") == f"wheels/{wheel}" for arg in commands[0].split()))


# --- the files kinlib writes into a student repository ---------------------------------

def _files() -> dict[str, str]:
    return environment(project(ROOT), WHEEL)


def check_requirements(text: str) -> None:
    problems = drift((ROOT / "pyproject.toml").read_text(), text)
    assert not problems, ("the student repository's binder/requirements.txt and "
                          "pyproject.toml have drifted apart (dependencies + extras "
                          + ", ".join(EXTRAS) + " + nbformat):\n  " + "\n  ".join(problems))


def check_runtime(text: str) -> None:
    requires = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["requires-python"]
    assert runtime_allowed(text, requires), \
        f"binder/runtime.txt asks for Python {runtime_python(text)}, " \
        f"pyproject.toml requires-python is {requires!r}"


def check_postbuild(text: str, wheel: str) -> None:
    lines = text.splitlines()
    assert lines and re.fullmatch(r"#!\s*(/usr/bin/env\s+bash|/bin/bash)", lines[0]), \
        f"binder/postBuild should start with a bash shebang, not {lines[:1]}"
    assert "set -euo pipefail" in lines, "binder/postBuild should `set -euo pipefail`"
    assert installs_wheel_without_deps(text, wheel), \
        f"binder/postBuild should install wheels/{wheel} with `pip install --no-deps " \
        f"--no-index` and nothing else: its pip commands are {install_commands(text)}"
    # it regenerates nothing: no course tool runs at build time
    assert "kinlib.assign" not in text and "instructor" not in text, \
        f"binder/postBuild must build and regenerate nothing:\n{text}"


def test_binder_requirements_match_pyproject():
    check_requirements(_files()["binder/requirements.txt"])


def test_runtime_is_a_python_pyproject_allows():
    check_runtime(_files()["binder/runtime.txt"])


def test_postbuild_is_a_strict_bash_script_installing_the_shipped_wheel_without_deps():
    check_postbuild(_files()["binder/postBuild"], WHEEL)


def test_the_course_repository_has_no_binder_folder():
    """Binder and repo2docker look for binder/ (or .binder/) first: the instructor's
    repository must not be what a student's image is built from."""
    for name in ("binder", ".binder"):
        assert not (ROOT / name).exists(), \
            f"{name}/ is back in the course repository: the student environment lives in " \
            "kinlib/student/templates and goes into the student repository"


# --- controls: the checks above can fail ----------------------------------------------

def test_drift_reports_each_kind_of_difference():
    pyproject = (ROOT / "pyproject.toml").read_text()
    requirements = _files()["binder/requirements.txt"]
    lines = requirement_lines(requirements)
    assert {canonicalize_name(Requirement(line).name) for line in lines} >= {
        "numpy", "jupyterlab", "nbformat"}
    assert not drift(pyproject, requirements)

    dropped = requirements.replace("jupyterlab>=4\n", "")
    assert drift(pyproject, dropped) == [
        "jupyterlab: in pyproject.toml (>=4) but not in binder/requirements.txt"]

    no_nbformat = requirements.replace("nbformat>=5\n", "")
    assert drift(pyproject, no_nbformat) == [
        "nbformat: in pyproject.toml (>=5) but not in binder/requirements.txt"]

    loosened = requirements.replace("numpy>=1.24", "numpy>=1.20")
    assert drift(pyproject, loosened) == [
        "numpy: pyproject.toml has >=1.24, binder/requirements.txt has >=1.20"]

    added = requirements + "pytest>=8\n-e .\n"
    assert drift(pyproject, added) == [
        "binder/requirements.txt: '-e .' is not a plain requirement "
        "(kinlib is installed by binder/postBuild)",
        "pytest: in binder/requirements.txt (>=8) but not in pyproject.toml"]

    assert "binder/requirements.txt: 'kinlib>=0.1' is kinlib itself (binder/postBuild " \
        "installs the shipped wheel)" in drift(pyproject, requirements + "kinlib>=0.1\n")

    twice = requirements + "JupyterLab>=4\n"
    assert drift(pyproject, twice) == ["binder/requirements.txt: jupyterlab is listed twice"]

    # and the other way: a dependency added to pyproject.toml alone
    grown = pyproject.replace('    "numpy>=1.24",\n', '    "numpy>=1.24",\n    "pyyaml>=6",\n')
    assert grown != pyproject
    assert drift(grown, requirements) == [
        "pyyaml: in pyproject.toml (>=6) but not in binder/requirements.txt"]

    assert drift(pyproject, requirements, extras=("lab", "labs")) == [
        "pyproject.toml has no optional-dependency group 'labs'"]
    assert "pyproject.toml's 'grade' group has no jupyterlab" in drift(
        pyproject, requirements, picked=(("grade", "jupyterlab"),))


def test_runtime_and_postbuild_checks_can_fail():
    assert runtime_allowed("python-3.11\n", ">=3.10")
    assert not runtime_allowed("python-3.9\n", ">=3.10")
    good = _files()["binder/postBuild"]
    assert installs_wheel_without_deps(good, WHEEL)
    assert not installs_wheel_without_deps(good, "kinlib-9.9-py3-none-any.whl")
    assert not installs_wheel_without_deps(good.replace("--no-deps ", ""), WHEEL)
    assert not installs_wheel_without_deps(good + "pip install -r x.txt\n", WHEEL)
    assert not installs_wheel_without_deps(
        "set -euo pipefail\npython -m pip install --no-deps --no-index .\n", WHEEL)
    assert not installs_wheel_without_deps("# " + good.replace("\n", "\n# "), WHEEL)
    with pytest.raises(AssertionError, match="must build and regenerate nothing"):
        check_postbuild(good + "python -m kinlib.assign --root .\n", WHEEL)
