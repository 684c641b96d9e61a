"""The graded assignments: name → a function building its :class:`Assignment`.

Each module holds one assignment's checks; the name is the stem of the notebook in
``assignments/source/`` (and ``assignments/release/``).
"""

from __future__ import annotations

from importlib import import_module

__all__ = ["ASSIGNMENTS"]


def _lazy(module: str):
    def build():
        return import_module(f"{__name__}.{module}").assignment()
    return build


ASSIGNMENTS = {
    "01_rotations": _lazy("rotations"),
    "02_forward_kinematics": _lazy("forward_kinematics"),
    "03_jacobian_and_ik": _lazy("jacobian_ik"),
    "04_planning": _lazy("planning"),
    "05_orientation_kinematics": _lazy("orientation"),
    "06_differential_kinematics": _lazy("differential"),
}
