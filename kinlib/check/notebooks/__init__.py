"""The exercises of the course's notebooks, one module per notebook (``nb01`` … ``nb15``),
each defining ``EXERCISES``, a list of :class:`~kinlib.check.Exercise` in order."""

from __future__ import annotations

import pkgutil
import re
from functools import cache
from importlib import import_module

from ...errors import KinlibError

__all__ = ["find", "every", "of_notebook", "NOTEBOOKS"]

#: the notebooks that have exercises, by number
NOTEBOOKS = tuple(sorted(m.name[2:] for m in pkgutil.iter_modules(__path__)
                         if re.fullmatch(r"nb\d\d", m.name)))
_ID = re.compile(r"(\d\d)\.(\d+)")


@cache
def _of(notebook: str) -> dict:
    module = import_module(f"{__name__}.nb{notebook}")
    out = {}
    for ex in module.EXERCISES:
        if ex.notebook != notebook or ex.id in out:
            raise KinlibError(f"exercise {ex.id} is misplaced or repeated in nb{notebook}")
        out[ex.id] = ex
    return out


def find(exercise_id: str):
    m = _ID.fullmatch(exercise_id) if isinstance(exercise_id, str) else None
    if m is None or m.group(1) not in NOTEBOOKS:
        raise KinlibError(f"check: expected an exercise id like '03.2' (a notebook number "
                          f"{', '.join(NOTEBOOKS)}, then the exercise's), got {exercise_id!r}")
    known = _of(m.group(1))
    if exercise_id not in known:
        raise KinlibError(f"check: notebook {m.group(1)} has no exercise {exercise_id}; its "
                          f"exercises are {', '.join(known)}")
    return known[exercise_id]


def of_notebook(notebook: str) -> list:
    if notebook not in NOTEBOOKS:
        raise KinlibError(f"exercises: expected a notebook number ({', '.join(NOTEBOOKS)}), "
                          f"got {notebook!r}")
    return list(_of(notebook).values())


def every() -> list:
    return [ex for nb in NOTEBOOKS for ex in _of(nb).values()]
