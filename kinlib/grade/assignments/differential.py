"""Assignment 06 · differential kinematics: the exponential of a twist, forward kinematics
by the product of exponentials, the space Jacobian (numerically, and of a planar 3R arm
derived with sympy: :mod:`._sj_symbolic`), manipulability, the direction a
singular Jacobian loses, and a damped least-squares IK loop that keeps within the joint
limits.

Twists and screw axes are ``[v; ω]``, linear part first (Modern Robotics writes ``[ω; v]``:
a submission that uses that order gets the ``rows`` diagnosis). The references are
kinlib's: :func:`kinlib.exp_se3`, :func:`kinlib.poe_fk`, :func:`kinlib.space_jacobian`
(mistakes: :func:`kinlib.body_jacobian` and the adjoint carried wrongly),
:func:`kinlib.manipulability` and :func:`kinlib.is_near_singular` (:mod:`._singular`), and
forward kinematics of the IK answer (:mod:`._limited_ik`).
"""

from __future__ import annotations

from functools import cache

import numpy as np

import kinlib as kl
from kinlib.check.mistakes import DEGREES, ROWS, TRANSPOSED

from .._checks import Assignment, Check, Mistake, Verdict
from ._limited_ik import ik_check
from ._singular import lost_direction_check, manipulability_check
from ._sj_symbolic import space_jacobian_3r_check
from .common import random_rotations, random_unit_vectors
from .jacobian_ik import prismatic_robots

__all__ = ["assignment", "chains", "random_chain", "exp_products", "space_jacobian_model",
           "robot_chain"]


# -- chains: kinlib's robots and random screw chains ----------------------------------------
@cache
def robot_chain(name: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(S, M, limits)`` of one of kinlib's robots (or assignment 03's prismatic ones)."""
    from kinlib import robots

    if name in ("stanford", "scara"):
        robot = {r.name: r for r in prismatic_robots()}[name]
    elif name == "planar_2r":
        robot = robots.planar_2r(1.0, 0.7)
    else:
        robot = getattr(robots, name)()
    S, M = kl.screw_axes(robot)
    return S, M, np.array(robot.limits, dtype=float)


ROBOTS = ("puma560", "ur5", "panda", "three_dof_arm", "planar_2r", "stanford", "scara")


def chain_q(rng, S, limits) -> np.ndarray:
    """Random joint values: within finite limits, else an angle in [−π, π] (revolute) or a
    slide in [−0.3, 0.5] (prismatic)."""
    out = np.empty(S.shape[1])
    for i, (lo, hi) in enumerate(limits):
        if np.isfinite(lo) and np.isfinite(hi):
            out[i] = rng.uniform(lo, hi)
        elif np.allclose(S[3:, i], 0):
            out[i] = rng.uniform(-0.3, 0.5)
        else:
            out[i] = rng.uniform(-np.pi, np.pi)
    return out


def random_chain(rng, n: int, p_prismatic: float = 0.25) -> tuple[np.ndarray, np.ndarray]:
    """``(S, M)``: n screw axes (revolute ``[−ω × p; ω]`` with unit ω through a point p, or
    prismatic ``[v; 0]`` with unit v) and a random home pose M.

    >>> S, M = random_chain(np.random.default_rng(1), 4)
    >>> w, v = np.linalg.norm(S[3:], axis=0), np.linalg.norm(S[:3], axis=0)
    >>> S.shape, bool(np.allclose(np.where(w > 0, w, v), 1.0))  # unit ω, or ω = 0 and unit v
    ((6, 4), True)
    """
    S = np.zeros((6, n))
    axes = random_unit_vectors(rng, n)
    for i in range(n):
        if rng.random() < p_prismatic:
            S[:3, i] = axes[i]
        else:
            S[:3, i] = -np.cross(axes[i], rng.uniform(-0.8, 0.8, 3))
            S[3:, i] = axes[i]
    return S, kl.transform(random_rotations(rng, 1)[0], rng.uniform(-1.0, 1.0, 3))


def chains(rng, per_robot: int, random_n: range) -> list[tuple]:
    """``(M, S, q)`` cases: each robot at home and at ``per_robot`` random configurations,
    then one random chain for each n in ``random_n`` (twice)."""
    out = []
    for name in ROBOTS:
        S, M, limits = robot_chain(name)
        out.append((M, S, np.zeros(S.shape[1])))
        out += [(M, S, chain_q(rng, S, limits)) for _ in range(per_robot)]
    for n in list(random_n) * 2:
        S, M = random_chain(rng, n)
        out.append((M, S, chain_q(rng, S, np.full((n, 2), np.inf) * [-1, 1])))
    return out


# -- the exponential of a twist -------------------------------------------------------------
def _with(T, R=None, p=None) -> np.ndarray:
    out = np.array(T, dtype=float)
    if R is not None:
        out[:3, :3] = R
    if p is not None:
        out[:3, 3] = p
    return out


def _exp(xi) -> np.ndarray:
    return kl.exp_se3(np.asarray(xi, dtype=float))


def _screw_scaled(xi):
    """p = G(θ) v with v not divided by θ: θ times the right translation."""
    T = _exp(xi)
    return _with(T, p=np.linalg.norm(xi[3:]) * T[:3, 3])


EXP_MISTAKES = [
    ROWS.of(lambda xi: _exp(np.roll(xi, 3)),
            "you read the twist as [ω; v] (Modern Robotics' order): the course's twists are "
            "[v; ω], linear part first, so v = xi[:3] and ω = xi[3:]"),
    Mistake("V", "the translation is not v itself: moving along the twist for unit time "
                 "takes the origin to p = V v with V = I + (1 − cos θ)/θ² [ω] + (θ − sin θ)/θ³ "
                 "[ω]², θ = |ω| (p = v only when ω = 0)",
            lambda xi: _with(_exp(xi), p=xi[:3])),
    Mistake("screw", "your translation is θ = |ω| times too large: the unit screw is "
                     "S = ξ/θ, so p = (I θ + (1 − cos θ)[ω̂] + (θ − sin θ)[ω̂]²) v/θ with "
                     "ω̂ = ω/θ — divide v by θ as well", _screw_scaled),
    TRANSPOSED.of(lambda xi: _with(_exp(xi), R=_exp(xi)[:3, :3].T),
                  "your rotation is the transpose of e^[ω]: Rodrigues' formula is "
                  "R = I + (sin θ/θ)[ω] + ((1 − cos θ)/θ²)[ω]², with a plus before the sine"),
    Mistake("small angle", "your answer is the pure translation [I, v; 0, 1], but ω ≠ 0: "
                           "treat only ω = 0 (or |ω| below about 1e-12) as a pure "
                           "translation; for small |ω| the formula still works (or use its "
                           "series: (1 − cos θ)/θ² → 1/2, (θ − sin θ)/θ³ → 1/6)",
            lambda xi: _with(np.eye(4), p=xi[:3])),
]
_EXP_RULE = Check("exp_twist", 0, "", lambda rng: [], _exp, EXP_MISTAKES)


def _judge_exp(args, got):
    v = _EXP_RULE.verdict(args, got)
    if v.key == "nan" and not np.any(args[0][3:]):
        return Verdict(False, "zero angle", "NaN for a twist with ω = 0 (a pure translation): "
                                            "there θ = |ω| = 0 and e^[ξ] = [I, v; 0, 1]; never "
                                            "divide by θ = 0", v.expected)
    return v


def _exp_error_hint(args, error: str):
    if "NotImplementedError" not in error and not np.any(args[0][3:]):
        return ("This twist has ω = 0 (a pure translation): e^[ξ] = [I, v; 0, 1], without "
                "dividing by |ω|")
    return None


def _exp_cases(rng):
    h = np.pi / 2
    out = [np.zeros(6), np.array([1.0, 2.0, 3.0, 0.0, 0.0, 0.0]),
           np.array([0.0, 0.0, 0.0, 0.0, 0.0, h]), np.array([0.0, 0.0, 1.0, 0.0, 0.0, h]),
           np.array([0.0, 0.5, 0.0, np.pi, 0.0, 0.0]),  # a half turn about x through a point
           np.array([0.3, 0.0, 0.2, 0.0, 0.0, np.pi]), np.array([0.0, 0.0, 0.0, 1.0, 0.0, 0.0])]
    for v in rng.normal(size=(4, 3)):  # pure translations
        out.append(np.concatenate([v, np.zeros(3)]))
    for theta in (1e-12, 1e-9, 1e-7, 1e-5, 1e-5, 1e-4, 1e-4, 3e-4, 1e-3, 1e-2):  # tiny turns
        v = rng.normal(size=3)
        out.append(np.concatenate([v / np.linalg.norm(v) * rng.uniform(1.0, 3.0),
                                   theta * random_unit_vectors(rng, 1)[0]]))
    for k, theta in enumerate((np.pi, np.pi, np.pi - 1e-6, 2 * np.pi, 3 * np.pi / 2, 4.5, 7.0,
                               10.0, 12.6, 20.0)):  # half turns and more than a turn
        w = random_unit_vectors(rng, 1)[0]
        p = rng.uniform(-1.0, 1.0, 3)
        v = -np.cross(w, p) + (k % 3) * 0.2 * w  # about an axis through p, with some pitch
        out.append(np.concatenate([v, w]) * theta)
    for _ in range(26):  # any twist
        out.append(np.concatenate([rng.normal(size=3), rng.normal(size=3) * rng.uniform(0.1,
                                                                                         1.5)]))
    return [(xi,) for xi in out]


# -- forward kinematics by the product of exponentials --------------------------------------
def exp_products(S, q, *, reverse=False, read=lambda s: s, angle=lambda t: t) -> np.ndarray:
    """e^{[S_1]q_1} ⋯ e^{[S_n]q_n} (``reverse``: in the opposite order). ``read`` and
    ``angle`` make the mistake models: how a twist and a joint value were read.

    >>> S, M, _ = robot_chain("planar_2r")
    >>> bool(np.allclose(exp_products(S, [0.3, 0.5]) @ M, kl.poe_fk(M, S, [0.3, 0.5])))
    True
    """
    S, q = np.asarray(S, dtype=float), np.asarray(q, dtype=float)
    factors = [kl.exp_se3(read(S[:, i]) * angle(q[i])) for i in range(S.shape[1])]
    T = np.eye(4)
    for E in factors[::-1] if reverse else factors:
        T = T @ E
    return T


FK_MISTAKES = [
    Mistake("order", "the exponentials are multiplied in the reverse order: the joint nearest "
                     "the base stands leftmost, T = e^[S1]q1 e^[S2]q2 ⋯ e^[Sn]qn M",
            lambda M, S, q: exp_products(S, q, reverse=True) @ M),
    Mistake("body", "M stands on the left: M e^[S1]q1 ⋯ is the body form, which needs the "
                    "body screw axes B_i = Ad(M⁻¹) S_i; with the space axes S_i the home pose "
                    "M goes on the right, T = e^[S1]q1 ⋯ e^[Sn]qn M",
            lambda M, S, q: M @ exp_products(S, q)),
    Mistake("home", "the home pose M is missing: T = e^[S1]q1 ⋯ e^[Sn]qn M (the product of "
                    "the exponentials alone is the motion of the end effector from home, not "
                    "its pose)", lambda M, S, q: exp_products(S, q)),
    ROWS.of(lambda M, S, q: exp_products(S, q, read=lambda s: np.roll(s, 3)) @ M,
            "you read the screw axes as [ω; v] (Modern Robotics' order): the columns of S are "
            "[v; ω], linear part first"),
    DEGREES.of(lambda M, S, q: exp_products(S, q, angle=np.deg2rad) @ M),
]


def _fk_cases(rng):
    out = chains(rng, per_robot=5, random_n=range(1, 8))
    M, S = robot_chain("planar_2r")[1], robot_chain("planar_2r")[0]
    out.append((M, S, np.array([np.pi / 2, -np.pi / 2])))
    return out


# -- the space Jacobian ---------------------------------------------------------------------
def _mr_adjoint(T) -> np.ndarray:
    """Modern Robotics' adjoint [[R, 0], [[p]R, R]], right for [ω; v] twists only."""
    R, p = T[:3, :3], T[:3, 3]
    A = np.zeros((6, 6))
    A[:3, :3] = A[3:, 3:] = R
    A[3:, :3] = kl.skew(p) @ R
    return A


def _swapped_skew_adjoint(T) -> np.ndarray:
    """[[R, R[p]], [0, R]]: the product [p]R written the other way round."""
    A = kl.adjoint(T)
    A[:3, 3:] = T[:3, :3] @ kl.skew(T[:3, 3])
    return A


def space_jacobian_model(S, q, *, carry=kl.adjoint, reverse=False, inverse=False):
    """Column i = carry(T) S_i with T = e^{[S_1]q_1} ⋯ e^{[S_{i−1}]q_{i−1}} (``reverse``:
    that product in the opposite order; ``inverse``: T⁻¹)."""
    S, q = np.asarray(S, dtype=float), np.asarray(q, dtype=float)
    J = np.empty_like(S)
    for i in range(S.shape[1]):
        T = exp_products(S[:, :i], q[:i], reverse=reverse)
        J[:, i] = carry(kl.transform_inverse(T) if inverse else T) @ S[:, i]
    return J


SJ_MISTAKES = [
    Mistake("untransformed", "you returned the screw axes themselves: S_i is joint i's axis at "
                             "home; at q the joints before it have moved it, so column i is "
                             "Ad(e^[S1]q1 ⋯ e^[S(i−1)]q(i−1)) S_i (only column 1 is S_1)",
            lambda S, q: np.array(S, dtype=float)),
    Mistake("order", "the joints before joint i are multiplied in the reverse order: column i "
                     "is Ad(T) S_i with T = e^[S1]q1 e^[S2]q2 ⋯ e^[S(i−1)]q(i−1), the joint "
                     "nearest the base leftmost",
            lambda S, q: space_jacobian_model(S, q, reverse=True)),
    Mistake("inverse", "you carried S_i with Ad(T⁻¹) instead of Ad(T): the product T = "
                       "e^[S1]q1 ⋯ e^[S(i−1)]q(i−1) moves the axis from its home place to where "
                       "it is at q, [J_i] = T [S_i] T⁻¹",
            lambda S, q: space_jacobian_model(S, q, inverse=True)),
    Mistake("body", "this is the body Jacobian's recursion (the joints after joint i, carried "
                    "back with Ad⁻¹): the space Jacobian carries S_i forward through the joints "
                    "before it, J_i = Ad(e^[S1]q1 ⋯ e^[S(i−1)]q(i−1)) S_i", kl.body_jacobian),
    Mistake("mr adjoint", "you used Modern Robotics' adjoint [[R, 0], [[p]R, R]], which is for "
                          "twists [ω; v]; for the course's [v; ω] it is Ad_T = [[R, [p]R], "
                          "[0, R]]",
            lambda S, q: space_jacobian_model(S, q, carry=_mr_adjoint)),
    Mistake("adjoint", "the upper-right block of Ad_T is [p]R (the skew matrix of p times R), "
                       "not R[p]: Ad_T = [[R, [p]R], [0, R]]",
            lambda S, q: space_jacobian_model(S, q, carry=_swapped_skew_adjoint)),
    ROWS.of(lambda S, q: np.roll(kl.space_jacobian(S, q), 3, axis=0),
            "your rows are in the order [ω; v] (Modern Robotics'): the course's Jacobian has "
            "the linear part first, like the screw axes, rows [v; ω]"),
]


def _sj_cases(rng):
    return [(S, q) for _, S, q in chains(rng, per_robot=5, random_n=range(1, 8))]


def assignment() -> Assignment:
    checks = [
        Check("exp_twist", 6, "e^[ξ] of a twist ξ = [v; ω]", _exp_cases, judge=_judge_exp,
              on_error=_exp_error_hint),
        Check("poe_fk", 6, "T = e^[S1]q1 ⋯ e^[Sn]qn M", _fk_cases, kl.poe_fk, FK_MISTAKES),
        Check("space_jacobian", 8, "J_s, column i = Ad(e^[S1]q1 ⋯ e^[S(i−1)]q(i−1)) S_i",
              _sj_cases, kl.space_jacobian, SJ_MISTAKES),
        space_jacobian_3r_check(4),
        manipulability_check(4),
        lost_direction_check(6),
        ik_check(10),
    ]
    return Assignment("06_differential_kinematics", "Differential kinematics", checks)
