"""Real wrong answers to the notebooks' exercises, each with the diagnosis it must get:
one module per notebook (``nb01`` …), each defining ``WRONG = {exercise id: [(answer,
mistake key), ...]}``. The answers are what a student would really write: rows for columns,
degrees, the other elbow, ``q1 q2`` for ``q2 q1``... (tests/test_exercises.py)."""

from importlib import import_module
from pathlib import Path

WRONG = {}
for _path in sorted(Path(__file__).parent.glob("nb[0-9][0-9].py")):
    WRONG.update(import_module(f"{__name__}.{_path.stem}").WRONG)
