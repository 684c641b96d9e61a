"""The course tools' own dependencies (nbformat, nbclient, nbconvert: the ``course``
extra), imported on first use by :mod:`kinlib.assign`, :mod:`kinlib.site` and the grader,
with a message naming the extra when one is missing. kinlib's runtime needs none of them.
"""

from __future__ import annotations

import importlib

from .errors import KinlibError

__all__ = ["course_import", "COURSE_EXTRA", "COURSE_MODULES"]

COURSE_EXTRA = "pip install 'kinlib[course]'"
COURSE_MODULES = ("nbformat", "nbclient", "nbconvert")


def course_import(name: str, tool: str = "the course's tools"):
    """The module ``name``, one of the course tools' own dependencies, imported; a
    :class:`KinlibError` naming the extra that installs it when it cannot be imported.

    kinlib's runtime does not need nbformat, nbclient or nbconvert; ``kinlib.assign``,
    ``kinlib.site`` and the grader's old-notebook converter do.

    >>> course_import("json").__name__
    'json'
    >>> course_import("no_such_module_here", "python -m kinlib.site")
    Traceback (most recent call last):
    ...
    kinlib.errors.KinlibError: python -m kinlib.site needs no_such_module_here, which is not \
installed (No module named 'no_such_module_here'): pip install 'kinlib[course]'
    """
    try:
        return importlib.import_module(name)
    except ImportError as exc:
        raise KinlibError(f"{tool} needs {name}, which is not installed ({exc}): "
                          f"{COURSE_EXTRA}") from None
