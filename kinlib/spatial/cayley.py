r"""Cayley's formula: a rotation from the three parameters of a skew-symmetric matrix.

For every proper orthonormal R without an eigenvalue −1 there is a skew-symmetric S with
(seed 002)

.. math:: R = (I - S)^{-1}(I + S), \qquad S = [s]_\times ,

and :math:`s = \tan\frac\theta2\, u` for a rotation of θ about u. In closed form
:math:`R = I + \frac{2}{1 + s^Ts}\left(S + S^2\right)` and, back,
:math:`s = \frac{\operatorname{vee}(R - R^T)}{1 + \operatorname{tr}R}`. The parameters run
off to infinity as θ → π: a half turn has no Cayley parameters.
"""

from __future__ import annotations

import numpy as np

from .._validate import as_array, fmt_index, is_symbolic
from ..errors import KinlibError
from .quaternions import quat_from_matrix
from .rotations import skew

__all__ = ["matrix_from_cayley", "cayley_from_matrix"]

# w = cos(θ/2) below this means |s| = tan(θ/2) > 1e8: θ within 2e-8 rad of π.
_HALF_TURN = 1e-8


def matrix_from_cayley(s):
    r"""Rotation matrix :math:`(I - S)^{-1}(I + S)` with ``S = skew(s)``.

    Computed in closed form, :math:`I + \frac{2}{1 + |s|^2}(S + S^2)`. Sympy input gives a
    ``sympy.Matrix``.

    >>> matrix_from_cayley([0.0, 0.0, 1.0]).round(12) + 0.0  # tan(45°): 90° about z
    array([[ 0., -1.,  0.],
           [ 1.,  0.,  0.],
           [ 0.,  0.,  1.]])
    """
    if is_symbolic(s):
        import sympy as sp

        from ..symbolic import _sym

        S = _sym.skew(s)
        n2 = sum(sp.sympify(e) ** 2 for e in s)
        return sp.eye(3) + 2 / (1 + n2) * (S + S * S)
    a = as_array(s, "s", (3,))
    S = skew(a)
    k = 2.0 / (1.0 + np.einsum("...i,...i->...", a, a))
    return np.eye(3) + k[..., None, None] * (S + S @ S)


def cayley_from_matrix(R):
    r"""The Cayley parameters ``s = tan(θ/2) u`` of a rotation matrix.

    Raises :class:`KinlibError` for rotations by (or within 2e-8 rad of) 180°, where
    ``I + R`` is singular and the parameters are infinite.

    >>> cayley_from_matrix(matrix_from_cayley([0.1, -0.2, 0.3])).round(12)
    array([ 0.1, -0.2,  0.3])
    """
    q = quat_from_matrix(R)  # accurate near θ = π, where 1 + tr R cancels
    w = q[..., 0]
    bad = w < _HALF_TURN
    if np.any(bad):
        theta = 2.0 * np.arctan2(np.linalg.norm(q[..., 1:], axis=-1), w)
        raise KinlibError(
            f"R{fmt_index(w.shape, bad)}: Cayley's formula is undefined for a rotation of "
            f"180° (I + R is singular; the parameters tan(θ/2)·u are infinite); this one turns "
            f"θ = {np.rad2deg(theta[bad].flat[0]):.9g}°"
        )
    return q[..., 1:] / w[..., None]
