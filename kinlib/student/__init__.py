"""What students receive: a repository of its own, written by
``python -m kinlib.assign --student-repo DIR`` (``make student-repo``).

It holds the student editions that :mod:`kinlib.assign` makes (``notebooks/``, and the
released assignments in ``assignments/``), a README for students, kinlib's wheel built from
the course repository (``wheels/``) and the environment repo2docker builds for Binder and
a JupyterHub's image (``binder/``: ``requirements.txt``, ``runtime.txt`` and a ``postBuild``
that installs the shipped wheel, and regenerates nothing). Nothing an instructor keeps goes
in: no instructor edition, no assignment source, no grading secret, no tests.

Written into a clone of the published student repository, a release updates it in place:
``.git`` and files the release does not produce stay, changed files are rewritten, and the
files the previous release wrote that are no longer produced are removed (the manifest,
``.kinlib-student-release.json``, committed with the repository, lists them). The wheel is
built with fixed timestamps, so a release that changed nothing rewrites nothing. A folder
that is neither empty nor a previous release, or one that would publish or mix with the
instructor's repository, is refused (:func:`check_destination`).

The templates of the README and of the environment ship with the package
(``kinlib/student/templates``).
"""

from __future__ import annotations

import tempfile
from pathlib import Path

from ._environment import (
    RUNTIME_EXTRAS,
    TEMPLATES,
    build_wheel,
    environment,
    project,
    requirements,
    template,
)
from ._readme import binder_url, readme, title
from ._repo import FORMAT, MANIFEST, Written, check_destination, previous_release, write_files

__all__ = ["write_student_repo", "Written", "check_destination", "previous_release",
           "environment", "requirements", "readme", "binder_url", "build_wheel", "project",
           "template", "title", "MANIFEST", "FORMAT", "TEMPLATES", "RUNTIME_EXTRAS",
           "NOTEBOOKS", "ASSIGNMENTS", "WHEELS"]

#: the student repository's folders: the notebooks, the assignments, kinlib's wheel
NOTEBOOKS, ASSIGNMENTS, WHEELS = "notebooks", "assignments", "wheels"


def write_student_repo(root: Path | str, dest: Path | str, *, notebooks: dict[str, str],
                       assignments: dict[str, str], solution_marker: str,
                       repo_url: str | None = None) -> Written:
    """Write the student repository into ``dest``, from the course repository ``root``.

    Parameters
    ----------
    root : path
        The course (instructor) repository: kinlib's wheel is built from its
        ``pyproject.toml``, ``README.md`` and ``kinlib/``.
    dest : path
        A new or empty folder (``.git`` alone may be there), or a previous release.
    notebooks, assignments : dict
        File name -> text of each student-edition notebook and released assignment.
    solution_marker : str
        The line that starts a solution block: a notebook in ``dest`` holding it, which
        the release would leave in place, is refused before anything is written.
    repo_url : str, optional
        The published student repository's address, for the README's Binder link and
        clone command; by default the previous release's.

    Returns
    -------
    Written
        The release's files, those written, those removed.
    """
    root, dest = Path(root), Path(dest)
    previous = check_destination(root, dest, solution_marker)
    if repo_url is None and previous:
        repo_url = previous.get("repo_url")
    if repo_url:
        binder_url(repo_url)  # refuses what is not an https address before any work
    pyproject = project(root)
    with tempfile.TemporaryDirectory(prefix="kinlib-student-") as tmp:
        wheel = build_wheel(root, Path(tmp))
        files = {f"{WHEELS}/{wheel.name}": wheel.read_bytes()}
    text = {"README.md": readme(notebooks, assignments, wheel.name, repo_url),
            ".gitignore": template("gitignore"),
            **environment(pyproject, wheel.name),
            **{f"{NOTEBOOKS}/{name}": t for name, t in notebooks.items()},
            **{f"{ASSIGNMENTS}/{name}": t for name, t in assignments.items()}}
    files.update({rel: t.encode("utf-8") for rel, t in text.items()})
    manifest = {"kinlib": pyproject["version"], "repo_url": repo_url}
    return write_files(dest, files, previous, manifest)
