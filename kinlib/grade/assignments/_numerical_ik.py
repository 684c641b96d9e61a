"""The numerical-IK half of assignment 03 (the Jacobian and inverse kinematics): one
damped-least-squares step (:func:`dls`, its mistake models :data:`DLS_MISTAKES`, the judge
that also spots the Jacobian-transpose step, and the cases) and the 6-vector pose error
(:func:`pose_error_reference`, :data:`POSE_MISTAKES`, the judge of the angles near 0 and π,
and the cases); the Jacobian, the 2R arm's IK and ``assignment()`` are in
:mod:`.jacobian_ik`, which imports these.
"""

from __future__ import annotations

import numpy as np

import kinlib as kl

from .._checks import Check, Mistake, Verdict, close
from .common import random_rotations, random_unit_vectors

__all__ = ["DLS_MISTAKES", "POSE_MISTAKES", "_dls_cases", "_judge_dls", "_judge_pose", "_pose",
           "_pose_cases", "dls", "pose_error_reference"]


# -- one damped least-squares step ----------------------------------------------------------
def dls(J, e, damping) -> np.ndarray:
    J, e = np.asarray(J, dtype=float), np.asarray(e, dtype=float)
    return J.T @ np.linalg.solve(J @ J.T + damping**2 * np.eye(len(J)), e)


DLS_MISTAKES = [
    Mistake("lambda", "the damping enters squared: Δq = Jᵀ (J Jᵀ + λ² I)⁻¹ e; you added λ I "
                      "(the two agree only at λ = 0 and λ = 1)",
            lambda J, e, lam: dls(J, e, np.sqrt(lam))),
    Mistake("sign", "your step has the wrong sign: it must reduce the error e = target − "
                    "current, Δq = +Jᵀ (J Jᵀ + λ² I)⁻¹ e", lambda J, e, lam: -dls(J, e, lam)),
    Mistake("undamped", "the damping is missing: you returned the plain (pseudo-)inverse step "
                        "J⁺ e; damped least squares is Δq = Jᵀ (J Jᵀ + λ² I)⁻¹ e",
            lambda J, e, lam: np.linalg.pinv(np.asarray(J)) @ e),
    Mistake("inverse", "(J Jᵀ + λ² I) must be inverted (solve the system), not multiplied: "
                       "Δq = Jᵀ (J Jᵀ + λ² I)⁻¹ e",
            lambda J, e, lam: J.T @ ((J @ J.T + lam**2 * np.eye(len(J))) @ e)),
]
_DLS_DEFAULT = Check("dls_step", 0, "", lambda rng: [], dls, DLS_MISTAKES)


def _parallel(a, b) -> bool:
    na, nb = float(np.linalg.norm(a)), float(np.linalg.norm(b))
    return na > 0 and nb > 0 and abs(float(a @ b)) >= (1 - 1e-9) * na * nb


def _judge_dls(args, got):
    v = _DLS_DEFAULT.verdict(args, got)
    if v.ok or v.key != "wrong":
        return v
    J, e, _ = args
    grad = np.asarray(J).T @ e
    a = np.asarray(got, dtype=float)
    if _parallel(a, grad) and not _parallel(np.asarray(v.expected), grad):
        return Verdict(False, "transpose", "this is the Jacobian-transpose step α Jᵀ e (the "
                                           "gradient direction): damped least squares solves "
                                           "for the step, Δq = Jᵀ (J Jᵀ + λ² I)⁻¹ e", v.expected)
    return v


def _conditioned(rng, m, n, max_cond=1e3):
    while True:
        J = rng.normal(size=(m, n)) * rng.uniform(0.2, 2.0)
        if np.linalg.cond(J) < max_cond:
            return J


def _dls_cases(rng):
    from kinlib.robots import puma560

    lams = (0.01, 0.1, 1.0, 2.0)
    out = [(np.eye(2), np.array([1.0, 0.5]), 0.0), (np.eye(2), np.array([1.0, 0.5]), 1.0),
           (np.array([[1.0, 2.0, 0.0]]), np.array([0.3]), 0.5)]
    for i in range(12):  # square and full rank: λ = 0 too
        m = (6, 2, 3)[i % 3]
        out.append((_conditioned(rng, m, m), rng.normal(size=m), (0.0, *lams)[i % 5]))
    for i in range(12):  # 6×7, redundant
        out.append((_conditioned(rng, 6, 7), rng.normal(size=6), lams[i % 4]))
    for i in range(12):  # 3×2, more rows than joints
        out.append((rng.normal(size=(3, 2)), rng.normal(size=3), lams[i % 4]))
    for i in range(4):  # 3×4 and 2×3, redundant
        m = 3 - i % 2
        out.append((_conditioned(rng, m, m + 1), rng.normal(size=m), lams[i]))
    for i in range(8):  # 2×2 near singular, damped
        U, _ = np.linalg.qr(rng.normal(size=(2, 2)))
        V, _ = np.linalg.qr(rng.normal(size=(2, 2)))
        J = U @ np.diag([rng.uniform(0.5, 2.0), 10.0 ** rng.uniform(-8, -4)]) @ V.T
        out.append((J, rng.normal(size=2), lams[i % 4]))
    puma = puma560()
    for i in range(10):  # a real arm's Jacobian (6×6), and the planar 2R arm's (6×2)
        J = puma.jacobian(rng.uniform(*puma.limits.T))
        lam = (0.0, *lams)[i % 5]
        if lam == 0.0 and np.linalg.cond(J) > 1e3:  # λ = 0 only where J⁻¹ is well defined
            lam = 0.1
        out.append((J, rng.normal(size=6) * 0.1, lam))
        t1, t2 = rng.uniform(-np.pi, np.pi, 2)
        J2 = np.zeros((6, 2))
        J2[[0, 1, 5]] = kl.planar_2r_jacobian(t1, t2, 1.0, 0.7)
        out.append((J2, rng.normal(size=6) * 0.1, lams[i % 4]))
    return [(J, e, float(lam)) for J, e, lam in out]


# -- the pose error -------------------------------------------------------------------------
def pose_error_reference(T, T_target) -> np.ndarray:
    T, T_target = np.asarray(T, dtype=float), np.asarray(T_target, dtype=float)
    omega = kl.log_so3(T_target[:3, :3] @ T[:3, :3].T)
    return np.concatenate([T_target[:3, 3] - T[:3, 3], omega])


def _accept_pose(T, T_target):
    e = pose_error_reference(T, T_target)
    if np.pi - np.linalg.norm(e[3:]) < 1e-6:  # at θ = π, k and −k are the same rotation
        return [np.concatenate([e[:3], -e[3:]])]
    return []


def _skew_part(R):
    return 0.5 * np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]])


def _err(T, Tt, dp=None, omega=None):
    e = pose_error_reference(T, Tt)
    return np.concatenate([e[:3] if dp is None else dp, e[3:] if omega is None else omega])


POSE_MISTAKES = [
    Mistake("sign", "the position error has the wrong sign: e_p = p_target − p (from where "
                    "the end effector is to where it should be)",
            lambda T, Tt: _err(T, Tt, dp=T[:3, 3] - Tt[:3, 3])),
    Mistake("sign", "the whole error is negated: e = [p_target − p; ω] with "
                    "ω = log(R_target Rᵀ), the motion that takes the current pose to the target",
            lambda T, Tt: -pose_error_reference(T, Tt)),
    Mistake("rotation sign", "the rotation error turns the wrong way: it is the rotation from "
                             "the current to the target orientation, R_err = R_target Rᵀ, "
                             "not R Rᵀ_target", lambda T, Tt: _err(T, Tt, omega=-_err(T, Tt)[3:])),
    Mistake("frame", "your rotation error is expressed in the end-effector frame, "
                     "log(Rᵀ R_target): the Jacobian's ω is in the base frame, so use "
                     "log(R_target Rᵀ) = R log(Rᵀ R_target)",
            lambda T, Tt: _err(T, Tt, omega=kl.log_so3(T[:3, :3].T @ Tt[:3, :3]))),
    Mistake("order", "your error is in the order [ω; v]: stack it like the Jacobian's rows, "
                     "[p_target − p; ω]", lambda T, Tt: np.roll(pose_error_reference(T, Tt), 3)),
    Mistake("sin", "you returned sin θ·k (the skew part of R_err) instead of θ·k: take the "
                   "angle θ = atan2(|w|, (tr R_err − 1)/2) or arccos((tr R_err − 1)/2) and "
                   "scale the unit axis by it",
            lambda T, Tt: _err(T, Tt, omega=_skew_part(Tt[:3, :3] @ T[:3, :3].T))),
]


_POSE_DEFAULT = Check("pose_error", 0, "", lambda rng: [], pose_error_reference, POSE_MISTAKES,
                      accept=_accept_pose)


def _judge_pose(args, got):
    v = _POSE_DEFAULT.verdict(args, got)
    if v.ok or v.key not in ("wrong", "nan"):
        return v
    angle = float(np.linalg.norm(v.expected[3:]))
    right_p = got is not None and v.key == "wrong" and close(np.asarray(got, dtype=float)[:3],
                                                             v.expected[:3], 1e-6)
    if v.key == "nan" and angle < 1e-6:
        return Verdict(False, "zero angle", "NaN when the orientation is already (almost) "
                                            "right, θ ≈ 0: then ω = 0 (or the skew part of "
                                            "R_err), never divide by sin θ = 0", v.expected)
    if angle > np.pi - 1e-3 and (v.key == "nan" or right_p):
        return Verdict(False, "near pi", f"wrong at θ = {angle:.6g}, near π, where sin θ ≈ 0 "
                                         "and the skew part of R_err vanishes: take k from the "
                                         "symmetric part, ½(R_err + R_errᵀ) − cos θ I = "
                                         "(1 − cos θ) k kᵀ, with the sign of the skew part",
                       v.expected)
    return v


def _pose(R, p) -> np.ndarray:
    T = np.eye(4)
    T[:3, :3], T[:3, 3] = R, p
    return T


def _pose_cases(rng):
    Rs = random_rotations(rng, 52)
    out = [(np.eye(4), np.eye(4)), (np.eye(4), _pose(np.eye(3), [0.1, -0.2, 0.3])),
           (np.eye(4), _pose(kl.rotz(0.3), [0.0, 0.0, 0.0])),
           (_pose(kl.rotx(1.0), [1.0, 2.0, 3.0]), _pose(kl.rotx(1.0), [1.0, 2.0, 3.0]))]
    for i in range(26):  # two random poses
        out.append((_pose(Rs[2 * i], rng.uniform(-1, 1, 3)),
                    _pose(Rs[2 * i + 1], rng.uniform(-1, 1, 3))))
    for k, angle in enumerate([1e-9, 1e-7, 1e-4, 0.01, 0.5, 1.5, 2.5, 3.0, np.pi - 1e-4,
                               np.pi - 1e-7, 2.0, 1.0]):  # a given error angle about a random axis
        R = random_rotations(rng, 1)[0]
        dR = kl.matrix_from_axis_angle(random_unit_vectors(rng, 1)[0], angle)
        p = rng.uniform(-1, 1, 3)
        out.append((_pose(R, p), _pose(dR @ R, p + (k % 2) * rng.uniform(-0.1, 0.1, 3))))
    for k in random_unit_vectors(rng, 4):  # θ = π exactly: k and −k both right
        R = random_rotations(rng, 1)[0]
        out.append((_pose(R, rng.uniform(-1, 1, 3)),
                    _pose(kl.matrix_from_axis_angle(k, np.pi) @ R, rng.uniform(-1, 1, 3))))
    out.append((np.eye(4), _pose(kl.rotx(np.pi), [0.0, 0.0, 0.0])))
    for _ in range(28):  # an arm's pose and a target near it, as in an IK loop
        R = random_rotations(rng, 1)[0]
        dR = kl.exp_so3(rng.normal(size=3) * 0.2)
        p = rng.uniform(-1, 1, 3)
        out.append((_pose(R, p), _pose(dR @ R, p + rng.normal(size=3) * 0.05)))
    return out
