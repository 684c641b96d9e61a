"""Notebook 07 · screw motion and dual quaternions: the slide along the axis, the dual
quaternion of a pose, the dual angle, ScLERP."""

import numpy as np

from .._symbolic import expression_judge
from .._verdict import Mistake, Verdict
from ..mistakes import HALF_ANGLE, ORDER, SIGN, XYZW
from ._make import choice, function, judged, value

# --- 07.1 · the slide d of a screw, without kinlib's screw function -----------------------


def _T_try():
    from ... import matrix_from_axis_angle, transform

    return transform(matrix_from_axis_angle([1.0, 2.0, 2.0], 1.2), [0.4, -0.2, 0.7])


def _slide():
    from ... import dual_quat_from_transform, screw_from_dual_quat

    return screw_from_dual_quat(dual_quat_from_transform(_T_try()))[3]


def _skew_part(R):
    """(r32 − r23, r13 − r31, r21 − r12) = 2 sin θ l."""
    return np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]])


# --- 07.2 · a rotation about a line off the origin: is there a slide? ---------------------


def _slide_of_a_rotation_off_the_origin() -> str:
    """The right option, from kinlib: the slide of a pure rotation about a line through c."""
    from ... import (
        dual_quat_from_transform,
        matrix_from_axis_angle,
        screw_from_dual_quat,
        transform,
    )

    R, c = matrix_from_axis_angle([0.3, -0.4, 0.866], 1.9), np.array([1.0, 0.5, -0.2])
    d = screw_from_dual_quat(dual_quat_from_transform(transform(R, c - R @ c)))[3]
    return "a" if abs(d) < 1e-9 else "b"


# --- 07.3 · a pure translation; 07.4 · any pose ----------------------------------------


def _mul(p, q):
    from ... import quat_multiply

    return quat_multiply(p, q)


def _pure(t):
    return np.r_[0.0, np.asarray(t, dtype=float)]


def _dq_of(q_rot, t):
    from ... import dual_quat_from_transform, matrix_from_quat, transform

    return dual_quat_from_transform(transform(matrix_from_quat(q_rot), t))


T_PURE = np.array([1.0, 2.0, 3.0])


def _q(axis, angle):
    u = np.asarray(axis, dtype=float)
    return np.r_[np.cos(angle / 2), np.sin(angle / 2) * u / np.linalg.norm(u)]


CASES = [(_q([0, 0, 1], 0.0), np.array([1.0, 2.0, 3.0])),
         (_q([0, 0, 1], np.pi / 2), np.array([1.0, 0.0, 0.0])),
         (_q([1, 2, 2], 1.2), np.array([0.4, -0.2, 0.7])),
         (_q([-0.3, 0.5, 0.8], 5.0), np.array([-1.0, 0.5, 2.0])),     # w < 0
         (_q([1, 0, 0], np.pi), np.array([0.0, 1.5, -0.5])),
         (_q([2, -1, 1], 2.6), np.array([0.3, 0.3, -1.2]))]


# --- 07.5 · the cosine of the dual half angle --------------------------------------------


def _symbols():
    import sympy as sp

    return sp.symbols("theta d epsilon", real=True)


def _cos_dual(half=True, inner_half=True, sign=-1):
    def model():
        import sympy as sp

        th, d, eps = _symbols()
        a = th / 2 if half else th
        b = d / 2 if half and inner_half else d
        return sp.cos(a) + sign * eps * b * sp.sin(a)
    return model


def _first_order(expr):
    """``expr`` cut after the first power of ε (the notebook's ``dual``)."""
    import sympy as sp

    eps = _symbols()[2]
    e = sp.expand(sp.series(expr, eps, 0, 2).removeO())
    return e.coeff(eps, 0) + eps * e.coeff(eps, 1)


_DUAL_ANGLE_MISTAKES = (
    Mistake("chain rule", "the dual part is d/dθ of cos(θ/2) times d: the inner derivative of "
                          "θ/2 brings a factor ½, so it is −(d/2) sin(θ/2)",
            _cos_dual(inner_half=False)),
    Mistake("derivative sign", "the derivative of cos is −sin: cos(a + εb) = cos a − ε b sin a",
            _cos_dual(sign=1)),
    HALF_ANGLE.of(_cos_dual(half=False), "this is cos(θ + εd), the whole dual angle: the "
                                         "scalar part of the dual quaternion is cos of the "
                                         "half angle, (θ + εd)/2"),
)


def _dual_angle_judge():
    """Exact, with the named mistakes; and an answer that is right only once cut after ε
    (still cos((θ + εd)/2), or with ε² terms left) is told to expand."""
    right = expression_judge(_cos_dual(), what="a sympy expression in theta, d and epsilon",
                             swaps=(), mistakes=_DUAL_ANGLE_MISTAKES)

    def judge(args, got):
        verdict = right(args, got)
        if verdict.key != "wrong":
            return verdict
        try:
            expanded = _first_order(got)
        except Exception:  # not something sympy can expand in ε
            return verdict
        if right(args, expanded).ok:
            return Verdict(False, "not expanded", "this is cos((θ + εd)/2) itself, not yet "
                                                  "written to first order in ε: expand it "
                                                  "with the notebook's `dual` (ε² = 0 ends "
                                                  "the series after the ε term)")
        return verdict
    return judge


# --- 07.6 · the path of the body origin under ScLERP --------------------------------------


def _origin_path_under_sclerp() -> str:
    """The right option, from kinlib: the origin's ScLERP path is a helix about the axis."""
    from ... import (
        dual_quat_from_transform,
        dual_quat_sclerp,
        matrix_from_axis_angle,
        screw_from_dual_quat,
        transform,
        transform_from_dual_quat,
    )

    T1 = transform(matrix_from_axis_angle([0, 0, 1.0], np.deg2rad(150)), [1.0, 2.2, 1.0])
    dq0, dq1 = dual_quat_from_transform(np.eye(4)), dual_quat_from_transform(T1)
    ts = np.linspace(0.0, 1.0, 9)
    path = transform_from_dual_quat(dual_quat_sclerp(dq0, dq1, ts))[:, :3, 3]
    l, m, _, d = screw_from_dual_quat(dq1)
    c = np.cross(l, m)
    radius = np.linalg.norm(np.cross(path - c, l), axis=1)
    height = (path - c) @ l
    straight = np.allclose(np.cross(path[-1] - path[0], path - path[0]), 0.0)
    helix = (radius[0] > 1e-3 and np.allclose(radius, radius[0])
             and np.allclose(height - height[0], ts * d))
    return "b" if helix and not straight else ("a" if straight else "c")


EXERCISES = [
    value("07.1", "compute", "the slide d of a screw: l·t", _slide,
          Mistake("norm", "that is |t|, the whole length of the translation: the slide is "
                          "only its part along the axis, d = l·t; the rest, t⊥, moves the "
                          "axis off the origin", lambda: np.linalg.norm(_T_try()[:3, 3])),
          Mistake("z component", "that is t_z, the slide along z: this screw's axis is "
                                 "(1, 2, 2)/3, not z. Take l from the rotation",
                  lambda: _T_try()[2, 3]),
          Mistake("unit axis", "your axis is not a unit vector: (r32 − r23, r13 − r31, "
                               "r21 − r12) is 2 sin θ l; divide by its length",
                  lambda: _skew_part(_T_try()[:3, :3]) @ _T_try()[:3, 3]),
          SIGN.of(lambda: -_slide(), "your axis points the other way: with θ in [0, π] "
                                     "the axis is the direction of (r32 − r23, r13 − r31, "
                                     "r21 − r12) (kl.axis_angle_from_matrix gives it)"),
          what="a number",
          explain="d = l·t keeps only the part of the translation along the axis; the rest, "
                  "t⊥, is absorbed by moving the axis off the origin."),
    choice("07.2", "predict", "the slide of a rotation about a line off the origin",
           {"a": "d = 0", "b": "d = |t| ≠ 0: the origin moves, so there is a translation",
            "c": "d grows with the distance of the line from the origin"},
           _slide_of_a_rotation_off_the_origin(),
           {"b": ("norm", "the origin does move, t = c − R c ≠ 0, but d is only the part of t "
                          "along the axis, l·t, and l·(c − R c) = l·c − (Rᵀl)·c = 0 because "
                          "R l = l"),
            "c": ("distance", "moving the line changes t = c − R c, but only across the axis: "
                              "l·(c − R c) = l·c − (Rᵀl)·c = 0 for every point c, since "
                              "R l = l")}),
    value("07.3", "compute", "the dual quaternion of a pure translation",
          lambda: _dq_of(np.r_[1.0, 0, 0, 0], T_PURE),
          Mistake("half", "the ½ is missing: q_d = ½ (0, t) q_r (the translation is read "
                          "back as t = 2 q_d q̄_r)", lambda: np.r_[1.0, 0, 0, 0, _pure(T_PURE)]),
          XYZW.of(lambda: np.r_[1.0, 0, 0, 0, 0.5 * T_PURE, 0.0],
                  "you wrote the pure quaternion (0, t) as [t, 0], scalar last: kinlib's "
                  "quaternions are [w, x, y, z], so (0, t) = [0, t_x, t_y, t_z]"),
          XYZW.of(lambda: np.r_[0.0, 0, 0, 1, 0.5 * T_PURE, 0.0],
                  "both parts are [x, y, z, w], scalar last: kinlib's quaternions are "
                  "[w, x, y, z]; the identity rotation is [1, 0, 0, 0]"),
          Mistake("parts swapped", "the two halves are swapped: kinlib stores the real part "
                                   "(the rotation q_r) first, then the dual part q_d",
                  lambda: np.r_[0.0, 0.5 * T_PURE, 1.0, 0, 0, 0]),
          accept=lambda: [-_dq_of(np.r_[1.0, 0, 0, 0], T_PURE)],
          what="a dual quaternion (8 numbers)",
          explain="with q_r = 1 the dual part is ½ (0, t) = (0, 0.5, 1, 1.5): half the "
                  "translation, which t = 2 q_d q̄_r doubles back."),
    function("07.4", "the dual quaternion [q_r, ½ (0, t) q_r] of a pose", CASES, _dq_of,
             ORDER.of(lambda q, t: np.r_[q, 0.5 * _mul(q, _pure(t))],
                      "½ q_r (0, t) is the other order: that pose turns first and then "
                      "moves by R t. For the pose (R, t), q_d = ½ (0, t) q_r, with (0, t) on "
                      "the left"),
             Mistake("half", "the ½ is missing: q_d = ½ (0, t) q_r; without it the "
                             "translation comes back doubled",
                     lambda q, t: np.r_[q, _mul(_pure(t), q)]),
             Mistake("no q_r", "q_d is not ½ (0, t) alone: it is ½ (0, t) q_r, the "
                               "translation quaternion times the rotation",
                     lambda q, t: np.r_[q, 0.5 * _pure(t)]),
             XYZW.of(lambda q, t: np.r_[q, 0.5 * _mul(np.r_[t, 0.0], q)],
                     "you built the pure quaternion as [t, 0], scalar last: (0, t) is "
                     "[0, t_x, t_y, t_z] in kinlib's [w, x, y, z]"),
             accept=lambda q, t: [-_dq_of(q, t)], what="a dual quaternion (8 numbers)",
             explain="(0, t) stands on the left of q_r because the pose turns first and then "
                     "moves, p ↦ R p + t; q_r (0, t) would move by t in the turned frame, by R t."),
    judged("07.5", "derive", "cos of the dual half angle (θ + εd)/2", _dual_angle_judge(),
           diagnoses=("chain rule", "derivative sign", HALF_ANGLE.key, "not expanded"),
           explain="cos(θ/2) − ε (d/2) sin(θ/2): the real part is the scalar of q_r, the ε part "
                   "the scalar −(d/2) sin(θ/2) of q_d. The dual angle θ + εd carries the slide d "
                   "next to the angle θ, as a derivative: f(a + εb) = f(a) + ε b f'(a)."),
    choice("07.6", "predict", "the path of the body origin under ScLERP",
           {"a": "a straight line from its start to its end position",
            "b": "a helix about the relative screw axis: it circles the axis and rises "
                 "along it at a constant rate",
            "c": "a great-circle arc, like slerp"},
           _origin_path_under_sclerp(),
           {"a": ("straight", "a straight line is the shortcut's path for the origin (the "
                              "translation interpolated linearly). ScLERP turns the body about "
                              "the relative screw axis while sliding along it, and every point "
                              "off that axis, the origin too, circles it"),
            "c": ("sphere", "slerp's great circle lies on the sphere of unit quaternions, not "
                            "in the space the body moves in: the origin circles the screw axis "
                            "at a fixed distance while sliding along it")}),
]
