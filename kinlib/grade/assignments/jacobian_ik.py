"""Assignment 03 · the Jacobian and inverse kinematics: the geometric Jacobian from the
joint axes and origins (seed 004), the determinant of the planar 2R arm's Jacobian derived
with sympy, the closed-form IK of the planar 2R arm (seed 001), one damped-least-squares
step and the 6-vector pose error that drive numerical IK.

The references: the Jacobian's column formula (which is :meth:`kinlib.Robot.jacobian` for
z-axes and origins read off :meth:`kinlib.Robot.link_poses`, as the tests show),
:func:`kinlib.planar_2r_fk` / :func:`kinlib.planar_2r_ik` for the 2R arm (any elbow is right:
the judge runs the forward kinematics of the answer), numpy's solve for the DLS step and
:func:`kinlib.log_so3` for the rotation error.
"""

from __future__ import annotations

import numpy as np

import kinlib as kl

from .._checks import RIGHT, Assignment, Check, Mistake, Verdict, as_numeric, close, fmt
from .._symbolic import symbolic_check
from ._numerical_ik import _dls_cases, _judge_dls, _judge_pose, _pose_cases
from ._numerical_ik import _pose as _pose
from ._numerical_ik import dls as dls
from ._numerical_ik import pose_error_reference as pose_error_reference
from .common import DEGREES, jacobian_2r, random_unit_vectors, symbolic_2r_cases

REVOLUTE, PRISMATIC = "revolute", "prismatic"


# -- the geometric Jacobian -----------------------------------------------------------------
def jacobian_columns(z_axes, origins, joint_types, *, linear=None, prismatic=None,
                     shift: int = 0) -> np.ndarray:
    """J (6×n), rows [v; ω]: revolute column [z_{i−1} × (o_n − o_{i−1}); z_{i−1}], prismatic
    [z_{i−1}; 0]. The keywords make the mistake models: ``linear(z, o_n, o_{i−1})`` the
    revolute linear part, ``prismatic(z, o_n, o_{i−1})`` the prismatic column, ``shift=1``
    reads o_i instead of o_{i−1}."""
    z = np.asarray(z_axes, dtype=float).reshape(-1, 3)
    o = np.asarray(origins, dtype=float).reshape(-1, 3)
    n = len(joint_types)
    J = np.zeros((6, n))
    for i, kind in enumerate(joint_types):
        on, oi = o[n], o[i + shift]
        if kind == REVOLUTE:
            J[:3, i] = np.cross(z[i], on - oi) if linear is None else linear(z[i], on, oi)
            J[3:, i] = z[i]
        elif prismatic is not None:
            J[:, i] = prismatic(z[i], on, oi)
        else:
            J[:3, i] = z[i]
    return J


def _revolute_column(z, on, oi):
    return np.concatenate([np.cross(z, on - oi), z])


TRANSPOSED_J = "you returned Jᵀ: J has 6 rows [v; ω] and one column per joint"
JACOBIAN_MISTAKES = [  # the first model that matches names the mistake
    Mistake("prismatic", "a prismatic joint's column is [z_{i−1}; 0] (linear part first): "
                         "you returned [0; z_{i−1}]",
            lambda z, o, t: jacobian_columns(z, o, t, prismatic=lambda a, on, oi: np.concatenate(
                [np.zeros(3), a]))),
    Mistake("order", "your rows are in the order [ω; v]: the course's Jacobian has the linear "
                     "velocity first, rows [v; ω], so column i of a revolute joint is "
                     "[z_{i−1} × (o_n − o_{i−1}); z_{i−1}]",
            lambda z, o, t: np.roll(jacobian_columns(z, o, t), 3, axis=0)),
    Mistake("cross", "the cross product is reversed, (o_n − o_{i−1}) × z_{i−1}: the end "
                     "effector's velocity is ω × r = z_{i−1} × (o_n − o_{i−1}), the axis "
                     "first (a × b = −b × a)",
            lambda z, o, t: jacobian_columns(z, o, t, linear=lambda a, on, oi: np.cross(
                on - oi, a))),
    Mistake("origins", "you used o_i instead of o_{i−1}: joint i turns about the axis z_{i−1} "
                       "through the origin o_{i−1} of frame i−1, which is origins[i − 1] for "
                       "joint i (origins[0] = o_0 for the first joint)",
            lambda z, o, t: jacobian_columns(z, o, t, shift=1)),
    Mistake("prismatic", "a prismatic joint's column was built like a revolute one: sliding "
                         "along z_{i−1} moves the end effector with velocity z_{i−1} and does "
                         "not turn it, so the column is [z_{i−1}; 0]",
            lambda z, o, t: jacobian_columns(z, o, t, prismatic=_revolute_column)),
    Mistake("subtract", "the lever arm is missing o_{i−1}: you computed z_{i−1} × o_n; the "
                        "arm from the joint's axis to the end effector is o_n − o_{i−1}",
            lambda z, o, t: jacobian_columns(z, o, t, linear=lambda a, on, oi: np.cross(a, on))),
    Mistake("transposed", TRANSPOSED_J, lambda z, o, t: jacobian_columns(z, o, t).T),
]


_JACOBIAN_DEFAULT = Check("geometric_jacobian", 0, "", lambda rng: [], jacobian_columns,
                          JACOBIAN_MISTAKES)


def _judge_jacobian(args, got):
    v = _JACOBIAN_DEFAULT.verdict(args, got)
    if v.key == "shape" and v.expected.shape[0] != v.expected.shape[1]:
        a = np.asarray(got, dtype=float)  # "shape" means it is a numeric array
        if a.shape == v.expected.shape[::-1] and close(a.T, v.expected, 1e-6):
            return Verdict(False, "transposed", TRANSPOSED_J, v.expected)
    return v


def robot_frames(robot, q) -> tuple[np.ndarray, np.ndarray, list[str]]:
    """(z_axes, origins, joint_types) of a kinlib DH robot at q: z_{i−1} and o_{i−1} are
    the z axis and origin of DH frame i − 1, which is link ``link{i-1}``."""
    poses = robot.link_poses(q)
    n = robot.dof
    z = np.array([poses[f"link{i}"][:3, 2] for i in range(n)])
    o = np.array([poses[f"link{i}"][:3, 3] for i in range(n + 1)])
    types = [PRISMATIC if r.joint == PRISMATIC else REVOLUTE for r in robot.dh_rows]
    return z, o, types


def prismatic_robots() -> list:
    """A Stanford arm (RRP + wrist, Spong's table) and a SCARA (RRPR), in metres."""
    h = np.pi / 2
    stanford = kl.Robot.from_dh(
        [kl.DHRow(a=0.0, alpha=-h, d=0.4), kl.DHRow(a=0.0, alpha=h, d=0.15),
         kl.DHRow(a=0.0, alpha=0.0, theta=0.0, joint=PRISMATIC, offset=0.3),
         kl.DHRow(a=0.0, alpha=-h), kl.DHRow(a=0.0, alpha=h), kl.DHRow(a=0.0, alpha=0.0, d=0.1)],
        name="stanford")
    scara = kl.Robot.from_dh(
        [kl.DHRow(a=0.45, alpha=0.0, d=0.3), kl.DHRow(a=0.35, alpha=np.pi),
         kl.DHRow(a=0.0, alpha=0.0, joint=PRISMATIC, offset=0.05),
         kl.DHRow(a=0.0, alpha=0.0, d=0.08)], name="scara")
    return [stanford, scara]


def _robot_q(rng, robot):
    return np.array([rng.uniform(-0.2, 0.4) if r.joint == PRISMATIC else rng.uniform(-np.pi,
                                                                                      np.pi)
                     for r in robot.dh_rows])


def _jacobian_cases(rng):
    from kinlib.robots import puma560, three_dof_arm

    out = [(np.array([[0.0, 0.0, 1.0]]), np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]]),
            [REVOLUTE]),
           (np.array([[0.0, 0.0, 1.0]]), np.array([[0.0, 0.0, 0.0], [0.3, 0.0, 0.5]]),
            [PRISMATIC])]
    for i in range(56):  # n = 1..7, eight each; mostly mixed types
        n = 1 + i % 7
        kinds = [PRISMATIC if rng.random() < 0.35 else REVOLUTE for _ in range(n)]
        if i % 8 == 6:
            kinds = [REVOLUTE] * n
        elif i % 8 == 7:
            kinds = [PRISMATIC] * n
        elif n >= 2 and PRISMATIC not in kinds:
            kinds[int(rng.integers(n))] = PRISMATIC
        out.append((random_unit_vectors(rng, n), rng.uniform(-1.0, 1.0, (n + 1, 3)), kinds))
    puma, arm = puma560(), three_dof_arm()
    robots = [puma] * 6 + [arm] * 4 + [r for r in prismatic_robots() for _ in range(4)]
    out.append(robot_frames(puma, np.array(puma.poses["zero"])))
    out += [robot_frames(r, _robot_q(rng, r)) for r in robots]
    return out


# -- det J of the 2R arm, derived with sympy --------------------------------------------------
def _det(*args, **kwargs):
    return jacobian_2r(*args, **kwargs).det()


def det_check() -> Check:
    """``det_jacobian_2r(theta1, theta2, l1, l2)``: det ∂(x, y)/∂(θ1, θ2), a sympy
    expression (the reference: kinlib's DH product of the arm, differentiated)."""
    from kinlib.symbolic import simplify_rotation

    def unit(length: int):  # the derivation with one link length left out (set to 1)
        def model(t1, t2, l1, l2):
            return _det(t1, t2, *((1, l2) if length == 1 else (l1, 1)))
        return model
    missing = ("a link length is missing from your answer: the tip is at "
               "x = l1 cos θ1 + l2 cos(θ1 + θ2), y = l1 sin θ1 + l2 sin(θ1 + θ2), both lengths "
               "in both")
    return symbolic_check(
        "det_jacobian_2r", 3, "det J of the planar 2R arm derived with sympy",
        symbolic_2r_cases, _det, names=("theta1", "theta2", "l1", "l2"),
        show=simplify_rotation,
        mistakes=[Mistake("sign", "right up to the sign: the columns of J are ∂p/∂θ1 then "
                                  "∂p/∂θ2, in the joints' order, and det [[a, b], [c, d]] = "
                                  "ad − bc", lambda *a: -_det(*a)),
                  Mistake("factor", missing, unit(1)), Mistake("factor", missing, unit(2)),
                  Mistake("factor", missing, lambda t1, t2, l1, l2: _det(t1, t2, 1, 1)),
                  Mistake("absolute", "θ2 is the angle of link 2 relative to link 1 (DH): "
                                      "link 2 points at θ1 + θ2, so the tip is at "
                                      "l1 cos θ1 + l2 cos(θ1 + θ2), not l1 cos θ1 + l2 cos θ2",
                          lambda *a: _det(*a, absolute=True)),
                  Mistake("cos", "cos θ2 where sin θ2 belongs: link 2 is turned by a right "
                                 "angle in your forward kinematics; it points along "
                                 "(cos(θ1 + θ2), sin(θ1 + θ2))",
                          lambda *a: _det(*a, turned=True))])


# -- the 2R arm's inverse kinematics --------------------------------------------------------
REACH_TOL = 1e-9  # relative: a target this close outside the workspace counts as reachable


def reachable(x, y, l1, l2) -> bool:
    r, s = float(np.hypot(x, y)), l1 + l2
    return abs(l1 - l2) - REACH_TOL * s <= r <= s + REACH_TOL * s


def _tip(t1, t2, l1, l2) -> np.ndarray:
    return kl.planar_2r_fk(t1, t2, l1, l2)[:2, 3]


def _same_angles(a, b) -> bool:
    d = (np.asarray(a, dtype=float) - np.asarray(b, dtype=float) + np.pi) % (2 * np.pi) - np.pi
    return bool(np.all(np.abs(d) <= 1e-6))


def _judge_ik(args, got):
    x, y, l1, l2 = args
    target = np.array([x, y])
    r = float(np.hypot(x, y))
    workspace = f"|l1 − l2| = {abs(l1 - l2):.6g} ≤ r ≤ l1 + l2 = {l1 + l2:.6g}"
    if not reachable(x, y, l1, l2):
        if got is None:
            return RIGHT
        a, bad = as_numeric(got, (2,), "None")
        if a is None and bad.key == "nan":
            return Verdict(False, "nan unreachable", f"returned NaN for an unreachable target "
                                                     f"(r = {r:.6g}, outside {workspace}): "
                                                     "return None when |c2| > 1", None)
        return Verdict(False, "unreachable", f"returned {fmt(got, 80)} for a target the arm "
                                             f"cannot reach (r = {r:.6g}, outside {workspace}): "
                                             "return None when |c2| > 1 (beyond a tiny "
                                             "tolerance)", None)
    up = kl.planar_2r_ik(x, y, l1, l2, elbow="up")
    expected = np.array([float(up.theta1), float(up.theta2)])
    edge = min(abs(r - (l1 + l2)), abs(r - abs(l1 - l2))) <= 1e-9 * (l1 + l2)
    rounding = (" This target is on the workspace boundary: rounding puts c2 a hair outside "
                "[−1, 1], so allow a tiny tolerance and clip c2 to [−1, 1] before the "
                "square root." if edge else "")
    if got is None:
        return Verdict(False, "missed", f"returned None, but the target is reachable "
                                        f"(r = {r:.6g}, {workspace}).{rounding}", expected)
    a, bad = as_numeric(got, (2,), "a pair (theta1, theta2)")
    if a is None:
        if bad.key == "nan" and r < 1e-9:
            return Verdict(False, "base", "returned NaN for the target at the base (x = y = 0, "
                                          "reachable with θ2 = π when l1 = l2, and then any θ1 "
                                          "works): do not divide by r = √(x² + y²); "
                                          "atan2(0, 0) = 0 is fine", expected)
        if bad.key == "nan" and edge:
            return Verdict(False, "boundary", f"returned NaN.{rounding}", expected)
        return Verdict(bad.ok, bad.key, bad.message, expected)
    if close(_tip(a[0], a[1], l1, l2), target, 1e-6):
        return RIGHT
    if close(_tip(*np.deg2rad(a), l1, l2), target, 1e-6):
        return Verdict(False, "degrees", DEGREES.message, expected)
    down = kl.planar_2r_ik(x, y, l1, l2, elbow="down")
    if any(_same_angles(a, m) for m in ((up.theta1, down.theta2), (down.theta1, up.theta2))):
        return Verdict(False, "branches", "θ1 belongs to the other elbow: θ1 = atan2(y, x) − "
                                          "atan2(l2 s2, l1 + l2 c2) must use the same s2 (the "
                                          "same sign of the square root) as θ2 = atan2(s2, c2)",
                       expected)
    if close(_tip(a[1], a[0], l1, l2), target, 1e-6):
        return Verdict(False, "order", "your angles come in the wrong order: return "
                                       "(theta1, theta2)", expected)
    for mirror in ((x, -y), (-x, y), (-x, -y)):
        if close(_tip(a[0], a[1], l1, l2), np.array(mirror), 1e-6):
            return Verdict(False, "quadrant", "your answer reaches the mirror image "
                                              f"{fmt(tuple(map(float, mirror)))} of the target: "
                                              "arccos, arcsin or arctan(y/x) lose the quadrant; "
                                              "use atan2 for both angles, θ2 = atan2(s2, c2), "
                                              "θ1 = atan2(y, x) − atan2(l2 s2, l1 + l2 c2)",
                           expected)
    miss = float(np.linalg.norm(_tip(a[0], a[1], l1, l2) - target))
    return Verdict(False, "wrong", f"the forward kinematics of your angles misses the target "
                                   f"by {miss:.3g}", expected)


def _polar(r, phi):
    return float(r * np.cos(phi)), float(r * np.sin(phi))


def _ik_cases(rng):
    out = [(1.0, 1.0, 1.0, 1.0), (2.0, 0.0, 1.0, 1.0), (0.0, 0.0, 1.0, 1.0),
           (3.0, 0.0, 1.0, 1.0), (0.2, 0.0, 1.0, 0.5), (0.0, -1.5, 1.0, 0.5)]
    for l1, l2 in ((1.0, 0.8), (0.6, 1.1)):  # the four quadrants and the four half-axes
        for phi in np.arange(8) * np.pi / 4 + np.pi / 8 * (l1 < l2):
            out.append((*_polar(0.9 * (l1 + l2) - 0.1, phi), l1, l2))
        out += [(1.3, 0.0, l1, l2), (-1.3, 0.0, l1, l2), (0.0, 1.3, l1, l2), (0.0, -1.3, l1, l2)]
    for _ in range(30):  # reachable
        l1, l2 = rng.uniform(0.3, 1.5, 2)
        r = rng.uniform(abs(l1 - l2) + 0.02, l1 + l2 - 0.02)
        out.append((*_polar(r, rng.uniform(-np.pi, np.pi)), float(l1), float(l2)))
    for k in range(12):  # on the boundary, up to 1e-12 either side (l1 = l2: at the base)
        l1, l2 = (float(v) for v in rng.uniform(0.3, 1.5, 2))
        delta = (0.0, 1e-12, -1e-12)[k % 3]
        if k < 6:
            r = l1 + l2 + delta
        elif k < 10:
            l2 = l2 if abs(l1 - l2) > 0.05 else l1 + 0.2
            r = abs(l1 - l2) + delta
        else:
            l2, r = l1, abs(delta)
        out.append((*_polar(r, rng.uniform(-np.pi, np.pi)), l1, l2))
    for k in range(12):  # unreachable, |c2| ≥ 1 + 1e-5: too far, or too close to the base
        l1, l2 = (float(v) for v in rng.uniform(0.3, 1.5, 2))
        if k < 6:  # c2 = 1 + δ
            r = np.sqrt(l1**2 + l2**2 + 2 * l1 * l2 * (1 + (1e-5, 1e-4, 1e-3, 0.05, 0.5, 2)[k]))
        else:
            l2 = l2 if abs(l1 - l2) > 0.2 else l1 + 0.3
            if k < 9:  # c2 = −1 − δ
                r = np.sqrt((l1 - l2) ** 2 - 2 * l1 * l2 * (1e-5, 1e-4, 1e-3)[k - 6])
            else:
                r = abs(l1 - l2) * (0.7, 0.3, 0.0)[k - 9]
        out.append((*_polar(r, rng.uniform(-np.pi, np.pi)), l1, l2))
    return out


def _ik_error_hint(args, error: str):
    x, y, l1, l2 = (float(a) for a in args)
    r = np.hypot(x, y)
    if not abs(l1 - l2) - 1e-9 <= r <= l1 + l2 + 1e-9:
        return ("This target is out of reach: return None for it instead of raising "
                "(check |c2| ≤ 1 before taking the square root)")
    return None


def assignment() -> Assignment:
    checks = [
        Check("geometric_jacobian", 7, "geometric Jacobian [v; ω] from the axes z_{i−1} and "
              "origins o_{i−1}", _jacobian_cases, judge=_judge_jacobian),
        det_check(),
        Check("ik_2r", 10, "closed-form IK of the planar 2R arm (None when unreachable)",
              _ik_cases, judge=_judge_ik, on_error=_ik_error_hint),
        Check("dls_step", 6, "damped least-squares step Δq = Jᵀ (J Jᵀ + λ² I)⁻¹ e",
              _dls_cases, judge=_judge_dls),
        Check("pose_error", 6, "pose error [p_target − p; log(R_target Rᵀ)]", _pose_cases,
              judge=_judge_pose),
    ]
    return Assignment("03_jacobian_and_ik", "Jacobian and inverse kinematics", checks)
