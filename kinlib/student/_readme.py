"""The student repository's README.md: how to start (Binder, the hub, a laptop), how the
exercises' checks and the assignments' self-check work, and what the course holds."""

from __future__ import annotations

import json
import re
from string import Template
from urllib.parse import quote, urlsplit

from ..errors import KinlibError
from ._environment import template

__all__ = ["readme", "binder_url", "title", "URLPATH"]

#: where Binder opens JupyterLab: the notebooks' folder
URLPATH = "lab/tree/notebooks"


def binder_url(repo_url: str) -> str:
    """The mybinder.org address that builds the repository at ``repo_url`` (its default
    branch) and opens JupyterLab on its notebooks.

    >>> binder_url("https://github.com/our-course/kinematics.git")
    'https://mybinder.org/v2/gh/our-course/kinematics/HEAD?urlpath=lab/tree/notebooks'
    >>> binder_url("https://gitlab.com/our-course/kinematics")
    'https://mybinder.org/v2/gl/our-course%2Fkinematics/HEAD?urlpath=lab/tree/notebooks'
    >>> binder_url("https://git.example.edu/kinematics")
    'https://mybinder.org/v2/git/https%3A%2F%2Fgit.example.edu%2Fkinematics/HEAD?urlpath=lab/tree/notebooks'
    """
    parts = urlsplit(repo_url)
    if parts.scheme not in ("https", "http") or not parts.netloc:
        raise KinlibError(f"--repo-url {repo_url!r}: expected the student repository's "
                          "https address, such as https://github.com/OWNER/NAME")
    path = re.sub(r"\.git$", "", parts.path.strip("/"))
    if parts.netloc in ("github.com", "www.github.com") and path.count("/") == 1:
        spec = f"gh/{path}"
    elif parts.netloc == "gitlab.com" and path:
        spec = f"gl/{quote(path, safe='')}"
    else:
        spec = f"git/{quote(repo_url, safe='')}"
    return f"https://mybinder.org/v2/{spec}/HEAD?urlpath={URLPATH}"


def title(notebook_text: str, where: str = "notebook") -> str:
    """The title of a notebook (its JSON text): the first line of its first cell, without
    the heading's ``#``."""
    try:
        cells = json.loads(notebook_text)["cells"]
        first = cells[0]["source"]
    except (ValueError, KeyError, IndexError, TypeError):
        raise KinlibError(f"{where}: not a notebook with a first cell") from None
    text = "".join(first) if isinstance(first, list) else first
    return text.strip().splitlines()[0].lstrip("#").strip() if text.strip() else where


def _listing(folder: str, notebooks: dict[str, str]) -> str:
    return "\n".join(f"- [{title(text, name)}]({folder}/{name})"
                     for name, text in sorted(notebooks.items()))


def readme(notebooks: dict[str, str], assignments: dict[str, str], wheel: str,
           repo_url: str | None = None) -> str:
    """The README of a student repository holding ``notebooks`` and ``assignments`` (file
    name -> notebook text) and the wheel ``wheels/<wheel>``; ``repo_url``, the published
    repository's address, gives the Binder link and the clone command."""
    if repo_url:
        link = binder_url(repo_url)
        binder = (f"[Open the notebooks on Binder]({link}): it opens JupyterLab on "
                  "`notebooks/` (the first start can take a few minutes).")
    else:
        binder = ("Open the Binder link your instructor gave you: it opens JupyterLab on "
                  "`notebooks/` (the first start can take a few minutes).")
    return Template(template("README.md")).substitute(
        n_notebooks=_count(len(notebooks)), n_assignments=_count(len(assignments)),
        binder=binder, clone_url=repo_url or "<this repository's address>", wheel=wheel,
        notebook_list=_listing("notebooks", notebooks),
        assignment_list=_listing("assignments", assignments))


def _count(n: int) -> str:
    words = ("no", "one", "two", "three", "four", "five", "six", "seven", "eight", "nine",
             "ten", "eleven", "twelve", "thirteen", "fourteen", "fifteen", "sixteen")
    return words[n] if n < len(words) else str(n)
