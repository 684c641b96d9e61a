r"""Unit quaternions (Euler parameters), Hamilton convention, scalar first ``[w, x, y, z]``.

A rotation of θ about the unit axis u is :math:`q = (\cos\frac\theta2, u \sin\frac\theta2)`;
q and −q are the same rotation. The product follows :math:`i^2 = j^2 = k^2 = ijk = -1`:

.. math:: (r_1, v_1)(r_2, v_2) = (r_1 r_2 - v_1 \cdot v_2,\; r_1 v_2 + r_2 v_1 + v_1 \times v_2)

and a vector p is rotated by conjugation, :math:`p' = q\,(0, p)\,q^{-1}`. Composition is
``quat_multiply(q2, q1)``: first q1, then q2 (like ``R2 @ R1``).
"""

from __future__ import annotations

import numpy as np

from .._accel import MIN_BATCH, kernel
from .._validate import as_array, as_unit_vectors, broadcast, fmt_index, py_scalar, unit_rows
from ..errors import KinlibError
from .rotations import check_rotation

__all__ = [
    "quat_multiply",
    "quat_conjugate",
    "quat_inverse",
    "quat_normalize",
    "quat_rotate",
    "quat_from_axis_angle",
    "axis_angle_from_quat",
    "matrix_from_quat",
    "quat_from_matrix",
    "quat_slerp",
    "quat_xyzw_from_wxyz",
    "quat_wxyz_from_xyzw",
]

_ZERO = 1e-12


def _quat(q, name="q"):
    return as_array(q, name, (4,))


def _norm(q):
    return np.sqrt(np.einsum("...i,...i->...", q, q))


def _nonzero(q, name, n=None):
    n = _norm(q) if n is None else n
    small = n <= _ZERO
    if np.any(small):
        where = fmt_index(q.shape[:-1], small)
        raise KinlibError(
            f"{name}{where}: the zero quaternion has no inverse and is no rotation; "
            f"expected a non-zero [w, x, y, z] (norm {n[small].flat[0]:.3g})"
        )
    return n


def quat_multiply(p, q):
    r"""Hamilton product ``p q`` (batched, broadcasting over leading dimensions).

    >>> i, j = [0.0, 1, 0, 0], [0.0, 0, 1, 0]
    >>> quat_multiply(i, j)  # ij = k
    array([0., 0., 0., 1.])
    >>> quat_multiply(i, i)  # i² = −1
    array([-1.,  0.,  0.,  0.])
    """
    a, b = _quat(p, "p"), _quat(q, "q")
    broadcast((a, 1, "p"), (b, 1, "q"))
    w1, x1, y1, z1 = np.moveaxis(a, -1, 0)
    w2, x2, y2, z2 = np.moveaxis(b, -1, 0)
    return np.stack(
        [
            w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2,
            w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
            w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
            w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2,
        ],
        axis=-1,
    )


def quat_conjugate(q):
    """Conjugate ``(w, −v)``; for a unit quaternion this is the inverse rotation.

    >>> quat_conjugate([1.0, 2.0, 3.0, 4.0])
    array([ 1., -2., -3., -4.])
    """
    a = _quat(q)
    return a * np.array([1.0, -1.0, -1.0, -1.0])


def quat_inverse(q):
    """Inverse ``q̄ / |q|²`` of a non-zero quaternion.

    >>> q = [1.0, 2.0, 3.0, 4.0]
    >>> quat_multiply(q, quat_inverse(q)).round(15) + 0.0
    array([1., 0., 0., 0.])
    """
    a = _quat(q)
    n = _nonzero(a, "q")
    return quat_conjugate(a) / (n * n)[..., None]


def quat_normalize(q):
    """``q / |q|``; the zero quaternion raises :class:`KinlibError`.

    >>> quat_normalize([0.0, 0.0, 0.0, 2.0])
    array([0., 0., 0., 1.])
    """
    return _unit(q, "q")


def _unit(q, name):
    """``q`` checked and normalised (robust to huge and tiny entries)."""
    a = _quat(q, name)
    u, n = unit_rows(a)
    _nonzero(a, name, n)
    return u


def quat_rotate(q, v):
    r"""Rotate vectors ``v`` by the rotation of ``q``: the vector part of :math:`q (0, v) q^{-1}`.

    Computed as :math:`v + 2w (u \times v) + 2 u \times (u \times v)` for the normalised
    ``q = (w, u)``; q need not be unit (the conjugation by the inverse cancels its norm).

    >>> q = quat_from_axis_angle([0.0, 0.0, 1.0], np.pi / 2)
    >>> quat_rotate(q, [1.0, 0.0, 0.0]).round(12) + 0.0
    array([0., 1., 0.])
    """
    a = quat_normalize(q)
    b = as_array(v, "v", (3,))
    broadcast((a, 1, "q"), (b, 1, "v"))
    w, u = a[..., :1], a[..., 1:]
    t = 2.0 * np.cross(u, b)
    return b + w * t + np.cross(u, t)


def quat_from_axis_angle(axis, angle):
    r"""Unit quaternion :math:`(\cos\frac\theta2, u\sin\frac\theta2)` of a rotation by
    ``angle`` about ``axis`` (normalised; a zero axis raises :class:`KinlibError`).

    >>> quat_from_axis_angle([0.0, 0.0, 1.0], np.pi).round(12) + 0.0
    array([0., 0., 0., 1.])
    """
    u = as_unit_vectors(axis, "axis")
    t = as_array(angle, "angle")
    batch = broadcast((u, 1, "axis"), (t, 0, "angle"))
    half = 0.5 * t[..., None]
    out = np.empty(batch + (4,))
    out[..., :1] = np.cos(half)
    out[..., 1:] = np.sin(half) * u
    return out


def axis_angle_from_quat(q):
    """``(axis, angle)`` of a quaternion, with the angle in [0, π].

    ``q`` is normalised first. For the identity the axis is undefined and ``[1, 0, 0]``
    is returned. The angle is a Python float for one quaternion, an array for a batch.

    >>> axis, angle = axis_angle_from_quat([np.sqrt(0.5), 0.0, np.sqrt(0.5), 0.0])
    >>> axis.round(12) + 0.0, round(angle, 12)
    (array([0., 1., 0.]), 1.570796326795)
    """
    v, s, angle = _half_turn_parts(quat_normalize(q))
    tiny = s <= 1e-300
    axis = np.where(tiny[..., None], [1.0, 0.0, 0.0], v / np.where(tiny, 1.0, s)[..., None])
    return axis, py_scalar(angle)


def _half_turn_parts(a):
    """For unit quaternions ``a``: ``(v, |v|, angle)`` of the one with ``w >= 0`` (the same
    rotation, angle in [0, π]): its vector part, that part's norm and ``2 atan2(|v|, w)``."""
    a = np.where(a[..., :1] < 0, -a, a)
    v = a[..., 1:]
    # hypot, not sqrt(v·v): the squares underflow for angles below ~1e-154
    s = np.hypot(np.hypot(v[..., 0], v[..., 1]), v[..., 2])
    return v, s, 2.0 * np.arctan2(s, a[..., 0])


def matrix_from_quat(q):
    r"""Rotation matrix of a quaternion (normalised first; zero raises).

    .. math::

        R = \begin{bmatrix}
        1-2(y^2+z^2) & 2(xy-wz) & 2(xz+wy)\\
        2(xy+wz) & 1-2(x^2+z^2) & 2(yz-wx)\\
        2(xz-wy) & 2(yz+wx) & 1-2(x^2+y^2)\end{bmatrix}

    >>> matrix_from_quat([0.0, 0.0, 0.0, 1.0])  # 180° about z
    array([[-1.,  0.,  0.],
           [ 0., -1.,  0.],
           [ 0.,  0.,  1.]])
    """
    a = _quat(q)
    if a.size and np.abs(a).max() > 1e150:  # |q|² would overflow: scale each row first
        a = unit_rows(a)[0]
    if a.size < 4 * MIN_BATCH:
        return _matrix_from_quat_numpy(a)
    flat = np.ascontiguousarray(a.reshape(-1, 4))
    out = np.empty((len(flat), 3, 3))
    fn = kernel("matrix_from_quat", lambda: (flat[:0], out[:0]))
    if fn is None:
        return _matrix_from_quat_numpy(a)
    if fn(flat, out) >= 0:
        _nonzero(a, "q")
    return out.reshape(a.shape[:-1] + (3, 3))


def _matrix_from_quat_numpy(a):
    """The numpy reference of :func:`matrix_from_quat` for a checked (..., 4) array."""
    n2 = np.einsum("...i,...i->...", a, a)
    if np.any(n2 <= _ZERO * _ZERO):
        _nonzero(a, "q")
    s = 2.0 / n2
    w, x, y, z = np.moveaxis(a, -1, 0)
    xs, ys, zs = x * s, y * s, z * s
    xx, yy, zz = x * xs, y * ys, z * zs
    xy, xz, yz = x * ys, x * zs, y * zs
    wx, wy, wz = w * xs, w * ys, w * zs
    R = np.empty(a.shape[:-1] + (3, 3))
    R[..., 0, 0] = 1.0 - (yy + zz)
    R[..., 0, 1] = xy - wz
    R[..., 0, 2] = xz + wy
    R[..., 1, 0] = xy + wz
    R[..., 1, 1] = 1.0 - (xx + zz)
    R[..., 1, 2] = yz - wx
    R[..., 2, 0] = xz - wy
    R[..., 2, 1] = yz + wx
    R[..., 2, 2] = 1.0 - (xx + yy)
    return R


def quat_from_matrix(R):
    r"""Unit quaternion (``w >= 0``) of a rotation matrix, accurate for every rotation.

    Shepperd's method: of :math:`4w^2 = 1 + \operatorname{tr} R` and
    :math:`4x^2 = 1 + 2R_{11} - \operatorname{tr} R` (and likewise y, z), the largest is
    taken with a square root and the other three components follow from sums and
    differences of off-diagonal entries divided by it — never by a number near zero, so
    180° rotations (trace −1) are as accurate as small ones.

    >>> quat_from_matrix(np.diag([-1.0, -1.0, 1.0]))  # 180° about z
    array([0., 0., 0., 1.])
    """
    m = check_rotation(R)
    if m.size < 9 * MIN_BATCH:
        return _quat_from_matrix_numpy(m)
    flat = np.ascontiguousarray(m.reshape(-1, 3, 3))
    out = np.empty((len(flat), 4))
    fn = kernel("quat_from_matrix", lambda: (flat[:0], out[:0]))
    if fn is None:
        return _quat_from_matrix_numpy(m)
    fn(flat, out)
    return out.reshape(m.shape[:-2] + (4,))


def _quat_from_matrix_numpy(m):
    """The numpy reference of :func:`quat_from_matrix` for a checked (..., 3, 3) array."""
    m00, m01, m02 = m[..., 0, 0], m[..., 0, 1], m[..., 0, 2]
    m10, m11, m12 = m[..., 1, 0], m[..., 1, 1], m[..., 1, 2]
    m20, m21, m22 = m[..., 2, 0], m[..., 2, 1], m[..., 2, 2]
    t = np.stack(
        [
            1.0 + m00 + m11 + m22,
            1.0 + m00 - m11 - m22,
            1.0 - m00 + m11 - m22,
            1.0 - m00 - m11 + m22,
        ]
    )
    k = np.argmax(t, axis=0)
    d21, d02, d10 = m21 - m12, m02 - m20, m10 - m01
    s10, s02, s21 = m10 + m01, m02 + m20, m21 + m12
    # Row k of the symmetric matrix K (= 4 q_k q); each row is q up to a positive factor.
    rows = np.stack(
        [
            np.choose(k, [t[0], d21, d02, d10]),
            np.choose(k, [d21, t[1], s10, s02]),
            np.choose(k, [d02, s10, t[2], s21]),
            np.choose(k, [d10, s02, s21, t[3]]),
        ],
        axis=-1,
    )
    rows *= (np.where(rows[..., 0] < 0, -1.0, 1.0) / _norm(rows))[..., None]
    return rows


def quat_slerp(q0, q1, t):
    r"""Spherical linear interpolation from ``q0`` (t = 0) to ``q1`` (t = 1), shortest path.

    .. math:: q(t) = \frac{\sin((1-t)\Omega)}{\sin\Omega} q_0 + \frac{\sin(t\Omega)}{\sin\Omega} q_1

    where Ω is the angle between q0 and q1, after q1 is negated if needed so that
    Ω ≤ 90° (the rotation turns the short way). The rotation angle grows uniformly in t.
    ``t`` may be an array: the result has shape ``broadcast(q0, q1, t) + (4,)``.
    t outside [0, 1] raises :class:`KinlibError`.

    >>> q0 = [1.0, 0.0, 0.0, 0.0]
    >>> q1 = quat_from_axis_angle([0.0, 0.0, 1.0], np.pi / 2)
    >>> quat_slerp(q0, q1, 0.5).round(6)
    array([0.92388 , 0.      , 0.      , 0.382683])
    """
    a, b = _unit(q0, "q0"), _unit(q1, "q1")
    tt = as_array(t, "t")
    if np.any((tt < 0.0) | (tt > 1.0)):
        bad = (tt < 0.0) | (tt > 1.0)
        raise KinlibError(
            f"t{fmt_index(tt.shape, bad)}: expected values in [0, 1], got "
            f"{tt[bad].flat[0]:g}"
        )
    broadcast((a, 1, "q0"), (b, 1, "q1"), (tt, 0, "t"))
    b = np.where(np.einsum("...i,...i->...", a, b)[..., None] < 0, -b, b)
    # Ω from chord lengths: accurate for tiny and for large angles alike.
    omega = 2.0 * np.arctan2(_norm(a - b), _norm(a + b))
    sinc_om = np.sinc(omega / np.pi)  # sin Ω / Ω, = 1 at Ω = 0
    ta = tt[..., None]
    w0 = (1.0 - ta) * np.sinc((1.0 - ta) * omega[..., None] / np.pi) / sinc_om[..., None]
    w1 = ta * np.sinc(ta * omega[..., None] / np.pi) / sinc_om[..., None]
    out = w0 * a + w1 * b
    return out / _norm(out)[..., None]


def quat_xyzw_from_wxyz(q):
    """Scalar-last ``[x, y, z, w]`` (ROS, scipy) from kinlib's ``[w, x, y, z]``.

    >>> quat_xyzw_from_wxyz([1.0, 2.0, 3.0, 4.0])
    array([2., 3., 4., 1.])
    """
    return np.roll(_quat(q), -1, axis=-1)


def quat_wxyz_from_xyzw(q):
    """kinlib's ``[w, x, y, z]`` from scalar-last ``[x, y, z, w]``.

    >>> quat_wxyz_from_xyzw([2.0, 3.0, 4.0, 1.0])
    array([1., 2., 3., 4.])
    """
    return np.roll(_quat(q), 1, axis=-1)
