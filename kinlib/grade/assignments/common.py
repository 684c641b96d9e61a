"""Pieces shared by the assignments' checks: random inputs (the common mistakes are
:mod:`kinlib.check.mistakes`, shared with the notebooks)."""

from __future__ import annotations

import numpy as np

import kinlib as kl
from kinlib.check.mistakes import DEGREES, TRANSPOSED, wxyz_read_as_xyzw

__all__ = ["DEGREES", "TRANSPOSED", "random_quats", "random_rotations",
           "random_unit_vectors", "wxyz_read_as_xyzw"]


def random_unit_vectors(rng: np.random.Generator, n: int) -> np.ndarray:
    v = rng.normal(size=(n, 3))
    return v / np.linalg.norm(v, axis=1, keepdims=True)


def random_quats(rng: np.random.Generator, n: int) -> np.ndarray:
    """Unit quaternions [w, x, y, z], uniform on the sphere, w of either sign."""
    q = rng.normal(size=(n, 4))
    return q / np.linalg.norm(q, axis=1, keepdims=True)


def random_rotations(rng: np.random.Generator, n: int) -> np.ndarray:
    return kl.matrix_from_quat(random_quats(rng, n))
