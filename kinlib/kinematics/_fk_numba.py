"""The numba kernels of :mod:`kinlib.kinematics._fk` (private; imported only when numba is
wanted).

``tree`` fills every frame of a tree, ``chain`` computes the last frame of a path (see
``ChainTable``) and ``chain_jacobian`` that pose with its geometric Jacobian. Each is
compiled once, for one core, and cached on disk by numba; they release the GIL, so a large
batch is spread over the cores by running slices of it in threads
(:func:`kinlib.kinematics._fk.in_threads`), not by a second, parallel compilation.
"""

import numba
import numpy as np

__all__ = ["chain", "chain_jacobian", "tree"]


@numba.njit(cache=True)
def tree(q, sel, ints, floats, M):  # pragma: no cover - compiled
    N = q.shape[0]
    out = np.empty((N, ints.shape[1] + 1, 4, 4))
    L = np.empty((3, 4))
    for i in range(N):
        for r in range(4):
            for c in range(4):
                out[i, 0, r, c] = 1.0 if r == c else 0.0
        for s in range(sel.shape[0]):
            j = sel[s]
            k = ints[1, j]
            f1 = 0.0
            f2 = 0.0
            if k != 0:
                qe = q[i, ints[2, j]] * floats[0, j] + floats[1, j]
                if k == 1:
                    f1 = np.sin(qe)
                    h = np.sin(0.5 * qe)
                    f2 = 2.0 * h * h
                else:
                    f1 = qe
            for r in range(3):
                for c in range(4):
                    L[r, c] = M[j, 0, r, c] + f1 * M[j, 1, r, c] + f2 * M[j, 2, r, c]
            p = ints[0, j]
            for r in range(3):
                for c in range(4):
                    acc = out[i, p, r, 0] * L[0, c] + out[i, p, r, 1] * L[1, c] \
                        + out[i, p, r, 2] * L[2, c]
                    if c == 3:
                        acc += out[i, p, r, 3]
                    out[i, j + 1, r, c] = acc
            out[i, j + 1, 3, 0] = 0.0
            out[i, j + 1, 3, 1] = 0.0
            out[i, j + 1, 3, 2] = 0.0
            out[i, j + 1, 3, 3] = 1.0
    return out


# No kernel here uses fastmath: it would let LLVM reassociate the two-term reduction below
# (x − k·hi) − k·lo into x − k·(hi + lo), and sin(10π) would come out as 0.
# sin and cos together: one Cody–Waite reduction by π/2, then fdlibm's kernel polynomials
# (libm's sin and cos each redo the reduction; for joint angles beyond ±0.86 rad that is
# most of the FK kernel's time). Within 1 ulp of libm for |x| <= 1e5; libm beyond.
_PIO2_HI = 1.57079632673412561417e+00
_PIO2_LO = 6.07710050650619224932e-11
_INV_PIO2 = 6.36619772367581382433e-01
_S = (-1.66666666666666324348e-01, 8.33333333332248946124e-03, -1.98412698298579493134e-04,
      2.75573137070700676789e-06, -2.50507602534068634195e-08, 1.58969099521155010221e-10)
_C = (4.16666666666666019037e-02, -1.38888888888741095749e-03, 2.48015872894767294178e-05,
      -2.75573143513906633035e-07, 2.08757232129817482790e-09, -1.13596475577881948265e-11)


@numba.njit(cache=True)
def sincos(x):  # pragma: no cover - compiled
    if abs(x) > 1e5:
        return np.sin(x), np.cos(x)
    k = np.floor(x * _INV_PIO2 + 0.5)
    r = (x - k * _PIO2_HI) - k * _PIO2_LO
    z = r * r
    ps = _S[0] + z * (_S[1] + z * (_S[2] + z * (_S[3] + z * (_S[4] + z * _S[5]))))
    pc = _C[0] + z * (_C[1] + z * (_C[2] + z * (_C[3] + z * (_C[4] + z * _C[5]))))
    s = r + r * z * ps
    hz = 0.5 * z
    w = 1.0 - hz
    c = w + (((1.0 - w) - hz) + z * z * pc)
    n = int(k) & 3
    if n == 0:
        return s, c
    if n == 1:
        return c, -s
    if n == 2:
        return -s, -c
    return -c, s


@numba.njit(cache=True)
def _walk(q, i, ints, floats, D, T, Z, O):  # pragma: no cover - compiled
    """T = D_0 Z(q_1) D_1 ... Z(q_m) D_m for configuration i; Z[k], O[k] get joint k's
    world axis (the z column before its motion) and origin."""
    for r in range(3):
        for c in range(4):
            T[r, c] = D[0, r, c]
    for k in range(ints.shape[1]):
        for r in range(3):
            Z[k, r] = T[r, 2]
            O[k, r] = T[r, 3]
        qe = q[i, ints[1, k]] * floats[0, k] + floats[1, k]
        if ints[0, k] == 1:  # T @ Rz(qe)
            sq, cq = sincos(qe)
            for r in range(3):
                a = T[r, 0]
                b = T[r, 1]
                T[r, 0] = cq * a + sq * b
                T[r, 1] = cq * b - sq * a
        else:  # T @ Tz(qe)
            for r in range(3):
                T[r, 3] += qe * T[r, 2]
        if ints[2, k] == 1:  # T @ D[k + 1] with D's rotation about x only: column 0 stays
            for r in range(3):
                t0 = T[r, 0]
                t1 = T[r, 1]
                t2 = T[r, 2]
                T[r, 1] = t1 * D[k + 1, 1, 1] + t2 * D[k + 1, 2, 1]
                T[r, 2] = t1 * D[k + 1, 1, 2] + t2 * D[k + 1, 2, 2]
                T[r, 3] += t0 * D[k + 1, 0, 3] + t1 * D[k + 1, 1, 3] + t2 * D[k + 1, 2, 3]
            continue
        for r in range(3):  # T @ D[k + 1], D affine (bottom row 0 0 0 1)
            t0 = T[r, 0]
            t1 = T[r, 1]
            t2 = T[r, 2]
            t3 = T[r, 3]
            for c in range(4):
                T[r, c] = t0 * D[k + 1, 0, c] + t1 * D[k + 1, 1, c] + t2 * D[k + 1, 2, c]
            T[r, 3] += t3


@numba.njit(cache=True)
def _columns(T, Z, O, ints, floats, J):  # pragma: no cover - compiled
    """The geometric Jacobian into J (6, dof): zeroed, then each moving joint's column
    (times its multiplier) added into the column of the q that drives it."""
    for r in range(6):  # (loops, not array expressions: quicker to compile)
        for j in range(J.shape[1]):
            J[r, j] = 0.0
    for k in range(ints.shape[1]):
        col = ints[1, k]
        w = floats[0, k]
        z0, z1, z2 = Z[k, 0], Z[k, 1], Z[k, 2]
        if ints[0, k] == 1:
            d0 = T[0, 3] - O[k, 0]
            d1 = T[1, 3] - O[k, 1]
            d2 = T[2, 3] - O[k, 2]
            J[0, col] += w * (z1 * d2 - z2 * d1)
            J[1, col] += w * (z2 * d0 - z0 * d2)
            J[2, col] += w * (z0 * d1 - z1 * d0)
            J[3, col] += w * z0
            J[4, col] += w * z1
            J[5, col] += w * z2
        else:
            J[0, col] += w * z0
            J[1, col] += w * z1
            J[2, col] += w * z2


# Arrays are made with np.empty and filled by loops, never np.zeros or another dtype: each
# allocation function and dtype numba meets is one more compilation on a first call.
CHUNKS = 64  # scratch arrays are allocated once per chunk of configurations, not per one


BLOCK = 64  # configurations advanced together, joint by joint


def chain(q, ints, floats, D):  # pragma: no cover - compiled
    """End poses of the chain for every configuration.

    Configurations go through the joints in blocks of :data:`BLOCK`, stored as 12
    rows of BLOCK numbers (structure of arrays): each joint's update then runs along the
    block, where the CPU overlaps and vectorises it, instead of one configuration's long
    chain of dependent products at a time (about 1.7× faster on one core).
    """
    N = q.shape[0]
    m = ints.shape[1]
    out = np.empty((N, 4, 4))
    for blk in range((N + BLOCK - 1) // BLOCK):
        start = blk * BLOCK
        nb = min(BLOCK, N - start)
        T = np.empty((12, BLOCK))
        s = np.empty(BLOCK)
        c = np.empty(BLOCK)
        for e in range(12):
            v = D[0, e // 4, e % 4]
            for i in range(nb):
                T[e, i] = v
        for k in range(m):
            col = ints[1, k]
            w = floats[0, k]
            o = floats[1, k]
            if ints[0, k] == 1:  # T @ Rz(qe)
                for i in range(nb):
                    s[i], c[i] = sincos(q[start + i, col] * w + o)
                for r in range(3):
                    for i in range(nb):
                        a = T[4 * r, i]
                        b = T[4 * r + 1, i]
                        T[4 * r, i] = c[i] * a + s[i] * b
                        T[4 * r + 1, i] = c[i] * b - s[i] * a
            else:  # T @ Tz(qe)
                for i in range(nb):
                    s[i] = q[start + i, col] * w + o
                for r in range(3):
                    for i in range(nb):
                        T[4 * r + 3, i] += s[i] * T[4 * r + 2, i]
            d = D[k + 1]
            for r in range(3):  # T @ D[k + 1]
                for i in range(nb):
                    t0 = T[4 * r, i]
                    t1 = T[4 * r + 1, i]
                    t2 = T[4 * r + 2, i]
                    T[4 * r, i] = t0 * d[0, 0] + t1 * d[1, 0] + t2 * d[2, 0]
                    T[4 * r + 1, i] = t0 * d[0, 1] + t1 * d[1, 1] + t2 * d[2, 1]
                    T[4 * r + 2, i] = t0 * d[0, 2] + t1 * d[1, 2] + t2 * d[2, 2]
                    T[4 * r + 3, i] += t0 * d[0, 3] + t1 * d[1, 3] + t2 * d[2, 3]
        for i in range(nb):
            for e in range(12):
                out[start + i, e // 4, e % 4] = T[e, i]
            for e in range(3):
                out[start + i, 3, e] = 0.0
            out[start + i, 3, 3] = 1.0
    return out


def chain_jacobian(q, ints, floats, D, dof):  # pragma: no cover - compiled
    """The chain's end pose and its geometric Jacobian [v; ω] in the base frame:
    revolute column [z × (p − o); z], prismatic [z; 0], times the joint's multiplier,
    added into the column of the q that drives it (mimic joints share a column)."""
    N = q.shape[0]
    m = ints.shape[1]
    out = np.empty((N, 4, 4))
    J = np.empty((N, 6, dof))
    chunks = min(N, CHUNKS)
    for c in range(chunks):
        T = np.empty((3, 4))
        Z = np.empty((m, 3))
        O = np.empty((m, 3))
        for i in range(c * N // chunks, (c + 1) * N // chunks):
            _walk(q, i, ints, floats, D, T, Z, O)
            for r in range(3):
                for k in range(4):
                    out[i, r, k] = T[r, k]
            for k in range(3):
                out[i, 3, k] = 0.0
            out[i, 3, 3] = 1.0
            _columns(T, Z, O, ints, floats, J[i])
    return out, J


chain = numba.njit(cache=True, nogil=True)(chain)
chain_jacobian = numba.njit(cache=True, nogil=True)(chain_jacobian)
