r"""Unit dual quaternions and screw motion (Daniilidis 1999, Kenwright 2012).

A rigid motion (R, t) is the dual quaternion :math:`\hat q = q_r + \varepsilon q_d` with
:math:`\varepsilon^2 = 0`, the rotation quaternion :math:`q_r` and
:math:`q_d = \tfrac12 (0, t)\, q_r`; kinlib stores it as 8 numbers, ``[q_r (wxyz), q_d
(wxyz)]``. Products compose motions like matrices:
:math:`\hat q_1 \hat q_2 = q_{r1} q_{r2} + \varepsilon (q_{r1} q_{d2} + q_{d1} q_{r2})`.

By Chasles' theorem every rigid motion is a screw: a rotation θ about a line with unit
direction l and moment :math:`m = c \times l` (c any point on it) together with a
translation d along it. Then

.. math::

    q_r = \left(\cos\tfrac\theta2,\ \sin\tfrac\theta2\, l\right), \qquad
    q_d = \left(-\tfrac d2 \sin\tfrac\theta2,\
          \sin\tfrac\theta2\, m + \tfrac d2 \cos\tfrac\theta2\, l\right).
"""

from __future__ import annotations

import numpy as np

from .._validate import as_array, as_unit_vectors, broadcast, fmt_index, py_scalar
from ..conventions import ROTATION_TOL
from ..errors import KinlibError
from .quaternions import (
    matrix_from_quat,
    quat_conjugate,
    quat_from_matrix,
    quat_multiply,
    quat_rotate,
)
from .transforms import check_transform

__all__ = [
    "dual_quat_from_transform",
    "transform_from_dual_quat",
    "dual_quat_multiply",
    "dual_quat_conjugate",
    "dual_quat_transform_point",
    "screw_from_dual_quat",
    "dual_quat_from_screw",
    "dual_quat_sclerp",
]

_TOL = ROTATION_TOL  # a unit dual quaternion is a rigid transform: the same acceptance


def _pure(v):
    return np.concatenate([np.zeros(v.shape[:-1] + (1,)), v], axis=-1)


def _unit_dq(dq, name="dq"):
    """Check an (..., 8) unit dual quaternion; return (q_r, q_d) with q_r normalised."""
    a = as_array(dq, name, (8,))
    qr, qd = a[..., :4], a[..., 4:]
    n = np.linalg.norm(qr, axis=-1)
    bad = np.abs(n - 1.0) > _TOL
    if np.any(bad):
        raise KinlibError(
            f"{name}{fmt_index(n.shape, bad)}: expected a unit dual quaternion, but the real "
            f"part has norm {n[bad].flat[0]:.6g} (should be 1)"
        )
    dot = np.einsum("...i,...i->...", qr, qd)
    bad = np.abs(dot) > _TOL
    if np.any(bad):
        raise KinlibError(
            f"{name}{fmt_index(dot.shape, bad)}: expected a unit dual quaternion, but real·dual "
            f"= {dot[bad].flat[0]:.3g} (should be 0)"
        )
    qr = qr / n[..., None]
    qd = qd - (dot / n**2)[..., None] * qr
    return qr, qd


def dual_quat_from_transform(T):
    r"""Unit dual quaternion ``[q_r, ½ (0, t) q_r]`` of a rigid transform (``w_r >= 0``).

    >>> dual_quat_from_transform(np.eye(4))
    array([1., 0., 0., 0., 0., 0., 0., 0.])
    """
    a = check_transform(T)
    qr = quat_from_matrix(a[..., :3, :3])
    qd = 0.5 * quat_multiply(_pure(a[..., :3, 3]), qr)
    return np.concatenate([qr, qd], axis=-1)


def _translation(qr, qd):
    return 2.0 * quat_multiply(qd, quat_conjugate(qr))[..., 1:]


def transform_from_dual_quat(dq):
    r"""Homogeneous transform of a unit dual quaternion: ``t = 2 q_d q_r*``.

    >>> from kinlib import rotz, transform
    >>> T = transform(rotz(0.5), [1.0, 2.0, 3.0])
    >>> bool(np.allclose(transform_from_dual_quat(dual_quat_from_transform(T)), T))
    True
    """
    qr, qd = _unit_dq(dq)
    T = np.zeros(qr.shape[:-1] + (4, 4))
    T[..., :3, :3] = matrix_from_quat(qr)
    T[..., :3, 3] = _translation(qr, qd)
    T[..., 3, 3] = 1.0
    return T


def dual_quat_multiply(a, b):
    r"""Product :math:`\hat a \hat b = a_r b_r + \varepsilon(a_r b_d + a_d b_r)`: first b, then a
    (like ``T_a @ T_b``).

    >>> from kinlib import rotx, transform
    >>> Ta, Tb = transform(rotx(0.3), [1.0, 0, 0]), transform(p=[0, 2.0, 0])
    >>> dq = dual_quat_multiply(dual_quat_from_transform(Ta), dual_quat_from_transform(Tb))
    >>> bool(np.allclose(transform_from_dual_quat(dq), Ta @ Tb))
    True
    """
    x, y = as_array(a, "a", (8,)), as_array(b, "b", (8,))
    broadcast((x, 1, "a"), (y, 1, "b"))
    real = quat_multiply(x[..., :4], y[..., :4])
    dual = quat_multiply(x[..., :4], y[..., 4:]) + quat_multiply(x[..., 4:], y[..., :4])
    return np.concatenate([real, dual], axis=-1)


def dual_quat_conjugate(dq):
    r"""Quaternion conjugate of both parts, :math:`q_r^* + \varepsilon q_d^*`: for a unit dual
    quaternion this is the inverse motion.

    >>> dq = dual_quat_from_transform(np.eye(4))
    >>> dual_quat_conjugate(dq)
    array([ 1., -0., -0., -0.,  0., -0., -0., -0.])
    """
    a = as_array(dq, "dq", (8,))
    return a * np.array([1.0, -1, -1, -1, 1, -1, -1, -1])


def dual_quat_transform_point(dq, p):
    r"""Apply the motion to points: :math:`p' = q_r p q_r^* + t`, the vector part of
    :math:`\hat q (1 + \varepsilon p) \bar{\hat q}^*`.

    >>> from kinlib import rotz, transform
    >>> dq = dual_quat_from_transform(transform(rotz(np.pi / 2), [1.0, 0.0, 0.0]))
    >>> dual_quat_transform_point(dq, [1.0, 0.0, 0.0]).round(12) + 0.0
    array([1., 1., 0.])
    """
    qr, qd = _unit_dq(dq)
    pts = as_array(p, "p", (3,))
    broadcast((qr, 1, "dq"), (pts, 1, "p"))
    return quat_rotate(qr, pts) + _translation(qr, qd)


def screw_from_dual_quat(dq):
    r"""Screw parameters ``(l, m, theta, d)`` of a unit dual quaternion.

    l is the unit axis direction, m = c × l its moment (c on the axis), θ ∈ [0, π] the
    rotation about it and d the translation along it. The axis point nearest the origin is
    :math:`c = \tfrac12\left(t_\perp + \cot\tfrac\theta2\, l \times t\right)` for the
    translation t. A pure translation (θ = 0) has l = t/|t|, d = |t| and m = 0 (the axis
    through the origin; any parallel line would do); the identity returns l = [0, 0, 1].
    For one dual quaternion θ and d are Python floats; for a batch, arrays.

    A quarter turn about the vertical line through c = (1, 0, 0) takes the origin to
    R(0 − c) + c = (1, −1, 0); add a lift of 0.5 along the line:

    >>> from kinlib import rotz, transform
    >>> T = transform(rotz(np.pi / 2), [1.0, -1.0, 0.5])
    >>> l, m, theta, d = screw_from_dual_quat(dual_quat_from_transform(T))
    >>> l.round(12) + 0.0, m.round(12) + 0.0, round(theta, 12), round(d, 12)
    (array([0., 0., 1.]), array([ 0., -1.,  0.]), 1.570796326795, 0.5)
    """
    qr, qd = _unit_dq(dq)
    sign = np.where(qr[..., :1] < 0, -1.0, 1.0)  # −dq is the same motion; θ in [0, π]
    qr, qd = sign * qr, sign * qd
    t = _translation(qr, qd)
    v = qr[..., 1:]
    s = np.linalg.norm(v, axis=-1)
    theta = 2.0 * np.arctan2(s, qr[..., 0])
    rot = s > 1e-12
    tn = np.linalg.norm(t, axis=-1)
    # Direction: the rotation axis, else the translation, else z.
    l_rot = v / np.where(rot, s, 1.0)[..., None]
    l_tr = np.where((tn > 0)[..., None], t / np.where(tn > 0, tn, 1.0)[..., None], [0.0, 0, 1])
    lvec = np.where(rot[..., None], l_rot, l_tr)
    d = np.einsum("...i,...i->...", lvec, t)
    t_perp = t - d[..., None] * lvec
    half = 0.5 * theta
    cot = np.where(rot, np.cos(half) / np.where(rot, np.sin(half), 1.0), 0.0)
    m = 0.5 * (np.cross(t, lvec) + cot[..., None] * t_perp)
    m = np.where(rot[..., None], m, 0.0)
    return lvec, m, py_scalar(theta), py_scalar(d)


def dual_quat_from_screw(l, m, theta, d):
    r"""Unit dual quaternion of the screw motion ``(l, m, theta, d)``.

    ``l`` is normalised; ``m`` must be perpendicular to it (it is a moment ``c × l``).

    >>> l, m = [0.0, 0.0, 1.0], [0.0, -1.0, 0.0]   # the vertical line through (1, 0, 0)
    >>> dq = dual_quat_from_screw(l, m, np.pi / 2, 0.5)
    >>> transform_from_dual_quat(dq).round(12) + 0.0
    array([[ 0. , -1. ,  0. ,  1. ],
           [ 1. ,  0. ,  0. , -1. ],
           [ 0. ,  0. ,  1. ,  0.5],
           [ 0. ,  0. ,  0. ,  1. ]])
    """
    lv = as_unit_vectors(l, "l")
    mv = as_array(m, "m", (3,))
    th = as_array(theta, "theta")
    dd = as_array(d, "d")
    batch = broadcast((lv, 1, "l"), (mv, 1, "m"), (th, 0, "theta"), (dd, 0, "d"))
    dot = np.einsum("...i,...i->...", lv, mv)
    bad = np.abs(dot) > _TOL * (1.0 + np.linalg.norm(mv, axis=-1))
    if np.any(bad):
        raise KinlibError(
            f"m{fmt_index(dot.shape, bad)}: the moment m = c × l must be perpendicular to the "
            f"axis direction l, but l·m = {dot[bad].flat[0]:.3g}"
        )
    h = 0.5 * th[..., None]
    c, s = np.cos(h), np.sin(h)
    hd = 0.5 * dd[..., None]
    out = np.empty(batch + (8,))
    out[..., 0:1] = c
    out[..., 1:4] = s * lv
    out[..., 4:5] = -hd * s
    out[..., 5:8] = s * mv + hd * c * lv
    return out


def dual_quat_sclerp(dq0, dq1, t):
    r"""Screw linear interpolation (ScLERP) from ``dq0`` (t = 0) to ``dq1`` (t = 1).

    The relative motion :math:`\hat q_0^* \hat q_1` is one screw: θ about the line (l, m)
    and d along it. The pose at t applies the fraction t of that screw,
    :math:`\hat q_0\, (\hat q_0^* \hat q_1)^t`: tθ about the same line and td along it, so
    every point of the body moves on a helix and the rotation angle grows uniformly. It is
    the rigid-motion analogue of :func:`~kinlib.quat_slerp`, and like it takes the short way
    (θ ≤ π). Unlike interpolating the translation linearly, the result does not depend on
    where the body frame's origin is placed.

    The translation is evaluated as
    :math:`t\,p + (\alpha - t)\,p_\perp + \tfrac{\beta}{\sin(\theta/2)}\,(v \times p)`
    with the relative translation p, the rotation quaternion's vector part v and ratios of
    sines written with ``sinc``, so it stays accurate as θ → 0 (where the screw axis runs off
    to infinity) and reduces to linear interpolation at θ = 0.

    ``t`` may be an array: the result has shape ``broadcast(dq0, dq1, t) + (8,)``.
    t outside [0, 1] raises :class:`KinlibError`.

    Half of a quarter turn about the vertical line through (1, 0, 0) with a lift of 1:

    >>> from kinlib import rotz, transform
    >>> T1 = transform(rotz(np.pi / 2), [1.0, -1.0, 1.0])
    >>> dq0, dq1 = dual_quat_from_transform(np.eye(4)), dual_quat_from_transform(T1)
    >>> dq = dual_quat_sclerp(dq0, dq1, 0.5)
    >>> T = transform_from_dual_quat(dq)
    >>> bool(np.allclose(T[:3, :3], rotz(np.pi / 4))), T[:3, 3].round(6) + 0.0
    (True, array([ 0.292893, -0.707107,  0.5     ]))
    """
    r0, d0 = _unit_dq(dq0, "dq0")
    r1, d1 = _unit_dq(dq1, "dq1")
    tt = as_array(t, "t")
    bad = (tt < 0.0) | (tt > 1.0)
    if np.any(bad):
        raise KinlibError(
            f"t{fmt_index(tt.shape, bad)}: expected values in [0, 1], got {tt[bad].flat[0]:g}"
        )
    broadcast((r0, 1, "dq0"), (r1, 1, "dq1"), (tt, 0, "t"))
    a = np.concatenate([r0, d0], axis=-1)
    rel = dual_quat_multiply(dual_quat_conjugate(a), np.concatenate([r1, d1], axis=-1))
    sign = np.where(rel[..., :1] < 0, -1.0, 1.0)  # the short way: w >= 0, θ in [0, π]
    rel = sign * rel
    qr, qd = rel[..., :4], rel[..., 4:]
    p = _translation(qr, qd)
    v = qr[..., 1:]
    s = np.linalg.norm(v, axis=-1)
    h = np.arctan2(s, qr[..., 0])  # θ/2
    sinc_h = np.sinc(h / np.pi)  # sin h / h, > 0 for h in [0, π/2]
    r_half = tt * np.sinc(tt * h / np.pi) / sinc_h  # sin(t h) / sin h
    r1_ = 2.0 * tt * np.sinc(2.0 * tt * h / np.pi) / sinc_h  # sin(2 t h) / sin h
    cos_h = np.cos(h)
    alpha = np.sin(tt * h) ** 2 + 0.5 * r1_ * cos_h
    beta_s = r_half**2 * cos_h - 0.5 * r1_
    vp = np.einsum("...i,...i->...", v, p)
    safe = np.where(s > 0.0, s, 1.0)
    p_perp = p - np.where((s > 0.0)[..., None], v * (vp / safe**2)[..., None], 0.0)
    pt = tt[..., None] * p + (alpha - tt)[..., None] * p_perp + beta_s[..., None] * np.cross(v, p)
    qt = np.concatenate([np.cos(tt * h)[..., None], r_half[..., None] * v], axis=-1)
    step = np.concatenate([qt, 0.5 * quat_multiply(_pure(pt), qt)], axis=-1)
    return dual_quat_multiply(a, step)
