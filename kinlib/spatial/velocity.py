r"""Angular velocity (seed 004): ``Ṙ = S(ω) R``, its addition along a chain, points on a
moving frame, and the Euler-angle rate map.

Differentiating ``R Rᵀ = I`` gives ``Ṙ Rᵀ + R Ṙᵀ = 0``: ``Ṙ Rᵀ`` is skew-symmetric, so
``Ṙ Rᵀ = S(ω)`` for one vector ω, the angular velocity (in the fixed frame). For a chain
``R⁰ₙ = R⁰₁ R¹₂ ⋯ Rⁿ⁻¹ₙ`` the product rule and ``R S(a) Rᵀ = S(Ra)`` give

.. math:: \omega^0_{0,n} = \sum_{i=1}^{n} R^0_{i-1}\, \omega^{i-1}_{i-1,i}.
"""

from __future__ import annotations

import numpy as np

from .._validate import as_array, as_tol, broadcast, fmt_index, is_symbolic, parse_seq, py_scalar
from ..conventions import GIMBAL_TOL, SKEW_TOL
from ..errors import KinlibError
from .rotations import check_rotation, rotx, roty, rotz, skew, vee

__all__ = ["angular_velocity", "rotation_derivative", "add_angular_velocities",
           "point_velocity", "euler_rate_matrix", "euler_rates_singular"]


def angular_velocity(R, R_dot, tol: float = SKEW_TOL) -> np.ndarray:
    """ω with ``Ṙ Rᵀ = S(ω)`` (the angular velocity in the fixed frame), batched.

    ``R_dot`` must be the derivative of a rotation: ``Ṙ Rᵀ`` skew-symmetric to within
    ``tol`` (relative to its size), else :class:`~kinlib.KinlibError`.

    >>> from kinlib import rotz
    >>> t, w = 0.3, 2.0                      # R(t) = Rz(w t): Ṙ = w Rz'(w t)
    >>> R_dot = w * np.array([[-np.sin(w * t), -np.cos(w * t), 0],
    ...                       [np.cos(w * t), -np.sin(w * t), 0], [0, 0, 0]])
    >>> angular_velocity(rotz(w * t), R_dot).round(12) + 0.0
    array([0., 0., 2.])
    """
    R = check_rotation(R)
    Rd = as_array(R_dot, "R_dot", (3, 3))
    tol = as_tol(tol)
    broadcast((R, 2, "R"), (Rd, 2, "R_dot"))
    W = Rd @ np.swapaxes(R, -1, -2)
    asym = np.abs(W + np.swapaxes(W, -1, -2)).max(axis=(-2, -1))
    size = np.maximum(np.abs(W).max(axis=(-2, -1)), 1.0)
    bad = asym > tol * size
    if bad.any():
        where = fmt_index(bad.shape, bad)
        raise KinlibError(f"R_dot{where}: not the derivative of a rotation: Ṙ Rᵀ should be "
                          f"skew-symmetric, but Ṙ Rᵀ + (Ṙ Rᵀ)ᵀ reaches "
                          f"{float(asym[bad].flat[0]):.3g}")
    return vee((W - np.swapaxes(W, -1, -2)) / 2.0)


def rotation_derivative(R, omega) -> np.ndarray:
    """``Ṙ = S(ω) R`` for the angular velocity ω (fixed frame), batched."""
    R = check_rotation(R)
    w = as_array(omega, "omega", (3,))
    broadcast((R, 2, "R"), (w, 1, "omega"))
    return skew(w) @ R


def add_angular_velocities(rotations, omegas) -> np.ndarray:
    """``ω⁰₀,ₙ = Σᵢ R⁰ᵢ₋₁ ωⁱ⁻¹ᵢ₋₁,ᵢ`` (seed 004): the angular velocity of the last frame.

    ``rotations`` (..., n, 3, 3) are the relative rotations ``Rⁱ⁻¹ᵢ``; ``omegas``
    (..., n, 3) are the relative angular velocities ``ωⁱ⁻¹ᵢ₋₁,ᵢ``, each expressed in frame
    i − 1. Returns ω in frame 0, (..., 3).

    >>> from kinlib import rotz, rotx
    >>> w = add_angular_velocities([rotz(np.pi / 2), rotx(0.3)], [[0, 0, 1.0], [1.0, 0, 0]])
    >>> w.round(12) + 0.0      # frame 1 spins about z; frame 2 about x₁ = y₀
    array([0., 1., 1.])
    """
    Rs = check_rotation(rotations, name="rotations")
    ws = as_array(omegas, "omegas", (3,))
    if Rs.ndim < 3 or ws.ndim < 2 or Rs.shape[-3] != ws.shape[-2]:
        raise KinlibError(f"rotations (..., n, 3, 3) and omegas (..., n, 3) need the same n, "
                          f"got shapes {Rs.shape} and {ws.shape}")
    batch = broadcast((Rs, 3, "rotations"), (ws, 2, "omegas"))
    total = np.zeros(batch + (3,))
    R0 = np.broadcast_to(np.eye(3), batch + (3, 3))
    for i in range(Rs.shape[-3]):
        total = total + np.einsum("...ij,...j->...i", R0, ws[..., i, :])
        R0 = R0 @ Rs[..., i, :, :]
    return total


def point_velocity(R, p_dot, omega, p_local) -> np.ndarray:
    """Velocity in frame A of a point fixed in a moving frame B: ``ṗᴬ = S(ω) R pᴮ + ḋ``.

    ``R`` is ``Rᴬ_B``, ``p_dot`` the velocity ``ḋ`` of B's origin, ``omega`` B's angular
    velocity, both in A; ``p_local`` is the point in B (seed 004's "easy extension").

    >>> from kinlib import rotz
    >>> point_velocity(rotz(0.0), [0, 0, 0], [0, 0, 2.0], [1.0, 0, 0])  # v = ω × r
    array([0., 2., 0.])
    """
    R = check_rotation(R)
    d = as_array(p_dot, "p_dot", (3,))
    w = as_array(omega, "omega", (3,))
    p = as_array(p_local, "p_local", (3,))
    broadcast((R, 2, "R"), (d, 1, "p_dot"), (w, 1, "omega"), (p, 1, "p_local"))
    return np.cross(w, np.einsum("...ij,...j->...i", R, p)) + d


def euler_rate_matrix(angles, seq: str):
    """E(φ) with ``ω = E(φ) φ̇`` (ω in the fixed frame) for any of the 24 sequences.

    Intrinsic ``"ABC"``: ``R = R_A(φ1) R_B(φ2) R_C(φ3)`` and
    ``ω = φ̇1 e_A + φ̇2 R_A(φ1) e_B + φ̇3 R_A(φ1) R_B(φ2) e_C``. Extrinsic ``"abc"``:
    ``R = R_c(φ3) R_b(φ2) R_a(φ1)`` and ``ω = φ̇3 e_c + φ̇2 R_c(φ3) e_b +
    φ̇1 R_c(φ3) R_b(φ2) e_a``. E is singular exactly at gimbal lock. Sympy angles give a
    ``sympy.Matrix``.

    >>> E = euler_rate_matrix([0.0, 0.0, 0.0], "ZYX")
    >>> E
    array([[0., 0., 1.],
           [0., 1., 0.],
           [1., 0., 0.]])
    """
    axes, intrinsic = parse_seq(seq)
    # the k-th rate turns about axis k as it stands after the rotations applied before it
    order = range(3) if intrinsic else range(2, -1, -1)
    if is_symbolic(angles):
        import sympy as sp

        from ..symbolic import _sym

        a = _sym.vector(angles, "angles")
        cols, R = [None] * 3, sp.eye(3)
        for k in order:
            cols[k] = R[:, axes[k]]
            R = R * _sym.axis_rotation(axes[k], a[k])
        return sp.Matrix.hstack(*cols)
    a = as_array(angles, "angles", (3,))
    E = np.empty(a.shape[:-1] + (3, 3))
    R = np.broadcast_to(np.eye(3), a.shape[:-1] + (3, 3))
    for k in order:
        E[..., :, k] = R[..., :, axes[k]]
        R = R @ (rotx, roty, rotz)[axes[k]](a[..., k])
    return E


def euler_rates_singular(angles, seq: str, tol: float = GIMBAL_TOL) -> bool | np.ndarray:
    """True where ``|det E(φ)| < tol``: the Euler rates cannot represent every ω (gimbal
    lock: middle angle ±π/2 for three different axes, 0 or π when first = last).

    ``|det E|`` is the sine of the middle angle's distance to its singular value, so the
    default (:data:`kinlib.conventions.GIMBAL_TOL`) agrees with
    :func:`~kinlib.euler_gimbal_lock`'s. A Python ``bool`` for one set of angles, a bool
    ndarray for a batch.

    >>> euler_rates_singular([0.3, np.pi / 2, -0.8], "ZYX")
    True
    >>> euler_rates_singular([[0.3, 0.2, -0.8], [0.0, 0.0, 0.0]], "ZYZ")
    array([False,  True])
    """
    E = euler_rate_matrix(as_array(angles, "angles", (3,)), seq)
    return py_scalar(np.abs(np.linalg.det(E)) < as_tol(tol))
