r"""How close a Jacobian is to losing rank: singular values, Yoshikawa's manipulability,
the condition number, the velocity ellipsoid and a near-singularity test.

All take any Jacobian ``J`` of shape (..., m, n): the 6×n geometric one, its 3×n position
rows, or the planar arm's 2×2. With the singular value decomposition
``J = U diag(σ) Vᵀ`` (σ₁ ≥ … ≥ σ_k ≥ 0, k = min(m, n)):

* manipulability ``w = √det(J Jᵀ) = σ₁ ⋯ σ_k`` (for m ≤ n; 0 at a singularity),
* condition number ``σ₁ / σ_k`` (∞ at a singularity),
* the velocity ellipsoid ``{J q̇ : |q̇| ≤ 1}`` has semi-axes ``σᵢ uᵢ``.

For the planar 2R arm's position Jacobian, ``w = |l1 l2 sin θ2|``.

One Jacobian gives a Python ``float`` (``bool`` for :func:`is_near_singular`), a batch an
ndarray of the batch shape.
"""

from __future__ import annotations

import numpy as np

from .._validate import as_array, as_tol, py_scalar
from ..conventions import SINGULAR_TOL
from ..errors import KinlibError

__all__ = ["singular_values", "manipulability", "condition_number", "velocity_ellipsoid",
           "is_near_singular"]


def _matrix(J) -> np.ndarray:
    a = as_array(J, "J")
    if a.ndim < 2:
        raise KinlibError(f"J: expected a matrix of shape (..., m, n), got shape {a.shape}")
    return a


def singular_values(J) -> np.ndarray:
    """σ₁ ≥ … ≥ σ_k of ``J`` (..., m, n), k = min(m, n).

    >>> singular_values([[3.0, 0.0], [0.0, -4.0]])
    array([4., 3.])
    """
    return np.linalg.svd(_matrix(J), compute_uv=False)


def manipulability(J) -> float | np.ndarray:
    """Yoshikawa's ``√det(J Jᵀ)``, computed as the product of the singular values (never
    NaN; exactly the volume factor of the velocity ellipsoid). For m > n (more task
    directions than joints) ``J Jᵀ`` is always singular and this is 0.

    >>> from kinlib import planar_2r_jacobian
    >>> manipulability(planar_2r_jacobian(0.3, np.pi / 2, 1.0, 0.5)[:2])
    0.5
    """
    a = _matrix(J)
    s = np.linalg.svd(a, compute_uv=False)
    w = np.prod(s, axis=-1)
    return py_scalar(np.where(a.shape[-2] > a.shape[-1], 0.0, w))


def condition_number(J) -> float | np.ndarray:
    """``σ₁ / σ_k``: 1 for an isotropic Jacobian, ∞ at a singularity (σ_k = 0).

    >>> condition_number([[2.0, 0.0], [0.0, 0.5]]), condition_number(np.zeros((2, 2)))
    (4.0, inf)
    """
    s = singular_values(J)
    small = s[..., -1]
    return py_scalar(np.where(small > 0, s[..., 0] / np.where(small > 0, small, 1.0), np.inf))


def velocity_ellipsoid(J) -> tuple[np.ndarray, np.ndarray]:
    """The ellipsoid ``{J q̇ : |q̇| ≤ 1}``: ``(axes, radii)``.

    ``axes`` (..., m, m) holds unit principal directions as columns (left singular vectors
    of J), ``radii`` (..., m) the semi-axis lengths (the singular values, padded with 0
    when n < m): the end effector moves fastest along ``axes[..., :, 0]``.

    >>> axes, radii = velocity_ellipsoid([[2.0, 0.0], [0.0, 0.5]])
    >>> radii
    array([2. , 0.5])
    """
    a = _matrix(J)
    U, s, _ = np.linalg.svd(a)
    m = a.shape[-2]
    radii = np.zeros(a.shape[:-2] + (m,))
    radii[..., : s.shape[-1]] = s
    return U, radii


def is_near_singular(J, tol: float = SINGULAR_TOL) -> bool | np.ndarray:
    """True where ``σ_k / σ₁ < tol`` (relative, so units do not matter), or J is all zero.

    A Python ``bool`` for one Jacobian, a bool ndarray for a batch.

    >>> from kinlib import planar_2r_jacobian
    >>> is_near_singular(planar_2r_jacobian(0.3, 0.0, 1.0, 1.0)[:2])
    True
    >>> is_near_singular(planar_2r_jacobian([0.3, 0.3], [0.0, 1.0], 1.0, 1.0)[:, :2])
    array([ True, False])
    """
    tol = as_tol(tol)
    s = singular_values(J)
    return py_scalar((s[..., 0] == 0) | (s[..., -1] < tol * s[..., 0]))
