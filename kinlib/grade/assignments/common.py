"""Pieces shared by the assignments' checks: random inputs and the common mistakes."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

import kinlib as kl

from .._checks import Mistake

__all__ = ["DEGREES", "TRANSPOSED", "MistakeKind", "random_quats", "random_rotations",
           "random_unit_vectors", "wxyz_read_as_xyzw"]


@dataclass(frozen=True)
class MistakeKind:
    """A mistake whose message is the same everywhere; ``of(model)`` makes the Mistake."""

    key: str
    message: str

    def of(self, model) -> Mistake:
        return Mistake(self.key, self.message, model)


DEGREES = MistakeKind("degrees", "you treated the angles as degrees (converted them with "
                                 "π/180, or returned degrees): angles are in radians "
                                 "throughout, as numpy's sin and cos expect")
TRANSPOSED = MistakeKind("transposed", "your matrix is the transpose of the right one: the "
                                       "frames are mixed up (R_AB versus R_BA), or the signs "
                                       "of the sines are swapped")


def random_unit_vectors(rng: np.random.Generator, n: int) -> np.ndarray:
    v = rng.normal(size=(n, 3))
    return v / np.linalg.norm(v, axis=1, keepdims=True)


def random_quats(rng: np.random.Generator, n: int) -> np.ndarray:
    """Unit quaternions [w, x, y, z], uniform on the sphere, w of either sign."""
    q = rng.normal(size=(n, 4))
    return q / np.linalg.norm(q, axis=1, keepdims=True)


def random_rotations(rng: np.random.Generator, n: int) -> np.ndarray:
    return kl.matrix_from_quat(random_quats(rng, n))


def wxyz_read_as_xyzw(f, *quats):
    """What ``f`` (quaternions in, quaternion out) gives if its code reads its inputs and
    writes its output in [x, y, z, w] order while the data are [w, x, y, z]."""
    return np.roll(f(*(np.roll(np.asarray(q), 1) for q in quats)), -1)
