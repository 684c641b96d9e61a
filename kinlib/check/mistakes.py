"""The classic mistakes of a kinematics course, named once.

Each is a :class:`~kinlib.check.MistakeKind`: a key and the diagnosis a student reads. A
notebook exercise or a grader check turns one into a :class:`~kinlib.check.Mistake` with a
model of the wrong answer (``TRANSPOSED.of(lambda: R.T)``), and may give a more specific
message for its own context. ``tests/test_check_mistakes.py`` produces every one of them
from a real wrong answer.
"""

from __future__ import annotations

import numpy as np

from ._verdict import Mistake, MistakeKind

__all__ = ["TRANSPOSED", "DEGREES", "EXTRINSIC", "SEQUENCE", "ORDER", "XYZW", "CONJUGATE",
           "SIGN", "OTHER_ELBOW", "MODIFIED_DH", "HALF_ANGLE", "LAMBDA", "FRAME", "ROWS",
           "SWAPPED", "CATALOGUE", "euler_matrix_mistakes", "wxyz_read_as_xyzw"]

TRANSPOSED = MistakeKind("transposed", "your matrix is the transpose of the right one: the "
                                       "frames are mixed up (R_AB versus R_BA), or the signs "
                                       "of the sines are swapped")
DEGREES = MistakeKind("degrees", "you treated the angles as degrees (converted them with "
                                 "π/180, or returned degrees): angles are in radians "
                                 "throughout, as numpy's sin and cos expect")
EXTRINSIC = MistakeKind("extrinsic", "intrinsic and extrinsic are swapped: rotations about "
                                     "the moving axes multiply left to right (R = R1 R2 R3), "
                                     "rotations about the fixed axes right to left "
                                     "(R = R3 R2 R1)")
SEQUENCE = MistakeKind("sequence", "this is another axis sequence: check which axis each "
                                   "angle turns about, in the order of the letters")
ORDER = MistakeKind("order", "the product is in the wrong order: matrix and quaternion "
                             "products do not commute; the transform applied first stands "
                             "on the right")
XYZW = MistakeKind("xyzw", "the quaternion is in [x, y, z, w] order (ROS, scipy; seed 002's "
                           "Euler parameters put ε4 last); the course's order is [w, x, y, z], "
                           "scalar first")
CONJUGATE = MistakeKind("conjugate", "this is the conjugate q* (the inverse rotation, Rᵀ): "
                                     "check the signs of the vector part")
SIGN = MistakeKind("sign", "the sign is wrong: the answer is right up to a factor −1")
OTHER_ELBOW = MistakeKind("other elbow", "this is the other elbow: s2 = +√(1 − c2²) is "
                                         "elbow \"down\" (θ2 ≥ 0), −√ is elbow \"up\"")
MODIFIED_DH = MistakeKind("modified", "this is Craig's modified DH, A = Rx(α) Tx(a) Rz(θ) "
                                      "Tz(d); the course's standard DH is A = Rz(θ) Tz(d) "
                                      "Tx(a) Rx(α)")
HALF_ANGLE = MistakeKind("half angle", "the half angle is missing: a unit quaternion is "
                                       "(cos θ/2, sin θ/2 u), Cayley's parameters tan(θ/2) k")
LAMBDA = MistakeKind("lambda", "the damping enters squared: Δq = Jᵀ (J Jᵀ + λ² I)⁻¹ e; you "
                               "added λ I")
FRAME = MistakeKind("frame", "this is expressed in the moving (body) frame: RᵀṘ and "
                             "log(Rᵀ R_t) give body-frame vectors; the course's ω and pose "
                             "error are in the fixed (base) frame: Ṙ Rᵀ, log(R_t Rᵀ)")
ROWS = MistakeKind("rows", "the rows are in the order [ω; v]: the course stacks the linear "
                           "part first, [v; ω], like the geometric Jacobian (Modern Robotics "
                           "writes [ω; v])")
SWAPPED = MistakeKind("swapped", "two of the angles (or arguments) are swapped")

#: every kind, by key
CATALOGUE = {k.key: k for k in (TRANSPOSED, DEGREES, EXTRINSIC, SEQUENCE, ORDER, XYZW,
                                 CONJUGATE, SIGN, OTHER_ELBOW, MODIFIED_DH, HALF_ANGLE, LAMBDA,
                                 FRAME, ROWS, SWAPPED)}

_OTHERS = ("XYZ", "ZXY", "YXZ", "YZX", "XZY", "ZYZ", "ZXZ", "XYX", "ZYX")


def euler_matrix_mistakes(seq: str) -> list[Mistake]:
    """The wrong matrices of an Euler/fixed-angle sequence ``seq`` (models take the three
    angles in letter order): the other kind of axes (intrinsic ↔ extrinsic: the product
    reversed), the letters read backwards, and other sequences."""
    from ..spatial.euler import matrix_from_euler

    swapped = seq.swapcase()
    out = [EXTRINSIC.of(lambda *a: matrix_from_euler(list(a), swapped),
                        f"this is {swapped!r}, not {seq!r}: "
                        + ("about the moving axes the matrices multiply left to right"
                           if seq.isupper() else
                           "about the fixed axes the matrices multiply right to left"))]
    out.append(SEQUENCE.of(lambda *a: matrix_from_euler(list(a)[::-1], seq),
                           "the angles are in the wrong order: give them in the order of "
                           "the letters"))
    for other in _OTHERS:
        other = other if seq.isupper() else other.lower()
        if other != seq:
            out.append(SEQUENCE.of(lambda *a, s=other: matrix_from_euler(list(a), s),
                                   f"this is the {other} sequence, not {seq}: each angle "
                                   "turns about the axis of its letter"))
    return out


def wxyz_read_as_xyzw(f, *quats):
    """What ``f`` (quaternions in, quaternion out) gives if its code reads its inputs and
    writes its output in [x, y, z, w] order while the data are [w, x, y, z]."""
    return np.roll(f(*(np.roll(np.asarray(q), 1) for q in quats)), -1)
