r"""The planar 2R arm in closed form (seed 001, Dorst fig. 5.4).

.. math:: {}^0A_2 = \begin{bmatrix} c_{12} & -s_{12} & 0 & l_1 c_1 + l_2 c_{12} \\
                                   s_{12} & c_{12} & 0 & l_1 s_1 + l_2 s_{12} \\
                                   0 & 0 & 1 & 0 \\ 0 & 0 & 0 & 1 \end{bmatrix}
   \qquad (5.4)
"""

from __future__ import annotations

import numpy as np

from ._validate import as_array, broadcast
from .errors import KinlibError

__all__ = ["planar_2r_fk"]


def _lengths(l1, l2):
    a1, a2 = as_array(l1, "l1"), as_array(l2, "l2")
    if (a1 <= 0).any() or (a2 <= 0).any():
        raise KinlibError(f"l1, l2: link lengths must be positive, got {l1!r}, {l2!r}")
    return a1, a2


def planar_2r_fk(theta1, theta2, l1, l2) -> np.ndarray:
    """Pose ``⁰A₂`` of the planar 2R arm's end (eq. 5.4), batched: ``(..., 4, 4)``.

    ``T[..., 0, 3]``, ``T[..., 1, 3]`` are x and y; the end's heading is
    ``φ = θ1 + θ2``.

    >>> planar_2r_fk(0.0, np.pi / 2, 1.0, 0.5)[:2, 3].round(12)
    array([1. , 0.5])
    """
    t1, t2 = as_array(theta1, "theta1"), as_array(theta2, "theta2")
    a1, a2 = _lengths(l1, l2)
    batch = broadcast((t1, 0, "theta1"), (t2, 0, "theta2"), (a1, 0, "l1"), (a2, 0, "l2"))
    c1, s1 = np.cos(t1), np.sin(t1)
    c12, s12 = np.cos(t1 + t2), np.sin(t1 + t2)
    T = np.zeros(batch + (4, 4))
    T[..., 0, 0], T[..., 0, 1], T[..., 0, 3] = c12, -s12, a1 * c1 + a2 * c12
    T[..., 1, 0], T[..., 1, 1], T[..., 1, 3] = s12, c12, a1 * s1 + a2 * s12
    T[..., 2, 2] = T[..., 3, 3] = 1.0
    return T
