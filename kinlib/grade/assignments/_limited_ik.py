"""The IK half of assignment 06 (differential kinematics): a damped least-squares loop whose
every iterate stays within the joint limits, returning ``(q, success)``.

An answer is judged by what it claims: q must lie within the limits (to 1e-9), and
``success=True`` must come with q whose forward kinematics reaches the target (1e-6 in
position and in rotation angle). Two kinds of targets:

- *reachable*: the pose of a configuration q* within the limits (kinlib's robots with their
  own or tightened limits, a joint of q* at its limit, a start q0 outside the limits), and
  a start near q*: a right loop reaches it, and ``success=False`` is wrong;
- *unreachable within the limits*, provably: planar chains (2R, 3R, RP, placed anywhere in
  space) whose every solution of the full pose is known in closed form and lies outside the
  limits, a target beyond the arm's reach and one off its plane. There the right answer is
  ``success=False`` — which a loop that never tries also gives, so those cases count only
  beside right answers to the reachable ones (:attr:`Check.is_trivial`).

The kind of each case is remembered when the cases are made (the judge and the credit rule
look it up); a case made elsewhere is classified by the reference loop from many starts.
"""

from __future__ import annotations

import numpy as np

import kinlib as kl
from kinlib._validate import wrap_angle

from .._checks import RIGHT, Check, Verdict, as_numeric, fmt

__all__ = ["ik_check", "limited_dls", "planar_chain", "solutions_3r", "circle_gap", "reached",
           "LIMIT_TOL"]

LIMIT_TOL = 1e-9  # how far outside its limits a returned joint value may be
REACH_TOL = 1e-6  # metres and radians
_KINDS: dict = {}  # case key -> (reachable, q_star)


def _key(args):
    _, S, limits, T_target, q0 = args
    return (np.asarray(T_target).tobytes(), np.asarray(q0).tobytes(),
            np.asarray(limits).tobytes(), np.asarray(S).tobytes())


def errors(M, S, q, T_target) -> tuple[float, float]:
    """(position error in metres, rotation angle in radians) of poe_fk(M, S, q) from the
    target."""
    T = kl.poe_fk(M, S, q)
    R_err = T_target[:3, :3] @ T[:3, :3].T
    return (float(np.linalg.norm(T_target[:3, 3] - T[:3, 3])),
            float(np.linalg.norm(kl.log_so3(R_err))))


def reached(M, S, q, T_target) -> bool:
    pos, rot = errors(M, S, q, T_target)
    return pos < REACH_TOL and rot < REACH_TOL


def limited_dls(M, S, limits, T_target, q0, damping=0.01, iterations=100):
    """The loop the notebook describes, with kinlib's kinematics: clip q0 into the limits;
    step by damped least squares on the first-order error of T_target T⁻¹ with the space
    Jacobian; clip every iterate; stop at the target (every entry of T within 1e-10) or when
    the clipped step vanishes. Returns ``(q, success)``.

    >>> S, M = planar_chain("RR", [1.0, 0.5])
    >>> limits = np.array([[-3.0, 3.0], [0.1, 2.0]])  # the elbow bends one way only
    >>> q, ok = limited_dls(M, S, limits, kl.poe_fk(M, S, [0.4, 1.0]), np.array([0.3, 0.8]))
    >>> ok, bool(np.allclose(q, [0.4, 1.0]))
    (True, True)
    >>> limited_dls(M, S, limits, kl.poe_fk(M, S, [0.4, -1.0]), np.array([0.3, 0.8]))[1]
    False
    """
    lo, hi = limits[:, 0], limits[:, 1]
    q = np.clip(np.asarray(q0, dtype=float), lo, hi)
    for _ in range(iterations):
        T = kl.poe_fk(M, S, q)
        if np.abs(T - T_target).max() < 1e-10:
            return q, True
        E = T_target @ kl.transform_inverse(T)
        W = 0.5 * (E[:3, :3] - E[:3, :3].T)
        e = np.concatenate([E[:3, 3], [W[2, 1], W[0, 2], W[1, 0]]])
        J = kl.space_jacobian(S, q)
        step = J.T @ np.linalg.solve(J @ J.T + damping**2 * np.eye(6), e)
        q_new = np.clip(q + step, lo, hi)
        if np.linalg.norm(q_new - q) < 1e-14:
            break
        q = q_new
    return q, False


# -- planar chains, placed anywhere: their solutions in closed form -------------------------
def planar_chain(kinds: str, lengths) -> tuple[np.ndarray, np.ndarray]:
    """``(S, M)`` of a chain in the xy plane: ``"R"`` a joint about z at the current point,
    ``"P"`` a slide along x; each length moves the next joint (and finally the tip) along x.

    >>> S, M = planar_chain("RR", [1.0, 0.5])
    >>> S.T + 0.0
    array([[ 0.,  0.,  0.,  0.,  0.,  1.],
           [ 0., -1.,  0.,  0.,  0.,  1.]])
    >>> M[:3, 3]
    array([1.5, 0. , 0. ])
    """
    S = np.zeros((6, len(kinds)))
    x = 0.0
    for i, (kind, length) in enumerate(zip(kinds, lengths, strict=True)):
        if kind == "R":
            S[:, i] = [0.0, -x, 0.0, 0.0, 0.0, 1.0]  # [−ω × p; ω] with ω = z, p = (x, 0, 0)
        else:
            S[:, i] = [1.0, 0.0, 0.0, 0.0, 0.0, 0.0]
        x += length
    return S, kl.transform(p=[x, 0.0, 0.0])


def placed(G, S, M) -> tuple[np.ndarray, np.ndarray]:
    """The chain moved by G: screw axes Ad_G S, home G M (so its poses are G T(q))."""
    return kl.adjoint(G) @ S, G @ M


def solutions_3r(T_local, l1, l2, l3) -> list[np.ndarray]:
    """Every (θ1, θ2, θ3) putting a planar 3R chain's tip at the planar pose ``T_local``:
    the 2R solutions for the wrist point, θ3 = φ − θ1 − θ2."""
    phi = np.arctan2(T_local[1, 0], T_local[0, 0])
    w = T_local[:2, 3] - l3 * np.array([np.cos(phi), np.sin(phi)])
    out = []
    for elbow in ("up", "down"):
        s = kl.planar_2r_ik(w[0], w[1], l1, l2, elbow=elbow)
        if s.success:
            t1, t2 = float(s.theta1), float(s.theta2)
            out.append(np.array([t1, t2, phi - t1 - t2]))
    return out


def circle_gap(theta, lo, hi) -> float:
    """How far the angle θ (any multiple of 2π) is from the interval [lo, hi]; 0 inside.

    >>> circle_gap(3.0, -1.0, 1.0), circle_gap(3.0 - 2 * np.pi, 2.5, 4.0)
    (2.0, 0.0)
    """
    best = np.inf
    for k in range(-3, 4):
        t = theta + 2 * np.pi * k
        best = min(best, max(lo - t, t - hi, 0.0))
    return float(best)


def _outside(q, limits, kinds, margin) -> bool:
    """Some joint of q is at least ``margin`` outside its limits (revolute: modulo 2π)."""
    for t, (lo, hi), kind in zip(q, limits, kinds, strict=True):
        gap = circle_gap(t, lo, hi) if kind == "R" else max(lo - t, t - hi, 0.0)
        if gap >= margin:
            return True
    return False


def _random_pose(rng):
    from .common import random_rotations

    return kl.transform(random_rotations(rng, 1)[0], rng.uniform(-0.5, 0.5, 3))


def _angle_outside(rng, lo, hi, margin=0.25):
    """An angle in (−π, π] at least ``margin`` outside [lo, hi] (width below 2π − 2 margin)."""
    t = rng.uniform(hi + margin, lo + 2 * np.pi - margin)
    return float(wrap_angle(t))


def _planar_unreachable(rng, kinds):
    """An unreachable-within-limits case of a planar chain, placed at a random pose."""
    n = len(kinds)
    lengths = rng.uniform(0.4, 1.0, n)
    limits = np.array([[rng.uniform(-2.6, -0.4), rng.uniform(0.4, 2.6)] if k == "R"
                       else [0.0, rng.uniform(0.2, 0.5)] for k in kinds])
    S, M = planar_chain(kinds, lengths)
    for _ in range(1000):
        q = np.array([rng.uniform(lo, hi) for lo, hi in limits])
        j = int(rng.integers(n))
        lo, hi = limits[j]
        q[j] = (_angle_outside(rng, lo, hi) if kinds[j] == "R"
                else rng.choice([lo - rng.uniform(0.1, 0.3), hi + rng.uniform(0.1, 0.4)]))
        T_local = kl.poe_fk(M, S, q)
        # 2R and RP: q is the only solution (modulo 2π); 3R: both elbows
        sols = solutions_3r(T_local, *lengths) if kinds == "RRR" else [q]
        if sols and all(_outside(s, limits, kinds, 0.1) for s in sols):
            break
    else:  # pragma: no cover
        raise RuntimeError("no unreachable target found")
    G = _random_pose(rng)
    S, M = placed(G, S, M)
    q0 = np.array([rng.uniform(lo, hi) for lo, hi in limits])
    return (M, S, limits, G @ T_local, q0)


def _out_of_reach(rng, off_plane: bool):
    """A target no configuration reaches: beyond a 2R arm's reach, or off a 3R arm's plane."""
    kinds = "RRR" if off_plane else "RR"
    lengths = rng.uniform(0.4, 1.0, len(kinds))
    S, M = planar_chain(kinds, lengths)
    limits = np.tile([-np.pi, np.pi], (len(kinds), 1))
    if off_plane:
        T_local = kl.poe_fk(M, S, rng.uniform(-2.0, 2.0, 3)) @ kl.transform(p=[0, 0, 0.1])
    else:
        phi = rng.uniform(-np.pi, np.pi)
        r = lengths.sum() + rng.uniform(0.1, 0.3)
        T_local = kl.transform(kl.rotz(rng.uniform(-np.pi, np.pi)),
                               [r * np.cos(phi), r * np.sin(phi), 0.0])
    G = _random_pose(rng)
    S, M = placed(G, S, M)
    return (M, S, limits, G @ T_local, rng.uniform(-1.0, 1.0, len(kinds)))


# -- reachable targets ----------------------------------------------------------------------
def _conditioned(S, q) -> bool:
    s = np.linalg.svd(kl.space_jacobian(S, q), compute_uv=False)
    return s[-1] / s[0] > 0.03


def _reachable(rng, S, M, limits, *, tight=False, at_limit=False, q0_outside=False):
    """A target posed by q* within the limits (away from them by 0.2 and from singular
    configurations), and a start q0 near q* from which the notebook's loop gets there in at
    most 60 steps; ``(case, q*)``."""
    n = S.shape[1]
    prismatic = np.all(S[3:] == 0, axis=0)[:, None]
    box = np.where(np.isfinite(limits), limits,
                   np.where(prismatic, [[-0.3, 0.5]], [[-np.pi, np.pi]]))
    for _ in range(1000):
        q = rng.uniform(box[:, 0] + 0.2, box[:, 1] - 0.2)
        if not _conditioned(S, q):
            continue
        lim = np.array(limits, dtype=float)
        if tight:  # limits close around q* on some joints
            for j in rng.choice(n, max(1, n // 2), replace=False):
                lim[j] = [q[j] - rng.uniform(0.05, 0.5), q[j] + rng.uniform(0.05, 0.5)]
        if at_limit:  # one joint of q* at a limit
            j = int(rng.integers(n))
            lim[j, int(rng.integers(2))] = q[j]
        q0 = q + rng.normal(size=n) * 0.12
        if q0_outside:  # a start outside tight limits of one joint: clip it first
            j = int(rng.integers(n))
            lim[j] = [q[j] - rng.uniform(0.05, 0.3), q[j] + rng.uniform(0.05, 0.3)]
            q0[j] = (lim[j, 1] + rng.uniform(0.05, 0.3) if rng.random() < 0.5
                     else lim[j, 0] - rng.uniform(0.05, 0.3))
        case = (M, S, lim, kl.poe_fk(M, S, q), q0)
        if limited_dls(*case, iterations=60)[1]:
            return case, q
    raise RuntimeError("no reachable target found")  # pragma: no cover


def _ik_cases(rng):
    from .differential import robot_chain

    cases = []
    for name, k in (("puma560", 4), ("ur5", 4), ("panda", 3), ("three_dof_arm", 2),
                    ("scara", 1), ("stanford", 1)):
        S, M, limits = robot_chain(name)
        for i in range(k):
            cases.append(_reachable(rng, S, M, limits, tight=i % 2 == 1, at_limit=i == 2,
                                    q0_outside=i == 3))
    for kinds, k in (("RR", 2), ("RRR", 3), ("RP", 1)):  # planar chains with tight limits
        for i in range(k):
            S, M = placed(_random_pose(rng), *planar_chain(kinds, rng.uniform(0.4, 1.0,
                                                                            len(kinds))))
            limits = np.tile([-np.inf, np.inf], (len(kinds), 1))
            cases.append(_reachable(rng, S, M, limits, tight=True, at_limit=i == 1))
    for kinds, k in (("RR", 4), ("RRR", 6), ("RP", 3)):
        cases += [(_planar_unreachable(rng, kinds), None) for _ in range(k)]
    cases += [(_out_of_reach(rng, off), None) for off in (False, True)]
    out = []
    for args, q_star in cases:
        args = tuple(np.array(a, dtype=float) for a in args)
        _KINDS[_key(args)] = (q_star is not None, q_star)
        out.append(args)
    if len(_KINDS) > 5000:  # (a long batch with many secrets: keep the newest cases)
        for key in list(_KINDS)[:-len(out)]:
            del _KINDS[key]
    return out


def _kind(args):
    """(reachable, q*) of a case: remembered from _ik_cases, else searched for."""
    known = _KINDS.get(_key(args))
    if known is not None:
        return known
    M, S, limits, T_target, _ = args
    rng = np.random.default_rng(0)
    finite = np.where(np.isfinite(limits), limits, np.tile([-np.pi, np.pi], (len(limits), 1)))
    for _ in range(30):
        q, ok = limited_dls(M, S, limits, T_target, rng.uniform(finite[:, 0], finite[:, 1]))
        if ok:
            return True, q
    return False, None


def _judge_ik(args, got):
    M, S, limits, T_target, _ = args
    n = S.shape[1]
    reachable, q_star = _kind(args)
    if not isinstance(got, tuple | list) or len(got) != 2:
        return Verdict(False, "type", f"returned {fmt(got, 80)}; expected a pair (q, success): "
                                      f"q an array of {n} joint values, success True or False",
                       q_star)
    q, bad = as_numeric(got[0], (n,), "joint values q")
    if q is None:
        return Verdict(bad.ok, bad.key, bad.message, q_star)
    success = got[1]
    if type(success) is not bool:
        return Verdict(False, "type", f"success is {fmt(success, 40)}; return True or False "
                                      "(a bool) as the second item", q_star)
    lo, hi = limits[:, 0], limits[:, 1]
    over = np.maximum(lo - q, q - hi)
    if over.max() > LIMIT_TOL:
        j = int(np.argmax(over))
        where = ("the target is reachable within the limits" if reachable else
                 "within the limits this target is unreachable: the answer is success False")
        return Verdict(False, "limits", f"joint {j + 1} (q[{j}] = {q[j]:.6g}) is outside its "
                                        f"limits [{lo[j]:.6g}, {hi[j]:.6g}]: clip every "
                                        f"iterate into the limits, np.clip(q, lo, hi) ({where})",
                       q_star)
    pos, rot = errors(M, S, q, T_target)
    hit = pos < REACH_TOL and rot < REACH_TOL
    if success:
        if hit:
            return RIGHT
        return Verdict(False, "claimed", f"you claimed success, but poe_fk(q) misses the target "
                                         f"by {pos:.3g} m and {rot:.3g} rad: claim it only when "
                                         "the pose error is (almost) zero, never because the "
                                         "step became small" + ("" if reachable else
                                                                " (this target is unreachable "
                                                                "within the limits)"), q_star)
    if hit:
        return Verdict(False, "unclaimed", f"your q reaches the target (to {pos:.2g} m, "
                                           f"{rot:.2g} rad) but you returned success False: "
                                           "test the pose error of the q you return", q_star)
    if reachable:
        return Verdict(False, "missed", f"you gave up {pos:.3g} m and {rot:.3g} rad from a "
                                        "target that is reachable within the limits (from a "
                                        "start near a solution): check the sign of the error "
                                        "(target relative to the current pose), the damping and "
                                        "the number of iterations", q_star)
    return RIGHT


def _ik_hint(args, error: str):
    if "Singular matrix" in error:
        return "J Jᵀ + λ² I is singular: the damping λ must be greater than 0"
    return None


def ik_check(points: float) -> Check:
    return Check("ik_with_limits", points, "damped least squares within the joint limits: "
                 "(q, success)", _ik_cases, judge=_judge_ik, on_error=_ik_hint,
                 is_trivial=lambda c: not _kind(c)[0],
                 trivial="of success False where the target is unreachable within the limits")
