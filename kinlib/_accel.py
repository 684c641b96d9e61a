"""Optional compiled kernels (private).

kinlib's reference implementations are numpy, and every function works without this
module. A few batched conversions are limited by numpy's per-operation cost rather than
by arithmetic — quaternion → matrix must write nine interleaved outputs, which numpy can
only do with strided passes or a transpose — and there a numba kernel is used when
numba is installed (``pip install 'kinlib[fast]'``, which ``make`` does) and the
environment variable ``KINLIB_NUMBA`` is not ``0``. Kernels are only used for batches of
at least :data:`MIN_BATCH`, so small calls never pay numba's import or compile time, and
the first such call does not wait for it either: it takes the numpy path while the kernel
is compiled (or loaded from numba's cache) in the background (:mod:`kinlib._background`).
The tests compare both paths.
"""

from __future__ import annotations

import functools
import os
from types import SimpleNamespace

import numpy as np

from ._background import KernelsUnavailable, compiled, warn_once

__all__ = ["MIN_BATCH", "kernel", "kernels", "numba_disabled"]

#: Smallest batch for which a compiled kernel is used.
MIN_BATCH = 2048


def _build(njit):
    @njit(cache=True, nogil=True)
    def matrix_from_quat(q, out):  # pragma: no cover - compiled
        """Rotation matrices of (n, 4) quaternions into out (n, 3, 3); returns the index of
        the first zero quaternion, or −1."""
        for n in range(q.shape[0]):
            w, x, y, z = q[n, 0], q[n, 1], q[n, 2], q[n, 3]
            n2 = w * w + x * x + y * y + z * z
            if n2 <= 1e-24:
                return n
            s = 2.0 / n2
            xs, ys, zs = x * s, y * s, z * s
            xx, yy, zz = x * xs, y * ys, z * zs
            xy, xz, yz = x * ys, x * zs, y * zs
            wx, wy, wz = w * xs, w * ys, w * zs
            out[n, 0, 0] = 1.0 - (yy + zz)
            out[n, 0, 1] = xy - wz
            out[n, 0, 2] = xz + wy
            out[n, 1, 0] = xy + wz
            out[n, 1, 1] = 1.0 - (xx + zz)
            out[n, 1, 2] = yz - wx
            out[n, 2, 0] = xz - wy
            out[n, 2, 1] = yz + wx
            out[n, 2, 2] = 1.0 - (xx + yy)
        return -1

    @njit(cache=True, nogil=True)
    def rotation_errors(R, err, det):  # pragma: no cover - compiled
        """max |RᵀR − I| and det R of (n, 3, 3) matrices into err (n,) and det (n,)."""
        for n in range(R.shape[0]):
            e = 0.0
            for i in range(3):
                for j in range(i, 3):
                    g = R[n, 0, i] * R[n, 0, j] + R[n, 1, i] * R[n, 1, j] + R[n, 2, i] * R[n, 2, j]
                    if i == j:
                        g -= 1.0
                    e = max(e, abs(g))
            err[n] = e
            det[n] = (
                R[n, 0, 0] * (R[n, 1, 1] * R[n, 2, 2] - R[n, 1, 2] * R[n, 2, 1])
                - R[n, 0, 1] * (R[n, 1, 0] * R[n, 2, 2] - R[n, 1, 2] * R[n, 2, 0])
                + R[n, 0, 2] * (R[n, 1, 0] * R[n, 2, 1] - R[n, 1, 1] * R[n, 2, 0])
            )

    @njit(cache=True, nogil=True)
    def quat_from_matrix(R, out):  # pragma: no cover - compiled
        """Shepperd's method on (n, 3, 3) rotations into out (n, 4), w >= 0."""
        for n in range(R.shape[0]):
            m00, m01, m02 = R[n, 0, 0], R[n, 0, 1], R[n, 0, 2]
            m10, m11, m12 = R[n, 1, 0], R[n, 1, 1], R[n, 1, 2]
            m20, m21, m22 = R[n, 2, 0], R[n, 2, 1], R[n, 2, 2]
            t0 = 1.0 + m00 + m11 + m22
            t1 = 1.0 + m00 - m11 - m22
            t2 = 1.0 - m00 + m11 - m22
            t3 = 1.0 - m00 - m11 + m22
            if t0 >= t1 and t0 >= t2 and t0 >= t3:
                w, x, y, z = t0, m21 - m12, m02 - m20, m10 - m01
            elif t1 >= t2 and t1 >= t3:
                w, x, y, z = m21 - m12, t1, m10 + m01, m02 + m20
            elif t2 >= t3:
                w, x, y, z = m02 - m20, m10 + m01, t2, m21 + m12
            else:
                w, x, y, z = m10 - m01, m02 + m20, m21 + m12, t3
            s = 1.0 / np.sqrt(w * w + x * x + y * y + z * z)
            if w < 0.0:
                s = -s
            out[n, 0] = w * s
            out[n, 1] = x * s
            out[n, 2] = y * s
            out[n, 3] = z * s

    return SimpleNamespace(
        matrix_from_quat=matrix_from_quat,
        rotation_errors=rotation_errors,
        quat_from_matrix=quat_from_matrix,
    )


@functools.cache
def numba_disabled() -> bool:
    """True when the environment says ``KINLIB_NUMBA=0``: use the numpy paths only (read
    once, when a kernel is first asked for)."""
    return os.environ.get("KINLIB_NUMBA", "1") == "0"


_built: list = []  # [the kernels' namespace, None (numba missing) or the failure]


def _kernels():
    """The kernels' namespace; None when numba is missing; else
    :class:`~kinlib._background.KernelsUnavailable` naming why they cannot be built."""
    if not _built:
        try:
            import numba
        except ImportError:
            _built.append(None)
        else:
            try:
                _built.append(_build(numba.njit))
            except Exception as exc:  # a numba these kernels do not support
                _built.append(exc)
    if isinstance(_built[0], Exception):
        exc = _built[0]
        raise KernelsUnavailable(
            f"kinlib: the compiled conversions could not be built, so the numpy path is used "
            f"({type(exc).__name__}: {exc}); set KINLIB_NUMBA=0 to skip them")
    return _built[0]


def kernels():
    """The compiled kernels (numba imported now), or ``None`` when numba is missing or
    disabled; a failure to build them is reported once, as a RuntimeWarning."""
    if numba_disabled():
        return None
    try:
        return _kernels()
    except KernelsUnavailable as exc:
        warn_once(str(exc))
        return None


def kernel(name: str, example, *, wait: bool = False):
    """The compiled conversion ``name`` once it is ready, else None: the caller uses its
    numpy path while it is compiled (or loaded from numba's cache) in the background (see
    :mod:`kinlib._background`). ``example()``: the call's arguments with an empty batch;
    ``wait=True`` waits for the kernel instead."""
    if numba_disabled():
        return None
    return compiled("_accel." + name, _kernels, name, example, wait=wait)
