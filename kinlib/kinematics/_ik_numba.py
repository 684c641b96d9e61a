"""The compiled Levenberg–Marquardt IK loop (private; see :mod:`kinlib.kinematics.ik` for the
method).

One target after another: every step (pose, Jacobian, log map,
Cholesky solve, projection into the limits) runs without returning to Python, and the
same pre-sampled starting configurations as the numpy reference are used. Compiled once,
for one core; it releases the GIL, so many targets are solved in slices in threads
(:func:`kinlib.kinematics._fk.in_threads`).
"""

import numba
import numpy as np

from ._fk_numba import _columns, _walk

__all__ = ["ik_lm"]

LAMBDA0, LAMBDA_MIN, LAMBDA_MAX = 1e-3, 1e-12, 1e8


@numba.njit(cache=True)
def _rotation_error(Rt, T, out):  # pragma: no cover - compiled
    """out = log(Rt Rᵀ)^∨ via the quaternion of Rt Rᵀ (accurate at 0 and at π)."""
    M = np.empty((3, 3))
    for r in range(3):
        for c in range(3):
            M[r, c] = Rt[r, 0] * T[c, 0] + Rt[r, 1] * T[c, 1] + Rt[r, 2] * T[c, 2]
    tr = M[0, 0] + M[1, 1] + M[2, 2]
    if tr >= M[0, 0] and tr >= M[1, 1] and tr >= M[2, 2]:
        w = 0.5 * np.sqrt(max(1.0 + tr, 0.0))
        f = 0.25 / w
        x, y, z = (M[2, 1] - M[1, 2]) * f, (M[0, 2] - M[2, 0]) * f, (M[1, 0] - M[0, 1]) * f
    elif M[0, 0] >= M[1, 1] and M[0, 0] >= M[2, 2]:
        x = 0.5 * np.sqrt(max(1.0 + 2.0 * M[0, 0] - tr, 0.0))
        f = 0.25 / x
        w, y, z = (M[2, 1] - M[1, 2]) * f, (M[0, 1] + M[1, 0]) * f, (M[0, 2] + M[2, 0]) * f
    elif M[1, 1] >= M[2, 2]:
        y = 0.5 * np.sqrt(max(1.0 + 2.0 * M[1, 1] - tr, 0.0))
        f = 0.25 / y
        w, x, z = (M[0, 2] - M[2, 0]) * f, (M[0, 1] + M[1, 0]) * f, (M[1, 2] + M[2, 1]) * f
    else:
        z = 0.5 * np.sqrt(max(1.0 + 2.0 * M[2, 2] - tr, 0.0))
        f = 0.25 / z
        w, x, y = (M[1, 0] - M[0, 1]) * f, (M[0, 2] + M[2, 0]) * f, (M[1, 2] + M[2, 1]) * f
    if w < 0.0:
        w, x, y, z = -w, -x, -y, -z
    s = np.sqrt(x * x + y * y + z * z)
    k = 2.0 * np.arctan2(s, w) / s if s > 1e-300 else 2.0
    out[0], out[1], out[2] = k * x, k * y, k * z
    return np.arctan2(s, w) * 2.0


@numba.njit(cache=True)
def _solve_spd(A, b, n):  # pragma: no cover - compiled
    """Solve A x = b for symmetric positive definite A (n×n) by Cholesky, in place in b."""
    for j in range(n):
        d = A[j, j]
        for k in range(j):
            d -= A[j, k] * A[j, k]
        d = np.sqrt(max(d, 1e-300))
        A[j, j] = d
        for i in range(j + 1, n):
            v = A[i, j]
            for k in range(j):
                v -= A[i, k] * A[j, k]
            A[i, j] = v / d
    for i in range(n):
        v = b[i]
        for k in range(i):
            v -= A[i, k] * b[k]
        b[i] = v / A[i, i]
    for i in range(n - 1, -1, -1):
        v = b[i]
        for k in range(i + 1, n):
            v -= A[k, i] * b[k]
        b[i] = v / A[i, i]


def ik_lm(targets, starts, lo, hi, wrap, ints, floats, D, position_only, tol_p, tol_r,
          max_iter, q_out, success, pe_out, re_out, iters):  # pragma: no cover - compiled
    """Solve target i from its starts into q_out[i], success[i] (bool), pe_out[i],
    re_out[i] and iters[i] (int64), arrays the caller made: allocating a bool and an
    int64 array here would cost the first call two more compilations."""
    n, attempts, dof = starts.shape
    m = ints.shape[1]
    rows = 3 if position_only else 6
    for i in range(n):
        iters[i] = 0
        Q = np.empty((1, dof))
        q_acc = np.empty(dof)
        T = np.empty((3, 4))
        Z = np.empty((m, 3))
        O = np.empty((m, 3))
        J = np.empty((6, dof))
        J_acc = np.empty((6, dof))
        e = np.empty(6)
        e_acc = np.empty(6)
        A = np.empty((dof, dof))
        g = np.empty(dof)
        row = np.int64(0)  # Q's one row (typed as the FK kernels' row: _walk compiled once)
        best = np.inf
        found = False
        for a in range(attempts):
            for j in range(dof):
                Q[0, j] = starts[i, a, j]
            lam = LAMBDA0
            cost_acc = np.inf
            for _ in range(max_iter):
                _walk(Q, row, ints, floats, D, T, Z, O)
                _columns(T, Z, O, ints, floats, J)
                for r in range(3):
                    e[r] = targets[i, r, 3] - T[r, 3]
                pe = np.sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2])
                re = _rotation_error(targets[i], T, e[3:])
                cost = pe * pe + (0.0 if position_only else re * re)
                iters[i] += 1
                ok = pe < tol_p and (position_only or re < tol_r)
                if cost < best or ok:
                    best = cost
                    pe_out[i] = pe
                    re_out[i] = re
                    for j in range(dof):
                        q_out[i, j] = Q[0, j]
                if ok:
                    found = True
                    break
                if cost < cost_acc:
                    cost_acc = cost
                    for j in range(dof):
                        q_acc[j] = Q[0, j]
                    for r in range(6):
                        e_acc[r] = e[r]
                        for j in range(dof):
                            J_acc[r, j] = J[r, j]
                    lam = max(lam / 3.0, LAMBDA_MIN)
                else:
                    lam *= 4.0
                    if lam > LAMBDA_MAX:
                        break
                for r in range(dof):  # (JᵀJ + λI) dq = Jᵀe
                    v = 0.0
                    for k in range(rows):
                        v += J_acc[k, r] * e_acc[k]
                    g[r] = v
                    for c in range(r + 1):
                        v = 0.0
                        for k in range(rows):
                            v += J_acc[k, r] * J_acc[k, c]
                        A[r, c] = v
                        A[c, r] = v
                    A[r, r] += lam
                _solve_spd(A, g, dof)
                for j in range(dof):
                    x = min(max(q_acc[j] + g[j], lo[j]), hi[j])
                    if wrap[j]:
                        x = np.pi - np.mod(np.pi - x, 2.0 * np.pi)
                    Q[0, j] = x
            if found:
                break
        success[i] = found


ik_lm = numba.njit(cache=True, nogil=True)(ik_lm)
