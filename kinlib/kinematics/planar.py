r"""The planar 2R arm in closed form (seed 001, Dorst fig. 5.4).

.. math:: {}^0A_2 = \begin{bmatrix} c_{12} & -s_{12} & 0 & l_1 c_1 + l_2 c_{12} \\
                                   s_{12} & c_{12} & 0 & l_1 s_1 + l_2 s_{12} \\
                                   0 & 0 & 1 & 0 \\ 0 & 0 & 0 & 1 \end{bmatrix}
   \qquad (5.4)

Its Jacobian maps ``(θ̇1, θ̇2)`` to ``(ẋ, ẏ, φ̇)`` with ``φ = θ1 + θ2``; the 2×2 position
part has determinant ``l1 l2 sin θ2``. The inverse kinematics follows seed 001:
``c2 = (x² + y² − l1² − l2²) / (2 l1 l2)``, ``s2 = ±√(1 − c2²)``, ``θ2 = atan2(s2, c2)``,
``θ1 = atan2(y, x) − atan2(l2 s2, l1 + l2 c2)``.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from .._validate import as_array, broadcast, py_scalar, wrap_angle
from ..conventions import ROUNDING_TOL
from ..errors import KinlibError

__all__ = ["Planar2RIK", "planar_2r_fk", "planar_2r_ik", "planar_2r_jacobian"]


def _lengths(l1, l2):
    a1, a2 = as_array(l1, "l1"), as_array(l2, "l2")
    if (a1 <= 0).any() or (a2 <= 0).any():
        raise KinlibError(f"l1, l2: link lengths must be positive, got {l1!r}, {l2!r}")
    return a1, a2


def _trig(theta1, theta2, l1, l2):
    """Checked inputs and ``l1, l2, c1, s1, c12, s12, batch shape`` (seed 001's notation)."""
    t1, t2 = as_array(theta1, "theta1"), as_array(theta2, "theta2")
    a1, a2 = _lengths(l1, l2)
    batch = broadcast((t1, 0, "theta1"), (t2, 0, "theta2"), (a1, 0, "l1"), (a2, 0, "l2"))
    return a1, a2, np.cos(t1), np.sin(t1), np.cos(t1 + t2), np.sin(t1 + t2), batch


def planar_2r_fk(theta1, theta2, l1, l2) -> np.ndarray:
    """Pose ``⁰A₂`` of the planar 2R arm's end (eq. 5.4), batched: ``(..., 4, 4)``.

    ``T[..., 0, 3]``, ``T[..., 1, 3]`` are x and y; the end's heading is
    ``φ = θ1 + θ2``.

    >>> planar_2r_fk(0.0, np.pi / 2, 1.0, 0.5)[:2, 3].round(12)
    array([1. , 0.5])
    """
    a1, a2, c1, s1, c12, s12, batch = _trig(theta1, theta2, l1, l2)
    T = np.zeros(batch + (4, 4))
    T[..., 0, 0], T[..., 0, 1], T[..., 0, 3] = c12, -s12, a1 * c1 + a2 * c12
    T[..., 1, 0], T[..., 1, 1], T[..., 1, 3] = s12, c12, a1 * s1 + a2 * s12
    T[..., 2, 2] = T[..., 3, 3] = 1.0
    return T


def planar_2r_jacobian(theta1, theta2, l1, l2) -> np.ndarray:
    """The 3×2 Jacobian of ``(x, y, φ)`` (seed 001), batched: ``(..., 3, 2)``.

    Rows ``[-l1 s1 - l2 s12, -l2 s12]``, ``[l1 c1 + l2 c12, l2 c12]``, ``[1, 1]``; the
    first two rows are the position Jacobian, ``det = l1 l2 sin θ2``.

    >>> J = planar_2r_jacobian(0.0, np.pi / 2, 1.0, 1.0)
    >>> J.round(12) + 0.0
    array([[-1., -1.],
           [ 1.,  0.],
           [ 1.,  1.]])
    >>> round(float(np.linalg.det(J[:2])), 12)  # l1 l2 sin θ2
    1.0
    """
    a1, a2, c1, s1, c12, s12, batch = _trig(theta1, theta2, l1, l2)
    J = np.empty(batch + (3, 2))
    J[..., 0, 0], J[..., 0, 1] = -a1 * s1 - a2 * s12, -a2 * s12
    J[..., 1, 0], J[..., 1, 1] = a1 * c1 + a2 * c12, a2 * c12
    J[..., 2, :] = 1.0
    return J


class Planar2RIK(NamedTuple):
    """Result of :func:`planar_2r_ik`: joint angles and whether the target is reachable.

    ``success`` is True where the target lies in the workspace annulus
    ``|l1 − l2| <= r <= l1 + l2`` (its rim included, to rounding). For an unreachable
    target, ``theta1, theta2`` is the closest configuration: the arm stretched towards
    the target (too far) or folded towards it (too close), and ``success`` is False. Never
    NaN. Angles lie in (−π, π]. For one target the three are a Python ``float``, ``float``
    and ``bool``; for a batch, ndarrays of the batch shape.
    """

    theta1: float | np.ndarray
    theta2: float | np.ndarray
    success: bool | np.ndarray


def planar_2r_ik(x, y, l1, l2, elbow: str = "up") -> Planar2RIK:
    """Joint angles that put the 2R arm's end at ``(x, y)`` (seed 001's atan2 form).

    ``elbow="up"`` takes ``s2 = −√(1 − c2²)`` (θ2 ≤ 0: for a target on the +x axis the
    elbow is above it), ``"down"`` takes ``s2 = +√(1 − c2²)``. On the workspace boundary
    (``|p| = l1 + l2`` or ``|l1 − l2|``) both branches coincide: ``θ2 = 0`` or ``π``. At the
    base with ``l1 = l2`` every θ1 works; θ1 = 0 is returned. Batched over x, y.

    >>> sol = planar_2r_ik(1.0, 1.0, 1.0, 1.0, elbow="down")
    >>> sol.theta1, sol.theta2, sol.success
    (0.0, 1.5707963267948966, True)
    >>> planar_2r_ik(3.0, 0.0, 1.0, 1.0).success
    False
    >>> planar_2r_ik([1.0, 3.0], 0.0, 1.0, 1.0).success
    array([ True, False])
    """
    if elbow not in ("up", "down"):
        raise KinlibError(f"elbow: expected 'up' or 'down', got {elbow!r}")
    px, py = as_array(x, "x"), as_array(y, "y")
    a1, a2 = _lengths(l1, l2)
    batch = broadcast((px, 0, "x"), (py, 0, "y"), (a1, 0, "l1"), (a2, 0, "l2"))
    c2 = (px * px + py * py - a1 * a1 - a2 * a2) / (2.0 * a1 * a2)
    tol = ROUNDING_TOL
    success = np.broadcast_to((c2 >= -1.0 - tol) & (c2 <= 1.0 + tol), batch)
    # |θ2| from the half-angle form tan²(θ2/2) = ((l1+l2)² − r²) / (r² − (l1−l2)²), whose
    # factors are differences of lengths: exact 0 on the rim where √(1 − c2²) would turn a
    # rounding error of c2 (1e-16) into θ2 ≈ 1e-8. Clipping gives the closest configuration
    # (stretched or folded) for unreachable targets.
    r = np.hypot(px, py)
    outer = np.sqrt(np.clip((a1 + a2 - r) * (a1 + a2 + r), 0.0, None))
    inner = np.sqrt(np.clip((r - np.abs(a1 - a2)) * (r + np.abs(a1 - a2)), 0.0, None))
    size = 2.0 * np.arctan2(outer, inner)  # in [0, π]
    folded = size >= np.pi
    theta2 = np.where(folded, np.pi, -size if elbow == "up" else size)[()]  # π, not −π
    s2 = np.where(folded, 0.0, np.sin(theta2))  # exact when folded: sin(π) is 1.2e-16
    c2 = np.where(folded, -1.0, np.cos(theta2))
    theta1 = np.arctan2(py, px) - np.arctan2(a2 * s2, a1 + a2 * c2)
    theta1 = np.broadcast_to(wrap_angle(theta1), batch)  # into (−π, π]
    theta2 = np.broadcast_to(wrap_angle(theta2), batch)  # already in (−π, π]; −0.0 → 0.0
    if not batch:
        return Planar2RIK(py_scalar(theta1), py_scalar(theta2), py_scalar(success))
    return Planar2RIK(theta1.copy(), theta2.copy(), success.copy())
