r"""Rotation matrices: the elementary rotations, skew-symmetric matrices, and checks.

A rotation matrix :math:`{}^A R_B` holds the unit axes of frame B written in frame A as
its columns (direction cosines). It is orthonormal, :math:`R^T R = I`, with
:math:`\det R = +1`; so :math:`R^{-1} = R^T`.
"""

from __future__ import annotations

import math

import numpy as np

from .._accel import MIN_BATCH, kernel
from .._validate import as_array, as_tol, fmt_index, is_symbolic, py_scalar
from ..conventions import ROTATION_TOL, SKEW_TOL
from ..errors import KinlibError

__all__ = [
    "rotx",
    "roty",
    "rotz",
    "skew",
    "vee",
    "is_rotation",
    "check_rotation",
    "nearest_rotation",
    "rotation_errors",
]


def _axis_rotation(axis: int, theta, name: str):
    if is_symbolic(theta):
        from ..symbolic import _sym

        return _sym.axis_rotation(axis, theta)
    t = as_array(theta, name)
    c, s = np.cos(t), np.sin(t)
    R = np.zeros(t.shape + (3, 3))
    i, j = (axis + 1) % 3, (axis + 2) % 3
    R[..., axis, axis] = 1.0
    R[..., i, i] = c
    R[..., j, j] = c
    R[..., i, j] = -s
    R[..., j, i] = s
    return R


def rotx(theta):
    r"""Rotation about the x-axis by ``theta`` radians.

    .. math:: R_x(\theta) = \begin{bmatrix}1&0&0\\0&c\theta&-s\theta\\0&s\theta&c\theta\end{bmatrix}

    ``theta`` may be an array (the result is ``theta.shape + (3, 3)``) or a sympy
    expression (the result is a ``sympy.Matrix``).

    >>> rotx(np.pi / 2).round(12) + 0.0
    array([[ 1.,  0.,  0.],
           [ 0.,  0., -1.],
           [ 0.,  1.,  0.]])
    >>> import sympy as sp
    >>> rotx(sp.Symbol("q"))
    Matrix([
    [1,         0,          0],
    [0, cos(q), -sin(q)],
    [0, sin(q),  cos(q)]])
    """
    return _axis_rotation(0, theta, "theta")


def roty(theta):
    r"""Rotation about the y-axis by ``theta`` radians.

    .. math:: R_y(\theta) = \begin{bmatrix}c\theta&0&s\theta\\0&1&0\\-s\theta&0&c\theta\end{bmatrix}

    >>> roty(np.pi / 2) @ [1.0, 0.0, 0.0]
    array([ 6.123...e-17,  0.000...e+00, -1.000...e+00])
    """
    return _axis_rotation(1, theta, "theta")


def rotz(theta):
    r"""Rotation about the z-axis by ``theta`` radians.

    .. math:: R_z(\theta) = \begin{bmatrix}c\theta&-s\theta&0\\s\theta&c\theta&0\\0&0&1\end{bmatrix}

    >>> rotz([0.0, np.pi]).shape
    (2, 3, 3)
    """
    return _axis_rotation(2, theta, "theta")


def skew(v):
    r"""The skew-symmetric matrix :math:`[v]_\times` with :math:`[v]_\times b = v \times b`.

    .. math:: [v]_\times = \begin{bmatrix}0&-v_z&v_y\\v_z&0&-v_x\\-v_y&v_x&0\end{bmatrix}

    >>> skew([1.0, 2.0, 3.0]) @ [4.0, 5.0, 6.0]
    array([-3.,  6., -3.])
    >>> np.cross([1.0, 2.0, 3.0], [4.0, 5.0, 6.0])
    array([-3.,  6., -3.])
    """
    if is_symbolic(v):
        from ..symbolic import _sym

        return _sym.skew(v)
    a = as_array(v, "v", (3,))
    S = np.zeros(a.shape[:-1] + (3, 3))
    x, y, z = a[..., 0], a[..., 1], a[..., 2]
    S[..., 0, 1], S[..., 0, 2] = -z, y
    S[..., 1, 0], S[..., 1, 2] = z, -x
    S[..., 2, 0], S[..., 2, 1] = -y, x
    return S


def _is_sympy_matrix(S) -> bool:
    return (type(S).__module__ or "").startswith("sympy")


def vee(S, tol: float = SKEW_TOL):
    r"""The vector of a skew-symmetric matrix: the inverse of :func:`skew`.

    Raises :class:`KinlibError` if ``S`` is not skew-symmetric within ``tol`` (relative to
    its size), because the result would silently drop the symmetric part.

    >>> vee(skew([1.0, 2.0, 3.0]))
    array([1., 2., 3.])

    Given a sympy matrix it returns a 3×1 ``sympy.Matrix`` (after proving S = −Sᵀ):

    >>> import sympy as sp
    >>> w = sp.symbols("w_x w_y w_z")
    >>> vee(skew(w)).T
    Matrix([[w_x, w_y, w_z]])
    """
    if is_symbolic(S) or _is_sympy_matrix(S):
        from ..symbolic import _sym

        return _sym.vee(S)
    a = as_array(S, "S", (3, 3))
    tol = as_tol(tol)
    asym = np.abs(a + np.swapaxes(a, -1, -2)).max(axis=(-2, -1))
    scale = 1.0 + np.abs(a).max(axis=(-2, -1))
    bad = asym > tol * scale
    if np.any(bad):
        where = fmt_index(a.shape[:-2], bad)
        raise KinlibError(
            f"S{where}: expected a skew-symmetric matrix (S = -Sᵀ), but max |S + Sᵀ| = "
            f"{asym[bad].flat[0]:.3g} (tolerance {tol:g})"
        )
    return np.stack([a[..., 2, 1], a[..., 0, 2], a[..., 1, 0]], axis=-1)


def rotation_errors(R) -> tuple[np.ndarray, np.ndarray]:
    """``(orthonormality error, det)`` of a batch of 3×3 matrices.

    The orthonormality error is ``max |RᵀR − I|`` over the nine entries.
    """
    a = as_array(R, "R", (3, 3))
    if a.size >= 9 * MIN_BATCH:
        flat = np.ascontiguousarray(a.reshape(-1, 3, 3))
        err, det = np.empty(len(flat)), np.empty(len(flat))
        fn = kernel("rotation_errors", lambda: (flat[:0], err[:0], det[:0]))
        if fn is not None:
            fn(flat, err, det)
            return err.reshape(a.shape[:-2]), det.reshape(a.shape[:-2])
    return _rotation_errors_numpy(a)


def _rotation_errors_numpy(a):
    """The numpy reference of :func:`rotation_errors` for a checked (..., 3, 3) array."""
    if a.ndim == 2:  # one matrix: the same sums on Python floats, without numpy's per-call cost
        (x0, x1, x2), (y0, y1, y2), (z0, z1, z2) = a.tolist()  # rows; columns c0 = (x0, y0, z0)
        errs = (abs(x0 * x0 + y0 * y0 + z0 * z0 - 1.0), abs(x1 * x1 + y1 * y1 + z1 * z1 - 1.0),
                abs(x2 * x2 + y2 * y2 + z2 * z2 - 1.0), abs(x0 * x1 + y0 * y1 + z0 * z1),
                abs(x0 * x2 + y0 * y2 + z0 * z2), abs(x1 * x2 + y1 * y2 + z1 * z2))
        err = math.nan if any(e != e for e in errs) else max(errs)  # NaN wins, as in np.max
        det = x0 * (y1 * z2 - z1 * y2) + y0 * (z1 * x2 - x1 * z2) + z0 * (x1 * y2 - y1 * x2)
        return np.float64(err), np.float64(det)
    with np.errstate(over="ignore", invalid="ignore"):  # huge entries: inf or NaN, judged
        return _rotation_errors_batch(a)


def _rotation_errors_batch(a):
    c0, c1, c2 = a[..., :, 0], a[..., :, 1], a[..., :, 2]

    def dot(u, v):
        return u[..., 0] * v[..., 0] + u[..., 1] * v[..., 1] + u[..., 2] * v[..., 2]

    err = np.max(
        np.abs(
            [
                dot(c0, c0) - 1.0,
                dot(c1, c1) - 1.0,
                dot(c2, c2) - 1.0,
                dot(c0, c1),
                dot(c0, c2),
                dot(c1, c2),
            ]
        ),
        axis=0,
    )
    # c0 · (c1 × c2), the cross product written out (np.cross costs more than the
    # arithmetic for one matrix; the same products in the same order: the same bits)
    det = (c0[..., 0] * (c1[..., 1] * c2[..., 2] - c1[..., 2] * c2[..., 1])
           + c0[..., 1] * (c1[..., 2] * c2[..., 0] - c1[..., 0] * c2[..., 2])
           + c0[..., 2] * (c1[..., 0] * c2[..., 1] - c1[..., 1] * c2[..., 0]))
    return err, det


def is_rotation(R, tol: float = ROTATION_TOL):
    """Whether ``R`` is a rotation matrix: ``max |RᵀR − I| <= tol`` and ``|det R − 1| <= tol``.

    Batched: returns a bool ndarray of the batch shape (a Python ``bool`` for one matrix).
    Input that is not numeric or not of shape (..., 3, 3) raises :class:`KinlibError`;
    NaN/inf gives ``False``.

    >>> is_rotation(rotz(0.3))
    True
    >>> is_rotation(np.diag([1.0, 1.0, -1.0]))  # a reflection
    False
    """
    a = as_array(R, "R", (3, 3), finite=False)
    tol = as_tol(tol)
    finite = np.isfinite(a).all(axis=(-2, -1))
    err, det = rotation_errors(np.where(finite[..., None, None], a, 0.0))
    return py_scalar(finite & (err <= tol) & (np.abs(det - 1.0) <= tol))


def check_rotation(R, name: str = "R", *, tol: float = ROTATION_TOL) -> np.ndarray:
    """Return ``R`` as a float array if it is a rotation matrix, else raise :class:`KinlibError`.

    ``name`` is what the message calls the matrix; ``tol`` bounds max |RᵀR − I| and
    |det R − 1| (as in :func:`is_rotation`). The message says which property failed
    (orthonormality or det = +1), by how much, and, for a batch, which matrix.

    >>> check_rotation(np.eye(3)).shape
    (3, 3)
    >>> check_rotation(2 * np.eye(3))
    Traceback (most recent call last):
    ...
    kinlib.errors.KinlibError: R is not a rotation matrix: its columns are not orthonormal, ...
    """
    a = as_array(R, name, (3, 3))
    tol = as_tol(tol)
    err, det = rotation_errors(a)
    bad_orth = ~(err <= tol)  # (NaN too: the products of huge entries overflow)
    if np.any(bad_orth):
        where = fmt_index(a.shape[:-2], bad_orth)
        raise KinlibError(
            f"{name}{where} is not a rotation matrix: its columns are not orthonormal, "
            f"max |RᵀR − I| = {err[bad_orth].flat[0]:.3g} (tolerance {tol:g})"
        )
    bad_det = ~(np.abs(det - 1.0) <= tol)
    if np.any(bad_det):
        where = fmt_index(a.shape[:-2], bad_det)
        d = det[bad_det].flat[0]
        hint = " (a reflection, not a rotation)" if d < 0 else ""
        raise KinlibError(
            f"{name}{where} is not a rotation matrix: det R = {d:.6g}, expected +1{hint} "
            f"(tolerance {tol:g})"
        )
    return a


def nearest_rotation(M) -> np.ndarray:
    r"""The rotation matrix closest to ``M`` in the Frobenius norm (SVD projection).

    With :math:`M = U \Sigma V^T`, the answer is :math:`U \operatorname{diag}(1, 1, d) V^T`
    where :math:`d = \det(U V^T)` keeps the determinant at +1.

    >>> M = rotz(0.3) + 1e-3  # a rotation with noise
    >>> is_rotation(nearest_rotation(M), tol=1e-12)
    True
    """
    a = as_array(M, "M", (3, 3))
    U, _, Vt = np.linalg.svd(a)
    d = np.sign(np.linalg.det(U @ Vt))
    d = np.where(d == 0, 1.0, d)
    U = U.copy()
    U[..., :, 2] *= d[..., None]
    return U @ Vt

