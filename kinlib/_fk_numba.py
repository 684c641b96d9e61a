"""The numba kernels of :mod:`kinlib._fk` (private; imported only when numba is wanted).

``tree`` fills every frame of a tree, ``chain`` computes the last frame of a path (see
``ChainTable``) and ``chain_jacobian`` that pose with its geometric Jacobian; the
``*_parallel`` twins spread the loop over configurations across the CPU cores. All are
cached on disk by numba.
"""

import types

import numba
import numpy as np

__all__ = ["chain", "chain_jacobian", "chain_jacobian_parallel", "chain_parallel", "tree"]


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


@numba.njit(cache=True, fastmath=True)
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
            cq = np.cos(qe)
            sq = np.sin(qe)
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
    """Add each moving joint's column (times its multiplier) into J (6, dof)."""
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


CHUNKS = 64  # scratch arrays are allocated once per chunk of configurations, not per one


def chain(q, ints, floats, D):  # pragma: no cover - compiled
    N = q.shape[0]
    m = ints.shape[1]
    out = np.zeros((N, 4, 4))
    chunks = min(N, CHUNKS)
    for c in numba.prange(chunks):
        T = np.empty((3, 4))
        Z = np.empty((m, 3))
        O = np.empty((m, 3))
        for i in range(c * N // chunks, (c + 1) * N // chunks):
            _walk(q, i, ints, floats, D, T, Z, O)
            for r in range(3):
                for k in range(4):
                    out[i, r, k] = T[r, k]
            out[i, 3, 3] = 1.0
    return out


def chain_jacobian(q, ints, floats, D, dof):  # pragma: no cover - compiled
    """The chain's end pose and its geometric Jacobian [v; ω] in the base frame:
    revolute column [z × (p − o); z], prismatic [z; 0], times the joint's multiplier,
    added into the column of the q that drives it (mimic joints share a column)."""
    N = q.shape[0]
    m = ints.shape[1]
    out = np.zeros((N, 4, 4))
    J = np.zeros((N, 6, dof))
    chunks = min(N, CHUNKS)
    for c in numba.prange(chunks):
        T = np.empty((3, 4))
        Z = np.empty((m, 3))
        O = np.empty((m, 3))
        for i in range(c * N // chunks, (c + 1) * N // chunks):
            _walk(q, i, ints, floats, D, T, Z, O)
            for r in range(3):
                for k in range(4):
                    out[i, r, k] = T[r, k]
            out[i, 3, 3] = 1.0
            _columns(T, Z, O, ints, floats, J[i])
    return out, J


def _parallel(fn, name):
    """``fn`` compiled with its prange loop spread over the cores, cached under ``name``."""
    code = fn.__code__.replace(co_name=name, co_qualname=name)
    return numba.njit(cache=True, parallel=True, fastmath=True)(
        types.FunctionType(code, fn.__globals__, name))


chain_parallel = _parallel(chain, "chain_par")
chain_jacobian_parallel = _parallel(chain_jacobian, "chain_jacobian_par")
chain = numba.njit(cache=True, fastmath=True)(chain)
chain_jacobian = numba.njit(cache=True)(chain_jacobian)
