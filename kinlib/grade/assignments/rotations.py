"""Assignment 01 · rotations: elementary rotations, ZYX Euler angles both ways (with gimbal
lock) and the ZYX matrix derived with sympy, axis-angle both ways, the quaternion product,
quaternion → matrix and back."""

from __future__ import annotations

import numpy as np

import kinlib as kl
from kinlib.check.judges import axis_angle_judge, euler_angles_judge

from .._checks import Assignment, Check, Mistake
from .._symbolic import symbolic_check
from .common import (
    DEGREES,
    TRANSPOSED,
    random_quats,
    random_rotations,
    random_unit_vectors,
    wxyz_read_as_xyzw,
)

ELEMENTARY = {"rotx": kl.rotx, "roty": kl.roty, "rotz": kl.rotz}
SIN_SIGN = ("the sign of sin is on the wrong side: you returned the transpose, the rotation "
            "by −θ. The column j of R is where the unit vector j goes: for rotz, x goes to "
            "(cos θ, sin θ, 0)")


def _angles(rng, n):
    fixed = [0.0, np.pi / 2, -np.pi / 2, np.pi, 0.1, -2.5, 3.0]
    return [(a,) for a in fixed] + [(float(a),) for a in rng.uniform(-np.pi, np.pi, n)]


def _elementary(name: str) -> Check:
    ref = ELEMENTARY[name]
    others = [Mistake("axis", f"this is {other}, not {name}: check which axis stays fixed "
                              f"(its row and column are 0, 0, 1)", f)
              for other, f in ELEMENTARY.items() if other != name]
    return Check(name, 2, f"rotation about {name[-1]} by θ", lambda rng: _angles(rng, 23),
                 ref, [Mistake("transposed", SIN_SIGN, lambda t: ref(t).T),
                       DEGREES.of(lambda t: ref(np.deg2rad(t))), *others])


def _zyx(a, b, g):
    return kl.matrix_from_euler([a, b, g], "ZYX")


def _euler_cases(rng):
    fixed = [(0.0, 0.0, 0.0), (0.3, 0.2, 0.1), (np.pi / 2, 0.0, 0.0), (0.0, np.pi / 2, 0.0),
             (0.0, 0.0, np.pi / 2), (1.0, -np.pi / 2, 0.5), (-2.0, 1.2, 3.0)]
    rand = rng.uniform([-np.pi, -np.pi / 2, -np.pi], [np.pi, np.pi / 2, np.pi], (53, 3))
    return fixed + [tuple(map(float, r)) for r in rand]


def _sequence_mistakes():
    out = [Mistake("extrinsic", "you multiplied in the fixed-axes (extrinsic) order "
                                "Rx(γ) Ry(β) Rz(α): Euler ZYX turns about the moving axes, so "
                                "R = Rz(α) Ry(β) Rx(γ), the first rotation leftmost",
                   lambda a, b, g: kl.rotx(g) @ kl.roty(b) @ kl.rotz(a))]
    for seq in ("XYZ", "ZXY", "YXZ", "YZX", "XZY", "ZYZ", "ZXZ"):
        out.append(Mistake("sequence", f"this is the {seq} sequence, not ZYX: α turns about "
                                       "z, then β about the new y, then γ about the newest x",
                           lambda a, b, g, s=seq: kl.matrix_from_euler([a, b, g], s)))
    return out


def _zyx_symbols(rng):
    """The grader's symbols: plain, other names without assumptions, gimbal lock with an
    exact β = ±π/2, and sums of symbols as the angles."""
    import sympy as sp

    k = int(rng.integers(1, 10))
    q, s = sp.symbols(f"q{k} s{k}", real=True)
    alpha, beta, gamma = sp.symbols("alpha beta gamma", real=True)
    return [(alpha, beta, gamma), sp.symbols(f"a{k} b{k} c{k}"),
            (alpha, int(rng.choice([1, -1])) * sp.pi / 2, gamma), (q + s, 2 * s, -q)]


def _zyx_symbolic() -> Check:
    def ry_flipped(a, b, g):
        return kl.rotz(a) * kl.roty(-b) * kl.rotx(g)
    return symbolic_check(
        "euler_zyx_symbolic", 3, "R = Rz(α) Ry(β) Rx(γ) derived with sympy", _zyx_symbols,
        lambda a, b, g: kl.matrix_from_euler([a, b, g], "ZYX"), names=("alpha", "beta", "gamma"),
        mistakes=[Mistake("extrinsic", "you multiplied in the fixed-axes (extrinsic) order "
                                       "Rx(γ) Ry(β) Rz(α): Euler ZYX turns about the moving "
                                       "axes, so the first rotation, Rz(α), stands leftmost",
                          lambda a, b, g: kl.rotx(g) * kl.roty(b) * kl.rotz(a)),
                  Mistake("sign", "the signs of sin β in R_y are swapped (you built R_y(−β)): "
                                  "R_y is the odd one out, its +sin is in row 1, column 3 "
                                  "(a turn about y takes z towards x)", ry_flipped)],
        swaps=[(0, 2)])


def _inverse_euler_cases(rng):
    cases = [(_zyx(*e),) for e in _euler_cases(rng)[:40]]
    for sign in (1.0, -1.0):  # gimbal lock, β = ±90° with exact zeros, several α, γ
        Ry = np.array([[0.0, 0.0, sign], [0.0, 1.0, 0.0], [-sign, 0.0, 0.0]])
        for a, g in rng.uniform(-np.pi, np.pi, (8, 2)):
            cases.append((kl.rotz(a) @ Ry @ kl.rotx(g),))
    cases += [(R,) for R in random_rotations(rng, 10)]
    return cases


def _aa_cases(rng):
    axes = random_unit_vectors(rng, 34)
    fixed = [([0.0, 0.0, 1.0], np.pi / 2), ([1.0, 0.0, 0.0], 0.0), ([0.0, 1.0, 0.0], np.pi),
             ([0.6, 0.8, 0.0], -1.0)]
    return [(np.array(k), a) for k, a in fixed] + \
        [(k, float(t)) for k, t in zip(axes, rng.uniform(-np.pi, np.pi, 34), strict=True)]


def _aa_inverse_cases(rng):
    out = [(kl.matrix_from_axis_angle(k, t),) for k, t in _aa_cases(rng)[4:34]]
    for k in random_unit_vectors(rng, 8):  # θ = π exactly: sin θ = 0
        out.append((kl.matrix_from_axis_angle(k, np.pi),))
    out += [(np.eye(3),), (kl.rotz(1e-9),), (kl.rotx(np.pi),)]
    out += [(R,) for R in random_rotations(rng, 9)]
    return out


def _quat_pairs(rng):
    qs = random_quats(rng, 80)
    fixed = [([1.0, 0, 0, 0], [0, 1.0, 0, 0]), ([0, 1.0, 0, 0], [0, 0, 1.0, 0]),
             ([0, 0, 1.0, 0], [0, 1.0, 0, 0])]
    return [(np.array(p), np.array(q)) for p, q in fixed] + \
        [(qs[i], qs[i + 1]) for i in range(0, 80, 2)]


def assignment() -> Assignment:
    mult = kl.quat_multiply
    checks = [_elementary("rotx"), _elementary("roty"), _elementary("rotz"),
              Check("euler_zyx_to_matrix", 2, "R = Rz(α) Ry(β) Rx(γ)", _euler_cases, _zyx,
                    [TRANSPOSED.of(lambda a, b, g: _zyx(a, b, g).T),
                     DEGREES.of(lambda a, b, g: _zyx(*np.deg2rad([a, b, g]))),
                     *_sequence_mistakes()]),
              _zyx_symbolic(),
              Check("matrix_to_euler_zyx", 5, "ZYX angles of R, also at gimbal lock",
                    _inverse_euler_cases, judge=euler_angles_judge("ZYX")),
              Check("axis_angle_to_matrix", 4, "Rodrigues' formula", _aa_cases,
                    kl.matrix_from_axis_angle,
                    [TRANSPOSED.of(lambda k, t: kl.matrix_from_axis_angle(k, t).T),
                     DEGREES.of(lambda k, t: kl.matrix_from_axis_angle(k, np.deg2rad(t))),
                     Mistake("rodrigues", "the (1 − cos θ) k kᵀ term is missing or wrong: "
                                          "R = cos θ I + sin θ [k]× + (1 − cos θ) k kᵀ",
                             lambda k, t: np.cos(t) * np.eye(3) + np.sin(t) * kl.skew(k))]),
              Check("matrix_to_axis_angle", 6, "axis and angle of R, also at θ = 0 and π",
                    _aa_inverse_cases, judge=axis_angle_judge),
              Check("quat_multiply", 4, "Hamilton product p ⊗ q, [w, x, y, z]", _quat_pairs,
                    mult,
                    [Mistake("order", "this is q ⊗ p: the product does not commute (the "
                                      "cross-product term changes sign). "
                                      "p ⊗ q = (p0 q0 − p·q, p0 q + q0 p + p × q)",
                             lambda p, q: mult(q, p)),
                     Mistake("xyzw", "you read and wrote the quaternions as [x, y, z, w]; "
                                     "the course's order is [w, x, y, z], scalar first",
                             lambda p, q: wxyz_read_as_xyzw(mult, p, q))]),
              Check("quat_to_matrix", 4, "rotation matrix of a unit quaternion [w, x, y, z]",
                    lambda rng: [(q,) for q in random_quats(rng, 36)] +
                    [(np.array(q),) for q in ([1.0, 0, 0, 0], [0, 1.0, 0, 0],
                                              [np.sqrt(.5), 0, 0, np.sqrt(.5)])],
                    kl.matrix_from_quat,
                    [Mistake("transposed", "you built the matrix of the conjugate q* (the "
                                           "transpose): check the signs of the w-terms, "
                                           "e.g. R21 = 2(xy + wz)",
                             lambda q: kl.matrix_from_quat(q).T),
                     Mistake("xyzw", "you read the quaternion as [x, y, z, w]; the course's "
                                     "order is [w, x, y, z], scalar first",
                             lambda q: kl.matrix_from_quat(np.roll(q, 1)))]),
              Check("matrix_to_quat", 4, "unit quaternion [w, x, y, z] of R (q or −q)",
                    _matrix_quat_cases, kl.quat_from_matrix,
                    [Mistake("xyzw", "you returned [x, y, z, w]; the course's order is "
                                     "[w, x, y, z], scalar first",
                             lambda R: np.roll(kl.quat_from_matrix(R), -1)),
                     Mistake("xyzw", "you returned [x, y, z, w]; the course's order is "
                                     "[w, x, y, z], scalar first",
                             lambda R: -np.roll(kl.quat_from_matrix(R), -1)),
                     Mistake("conjugate", "you returned the conjugate q* (the rotation Rᵀ): "
                                          "x = (R32 − R23)/(4w), not (R23 − R32)/(4w)",
                             lambda R: kl.quat_conjugate(kl.quat_from_matrix(R))),
                     Mistake("conjugate", "you returned the conjugate q* (the rotation Rᵀ): "
                                          "x = (R32 − R23)/(4w), not (R23 − R32)/(4w)",
                             lambda R: -kl.quat_conjugate(kl.quat_from_matrix(R)))],
                    accept=lambda R: [-kl.quat_from_matrix(R)],
                    on_error=_quat_error_hint),
              ]
    return Assignment("01_rotations", "Rotations", checks)


def _matrix_quat_cases(rng):
    out = [(R,) for R in random_rotations(rng, 30)]
    # half turns: w = 0, so a formula that divides by 4w breaks (Shepperd's method does not)
    out += [(kl.matrix_from_axis_angle(k, np.pi),) for k in random_unit_vectors(rng, 6)]
    out += [(kl.rotx(np.pi),), (kl.roty(np.pi),), (kl.rotz(np.pi),), (np.eye(3),),
            (kl.matrix_from_axis_angle([1.0, 1.0, 0.0], np.pi - 1e-9),)]
    return out


def _quat_error_hint(args, error: str):
    (R,) = args
    if 1.0 + np.trace(R) < 1e-6:
        return ("Here w = cos(θ/2) = 0 (a half turn): do not divide by w; start from the "
                "largest of w², x², y², z² (from the diagonal of R) and divide by that")
    return None
