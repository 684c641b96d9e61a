"""The numba kernels of :mod:`kinlib._fk` (private; imported only when numba is wanted).

``tree`` fills every frame of a tree, ``chain`` computes the last frame of a path (see
``ChainTable``); ``chain_parallel`` is ``chain`` compiled with its loop over
configurations spread across the CPU cores. All are cached on disk by numba.
"""

import types

import numba
import numpy as np

__all__ = ["chain", "chain_parallel", "tree"]


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


def chain(q, ints, floats, D):  # pragma: no cover - compiled
    N = q.shape[0]
    m = ints.shape[1]
    out = np.zeros((N, 4, 4))
    for i in numba.prange(N):
        T = np.empty((3, 4))
        for r in range(3):
            for c in range(4):
                T[r, c] = D[0, r, c]
        for k in range(m):
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
            for r in range(3):  # T @ D[k + 1], D affine (bottom row 0 0 0 1)
                t0 = T[r, 0]
                t1 = T[r, 1]
                t2 = T[r, 2]
                t3 = T[r, 3]
                for c in range(4):
                    T[r, c] = t0 * D[k + 1, 0, c] + t1 * D[k + 1, 1, c] \
                        + t2 * D[k + 1, 2, c]
                T[r, 3] += t3
        for r in range(3):
            for c in range(4):
                out[i, r, c] = T[r, c]
        out[i, 3, 3] = 1.0
    return out


# the same function under another name, so numba caches the parallel build separately
_code = chain.__code__.replace(co_name="chain_par", co_qualname="chain_par")
chain_parallel = numba.njit(cache=True, parallel=True)(
    types.FunctionType(_code, chain.__globals__, "chain_par"))
chain = numba.njit(cache=True)(chain)
