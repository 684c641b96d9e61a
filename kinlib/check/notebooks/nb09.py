"""Notebook 09 · Denavit–Hartenberg: the joint variable of a prismatic row, a row read back
from two frames, the 3-DOF arm's tip, one PUMA link transform, a modified-DH table."""

import numpy as np

from .._verdict import Mistake
from ..mistakes import DEGREES, MODIFIED_DH, ORDER, SIGN, SWAPPED
from ._make import choice, expression, function, value

# ---- 09.2: a row read back from frames i−1 and i -----------------------------------------

#: the rows (θ, d, a, α) the cases are built from: signs of every kind, a posed frame i−1
READ_BACK_ROWS = ((np.deg2rad(50), 0.6, 0.8, np.deg2rad(60)), (0.3, 0.0, 1.0, 0.0),
                  (-1.2, 0.4, 0.5, 1.1), (2.0, -0.3, 0.7, -0.8), (-0.5, 0.2, -0.6, -2.4),
                  (1.0, 0.0, 0.0, np.pi / 2), (-2.9, 1.1, 0.3, 2.8), (0.7, -0.9, -0.2, 0.4))


def _read_back_cases():
    from ... import dh_transform, matrix_from_euler, transform

    posed = transform(matrix_from_euler([0.4, -0.7, 1.9], "ZYX"), [0.3, -0.2, 0.5])
    cases = []
    for k, row in enumerate(READ_BACK_ROWS):
        T_prev = np.eye(4) if k % 2 == 0 else posed
        theta, d, a, alpha = row
        cases.append((T_prev, T_prev @ dh_transform(theta=theta, d=d, a=a, alpha=alpha)))
    return cases


def _read_back(T_prev, T):
    """θ, d, a, α of the standard DH row that takes frame i−1 (``T_prev``) to frame i."""
    o0, x0, z0 = T_prev[:3, 3], T_prev[:3, 0], T_prev[:3, 2]
    o1, x1, z1 = T[:3, 3], T[:3, 0], T[:3, 2]
    return np.array([np.arctan2(np.cross(x0, x1) @ z0, x0 @ x1), (o1 - o0) @ z0,
                     (o1 - o0) @ x1, np.arctan2(np.cross(z0, z1) @ x1, z0 @ z1)])


def _wrapped(T_prev, T):
    """The same row with θ or α (or both) a full turn further: also right."""
    r = _read_back(T_prev, T)
    turns = [(0, 1), (0, -1), (3, 1), (3, -1)]
    out = []
    for i, sgn in turns:
        w = r.copy()
        w[i] += sgn * 2 * np.pi
        out.append(w)
    both = r.copy()
    both[[0, 3]] = np.where(both[[0, 3]] < 0, both[[0, 3]] + 2 * np.pi, both[[0, 3]])
    return out + [both]


def _abs_angles(which):
    def model(T_prev, T):
        r = _read_back(T_prev, T)
        r[list(which)] = np.abs(r[list(which)])
        return r
    return model


def _permuted(order):
    return lambda T_prev, T: _read_back(T_prev, T)[list(order)]

# ---- 09.3: the 3-DOF arm's tip position -------------------------------------------------


def _tip(transform="dh_transform", alpha1_sign=1, reverse=False):
    """The tip position (3×1) of seed 000's 3-DOF arm, rows (θ1, d1, 0, ±90°),
    (θ2, 0, a2, 0), (θ3, 0, a3, 0), built with ``transform``, the product maybe reversed."""
    import sympy as sp

    from ... import dh_transform, mdh_transform

    f = {"dh_transform": dh_transform, "mdh_transform": mdh_transform}[transform]
    t1, t2, t3, d1, a2, a3 = sp.symbols("theta_1 theta_2 theta_3 d_1 a_2 a_3", real=True)
    A = [f(theta=t1, d=d1, a=0, alpha=alpha1_sign * sp.pi / 2),
         f(theta=t2, d=0, a=a2, alpha=0), f(theta=t3, d=0, a=a3, alpha=0)]
    if reverse:
        A = A[::-1]
    return (A[0] * A[1] * A[2])[:3, 3]


_TIP_MISTAKES = (  # the mistakes of a DH product
    MODIFIED_DH.of(lambda: _tip("mdh_transform"),
                   "this is the tip of the modified (Craig) product, mdh_transform or "
                   "Rx(α) Tx(a) Rz(θ) Tz(d) per row; the table is standard DH: "
                   "A_i = Rz(θ_i) Tz(d_i) Tx(a_i) Rx(α_i), kl.dh_transform"),
    SIGN.of(lambda: _tip(alpha1_sign=-1),
            "α_1 has the wrong sign: with α_1 = −90° the arm's plane is turned the other way "
            "about x_1 and the height comes out d_1 − (a_2 s_2 + a_3 s_23); the table has "
            "α_1 = +90°"),
    ORDER.of(lambda: _tip(reverse=True),
             "the product is reversed: T_03 = A_1 A_2 A_3, the base's transform on the left, "
             "because A_i is frame i seen from frame i−1"),
)


# ---- 09.4: one PUMA link transform -------------------------------------------------------

Q3 = 0.6


def _puma_row3(**change):
    from ... import dh_transform, mdh_transform
    from ...robots import puma560

    row = puma560().dh_rows[2]
    p = dict(theta=Q3 + row.offset, d=row.d, a=row.a, alpha=row.alpha)
    modified = change.pop("modified", False)
    p.update(change)
    return (mdh_transform if modified else dh_transform)(**p)


def _row3():
    from ...robots import puma560

    return puma560().dh_rows[2]


# ---- 09.5: the modified-DH table of the 3-DOF arm ----------------------------------------


def _standard():
    from ...robots import three_dof_arm

    return [(r.a, r.alpha, r.d) for r in three_dof_arm().dh_rows]


def _modified_table():
    """Row i of Craig's table: (a_{i−1}, α_{i−1}, d_i); a_0 = α_0 = 0; a tool row
    (a_n, α_n, 0) last."""
    std = _standard()
    prev = [(0.0, 0.0)] + [(a, al) for a, al, _ in std]
    return np.array([(a, al, d) for (a, al), d in zip(prev, [d for *_, d in std] + [0.0],
                                                      strict=True)])


EXERCISES = [
    choice("09.1", "predict", "the joint variable of a prismatic row",
           {"a": "θ_i", "b": "d_i", "c": "a_i", "d": "α_i"}, "b",
           {"a": ("revolute", "θ_i, the angle about z_{i−1}, is the variable of a revolute "
                              "joint; a prismatic joint slides along its axis z_{i−1}, and "
                              "the distance along z_{i−1} is d_i"),
            "c": ("link length", "a_i is measured along the common normal x_i, perpendicular "
                                 "to the joint axis: the link's length, fixed by its shape. A "
                                 "prismatic joint slides along its own axis z_{i−1}: d_i"),
            "d": ("twist", "α_i is the angle between the joint axes z_{i−1} and z_i, fixed by "
                           "the link's shape; a prismatic joint changes a length along "
                           "z_{i−1}: d_i")}),
    function("09.2", "a DH row read back from frames i−1 and i", _read_back_cases(), _read_back,
             *[Mistake("arccos", "arccos of a dot product gives the size of an angle, never its "
                                 "sign: θ_i is turned about z_{i−1} (α_i about x_i) by the right-"
                                 "hand rule, so use atan2 with the cross product's component "
                                 "along that axis: θ = atan2((x_{i−1} × x_i)·z_{i−1}, "
                                 "x_{i−1}·x_i)", _abs_angles(w)) for w in ((0, 3), (0,), (3,))],
             Mistake("x axis", "a_i is measured along the common normal x_i of frame i, not "
                               "along x_{i−1}: a = (o_i − o_{i−1})·x_i",
                     lambda T_prev, T: _read_back(T_prev, T) * [1, 1, 0, 1]
                     + [0, 0, (T[:3, 3] - T_prev[:3, 3]) @ T_prev[:3, 0], 0]),
             Mistake("distance", "d_i is only the part of o_{i−1} → o_i along z_{i−1}, not the "
                                 "whole distance between the origins",
                     lambda T_prev, T: _read_back(T_prev, T) * [1, 0, 1, 1]
                     + [0, np.linalg.norm(T[:3, 3] - T_prev[:3, 3]), 0, 0]),
             DEGREES.of(lambda T_prev, T: _read_back(T_prev, T) * [180 / np.pi, 1, 1, 180 / np.pi],
                        "return the angles in radians, as arctan2 gives them"),
             SWAPPED.of(_permuted((3, 1, 2, 0)), "θ and α are swapped: return (θ, d, a, α)"),
             SWAPPED.of(_permuted((0, 2, 1, 3)), "d and a are swapped: return (θ, d, a, α)"),
             SWAPPED.of(_permuted((0, 3, 2, 1)), "you returned (θ, α, a, d), the column order of "
                                                 "seed 001's PUMA table: return (θ, d, a, α)"),
             accept=_wrapped, what="an array (θ, d, a, α)",
             explain="o_i = o_{i−1} + d z_{i−1} + a x_i with z_{i−1} ⟂ x_i (DH1), so the dot "
                     "products pick out d and a; θ and α need atan2 of the cross product's "
                     "component along the axis they turn about, and the dot product, for "
                     "their sign."),
    expression("09.3", "the 3-DOF arm's tip position", _tip, *_TIP_MISTAKES,
               what="a 3×1 sympy Matrix", diagnoses=("swapped", "transposed"),
               explain="the result reads like the arm: in its vertical plane the 2R arm reaches "
                   "r = a_2 cos θ_2 + a_3 cos(θ_2 + θ_3) and rises to d_1 + a_2 sin θ_2 + "
                   "a_3 sin(θ_2 + θ_3); the base turns that plane by θ_1, so x = r cos θ_1, "
                   "y = r sin θ_1. α_1 = 90° is what stands the plane up: it turns z_1, the "
                   "shoulder axis, into the horizontal."),
    value("09.4", "compute", "A_3 of the PUMA 560 at q_3 = 0.6 rad", _puma_row3,
          MODIFIED_DH.of(lambda: _puma_row3(modified=True),
                         "this is Craig's modified DH, mdh_transform = Rx(α) Tx(a) Rz(θ) "
                         "Tz(d); seed 001's PUMA table is standard DH: A_3 = Rz(θ_3) Tz(d_3) "
                         "Tx(a_3) Rx(α_3), kl.dh_transform"),
          DEGREES.of(lambda: _puma_row3(alpha=np.rad2deg(_row3().alpha)),
                     "α_3 = 90 went in as 90 radians: convert the table's degrees with "
                     "np.deg2rad (or use π/2)"),
          Mistake("table pose", "the θ column of seed 001's table (90° for joint 3) is the "
                                "pose drawn in the book, not an offset: here θ_3 = q_3 = 0.6",
                  lambda: _puma_row3(theta=Q3 + np.deg2rad(90.0))),
          Mistake("millimetres", "the table is in millimetres; kinlib works in metres: "
                                 "a_3 = −0.02032 m",
                  lambda: _puma_row3(a=1000.0 * _row3().a)),
          SIGN.of(lambda: _puma_row3(alpha=-_row3().alpha),
                  "α_3 has the wrong sign: the table says α_3 = +90°"),
          SIGN.of(lambda: _puma_row3(a=-_row3().a),
                  "a_3 has the wrong sign: the table says a_3 = −20.32 mm (the forearm's "
                  "offset points along −x_3)"),
          SWAPPED.of(lambda: _puma_row3(theta=_row3().alpha, alpha=Q3),
                     "θ and α are swapped: kl.dh_transform takes (theta, d, a, alpha) in that "
                     "order; use the keywords"),
          what="a 4×4 matrix",
          explain="A_3 = Rz(0.6) Tx(−0.02032) Rx(π/2), with d_3 = 0: the table's θ_3 = 90° "
                  "is only the pose the book draws, and its millimetres and degrees become "
                  "metres and radians."),
    value("09.5", "compute", "the modified-DH table of the 3-DOF arm", _modified_table,
          Mistake("standard rows", "those are the standard rows: in Craig's table row i holds "
                                   "a_{i−1} and α_{i−1}, the length and twist of the link "
                                   "before joint i, so a and α move one row down (row 1 gets "
                                   "a_0 = α_0 = 0, the tool row a_3 and α_3), while d_i stays",
                  lambda: np.array(_standard() + [(0.0, 0.0, 0.0)])),
          Mistake("d moved", "d_i stays in row i: it is the offset along joint i's own axis in "
                             "both conventions; only a and α move one row down",
                  lambda: np.vstack([[0.0, 0.0, 0.0], np.array(_standard())])),
          DEGREES.of(lambda: _modified_table() * [1.0, 180.0 / np.pi, 1.0],
                     "α_0 … α_3 must be in radians: α_1 = π/2, not 90"),
          what="a 4×3 array",
          explain="a and α moved one row down, d stayed: row 1 is (a_0, α_0, d_1) = "
                  "(0, 0, 0.4), row 2 (a_1, α_1, 0) = (0, π/2, 0), row 3 (a_2, 0, 0) = "
                  "(0.5, 0, 0), and the fixed tool row carries (a_3, α_3) = (0.4, 0)."),
]
