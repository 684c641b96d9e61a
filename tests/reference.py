"""Helpers shared by the test modules: random unit vectors (and quaternions), numpy and
hypothesis flavours.

Imported as a sibling module (pytest puts tests/ on sys.path in its default import mode).
"""

import numpy as np
from hypothesis import assume
from hypothesis import strategies as st

__all__ = ["random_unit_vectors", "unit_vectors"]


def random_unit_vectors(n, rng, dim=3):
    """``n`` unit ``dim``-vectors, uniform on the sphere (normalised Gaussians)."""
    u = rng.normal(size=(n, dim))
    return u / np.linalg.norm(u, axis=-1, keepdims=True)


@st.composite
def unit_vectors(draw, dim=3):
    """A unit ``dim``-vector (4: a unit quaternion) from a non-tiny box sample (shrinks
    towards the axes)."""
    v = np.array(draw(st.tuples(*[st.floats(-1.0, 1.0)] * dim)))
    n = np.linalg.norm(v)
    assume(n > 1e-3)
    return v / n
