r"""Numeric inverse kinematics: damped least squares with Levenberg–Marquardt damping.

For a target pose ``(R_t, p_t)`` and the current pose ``(R, p) = fk(q)`` the error is

.. math:: e = \begin{bmatrix} p_t - p \\ \log(R_t R^T)^\vee \end{bmatrix}

(metres and radians, in the base frame), and each step solves

.. math:: (J^T J + \mu I)\,\Delta q = J^T e

with the geometric Jacobian J and the damping μ (texts that write the term as λ² I, as the
course's notebook 11 and assignment 03 do, have μ = λ²). A step that lowers ``|e|`` is kept
and μ shrinks (towards Gauss–Newton); one that does not is undone and μ grows (towards a
short gradient step).
After each step q is clipped into the joint limits (continuous joints are wrapped into
(−π, π]). An attempt that has not converged after ``max_iterations`` steps, or whose μ
has grown useless, restarts from a random configuration within the limits (seeded), up
to ``restarts`` times. Success means ``|p_t − p| < tol_position`` (metres) and the
rotation angle between ``R_t`` and ``R`` is below ``tol_rotation`` (radians) — never a
squared-error threshold. All targets are solved together, vectorised; an unreachable one
simply ends with ``success=False`` after its bounded number of steps.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._validate import as_array, as_tol, wrap_angle
from ..conventions import IK_POSITION_TOL, IK_ROTATION_TOL
from ..errors import KinlibError
from ..spatial.axis_angle import _log_so3_unchecked, log_so3
from ..spatial.transforms import check_transform
from . import _fk
from ._fk import in_threads

__all__ = ["IKResult", "solve_ik", "pose_error", "dls_step"]

_LAMBDA0, _LAMBDA_MIN, _LAMBDA_MAX = 1e-3, 1e-12, 1e8


@dataclass(frozen=True)
class IKResult:
    """What :meth:`kinlib.Robot.ik` found, per target (arrays with the targets' batch shape;
    plain Python numbers for a single target).

    q : the best configuration found (within the joint limits)
    success : whether it meets both tolerances
    position_error : ``|p_target − p(q)|`` in metres
    rotation_error : the angle between target and reached orientation, in radians
    iterations : steps taken, over all restarts
    """

    q: np.ndarray
    success: np.ndarray | bool
    position_error: np.ndarray | float
    rotation_error: np.ndarray | float
    iterations: np.ndarray | int


def pose_error(T, T_target) -> np.ndarray:
    r"""The error from the pose ``T`` to ``T_target``: ``[p_t − p; log(R_t Rᵀ)^∨]`` (6,).

    Metres, then radians: the translation still to go and the rotation vector of the
    rotation still to go, both in the base frame — the quantity ``robot.ik`` drives to zero,
    stacked like the geometric Jacobian's rows ``[v; ω]``. Batched over leading dimensions.

    >>> from kinlib import rotz, transform
    >>> pose_error(transform(p=[1.0, 0.0, 0.0]), transform(rotz(0.5), [1.0, 2.0, 0.0]))
    array([0. , 2. , 0. , 0. , 0. , 0.5])
    """
    T, T_target = check_transform(T, "T"), check_transform(T_target, "T_target")
    e_p = T_target[..., :3, 3] - T[..., :3, 3]
    e_r = log_so3(T_target[..., :3, :3] @ np.swapaxes(T[..., :3, :3], -1, -2))
    return np.concatenate(np.broadcast_arrays(e_p, e_r), axis=-1)


def dls_step(J, e, damping) -> np.ndarray:
    r"""One damped-least-squares step: ``Δq = Jᵀ (J Jᵀ + λ² I)⁻¹ e`` with ``λ = damping``.

    The ``Δq`` that minimises ``|J Δq − e|² + λ² |Δq|²``; ``λ = 0`` is the least-squares
    (pseudo-inverse) step. ``J`` is ``(..., m, n)``, ``e`` ``(..., m)``, ``damping`` a
    number ≥ 0 (with ``λ = 0`` the rows of ``J`` must be independent).

    >>> dls_step(np.array([[2.0, 0.0], [0.0, 1.0]]), np.array([2.0, 1.0]), 0.0)
    array([1., 1.])
    """
    J = as_array(J, "J")
    if J.ndim < 2:
        raise KinlibError(f"J: expected a Jacobian (..., m, n), got shape {J.shape}")
    m = J.shape[-2]
    e = as_array(e, "e", (m,))
    lam = as_tol(damping, "damping")
    A = J @ np.swapaxes(J, -1, -2) + lam**2 * np.eye(m)
    try:
        y = np.linalg.solve(A, e[..., None])[..., 0]
    except np.linalg.LinAlgError:
        raise KinlibError("dls_step: J Jᵀ + λ² I is singular: the rows of J are dependent; "
                          "give a damping > 0") from None
    return np.einsum("...mn,...m->...n", J, y)


def _errors(T_target, T, position_only):
    e_p = T_target[:, :3, 3] - T[:, :3, 3]
    e_r = _log_so3_unchecked(T_target[:, :3, :3] @ np.swapaxes(T[:, :3, :3], -1, -2))
    e = e_p if position_only else np.concatenate([e_p, e_r], axis=1)
    return e, np.linalg.norm(e_p, axis=1), np.linalg.norm(e_r, axis=1)


class _Limits:
    def __init__(self, robot):
        lim = robot.limits
        self.lo, self.hi = lim[:, 0], lim[:, 1]
        self.wrap = ~np.isfinite(self.lo) & ~np.isfinite(self.hi)
        self.sample_lo = np.where(np.isfinite(self.lo), self.lo, -np.pi)
        self.sample_hi = np.where(np.isfinite(self.hi), self.hi, np.pi)

    def project(self, q):
        q = np.clip(q, self.lo, self.hi)
        return np.where(self.wrap, wrap_angle(q), q)  # continuous joints into (−π, π]

    def sample(self, rng, n):
        return rng.uniform(self.sample_lo, self.sample_hi, (n, len(self.lo)))


def _targets(T_target, position_only):
    if position_only:
        a = as_array(T_target, "T_target")
        if a.shape[-1:] == (3,):
            T = np.zeros(a.shape[:-1] + (4, 4))
            T[..., :3, :3] = np.eye(3)
            T[..., :3, 3] = a
            T[..., 3, 3] = 1.0
            return T
    return check_transform(T_target, "T_target")


def _check_count(name, v, least):
    if isinstance(v, bool) or not isinstance(v, int | np.integer) or v < least:
        raise KinlibError(f"{name}: expected an integer >= {least}, got {v!r}")
    return int(v)


def _starts(robot, limits, q0, batch, n, attempts, seed):
    """Starting configurations (n, attempts, dof): q0 (if given) first, then seeded
    random ones within the limits."""
    rng = seed if isinstance(seed, np.random.Generator) else np.random.default_rng(seed)
    starts = limits.sample(rng, n * attempts).reshape(n, attempts, robot.dof)
    if q0 is not None:
        q = robot.check_q(q0, "q0")
        if q.ndim > 1 and q.shape[:-1] != batch:
            raise KinlibError(f"q0: expected shape {(robot.dof,)} or {batch + (robot.dof,)} "
                              f"for the targets' batch {batch}, got {q.shape}")
        starts[:, 0] = limits.project(np.broadcast_to(q, batch + (robot.dof,)).reshape(n, -1))
    return starts


RANKED = 16  # random starts per target compared before the first attempt


def _rank_starts(robot, link, T_t, starts, position_only, keep_first):
    """Put each target's most promising start first: of the first :data:`RANKED` random
    starts, order by initial pose error (metres + radians), best first."""
    n, attempts, dof = starts.shape
    k = min(attempts, RANKED)
    if k == 1:
        return np.ascontiguousarray(starts)  # one start: nothing to order
    head = starts[:, :k]
    T = robot.fk(head.reshape(-1, dof), link=link).reshape(n, k, 4, 4)
    err = np.linalg.norm(T[..., :3, 3] - T_t[:, None, :3, 3], axis=-1)
    if not position_only:
        cos = (np.einsum("nij,naij->na", T_t[:, :3, :3], T[..., :3, :3]) - 1.0) / 2.0
        err += np.arccos(np.clip(cos, -1.0, 1.0))
    if keep_first:
        err[:, 0] = -np.inf
    order = np.argsort(err, axis=1, kind="stable")
    starts[:, :k] = np.take_along_axis(head, order[..., None], axis=1)
    return np.ascontiguousarray(starts)


def solve_ik(robot, T_target, q0=None, *, link=None, position_only=False,
             tol_position=IK_POSITION_TOL, tol_rotation=IK_ROTATION_TOL, max_iterations=30,
             restarts=100, seed=0, compiled=None):
    """See :meth:`kinlib.Robot.ik`. ``compiled``: None, the compiled loop if it is ready
    (else the numpy reference, while the loop is prepared in the background: see
    :func:`kinlib.kinematics._fk.kernel`); True, the compiled loop (waiting for it; numpy
    only without numba); False, the numpy reference."""
    T_t = _targets(T_target, position_only)
    batch = T_t.shape[:-2]
    T_t = _fk.writable(np.ascontiguousarray(T_t.reshape(-1, 4, 4)))
    n = T_t.shape[0]
    tol_p, tol_r = as_tol(tol_position, "tol_position"), as_tol(tol_rotation, "tol_rotation")
    max_iterations = _check_count("max_iterations", max_iterations, 1)
    attempts = _check_count("restarts", restarts, 0) + 1
    link = robot.resolve_link(link)
    limits = _Limits(robot)
    starts = _starts(robot, limits, q0, batch, n, attempts, seed)
    starts = _rank_starts(robot, link, T_t, starts, position_only, q0 is not None)
    fn = None
    if compiled is not False:
        chain = robot.chain_table(link)
        out = (np.empty((n, robot.dof)), np.empty(n, dtype=bool), np.empty(n), np.empty(n),
               np.empty(n, dtype=np.int64))  # q, success, errors, iterations: filled by ik_lm

        def args(a, b):
            return (T_t[a:b], starts[a:b], limits.lo, limits.hi, limits.wrap, chain.ints,
                    chain.floats, chain.D, position_only, tol_p, tol_r, max_iterations,
                    *(o[a:b] for o in out))

        fn = _fk.kernel("ik_lm", lambda: args(0, 0), module="_ik_numba",
                        wait=_fk.wait_for_kernel(compiled, n, WAIT_MIN))
    if fn is not None:
        in_threads(fn, n, args, min_batch=8)
        q, success, pe, re, iters = out
    else:
        q, success, pe, re, iters = _solve_numpy(robot, link, T_t, starts, limits,
                                                 position_only, tol_p, tol_r, max_iterations)

    def shape(a):
        a = a.reshape(batch + a.shape[1:])
        return a.item() if a.ndim == 0 else a

    return IKResult(q.reshape(batch + (robot.dof,)), shape(success), shape(pe), shape(re),
                    shape(iters))


def _compiled_ik():
    """The compiled IK loop's module imported now, or None (as for the FK kernels:
    :func:`kinlib.kinematics._fk._compiled`)."""
    if _fk._compiled() is None:
        return None
    return _fk._load_kernels("_ik_numba")


#: from this many targets, a solve whose compiled loop is still being prepared waits for it
#: (the numpy path would take longer than the compile: bench/README.md, "the first call")
WAIT_MIN = 256


#: the numpy path's attempts side by side (see _solve_numpy). Numpy's cost per call, not the
#: arithmetic, is what a step of a few lanes costs, so a solve starts with FIRST_LANES lanes
#: in all (its targets' first attempts, FIRST_LANES // n each, at least one); a step in which
#: attempts of a target fail multiplies how many of its attempts may run at once by GROWTH,
#: up to WINDOW_MAX, and up to LANES_MAX // n (a few kB per lane: beyond that, numpy's arrays
#: outgrow the caches). The settings tried and their times: bench/README.md, "Without a
#: compiler" (one unreachable PUMA 560 target: 13-21 ms all at once, 34-43 ms with the
#: setting before, the first attempt alone and then 64)
FIRST_LANES = 128
WINDOW_MAX = 128
GROWTH = 128
LANES_MAX = 2048


class _Lanes:
    """The attempts running side by side in the numpy path: one row per (target, attempt),
    each field an array over the rows."""

    FIELDS = ("t", "a", "q", "lam", "steps", "cost_acc", "q_acc", "e_acc", "J_acc",
              "bcost", "bq", "bp", "br")

    def __init__(self, **fields):
        for name in self.FIELDS:
            setattr(self, name, fields[name])

    def keep(self, mask):
        for name in self.FIELDS:
            setattr(self, name, getattr(self, name)[mask])

    def extend(self, other):
        for name in self.FIELDS:
            setattr(self, name, np.concatenate([getattr(self, name), getattr(other, name)]))


def _launch(targets, attempts, starts, rows):
    """Fresh lanes: attempt ``attempts[k]`` of target ``targets[k]`` from its start."""
    m, dof = len(targets), starts.shape[2]
    q = starts[targets, attempts]
    return _Lanes(t=targets, a=attempts, q=q, lam=np.full(m, _LAMBDA0),
                  steps=np.zeros(m, dtype=np.int64), cost_acc=np.full(m, np.inf),
                  q_acc=q.copy(), e_acc=np.zeros((m, rows)), J_acc=np.zeros((m, 6, dof)),
                  bcost=np.full(m, np.inf), bq=q.copy(), bp=np.full(m, np.inf),
                  br=np.full(m, np.inf))


def _solve_numpy(robot, link, T_t, starts, limits, position_only, tol_p, tol_r, max_iter):
    """The reference: the same method as the compiled loop, vectorised.

    A target's attempts do not depend on each other (each starts afresh from its own
    start), only the answer does: the first attempt, in order, that succeeds; else the
    closest pose of all, the first of equals. So the attempts of every target run side by
    side as lanes of one vectorised loop: first :data:`FIRST_LANES` in all (at least one
    per target), then, after each step in which some fail, :data:`GROWTH` times as many
    (at most :data:`WINDOW_MAX` per target, and :data:`LANES_MAX` // n). A target is
    decided once an attempt succeeded and every earlier one has ended, or when all have
    failed; its lanes still running are then dropped, and the iterations reported are
    those of the attempts up to the deciding one, as if run one after another: the same
    answers and counts as the compiled loop, without paying numpy's cost per call once per
    restart of an unreachable target."""
    n, attempts, dof = starts.shape
    rows = 3 if position_only else 6
    sel = slice(0, rows)
    eye = np.eye(dof)
    chain = robot.chain_table(link)
    # per target and attempt, once the attempt has ended: its steps, success, closest pose
    ended = np.zeros((n, attempts), dtype=bool)
    ok_at = np.zeros((n, attempts), dtype=bool)
    it_at = np.zeros((n, attempts), dtype=np.int64)
    cost_at = np.full((n, attempts), np.inf)
    q_at = np.repeat(starts[:, :1], attempts, axis=1)
    p_at, r_at = np.full((n, attempts), np.inf), np.full((n, attempts), np.inf)
    first = min(attempts, max(1, FIRST_LANES // max(n, 1)))  # each target's first attempts
    widest = max(first, min(WINDOW_MAX, LANES_MAX // max(n, 1)))  # at most at once, each
    window = np.full(n, first, dtype=np.int64)
    running = np.full(n, first, dtype=np.int64)
    launched = np.full(n, first, dtype=np.int64)  # attempts started so far: 0 .. launched − 1
    limit = np.full(n, attempts)                # attempts that can still matter
    decided = np.zeros(n, dtype=bool)
    lanes = _launch(np.repeat(np.arange(n), first), np.tile(np.arange(first), n), starts, rows)
    while len(lanes.t):
        T, J = _fk.run_chain_jacobian(chain, lanes.q, compiled=False)
        e, ep, er = _errors(T_t[lanes.t], T, position_only)
        cost = ep * ep + (0.0 if position_only else er * er)
        lanes.steps += 1
        ok = (ep < tol_p) & (position_only | (er < tol_r))
        better = (cost < lanes.bcost) | ok
        lanes.bq[better], lanes.bcost[better] = lanes.q[better], cost[better]
        lanes.bp[better], lanes.br[better] = ep[better], er[better]
        improved = cost < lanes.cost_acc
        lanes.q_acc[improved], lanes.cost_acc[improved] = lanes.q[improved], cost[improved]
        lanes.e_acc[improved], lanes.J_acc[improved] = e[improved], J[improved]
        lanes.lam = np.where(improved, np.maximum(lanes.lam / 3.0, _LAMBDA_MIN),
                             lanes.lam * 4.0)
        # an attempt ends when it succeeds, after max_iter steps, or when λ has grown useless
        stop = ok | (lanes.steps >= max_iter) | (lanes.lam > _LAMBDA_MAX)
        fresh = None
        if stop.any():
            t, a = lanes.t[stop], lanes.a[stop]
            ended[t, a], ok_at[t, a], it_at[t, a] = True, ok[stop], lanes.steps[stop]
            cost_at[t, a], q_at[t, a] = lanes.bcost[stop], lanes.bq[stop]
            p_at[t, a], r_at[t, a] = lanes.bp[stop], lanes.br[stop]
            np.subtract.at(running, t, 1)
            # a target with failures in this step: GROWTH times the window, up to `widest`
            # (once per step: once per failure, 64 failing together overflowed int64 to 0,
            # and the target's later attempts were never launched)
            failed = np.unique(t[~ok[stop]])
            window[failed] = np.minimum(window[failed] * GROWTH, widest)
            hit = t[ok[stop]]
            np.minimum.at(limit, hit, a[ok[stop]])  # later attempts cannot matter now
            touched = np.unique(t)
            first_open = np.where(ended[touched].all(axis=1), attempts,
                                  np.argmin(ended[touched], axis=1))
            decided[touched] = (limit[touched] < first_open) | (first_open >= attempts)
            keep = ~stop & ~decided[lanes.t] & (lanes.a < limit[lanes.t])
            dropped = lanes.t[~stop & ~keep]
            np.subtract.at(running, dropped, 1)
            lanes.keep(keep)
            open_ = touched[~decided[touched]]
            more = np.minimum(window[open_] - running[open_], limit[open_] - launched[open_])
            more = np.maximum(more, 0)
            if more.any():
                new_t = np.repeat(open_, more)
                base = np.repeat(launched[open_] - np.cumsum(more) + more, more)
                new_a = base + np.arange(len(new_t))
                launched[open_] += more
                running[open_] += more
                fresh = _launch(new_t, new_a, starts, rows)
        if len(lanes.t):  # the damped step from the accepted point
            Ja = lanes.J_acc[:, sel]
            A = np.swapaxes(Ja, 1, 2) @ Ja + lanes.lam[:, None, None] * eye
            g = np.einsum("nij,ni->nj", Ja, lanes.e_acc)
            lanes.q = limits.project(lanes.q_acc + np.linalg.solve(A, g[..., None])[..., 0])
        if fresh is not None:
            lanes.extend(fresh)
    rows_ = np.arange(n)
    success = ok_at.any(axis=1)
    k = np.where(success, np.argmax(ok_at, axis=1),
                 np.argmin(np.where(np.isnan(cost_at), np.inf, cost_at), axis=1))
    counted = np.arange(attempts) <= np.where(success, k, attempts)[:, None]
    total = (it_at * counted).sum(axis=1)
    return q_at[rows_, k], success, p_at[rows_, k], r_at[rows_, k], total
