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
import itertools
import os
from concurrent.futures import ThreadPoolExecutor

import numpy as np

from .._accel import numba_disabled
from .._background import KernelsUnavailable, compiled, warn_once

__all__ = ["ChainTable", "FKTable", "run", "run_chain", "run_chain_jacobian", "in_threads"]

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


def _z_to(u: np.ndarray) -> np.ndarray:
    """A rotation B (as 4×4) with ``B @ e_z = u``: columns x', y', u, orthonormal."""
    B = np.eye(4)
    if np.array_equal(u, [0.0, 0.0, 1.0]):
        return B  # DH joints: no rounding at all
    helper = np.eye(3)[np.argmin(np.abs(u))]  # the coordinate axis least aligned with u
    x = np.cross(helper, u)
    x /= np.linalg.norm(x)
    B[:3, 0], B[:3, 1], B[:3, 2] = x, np.cross(u, x), u
    return B


class ChainTable:
    r"""A path of joints from the root as ``D_0 · Z(q_1) · D_1 ⋯ Z(q_m) · D_m``.

    Every moving joint ``origin · motion(u, q) · post`` is rewritten with a constant
    rotation ``B`` that takes z to its axis u: ``(origin B) · Z(q) · (Bᵀ post)``, where
    ``Z`` is ``Rz(q)`` (revolute) or ``Tz(q)`` (prismatic); neighbouring constants (and
    fixed joints) are multiplied together once. Applying ``Rz(q)`` on the right mixes two
    columns (12 products), so a joint costs one sin/cos pair and about 50 products.
    """

    def __init__(self, table: FKTable, joints, sel):
        D = [np.eye(4)]
        kinds, qidx, mult, offset = [], [], [], []
        for j, jt in zip(sel, joints, strict=True):
            if table.kind[j] == 0:
                D[-1] = D[-1] @ jt.origin @ jt.post
                continue
            B = _z_to(jt.axis)
            D[-1] = D[-1] @ jt.origin @ B
            kinds.append(table.kind[j])
            qidx.append(table.qidx[j])
            mult.append(table.mult[j])
            offset.append(table.offset[j])
            D.append(B.T @ jt.post)
        self.D = np.ascontiguousarray(np.stack(D)[:, :3, :])
        # row 2: 1 where D[k + 1] rotates about x only (every DH link): a cheaper product
        rx = [int(d[0, 0] == 1.0 and not d[0, 1:3].any() and not d[1:3, 0].any())
              for d in self.D[1:]]
        self.ints = np.array([kinds, qidx, rx], dtype=np.int64).reshape(3, -1)
        self.floats = np.array([mult, offset], dtype=float).reshape(2, -1)
        # for the numpy path (_chain_numpy): the constants as 4×4, which joints turn
        self.D4 = np.zeros((len(D), 4, 4))
        self.D4[:, :3], self.D4[:, 3, 3] = self.D, 1.0
        self.revolute = np.flatnonzero(self.ints[0] == 1)
        self.prismatic = np.flatnonzero(self.ints[0] == 2)
        self.all_revolute = len(self.revolute) == len(kinds)
        self.shared = len(set(qidx)) < len(qidx)  # mimic joints: columns of J shared
        #: q is the joint angles as they are: joint k driven by q[k], times 1, plus 0
        self.plain = (list(qidx) == list(range(len(qidx))) and not any(o != 0 for o in offset)
                      and not any(w != 1 for w in mult))


def _numpy(table: FKTable, q: np.ndarray, sel: np.ndarray, out: np.ndarray) -> None:
    f1, f2 = table.coefficients(q, sel)
    M = table.M[sel]
    L = M[:, 0] + f1[..., None, None] * M[:, 1] + f2[..., None, None] * M[:, 2]
    for k, j in enumerate(sel):
        np.matmul(out[:, table.parent[j]], L[:, k], out=out[:, j + 1])


class _Missing:
    """numba is not installed: the numpy path, silently."""


_modules: dict[str, object] = {}


def _import_kernels(module: str):
    """``kinlib.kinematics.<module>`` (numba kernels); None when numba is missing; else
    :class:`~kinlib._background.KernelsUnavailable` if building the kernels failed in any
    way (a numba or Python the kernels do not support: on Python 3.10
    ``CodeType.replace`` has no ``co_qualname``), naming the reason. Tried once."""
    import importlib

    if module not in _modules:
        try:
            _modules[module] = importlib.import_module(f"{__package__}.{module}")
        except ImportError as exc:
            _modules[module] = _Missing if exc.name == "numba" else exc
        except Exception as exc:  # numba there, but the kernels cannot be built with it
            _modules[module] = exc
    found = _modules[module]
    if found is _Missing:
        return None
    if isinstance(found, BaseException):
        raise KernelsUnavailable(
            f"kinlib: the compiled kernels ({__package__}.{module}) could not be built, so "
            f"the numpy path is used ({type(found).__name__}: {found}); set KINLIB_NUMBA=0 "
            "to skip them")
    return found


def _load_kernels(module: str):
    """``kinlib.kinematics.<module>`` imported now (not in the background), or None; a
    failure other than a missing numba is reported once, as a RuntimeWarning."""
    if numba_disabled():
        return None
    try:
        return _import_kernels(module)
    except KernelsUnavailable as exc:
        warn_once(str(exc))
        return None


def _compiled():
    """The numba kernels module, or None when numba is missing, KINLIB_NUMBA=0, or the
    kernels cannot be built here (see :func:`_import_kernels`). Imported now; the callers
    on the hot paths use :func:`kernel` instead, which never waits for numba."""
    return _load_kernels("_fk_numba")


#: from this many configurations, a call whose kernel is still being prepared waits for it
#: (the numpy path would take longer than the compile: bench/README.md, "the first call")
WAIT_MIN = 100_000


def kernel(name: str, example, *, module: str = "_fk_numba", wait: bool = False):
    """The compiled kernel ``<module>.<name>`` once it is ready, else None (see
    :mod:`kinlib._background`: it is then prepared in the background, and the caller takes
    its numpy path). ``example()``: the call's arguments with an empty batch (the same
    types: numba compiles the kernel for them). None for good when numba is missing or
    ``KINLIB_NUMBA=0``."""
    if numba_disabled():
        return None

    def load():
        if module != "_fk_numba" and _import_kernels("_fk_numba") is None:
            return None  # (the IK loop calls the FK kernels' helpers)
        return _import_kernels(module)

    return compiled(module + "." + name, load, name, example, wait=wait)


PARALLEL_MIN = 4096  # below this, starting the threads costs more than it saves


#: threads a large batch is split into (one per core, at most 8)
THREADS = max(1, min(os.cpu_count() or 1, 8))


@functools.cache
def _pool() -> ThreadPoolExecutor:
    return ThreadPoolExecutor(max_workers=THREADS, thread_name_prefix="kinlib")


def in_threads(kernel, n: int, args_of, min_batch: int = PARALLEL_MIN):
    """``kernel(*args_of(0, n))``, computed as slices ``[a, b)`` of the batch in threads, one
    per core, when ``n >= min_batch`` (the compiled kernels release the GIL); the slices'
    results (an array, or a tuple of arrays) joined in order, or None for a kernel that
    writes into slices of arrays it is given and returns None."""
    k = min(THREADS, n // max(1, min_batch // 2)) if n >= min_batch else 1
    if k <= 1:
        return kernel(*args_of(0, n))
    bounds = np.linspace(0, n, k + 1).astype(np.int64)
    futures = [_pool().submit(kernel, *args_of(a, b)) for a, b in itertools.pairwise(bounds)]
    parts = [f.result() for f in futures]
    if parts[0] is None:
        return None
    if isinstance(parts[0], tuple):
        return tuple(np.concatenate(p) for p in zip(*parts, strict=True))
    return np.concatenate(parts)


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``a × b`` over the last axis (np.cross's axis handling costs more than the products
    for a few vectors)."""
    a0, a1, a2 = a[..., 0], a[..., 1], a[..., 2]
    b0, b1, b2 = b[..., 0], b[..., 1], b[..., 2]
    return np.stack([a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0], axis=-1)


def _chain_numpy(chain: ChainTable, q: np.ndarray, dof: int | None = None):
    """The numpy path of a chain: the end pose (N, 4, 4), and with ``dof`` also the
    geometric Jacobian (N, 6, dof).

    Each moving joint's ``Z(q_k) D_k`` is formed for every configuration at once (Rz(q) on
    the left mixes two rows of ``D_k``; Tz(q) adds q to the translation's z), then the
    chain is one batched 4×4 product per joint: ``F_k = F_{k−1} Z(q_k) D_k`` from
    ``F_0 = D_0``. Joint k turns about the z axis of ``F_{k−1}`` through its origin, so its
    Jacobian column is ``[z × (p − o); z]`` (revolute) or ``[z; 0]`` (prismatic), times the
    joint's multiplier, added into the column of the q that drives it."""
    N, qidx = q.shape[0], chain.ints[1]
    plain = chain.plain and q.shape[1] == len(qidx)
    qe = q if plain else q[:, qidx] * chain.floats[0] + chain.floats[1]  # (N, m)
    D = chain.D4[1:]
    rev, pri = chain.revolute, chain.prismatic
    if chain.all_revolute:  # (most robots: plain slices, no fancy indexing)
        ZD = np.empty((N,) + D.shape)
        ZD[:, :, 2:] = D[:, 2:]
        s, c = np.sin(qe)[..., None], np.cos(qe)[..., None]
        ZD[:, :, 0] = c * D[:, 0] - s * D[:, 1]
        ZD[:, :, 1] = s * D[:, 0] + c * D[:, 1]
    else:
        ZD = np.repeat(D[None], N, axis=0)
        if len(rev):
            s, c = np.sin(qe[:, rev])[..., None], np.cos(qe[:, rev])[..., None]
            r0, r1 = D[rev, 0], D[rev, 1]
            ZD[:, rev, 0], ZD[:, rev, 1] = c * r0 - s * r1, s * r0 + c * r1
        if len(pri):
            ZD[:, pri, 2, 3] += qe[:, pri]
    F = np.repeat(chain.D4[:1], N, axis=0)
    if dof is None:
        for k in range(D.shape[0]):
            F = F @ ZD[:, k]
        return F
    frames = np.empty((N, D.shape[0], 3, 4))  # each joint's frame F_{k−1}: its axis z, origin o
    for k in range(D.shape[0]):
        frames[:, k] = F[:, :3]
        F = F @ ZD[:, k]
    J = np.zeros((N, 6, dof))
    if D.shape[0] == 0:
        return F, J
    z, o = frames[..., 2], frames[..., 3]
    columns = np.empty((N, D.shape[0], 6))
    if chain.all_revolute:
        columns[..., :3] = _cross(z, F[:, None, :3, 3] - o)
        columns[..., 3:] = z
    else:
        columns[..., :3] = z
        columns[..., 3:] = 0.0
        if len(rev):
            columns[:, rev, :3] = _cross(z[:, rev], F[:, None, :3, 3] - o[:, rev])
            columns[:, rev, 3:] = z[:, rev]
    if not plain:
        columns *= chain.floats[0][:, None]
    if chain.shared:
        np.add.at(np.moveaxis(J, 2, 0), qidx, np.moveaxis(columns, 1, 0))
    else:
        J[:, :, qidx] = np.swapaxes(columns, 1, 2)
    return F, J


def writable(a: np.ndarray) -> np.ndarray:
    """``a``, or a C-ordered copy of it if it is read-only (``np.broadcast_to``, a frozen
    array) or not C-contiguous (a transpose): numba types those apart, and would compile
    every kernel a second time for them."""
    return a if a.flags.writeable and a.flags.c_contiguous else np.array(a, order="C")


def wait_for_kernel(compiled: bool | None, n: int, least: int = WAIT_MIN) -> bool:
    """Whether a call with a batch of ``n`` (from ``least`` up) waits for its kernel
    rather than take the numpy path while the kernel is prepared: always with
    ``compiled=True``."""
    return bool(compiled) or n >= least


def _run_chain_kernel(name: str, q: np.ndarray, args: tuple, compiled: bool | None):
    """The chain kernel ``name`` on ``q`` and ``args`` (the chain's tables), in threads for
    a large batch; None when the caller is to take its numpy path (``compiled``: as for
    :func:`run_chain`)."""
    if compiled is False:
        return None
    q = writable(q)
    n = q.shape[0]
    fn = kernel(name, lambda: (q[:0], *args), wait=wait_for_kernel(compiled, n))
    if fn is None:
        return None
    if n < PARALLEL_MIN:  # (the common case: no slicing, no threads)
        return fn(q, *args)
    return in_threads(fn, n, lambda a, b: (q[a:b], *args))


def run_chain(chain: ChainTable, q: np.ndarray, *, compiled: bool | None = None):
    """Pose (N, 4, 4) at the end of the chain. ``compiled``: None, the compiled kernel if
    it is ready (see :func:`kernel`); True, the compiled kernel (waiting for it; numpy
    only without numba); False, the numpy path."""
    out = _run_chain_kernel("chain", q, (chain.ints, chain.floats, chain.D), compiled)
    return _chain_numpy(chain, q) if out is None else out


def run_chain_jacobian(chain: ChainTable, q: np.ndarray, *, compiled: bool | None = None):
    """``(T (N, 4, 4), J (N, 6, dof))`` at the end of the chain (``compiled``: as for
    :func:`run_chain`)."""
    out = _run_chain_kernel("chain_jacobian", q,
                            (chain.ints, chain.floats, chain.D, q.shape[1]), compiled)
    return _chain_numpy(chain, q, q.shape[1]) if out is None else out


def run(table: FKTable, q: np.ndarray, sel: np.ndarray, *, compiled: bool | None = None):
    """Frames (N, 1 + n_joints, 4, 4) for q (N, dof); only frames of ``sel`` are filled.

    Frame 0 is the root link (identity); frame ``j + 1`` is joint ``j``'s child link.
    ``compiled``: as for :func:`run_chain` (``KINLIB_NUMBA=0`` turns the kernels off);
    numba is imported when a kernel is first asked for, not with kinlib.
    """
    if compiled is not False:
        q = writable(q)
        args = (sel, table.ints, table.floats, table.M)
        fn = kernel("tree", lambda: (q[:0], *args), wait=wait_for_kernel(compiled, q.shape[0]))
        if fn is not None:
            return fn(q, *args)
    out = np.empty((q.shape[0], table.n + 1, 4, 4))
    out[:, 0] = np.eye(4)
    _numpy(table, q, sel, out)
    return out
