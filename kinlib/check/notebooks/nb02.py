"""Notebook 02 · transform arithmetic: operators, compound transforms, the closed-form
inverse, the cost of the two orders of products, a line vector in another frame."""

import numpy as np

from .._verdict import Mistake
from ..mistakes import DEGREES, ORDER, SIGN, SWAPPED, TRANSPOSED
from ._make import choice, value

Q = np.array([0.3, -0.2, 0.5])


def _translation(q):
    from ... import transform

    return transform(p=q)


def _compound_givens(to_radians=np.deg2rad):
    """ᴬT_B ({B} turned 90° about X̂_A, origin (0, 1, 0)) and ᴮT_C (30° about Ẑ_B, origin
    (2, 0, 0.5)), as the notebook describes them."""
    from ... import rotx, rotz, transform

    return (transform(rotx(to_radians(90)), [0.0, 1.0, 0.0]),
            transform(rotz(to_radians(30)), [2.0, 0.0, 0.5]))


def _inverse_given():
    from ... import roty, transform

    T = transform(roty(np.deg2rad(60)), [2.0, 0.0, -1.0])
    return T, T[:3, :3], T[:3, 3]


def _inverse_with(sign: int, transpose: bool):
    """[Rᵀ, sign·Rᵀp; 0 1] (transpose) or [R, sign·R p; 0 1] for the given ᴬT_B."""
    _, R, p = _inverse_given()
    Rt = R.T if transpose else R
    return _blocks(Rt, sign * Rt @ p)


def _blocks(R, p):
    T = np.eye(4)
    T[:3, :3], T[:3, 3] = R, p
    return T


def _operator_order() -> str:
    """Which product of T_Trans(q) and T_Rot(R) is [R q; 0 1], for a generic R and q."""
    from ... import matrix_from_axis_angle, transform

    R, q = matrix_from_axis_angle([1.0, 2.0, 2.0], 0.8), np.array([0.4, -1.0, 0.7])
    trans_rot = transform(p=q) @ transform(R)
    return "a" if np.allclose(trans_rot, transform(R, q)) else "b"


def _inverse_meaning() -> str:
    """What −Rᵀp is, for a generic T_AB: the origin of {A} described in {B} (option a), the
    origin of {B} in {A} (b), or the vector from A's to B's origin in B's axes (c)."""
    from ... import matrix_from_axis_angle, transform, transform_inverse, transform_points

    R, p = matrix_from_axis_angle([2.0, -1.0, 1.0], 1.1), np.array([0.5, -1.0, 2.0])
    column = -R.T @ p
    options = {"a": transform_points(transform_inverse(transform(R, p)), np.zeros(3)),
               "b": p, "c": R.T @ p}
    return next(k for k, v in options.items() if np.allclose(v, column))


def _mults(n: int = 4):
    """Multiplications with full n×n arithmetic: T (T P) is two matrix–vector products
    (n² each), (T T) P a matrix–matrix product (n³) and one matrix–vector product."""
    return np.array([2 * n * n, n ** 3 + n * n])


# ---- 02.7: a line vector (a force on its line of action) in another frame ---------------

LINE_B = np.array([5.0, 0.0, -20.0, -2.0, 6.0, -0.5])   # [f_B (N); m_B (N·m)], as the notebook


def _grip():
    """ᴬT_B of the gripper in exercise 02.7 and its blocks R, t."""
    from ... import matrix_from_euler, transform

    T = transform(matrix_from_euler(np.deg2rad([90.0, 30.0, 0.0]), "ZYX"), [0.5, 1.0, 0.8])
    return T, T[:3, :3], T[:3, 3]


def _line_in_A():
    """The line in {A} from its definition: a point of it (the one nearest B's origin,
    f × m / |f|²) mapped as a point, the force as a free vector, m_A = p_A × f_A."""
    from ... import transform_points, transform_vectors

    T, _, _ = _grip()
    f, m = LINE_B[:3], LINE_B[3:]
    point = np.cross(f, m) / (f @ f)
    f_A = transform_vectors(T, f)
    return np.r_[f_A, np.cross(transform_points(T, point), f_A)]


def _line_with(moment):
    """[R f_B; moment(R, t, f_B, m_B)]: a wrong moment with the force rotated right."""
    _, R, t = _grip()
    f, m = LINE_B[:3], LINE_B[3:]
    return np.r_[R @ f, moment(R, t, f, m)]


EXERCISES = [
    value("02.1", "compute", "the translation operator T_Trans(Q)", lambda: _translation(Q),
          SIGN.of(lambda: _translation(-Q),
                  "the translation column is −Q: that maps a fixed point into a frame moved "
                  "by Q; the operator moves the point forward, ᴬP₂ = ᴬP₁ + ᴬQ, so its "
                  "entries are +q_i"),
          TRANSPOSED.of(lambda: _translation(Q).T,
                        "Q is in the bottom row: with column vectors, [P₂; 1] = T [P₁; 1], "
                        "the translation is the last column and the bottom row is "
                        "(0, 0, 0, 1)"),
          what="a 4×4 array",
          explain="the entries are +q_i: the operator moves the point forward, "
                  "ᴬP₂ = ᴬP₁ + ᴬQ. Describing a point that stays put in a frame moved by Q "
                  "takes the inverse, with −q_i: seed 002's 'a vector moved forward = the "
                  "frame moved backward'."),
    choice("02.2", "predict", "is the order of rotation and translation important?",
           {"a": "T_Trans(Q) T_Rot(R): rotate first, then translate",
            "b": "T_Rot(R) T_Trans(Q): translate first, then rotate",
            "c": "both: they commute"}, _operator_order(),
           {"b": ("order", "T_Rot(R) T_Trans(Q) translates first and then turns the "
                           "translated point too: its last column is R q, not q. The "
                           "operator applied first stands on the right"),
            "c": ("commute", "they do not commute: rotating after translating also turns "
                             "the translation (R q ≠ q unless q lies on the rotation axis)")},
           explain="the operator applied first stands on the right: T_Trans(Q) T_Rot(R) "
                   "rotates about the origin, then translates. The demonstration below "
                   "shows both products."),
    value("02.3", "compute", "the compound transform ᴬT_C = ᴬT_B ᴮT_C",
          lambda: np.matmul(*_compound_givens()),
          DEGREES.of(lambda: np.matmul(*_compound_givens(float)),
                     "kl.rotx(90) turns by 90 radians: write the angles as np.deg2rad(90) "
                     "and np.deg2rad(30)"),
          ORDER.of(lambda: np.matmul(*_compound_givens()[::-1]),
                   "this is ᴮT_C ᴬT_B: read the frames like a chain, ᴬT_B ᴮT_C = ᴬT_C "
                   "(the inner frame letters meet)"),
          Mistake("elementwise", "`*` multiplies numpy arrays entry by entry; the matrix "
                                 "product is `@`", lambda: np.multiply(*_compound_givens())),
          Mistake("offset", "the rotation block is right, but the origin of {C} is not "
                            "ᴬP_BORG + ᴮP_CORG: ᴮP_CORG is measured along B's axes, so it is "
                            "rotated first, ᴬP_CORG = ᴬR_B ᴮP_CORG + ᴬP_BORG",
                  lambda: _blocks(_compound_givens()[0][:3, :3] @ _compound_givens()[1][:3, :3],
                                  _compound_givens()[0][:3, 3] + _compound_givens()[1][:3, 3])),
          what="a 4×4 array",
          explain="ᴬT_C = ᴬT_B ᴮT_C: the inner frame letters meet. Its blocks are "
                  "ᴬR_C = ᴬR_B ᴮR_C and ᴬP_CORG = ᴬR_B ᴮP_CORG + ᴬP_BORG."),
    choice("02.4", "predict", "the geometrical description of −Rᵀp",
           {"a": "the origin of {A}, described in {B}", "b": "the origin of {B}, described in {A}",
            "c": "the vector from A's origin to B's origin, in B's axes"}, _inverse_meaning(),
           {"b": ("transposed", "that is p = ᴬP_BORG itself, the last column of ᴬT_B; the "
                                "inverse describes {A} in {B}: the frames are swapped"),
            "c": ("sign", "that vector is +Rᵀp; the minus sign reverses it: −Rᵀp leads from "
                          "B's origin back to A's origin, ᴮP_AORG")},
           explain="−Rᵀp = ᴮP_AORG, the origin of {A} described in {B}: the demonstration "
                   "below lays it off from B's origin and lands on A's."),
    value("02.5", "compute", "the closed-form inverse ᴮT_A", lambda: _inverse_with(-1, True),
          SIGN.of(lambda: _inverse_with(+1, True),
                  "the translation has the wrong sign: ᴮP = Rᵀ(ᴬP − ᴬP_BORG), so the last "
                  "column is −Rᵀp"),
          Mistake("unrotated", "the translation is −p, measured along A's axes; ᴮT_A needs it "
                               "along B's axes: −Rᵀp",
                  lambda: _blocks(_inverse_given()[1].T, -_inverse_given()[2])),
          TRANSPOSED.of(lambda: _inverse_with(-1, False),
                        "the rotation block is ᴬR_B; the inverse needs ᴮR_A = ᴬR_Bᵀ, in the "
                        "block and in −Rᵀp"),
          TRANSPOSED.of(lambda: _inverse_given()[0].T,
                        "you transposed the whole 4×4 matrix: only the rotation block is "
                        "transposed; the translation becomes the column −Rᵀp and the bottom "
                        "row stays (0, 0, 0, 1)"),
          what="a 4×4 array",
          explain="ᴮT_A = [Rᵀ, −Rᵀp; 0 0 0 1]: a transpose and one matrix–vector product "
                  "instead of a general 4×4 inverse, and ᴮT_A ᴬT_B = I exactly."),
    value("02.6", "predict", "multiplications of ᴬT_B(ᴮT_C ᶜP) and (ᴬT_B ᴮT_C) ᶜP", _mults,
          SWAPPED.of(lambda: _mults()[::-1], "the two counts are swapped: the order that "
                                             "multiplies the two matrices first is the "
                                             "expensive one for a single point"),
          Mistake("additions", "those are the additions (an entry is a sum of 4 products: "
                               "3 additions); count the multiplications",
                  lambda: np.array([2 * 4 * 3, 4 * 4 * 3 + 4 * 3])),
          Mistake("3×3", "that is the count for the 3×3 rotations only; seed 002 counts the "
                         "full 4×4 homogeneous arithmetic", lambda: _mults(3)),
          Mistake("final product", "after the 4×4 × 4×4 product (64) the compound still "
                                   "multiplies the point: 16 more",
                  lambda: np.array([32, 4 ** 3])),
          what="two numbers",
          explain="32 against 80: for one point, pass the point through the chain; the "
                  "count below shows when the compound, computed once, pays off."),
    value("02.7", "compute", "a line vector (f, m) in another frame", _line_in_A,
          Mistake("free vector", "you rotated the moment like a free vector, R m_B: it is the "
                                 "moment about the origin, and A's origin is not B's. The "
                                 "line's points move by t, so m_A = R m_B + t × f_A",
                  lambda: _line_with(lambda R, t, f, m: R @ m)),
          Mistake("point", "you mapped f and m like points, adding t: neither is a point. "
                           "f is turned only (a free vector), and the translation enters "
                           "the moment alone, as t × f_A",
                  lambda: np.r_[_grip()[1] @ LINE_B[:3] + _grip()[2],
                                _grip()[1] @ LINE_B[3:] + _grip()[2]]),
          Mistake("cross order", "the new term has the wrong sign: m = p × f with the point "
                                 "first, so it is t × f_A, not f_A × t",
                  lambda: _line_with(lambda R, t, f, m: R @ m + np.cross(R @ f, t))),
          Mistake("unrotated", "t × f_B mixes two frames: t is written in {A}, f_B in {B}; "
                               "the term is t × f_A with f_A = R f_B",
                  lambda: _line_with(lambda R, t, f, m: R @ m + np.cross(t, f))),
          SWAPPED.of(lambda: np.r_[_line_in_A()[3:], _line_in_A()[:3]],
                     "the two halves are swapped: the line is np.r_[f_A, m_A], the force "
                     "first, as line_B is"),
          what="six numbers [f_A; m_A]",
          explain="f_A = R f_B, a free vector; m_A = R m_B + t × f_A: every point of the line "
                  "moved by t, and (R p + t) × R f = R (p × f) + t × R f. A line vector feels "
                  "the translation through its moment only."),
]
