r"""Euler angles (intrinsic) and fixed angles (extrinsic): all 24 sequences, both ways.

A sequence is three axis letters. UPPERCASE turns about the axes of the moving frame
(intrinsic, "Euler angles"), lowercase about the fixed axes (extrinsic, "fixed angles").
Angles are listed in the order of the letters:

.. math::

    R_{ZYX}(\alpha, \beta, \gamma) = R_z(\alpha) R_y(\beta) R_x(\gamma)
    = R_{xyz}(\gamma, \beta, \alpha)

12 sequences use three different axes (Tait–Bryan: roll-pitch-yaw, ZYX, ...) and 12 repeat
the first axis last (proper Euler: ZYZ, XYX, ...). The inverse problem has a singularity
where the first and last axes line up (gimbal lock): the middle angle is ±π/2 for
Tait–Bryan sequences, 0 or π for proper Euler sequences. There only the sum or the
difference of the outer angles is defined; kinlib sets the first angle to 0 (Craig).
"""

from __future__ import annotations

import numpy as np

from .._validate import as_array, as_tol, is_symbolic, parse_seq, py_scalar, wrap_angle
from ..conventions import GIMBAL_TOL, ROUNDING_TOL
from .rotations import check_rotation

__all__ = ["matrix_from_euler", "euler_from_matrix", "euler_gimbal_lock", "EULER_SEQUENCES"]

#: All 24 sequences: 12 intrinsic (UPPERCASE) and 12 extrinsic (lowercase).
EULER_SEQUENCES = tuple(
    s
    for base in ("xyz", "xzy", "yxz", "yzx", "zxy", "zyx", "xyx", "xzx", "yxy", "yzy", "zxz", "zyz")
    for s in (base.upper(), base)
)

# Gimbal lock is declared when the middle angle is within ROUNDING_TOL (1e-12) radians of
# its singular value: far above the ~1e-16 rounding of a matrix built at the singularity,
# and small enough that setting the first angle to 0 changes the matrix by < 1e-11.


def _parity(i: int, j: int) -> float:
    """+1 if axis j follows axis i cyclically (x→y→z→x), else −1."""
    return 1.0 if j == (i + 1) % 3 else -1.0


def _intrinsic(axes, intrinsic: bool, angles):
    """Axes and angles of the intrinsic sequence equivalent to ``axes``."""
    if intrinsic:
        return axes, angles
    return axes[::-1], angles[..., ::-1]


def matrix_from_euler(angles, seq: str):
    r"""Rotation matrix from three Euler (intrinsic) or fixed (extrinsic) angles.

    Parameters
    ----------
    angles : array_like, shape (..., 3), or three sympy expressions
        The angles in radians, in the order of the letters of ``seq``.
    seq : str
        Three axis letters, e.g. ``"ZYX"`` (intrinsic) or ``"xyz"`` (extrinsic).

    Returns
    -------
    R : ndarray, shape (..., 3, 3), or sympy.Matrix for symbolic angles
        Intrinsic ``"ABC"``: :math:`R_A(\theta_1) R_B(\theta_2) R_C(\theta_3)`;
        extrinsic ``"abc"``: :math:`R_c(\theta_3) R_b(\theta_2) R_a(\theta_1)`.

    Examples
    --------
    >>> from kinlib import rotx, roty, rotz
    >>> a, b, g = 0.1, 0.2, 0.3
    >>> R = matrix_from_euler([a, b, g], "ZYX")
    >>> bool(np.allclose(R, rotz(a) @ roty(b) @ rotx(g)))
    True
    >>> bool(np.allclose(R, matrix_from_euler([g, b, a], "xyz")))
    True
    """
    axes, intrinsic = parse_seq(seq)
    if is_symbolic(angles):
        from ..symbolic import _sym

        t = list(angles)
        if len(t) != 3:
            from ..errors import KinlibError

            raise KinlibError(f"angles: expected three angles, got {len(t)}")
        mats = [_sym.axis_rotation(ax, th) for ax, th in zip(axes, t, strict=True)]
        if not intrinsic:
            mats = mats[::-1]
        return mats[0] * mats[1] * mats[2]
    ang = as_array(angles, "angles", (3,))
    axes, ang = _intrinsic(axes, intrinsic, ang)
    c, s = np.cos(ang), np.sin(ang)
    batch = ang.shape[:-1]
    cols = [np.zeros(batch + (3,)) for _ in range(3)]
    for n in range(3):
        cols[n][..., n] = 1.0
    # Right-multiplying by R_k(θ) mixes two columns: col_i ← c col_i + s col_j,
    # col_j ← −s col_i + c col_j, with (i, j) the axes after k in cyclic order.
    for n, k in enumerate(axes):
        i, j = (k + 1) % 3, (k + 2) % 3
        cn, sn = c[..., n, None], s[..., n, None]
        ci, cj = cols[i], cols[j]
        cols[i], cols[j] = cn * ci + sn * cj, cn * cj - sn * ci
    return np.stack(cols, axis=-1)


def _solve(R, axes, zero_first: bool, tol: float):
    """Intrinsic angles of ``R`` for ``axes``; at lock the first (or the third) angle is 0."""
    a1, a2, a3 = axes
    proper = a1 == a3
    i, j = a1, a2
    k = 3 - i - j
    eps = _parity(i, j)
    Rij = lambda r, c: R[..., r, c]  # noqa: E731
    if proper:
        cb = Rij(i, i)
        sb = np.hypot(Rij(j, i), Rij(k, i))
        b = np.arctan2(sb, cb)
        lock = np.arctan2(sb, np.abs(cb)) <= tol
        a = np.arctan2(Rij(j, i), -eps * Rij(k, i))
    else:
        sb = eps * Rij(i, k)
        cb = np.hypot(Rij(i, i), Rij(i, j))
        b = np.arctan2(sb, cb)
        lock = np.arctan2(cb, np.abs(sb)) <= tol
        a = np.arctan2(-eps * Rij(j, k), Rij(k, k))
    if zero_first:
        a = np.where(lock, 0.0, a)
    # Third angle from row j of R_i(a)ᵀ R, whose entries are O(1) even near lock: this
    # keeps the round trip exact to rounding however ill-conditioned a itself is.
    ca, sa = np.cos(a), np.sin(a)
    rjj = ca * Rij(j, j) + eps * sa * Rij(k, j)
    if proper:
        rjk = ca * Rij(j, k) + eps * sa * Rij(k, k)
        c = np.arctan2(-eps * rjk, rjj)
    else:
        rji = ca * Rij(j, i) + eps * sa * Rij(k, i)
        c = np.arctan2(eps * rji, rjj)
    if not zero_first:
        # Lock with the third angle 0: column j of R = R_i(a) e_j.
        a = np.where(lock, np.arctan2(eps * Rij(k, j), Rij(j, j)), a)
        c = np.where(lock, 0.0, c)
    # (−π, π]: atan2 gives −π for a −0.0 argument
    return np.stack([wrap_angle(a), b + 0.0, wrap_angle(c)], axis=-1)


def euler_from_matrix(R, seq: str, *, tol: float = ROUNDING_TOL):
    r"""Euler (intrinsic) or fixed (extrinsic) angles of a rotation matrix.

    Parameters
    ----------
    R : array_like, shape (..., 3, 3)
        Rotation matrices (checked: orthonormal with det +1 to 1e-6).
    seq : str
        Three axis letters, e.g. ``"ZYX"`` or ``"xyz"``; see :func:`matrix_from_euler`.
    tol : float
        Gimbal lock is declared where the middle angle is within ``tol`` radians of its
        singular value (the default only absorbs rounding; see :func:`euler_gimbal_lock`).

    Returns
    -------
    angles : ndarray, shape (..., 3)
        In the order of the letters. The middle angle lies in [−π/2, π/2] (three different
        axes) or [0, π] (first axis = last); the outer two in (−π, π]. At gimbal lock the
        first angle is 0 and the third carries the rotation.

    Examples
    --------
    >>> R = matrix_from_euler([0.1, 0.2, 0.3], "ZYX")
    >>> euler_from_matrix(R, "ZYX")
    array([0.1, 0.2, 0.3])
    >>> euler_from_matrix(R, "xyz")
    array([0.3, 0.2, 0.1])

    At gimbal lock (β = π/2) only α + γ matters; the first angle is set to 0:

    >>> R = matrix_from_euler([0.4, np.pi / 2, 0.3], "XYZ")
    >>> euler_from_matrix(R, "XYZ").round(12) + 0.0
    array([0.        , 1.57079633, 0.7       ])
    """
    axes, intrinsic = parse_seq(seq)
    tol = as_tol(tol)
    Rm = check_rotation(R)
    if intrinsic:
        return _solve(Rm, axes, True, tol)
    return _solve(Rm, axes[::-1], False, tol)[..., ::-1]


def euler_gimbal_lock(R, seq: str, tol: float = GIMBAL_TOL):
    r"""Whether the middle angle of ``seq`` is within ``tol`` radians of its singular value.

    The singular values are ±π/2 for sequences of three different axes and 0 or π for
    sequences whose first and last axes are the same. There the first and third axes line
    up, the rotation loses a degree of freedom, and only the sum or difference of the outer
    angles is defined. Returns a Python ``bool`` for one matrix, a bool ndarray for a batch.
    The default ``tol`` is :data:`kinlib.conventions.GIMBAL_TOL`.

    >>> euler_gimbal_lock(matrix_from_euler([0.3, np.pi / 2, -0.2], "ZYX"), "ZYX")
    True
    >>> euler_gimbal_lock(matrix_from_euler([0.3, 0.2, -0.2], "ZYX"), "ZYX")
    False
    """
    axes, intrinsic = parse_seq(seq)
    tol = as_tol(tol)
    a = check_rotation(R)
    if not intrinsic:
        axes = axes[::-1]
    i, j = axes[0], axes[1]
    k = 3 - i - j
    if axes[0] == axes[2]:
        cb = a[..., i, i]
        sb = np.hypot(a[..., j, i], a[..., k, i])
        dist = np.arctan2(sb, np.abs(cb))
    else:
        sb = a[..., i, k]
        cb = np.hypot(a[..., i, i], a[..., i, j])
        dist = np.arctan2(cb, np.abs(sb))
    return py_scalar(dist <= tol)
