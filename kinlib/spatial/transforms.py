r"""Homogeneous transforms: frames, mappings, compounding and the closed-form inverse.

The pose of frame B in frame A is

.. math:: {}^A T_B = \begin{bmatrix} {}^A R_B & {}^A p_{B,org} \\ 0\;0\;0 & 1 \end{bmatrix},
          \qquad {}^A p = {}^A T_B\, {}^B p,\qquad {}^A T_C = {}^A T_B\, {}^B T_C ,

and its inverse needs no general matrix inversion (seed 002):

.. math:: {}^B T_A = \begin{bmatrix} R^T & -R^T p \\ 0 & 1 \end{bmatrix}.

Points carry a homogeneous 1 and feel the translation; free vectors (directions,
velocities, forces) carry a 0 and are only rotated.
"""

from __future__ import annotations

import numpy as np

from .._validate import as_array, as_tol, broadcast, fmt_index, is_symbolic
from ..conventions import ROTATION_TOL
from ..errors import KinlibError
from .rotations import check_rotation

__all__ = ["transform", "transform_inverse", "transform_points", "transform_vectors",
           "check_transform"]


def transform(R=None, p=None):
    r"""Homogeneous transform from a rotation ``R`` (default I) and translation ``p`` (default 0).

    Batched: ``R`` (..., 3, 3) and ``p`` (..., 3) broadcast to (..., 4, 4). ``R`` is checked
    to be a rotation. Sympy input gives a ``sympy.Matrix``.

    >>> from kinlib import rotz
    >>> transform(rotz(np.pi / 6), [10.0, 5.0, 0.0]).round(4)
    array([[ 0.866, -0.5  ,  0.   , 10.   ],
           [ 0.5  ,  0.866,  0.   ,  5.   ],
           [ 0.   ,  0.   ,  1.   ,  0.   ],
           [ 0.   ,  0.   ,  0.   ,  1.   ]])
    """
    if is_symbolic(R, p):
        from ..symbolic import _sym

        return _sym.transform(R, p)
    Rm = np.eye(3) if R is None else check_rotation(R)
    pv = np.zeros(3) if p is None else as_array(p, "p", (3,))
    batch = broadcast((Rm, 2, "R"), (pv, 1, "p"))
    T = np.zeros(batch + (4, 4))
    T[..., :3, :3] = Rm
    T[..., :3, 3] = pv
    T[..., 3, 3] = 1.0
    return T


def check_transform(T, name: str = "T", *, tol: float = ROTATION_TOL) -> np.ndarray:
    """``T`` as a float array of shape (..., 4, 4) if it is a rigid transform, else raise.

    Checks the bottom row ``[0, 0, 0, 1]`` and that the upper-left 3×3 block is a rotation
    (both to ``tol``, as :func:`~kinlib.check_rotation`); ``name`` is what the message
    calls ``T``. The same argument order as :func:`~kinlib.check_rotation`.

    >>> check_transform(np.eye(4)).shape
    (4, 4)
    >>> check_transform(np.ones((4, 4)), "T_ee")
    Traceback (most recent call last):
    ...
    kinlib.errors.KinlibError: T_ee: the bottom row of a homogeneous transform must be ...
    """
    a = as_array(T, name, (4, 4))
    tol = as_tol(tol)
    row_err = np.abs(a[..., 3, :] - [0.0, 0.0, 0.0, 1.0]).max(axis=-1)
    bad = row_err > tol
    if np.any(bad):
        where = fmt_index(a.shape[:-2], bad)
        row = np.asarray(a[..., 3, :])[bad][0] if a.ndim > 2 else a[3]
        raise KinlibError(
            f"{name}{where}: the bottom row of a homogeneous transform must be [0, 0, 0, 1], "
            f"got {np.array2string(row, precision=4)}"
        )
    check_rotation(a[..., :3, :3], f"{name}[:3, :3]", tol=tol)
    return a


def transform_inverse(T):
    r"""Closed-form inverse of a rigid transform:
    :math:`\begin{bmatrix}R^T & -R^Tp\\0&1\end{bmatrix}`.

    Also works on a ``sympy.Matrix``.

    >>> from kinlib import rotz
    >>> T = transform(rotz(0.3), [1.0, 2.0, 3.0])
    >>> bool(np.allclose(transform_inverse(T) @ T, np.eye(4)))
    True
    """
    if is_symbolic(T):
        import sympy as sp

        M = sp.Matrix(T)
        if M.shape != (4, 4):
            raise KinlibError(f"T: expected a 4×4 homogeneous transform, got shape {M.shape}")
        if any((e - v).is_zero is False for e, v in zip(M[3, :], (0, 0, 0, 1), strict=True)):
            raise KinlibError(
                f"T: the bottom row of a homogeneous transform must be [0, 0, 0, 1], "
                f"got {list(M[3, :])}"
            )
        Rt = M[:3, :3].T
        out = sp.eye(4)
        out[:3, :3] = Rt
        out[:3, 3] = -Rt * M[:3, 3]
        return out
    a = check_transform(T)
    Rt = np.swapaxes(a[..., :3, :3], -1, -2)
    out = np.zeros_like(a)
    out[..., :3, :3] = Rt
    out[..., :3, 3] = -np.einsum("...ij,...j->...i", Rt, a[..., :3, 3])
    out[..., 3, 3] = 1.0
    return out


def transform_points(T, P):
    r"""Map points: :math:`p' = R p + t` (homogeneous coordinate 1).

    ``T`` (..., 4, 4) and ``P`` (..., 3) broadcast: one transform and many points, many
    transforms and one point, or one each, pairwise.

    >>> from kinlib import rotz
    >>> T = transform(rotz(np.pi / 6), [10.0, 5.0, 0.0])  # seed 002's example
    >>> transform_points(T, [3.0, 7.0, 0.0]).round(3)
    array([ 9.098, 12.562,  0.   ])
    """
    a = check_transform(T)
    p = as_array(P, "P", (3,))
    broadcast((a, 2, "T"), (p, 1, "P"))
    return np.einsum("...ij,...j->...i", a[..., :3, :3], p) + a[..., :3, 3]


def transform_vectors(T, V):
    r"""Map free vectors: :math:`v' = R v` (homogeneous coordinate 0: no translation).

    >>> T = transform(p=[10.0, 5.0, 0.0])
    >>> transform_vectors(T, [1.0, 0.0, 0.0])
    array([1., 0., 0.])
    """
    a = check_transform(T)
    v = as_array(V, "V", (3,))
    broadcast((a, 2, "T"), (v, 1, "V"))
    return np.einsum("...ij,...j->...i", a[..., :3, :3], v)
