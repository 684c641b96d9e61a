r"""Forward kinematics over a joint tree, batched (private).

Each joint's local transform ``origin @ motion(q) @ post`` is written as

.. math:: L(q) = M_0 + f_1(q)\,M_1 + f_2(q)\,M_2

with :math:`(f_1, f_2) = (\sin q, 1-\cos q)` for a revolute joint (Rodrigues:
``motion = I + sin q K + (1 − cos q) K²``), :math:`(q, 0)` for a prismatic joint and
:math:`(0, 0)` for a fixed one. The matrices are precomputed once per robot, so a joint
costs three multiply-adds and one 4×4 product per configuration: the matrix stack of
seed 000, with the stack replaced by each frame's parent index.
"""

from __future__ import annotations

import functools
import os

import numpy as np

__all__ = ["FKTable", "run"]

_KIND = {"fixed": 0, "revolute": 1, "continuous": 1, "prismatic": 2}


class FKTable:
    """The robot's joints in traversal order as arrays the kernels read."""

    def __init__(self, joints_in_order, frame_of_link, q_index, mimic_source):
        n = len(joints_in_order)
        self.parent = np.empty(n, dtype=np.int64)   # frame index of the parent link
        self.kind = np.empty(n, dtype=np.int64)
        self.qidx = np.full(n, -1, dtype=np.int64)  # column of q driving the joint
        self.mult = np.ones(n)
        self.offset = np.zeros(n)
        self.M = np.zeros((n, 3, 4, 4))
        for j, jt in enumerate(joints_in_order):
            self.parent[j] = frame_of_link[jt.parent]
            self.kind[j] = _KIND[jt.type]
            if jt.type != "fixed":
                src, mult, off = mimic_source[jt.name]
                self.qidx[j], self.mult[j], self.offset[j] = q_index[src], mult, off
            O, P, u = jt.origin, jt.post, jt.axis
            if self.kind[j] == 1:
                K = np.zeros((4, 4))
                K[:3, :3] = [[0, -u[2], u[1]], [u[2], 0, -u[0]], [-u[1], u[0], 0]]
                self.M[j, 0] = O @ P
                self.M[j, 1] = O @ K @ P
                self.M[j, 2] = O @ K @ K @ P
            elif self.kind[j] == 2:
                D = np.zeros((4, 4))
                D[:3, 3] = u
                self.M[j, 0] = O @ P
                self.M[j, 1] = O @ D @ P
            else:
                self.M[j, 0] = O @ P
        self.n = n
        # packed for the compiled kernel (fewer arguments, less dispatch cost)
        self.ints = np.ascontiguousarray(np.stack([self.parent, self.kind, self.qidx]))
        self.floats = np.ascontiguousarray(np.stack([self.mult, self.offset]))
        for a in (self.parent, self.kind, self.qidx, self.mult, self.offset, self.M, self.ints,
                  self.floats):
            a.setflags(write=False)

    def coefficients(self, q: np.ndarray, sel: np.ndarray):
        """``f1, f2`` of the selected joints for q of shape (N, dof): each (N, len(sel))."""
        padded = np.concatenate([q, np.zeros((q.shape[0], 1))], axis=1)  # qidx -1: fixed
        qe = padded[:, self.qidx[sel]] * self.mult[sel] + self.offset[sel]
        kind = self.kind[sel]
        rev = kind == 1
        f1 = np.where(rev, np.sin(qe), np.where(kind == 2, qe, 0.0))
        h = np.sin(0.5 * qe)
        f2 = np.where(rev, 2.0 * h * h, 0.0)  # 1 − cos q without cancellation
        return f1, f2


def _numpy(table: FKTable, q: np.ndarray, sel: np.ndarray, out: np.ndarray) -> None:
    f1, f2 = table.coefficients(q, sel)
    M = table.M[sel]
    L = M[:, 0] + f1[..., None, None] * M[:, 1] + f2[..., None, None] * M[:, 2]
    for k, j in enumerate(sel):
        np.matmul(out[:, table.parent[j]], L[:, k], out=out[:, j + 1])


@functools.cache
def _compiled():
    if os.environ.get("KINLIB_NUMBA", "1") == "0":
        return None
    try:
        import numba
    except ImportError:
        return None

    @numba.njit(cache=True)
    def kernel(q, sel, ints, floats, M):  # pragma: no cover - compiled
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

    return kernel


def run(table: FKTable, q: np.ndarray, sel: np.ndarray, *, compiled: bool | None = None):
    """Frames (N, 1 + n_joints, 4, 4) for q (N, dof); only frames of ``sel`` are filled.

    Frame 0 is the root link (identity); frame ``j + 1`` is joint ``j``'s child link.
    ``compiled=None`` uses the numba kernel when numba is available (``KINLIB_NUMBA=0``
    turns it off); numba is imported on the first call, not with kinlib.
    """
    kernel = _compiled() if compiled is not False else None
    if kernel is not None:
        return kernel(q, sel, table.ints, table.floats, table.M)
    out = np.empty((q.shape[0], table.n + 1, 4, 4))
    out[:, 0] = np.eye(4)
    _numpy(table, q, sel, out)
    return out
