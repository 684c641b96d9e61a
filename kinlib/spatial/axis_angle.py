r"""Angle-axis rotations: Rodrigues' formula (vector and matrix form), its inverse, and the
exponential and logarithm maps of SO(3).

A rotation of θ about the unit axis u turns a vector b into (seed 000)

.. math:: b' = (1 - \cos\theta)(u \cdot b)\,u + \cos\theta\, b + \sin\theta\,(u \times b)

and as a matrix (seed 001, eq. 4.64)

.. math:: R = \cos\theta\, I + \sin\theta\, [u]_\times + (1 - \cos\theta)\, u u^T
          = e^{[\theta u]_\times}.
"""

from __future__ import annotations

import numpy as np

from .._validate import as_array, as_unit_vectors, broadcast, is_symbolic, unit_rows
from .quaternions import (
    _half_turn_parts,
    _quat_from_matrix_numpy,
    axis_angle_from_quat,
    quat_from_matrix,
)

__all__ = [
    "matrix_from_axis_angle",
    "axis_angle_from_matrix",
    "rodrigues_rotate",
    "exp_so3",
    "log_so3",
]


def _rodrigues_matrix(u, t):
    """``cos t I + sin t [u]x + (1 − cos t) u uᵀ`` for unit u (..., 3) and angles t (...).

    ``1 − cos t`` is evaluated as ``2 sin²(t/2)``, which keeps its relative accuracy for
    small angles.
    """
    c, s = np.cos(t), np.sin(t)
    v = 2.0 * np.sin(0.5 * t) ** 2
    x, y, z = u[..., 0], u[..., 1], u[..., 2]
    R = np.empty(np.broadcast_shapes(u.shape[:-1], c.shape) + (3, 3))
    R[..., 0, 0] = c + v * x * x
    R[..., 0, 1] = v * x * y - s * z
    R[..., 0, 2] = v * x * z + s * y
    R[..., 1, 0] = v * x * y + s * z
    R[..., 1, 1] = c + v * y * y
    R[..., 1, 2] = v * y * z - s * x
    R[..., 2, 0] = v * x * z - s * y
    R[..., 2, 1] = v * y * z + s * x
    R[..., 2, 2] = c + v * z * z
    return R


def matrix_from_axis_angle(axis, angle):
    r"""Rodrigues' rotation matrix for a rotation by ``angle`` about ``axis``:
    :math:`\cos\theta I + \sin\theta [u]_\times + (1-\cos\theta) uu^T`.

    ``axis`` is normalised (a zero axis raises :class:`KinlibError`); batched over
    ``axis`` (..., 3) and ``angle`` (...). Sympy input gives a ``sympy.Matrix`` (a symbolic
    axis is taken as unit).

    >>> matrix_from_axis_angle([0.0, 0.0, 2.0], np.pi / 2).round(12) + 0.0
    array([[ 0., -1.,  0.],
           [ 1.,  0.,  0.],
           [ 0.,  0.,  1.]])
    """
    if is_symbolic(axis, angle):
        from ..symbolic import _sym

        return _sym.axis_angle(axis, angle)
    u = as_unit_vectors(axis, "axis")
    t = as_array(angle, "angle")
    broadcast((u, 1, "axis"), (t, 0, "angle"))
    return _rodrigues_matrix(u, t)


def axis_angle_from_matrix(R):
    r"""The inverse problem: ``(axis, angle)`` of a rotation matrix, angle in [0, π].

    The textbook formulas :math:`\theta = \arccos\frac{\operatorname{tr}R - 1}{2}`,
    :math:`u = \frac{1}{2\sin\theta}(r_{32}-r_{23}, r_{13}-r_{31}, r_{21}-r_{12})` lose all
    accuracy near θ = 0 (arccos is flat) and divide by zero at θ = π. kinlib goes through
    the quaternion instead (:func:`quat_from_matrix`, accurate everywhere) and takes
    :math:`\theta = 2\,\mathrm{atan2}(|v|, w)`. At θ = 0 the axis is undefined and
    ``[1, 0, 0]`` is returned; at θ = π, u and −u are the same rotation.

    >>> axis, angle = axis_angle_from_matrix(matrix_from_axis_angle([1.0, 1.0, 0.0], np.pi))
    >>> (axis * np.sign(axis[0])).round(12) + 0.0, round(angle, 12)
    (array([0.70710678, 0.70710678, 0.        ]), 3.14159265359)
    """
    return axis_angle_from_quat(quat_from_matrix(R))


def rodrigues_rotate(v, axis, angle):
    r"""Rotate vectors by Rodrigues' vector formula (seed 000).

    .. math:: v' = (1-\cos\theta)(u\cdot v)\,u + \cos\theta\, v + \sin\theta\,(u\times v)

    >>> rodrigues_rotate([1.0, 0.0, 0.0], [0.0, 0.0, 1.0], np.pi / 2).round(12) + 0.0
    array([0., 1., 0.])
    """
    b = as_array(v, "v", (3,))
    u = as_unit_vectors(axis, "axis")
    t = as_array(angle, "angle")[..., None]
    broadcast((b, 1, "v"), (u, 1, "axis"), (t, 1, "angle"))
    c, s = np.cos(t), np.sin(t)
    dot = (u * b).sum(axis=-1, keepdims=True)
    return (1.0 - c) * dot * u + c * b + s * np.cross(u, b)


def exp_so3(w):
    r"""Rotation matrix :math:`e^{[w]_\times}` of the rotation vector ``w = θu``.

    .. math:: e^{[w]_\times} = I + \frac{\sin\theta}{\theta}[w]_\times
              + \frac{1-\cos\theta}{\theta^2}[w]_\times^2 , \qquad \theta = |w|

    evaluated as Rodrigues' formula with the unit axis :math:`u = w/\theta` (found without
    overflow) and :math:`1 - \cos\theta = 2\sin^2\frac\theta2` (no cancellation), so tiny,
    zero and huge vectors are all accurate.

    >>> exp_so3([0.0, 0.0, np.pi / 2]).round(12) + 0.0
    array([[ 0., -1.,  0.],
           [ 1.,  0.,  0.],
           [ 0.,  0.,  1.]])
    """
    a = as_array(w, "w", (3,))
    u, theta = unit_rows(a)  # scaled: no overflow for huge |w|
    u = np.where((theta > 0)[..., None], u, [0.0, 0.0, 1.0])  # any axis for w = 0
    return _rodrigues_matrix(u, theta)


def log_so3(R):
    r"""Rotation vector ``w = θu`` (θ in [0, π]) with ``exp_so3(w) == R``.

    >>> log_so3(exp_so3([0.1, -0.2, 0.3])).round(12)
    array([ 0.1, -0.2,  0.3])
    """
    axis, angle = axis_angle_from_matrix(R)
    return axis * np.asarray(angle)[..., None]


def _log_so3_unchecked(m: np.ndarray) -> np.ndarray:
    """:func:`log_so3` of rotations already known to be rotations (N, 3, 3), without the
    input checks: for loops that take the log of products of checked rotations at every
    step (the IK's rotation error).

    From the antisymmetric part ``(R − Rᵀ)/2 = sin θ [u]`` and ``cos θ = (tr R − 1)/2``:
    ``θ = atan2(sin θ, cos θ)`` and ``θu = θ/sin θ · sin θ u``, accurate from θ = 0 (where
    θ/sin θ → 1) up to about 3 rad; beyond, where ``sin θ u`` vanishes and its direction
    is lost, the rotations go :func:`log_so3`'s route (Shepperd's quaternion, then
    ``θ = 2 atan2(|v|, w)``), accurate up to π."""
    v = 0.5 * np.stack([m[:, 2, 1] - m[:, 1, 2], m[:, 0, 2] - m[:, 2, 0],
                        m[:, 1, 0] - m[:, 0, 1]], axis=-1)
    s = np.sqrt(np.einsum("ni,ni->n", v, v))
    angle = np.arctan2(s, 0.5 * (m[:, 0, 0] + m[:, 1, 1] + m[:, 2, 2] - 1.0))
    w = v * np.where(s > 1e-300, angle / np.where(s > 1e-300, s, 1.0), 1.0)[:, None]
    far = angle > _NEAR_HALF_TURN
    if far.any():
        q = _quat_from_matrix_numpy(m[far])
        v, s, angle = _half_turn_parts(q / np.linalg.norm(q, axis=-1, keepdims=True))
        w[far] = v * (angle / s)[..., None]  # s ≥ sin(3/2) here
    return w


#: above this angle (rad) the antisymmetric part of R loses the axis: the quaternion route
_NEAR_HALF_TURN = 3.0
