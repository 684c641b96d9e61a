"""Assignment 05's interpolation checks: slerp of unit quaternions, the dual-quaternion
product and ScLERP (screw linear interpolation) of unit dual quaternions.

The references are kinlib's :func:`~kinlib.quat_slerp`, :func:`~kinlib.dual_quat_multiply`
and :func:`~kinlib.dual_quat_sclerp`; −q (−q̂) is the same rotation (motion) and is accepted.
"""

from __future__ import annotations

import numpy as np

import kinlib as kl

from ...check import Rule
from .._checks import Check, Mistake, Verdict
from .common import random_quats, random_rotations, random_unit_vectors

__all__ = ["finite_model", "either_sign", "slerp_check", "dual_quat_multiply_check",
           "sclerp_check", "random_poses", "sclerp_model", "dlb", "dlb_plain", "decoupled",
           "long_way_sclerp"]


def _unit(q):
    q = np.asarray(q, dtype=float)
    return q / np.linalg.norm(q)


def finite_model(f):
    """A mistake model that does not apply where it is infinite or huge (a formula dividing
    by sin Ω ≈ 0, tan θ at θ = 90°): close() would match every answer to it there."""
    def model(*args):
        with np.errstate(all="ignore"):
            out = np.asarray(f(*args), dtype=float)
        if not np.isfinite(out).all() or np.abs(out).max() > 1e8:
            raise ValueError("the model does not apply here")
        return out
    return model


def either_sign(rule: Rule, special=None):
    """A judge for a quaternion or dual quaternion, where −x stands for the same rotation
    (pose): ``rule`` (which accepts −x itself), then its mistakes tried on −got too.
    ``special(args, verdict)`` may rename a verdict (a NaN where the formula divides 0/0)."""
    def judge(args, got):
        v = rule.verdict(args, got)
        if v.key == "wrong":
            flipped = rule.verdict(args, -np.asarray(got, dtype=float))
            if flipped.key != "wrong":
                v = flipped
        return special(args, v) if special is not None else v
    return judge


# -- slerp ----------------------------------------------------------------------------------
def _weights_formula(q0, q1, t, omega):
    """sin((1 − t)Ω)/sin Ω q0 + sin(tΩ)/sin Ω q1, as written (NaN where sin Ω = 0)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        return (np.sin((1 - t) * omega) * q0 + np.sin(t * omega) * q1) / np.sin(omega)


def _short(q0, q1):
    q0, q1 = np.asarray(q0, dtype=float), np.asarray(q1, dtype=float)
    return q1 if q0 @ q1 >= 0 else -q1


def _long_way(q0, q1, t):
    q0, q1 = np.asarray(q0, dtype=float), np.asarray(q1, dtype=float)
    return _weights_formula(q0, q1, t, np.arccos(np.clip(q0 @ q1, -1.0, 1.0)))


def _rotation_angle_as_omega(q0, q1, t, normalise):
    q1 = _short(q0, q1)
    theta = 2 * np.arccos(np.clip(q0 @ q1, -1.0, 1.0))  # the angle between the rotations
    q = _weights_formula(np.asarray(q0, dtype=float), q1, t, theta)
    return q / np.linalg.norm(q) if normalise else q


SLERP_MISTAKES = [
    Mistake("long way", "you interpolated the long way round: when q0·q1 < 0, replace q1 by "
                        "−q1 first (the same rotation), so that Ω ≤ 90° and the body turns "
                        "through the smaller angle", finite_model(_long_way)),
    Mistake("nlerp", "this is (1 − t) q0 + t q1 normalised (nlerp): it passes through the "
                     "right orientations, but not at a constant rate; slerp's weights are "
                     "sin((1 − t)Ω)/sin Ω and sin(tΩ)/sin Ω",
            lambda q0, q1, t: _unit((1 - t) * np.asarray(q0) + t * _short(q0, q1))),
    Mistake("linear", "(1 − t) q0 + t q1 is not a unit quaternion (it cuts through the "
                      "sphere); slerp's weights sin((1 − t)Ω)/sin Ω and sin(tΩ)/sin Ω keep "
                      "it on the sphere",
            lambda q0, q1, t: (1 - t) * np.asarray(q0) + t * _short(q0, q1)),
    Mistake("reversed", "your path runs from q1 (t = 0) to q0 (t = 1): q0's weight is "
                        "sin((1 − t)Ω)/sin Ω, q1's is sin(tΩ)/sin Ω",
            lambda q0, q1, t: kl.quat_slerp(q1, q0, t)),
    Mistake("angle", "Ω is the angle between q0 and q1 as 4-vectors, cos Ω = q0·q1: half the "
                     "angle between the two orientations. You used the rotation angle "
                     "2 arccos(q0·q1)",
            finite_model(lambda q0, q1, t: _rotation_angle_as_omega(q0, q1, t, False))),
    Mistake("angle", "Ω is the angle between q0 and q1 as 4-vectors, cos Ω = q0·q1: half the "
                     "angle between the two orientations. You used the rotation angle "
                     "2 arccos(q0·q1)",
            finite_model(lambda q0, q1, t: _rotation_angle_as_omega(q0, q1, t, True))),
]


def _slerp_accept(q0, q1, t):
    ref = kl.quat_slerp(q0, q1, t)
    out = [-ref]
    if abs(np.dot(q0, q1)) < 1e-12:  # Ω = 90° both ways: either turn of 180° is shortest
        other = np.cos(t * np.pi / 2) * np.asarray(q0) - np.sin(t * np.pi / 2) * np.asarray(q1)
        out += [other, -other]
    return out


def _slerp_cases(rng):
    qs = random_quats(rng, 84)
    ident = np.array([1.0, 0.0, 0.0, 0.0])
    qz = np.array([np.cos(np.pi / 4), 0.0, 0.0, np.sin(np.pi / 4)])
    near = kl.quat_multiply(qs[0], kl.quat_from_axis_angle(random_unit_vectors(rng, 1)[0],
                                                           1e-9))
    u = random_unit_vectors(rng, 1)[0]  # q0·q1 = 0: a half turn apart, Ω = 90° both ways
    fixed = [(ident, qz, 0.5), (qs[0], qs[0], 0.3), (qs[0], -qs[0], 0.7), (qs[0], near, 0.4),
             (-qs[0], near, 0.6), (qs[2], -qs[3], 0.0), (qs[2], -qs[3], 1.0),
             (ident, np.r_[0.0, u], 0.25), (qs[1], kl.quat_multiply(qs[1], np.r_[0.0, u]), 0.8)]
    out = [(np.asarray(a, dtype=float), np.asarray(b, dtype=float), float(t))
           for a, b, t in fixed]
    for i in range(4, 84, 2):  # random pairs, the short way across q1 → −q1 half the time
        out.append((qs[i], qs[i + 1], float(rng.uniform(0.0, 1.0))))
    return out


def _slerp_special(args, v):
    q0, q1, _ = args
    if v.key == "nan" and abs(abs(np.dot(q0, q1)) - 1.0) < 1e-12:
        return Verdict(False, "equal", "q0 and q1 are (nearly) the same rotation (q1 = ±q0): "
                                       "after the sign flip Ω ≈ 0 and sin Ω ≈ 0. When sin Ω "
                                       "is tiny, return (1 − t) q0 + t q1 normalised instead",
                       v.expected)
    return v


def slerp_check() -> Check:
    return Check("slerp", 5, "slerp of unit quaternions, the short way", _slerp_cases,
                 kl.quat_slerp, SLERP_MISTAKES, accept=_slerp_accept,
                 judge=either_sign(Rule(kl.quat_slerp, SLERP_MISTAKES, _slerp_accept),
                                   _slerp_special))


# -- dual quaternions -----------------------------------------------------------------------
def random_poses(rng, n, scale=1.0):
    """n random unit dual quaternions [q_r, q_d], either sign."""
    Rs = random_rotations(rng, n)
    ps = rng.uniform(-scale, scale, (n, 3))
    dq = kl.dual_quat_from_transform(np.array([kl.transform(R, p) for R, p in
                                               zip(Rs, ps, strict=True)]))
    return dq * np.where(rng.random(n) < 0.5, -1.0, 1.0)[:, None]


def _q(a):
    a = np.asarray(a, dtype=float)
    return a[:4], a[4:]


def _dq_model(real, dual):
    def model(a, b):
        (ar, ad), (br, bd) = _q(a), _q(b)
        m = kl.quat_multiply
        return np.r_[real(m, ar, ad, br, bd), dual(m, ar, ad, br, bd)]
    return model


DQ_MISTAKES = [
    Mistake("order", "this is b̂ â: the product does not commute. â b̂ (first b̂, then â, like "
                     "T_a T_b) = a_r b_r + ε (a_r b_d + a_d b_r)",
            lambda a, b: kl.dual_quat_multiply(b, a)),
    Mistake("dual terms", "a factor of the dual part is in the wrong order: it is "
                          "a_r b_d + a_d b_r, the real part of â standing left of b̂'s in both "
                          "terms (quaternion products do not commute)",
            _dq_model(lambda m, ar, ad, br, bd: m(ar, br),
                      lambda m, ar, ad, br, bd: m(ar, bd) + m(br, ad))),
    Mistake("dual terms", "a factor of the dual part is in the wrong order: it is "
                          "a_r b_d + a_d b_r, the real part of â standing left of b̂'s in both "
                          "terms (quaternion products do not commute)",
            _dq_model(lambda m, ar, ad, br, bd: m(ar, br),
                      lambda m, ar, ad, br, bd: m(bd, ar) + m(ad, br))),
    Mistake("epsilon", "ε² = 0: the product a_d b_d of the two dual parts vanishes, it does "
                       "not add to the real part",
            _dq_model(lambda m, ar, ad, br, bd: m(ar, br) + m(ad, bd),
                      lambda m, ar, ad, br, bd: m(ar, bd) + m(ad, br))),
    Mistake("halves", "you returned [dual part, real part]: the 8 numbers are the real part "
                      "q_r first, then the dual part q_d",
            lambda a, b: np.roll(kl.dual_quat_multiply(a, b), 4)),
]


def _dq_cases(rng):
    a, b = random_poses(rng, 38, 2.0), random_poses(rng, 38, 2.0)
    ident = kl.dual_quat_from_transform(np.eye(4))
    trans = [kl.dual_quat_from_transform(kl.transform(p=p)) for p in rng.normal(size=(2, 3))]
    rots = [kl.dual_quat_from_transform(kl.transform(R)) for R in random_rotations(rng, 2)]
    fixed = [(ident, a[0]), (a[1], ident), (trans[0], trans[1]), (rots[0], rots[1]),
             (a[2], kl.dual_quat_conjugate(a[2])), (rots[0], trans[0])]
    return fixed + list(zip(a, b, strict=True))


def _dq_accept(a, b):
    return [-kl.dual_quat_multiply(a, b)]


def dual_quat_multiply_check() -> Check:
    return Check("dual_quat_multiply", 3, "the product â b̂ of dual quaternions", _dq_cases,
                 kl.dual_quat_multiply, DQ_MISTAKES, accept=_dq_accept,
                 judge=either_sign(Rule(kl.dual_quat_multiply, DQ_MISTAKES, _dq_accept)))


# -- ScLERP ---------------------------------------------------------------------------------
def _relative(dq0, dq1):
    return kl.dual_quat_multiply(kl.dual_quat_conjugate(dq0), dq1)


def _translation(dq):
    qr, qd = _q(dq)
    return 2 * kl.quat_multiply(qd, kl.quat_conjugate(qr))[1:]


def _dq(qr, p):
    return np.r_[qr, 0.5 * kl.quat_multiply(np.r_[0.0, p], qr)]


def sclerp_model(dq0, dq1, t):
    """kinlib's ScLERP (the reference)."""
    return kl.dual_quat_sclerp(dq0, dq1, t)


def dlb(dq0, dq1, t):
    """Dual-quaternion linear blending: (1 − t) q̂0 + t q̂1 (short way), divided by its dual
    norm |b_r| + ε (b_r·b_d)/|b_r|."""
    dq0, dq1 = np.asarray(dq0, dtype=float), np.asarray(dq1, dtype=float)
    if dq0[:4] @ dq1[:4] < 0:
        dq1 = -dq1
    br, bd = _q((1 - t) * dq0 + t * dq1)
    n = np.linalg.norm(br)
    cr = br / n
    return np.r_[cr, bd / n - cr * (cr @ bd) / n]


def dlb_plain(dq0, dq1, t):
    """The blend divided by |b_r| only (the same pose as :func:`dlb`, another 8-vector)."""
    dq0, dq1 = np.asarray(dq0, dtype=float), np.asarray(dq1, dtype=float)
    if dq0[:4] @ dq1[:4] < 0:
        dq1 = -dq1
    b = (1 - t) * dq0 + t * dq1
    return b / np.linalg.norm(b[:4])


def decoupled(dq0, dq1, t):
    """Slerp of the rotations, linear interpolation of the translations."""
    (r0, _), (r1, _) = _q(dq0), _q(dq1)
    p = (1 - t) * _translation(dq0) + t * _translation(dq1)
    return _dq(kl.quat_slerp(r0, r1, t), p)


def long_way_sclerp(dq0, dq1, t):
    """ScLERP without the short-way sign flip of the relative motion (where its w < 0)."""
    rel = _relative(dq0, dq1)
    if rel[0] >= 0:
        return sclerp_model(dq0, dq1, t)
    l, m, theta, d = kl.screw_from_dual_quat(rel)  # the screw of −rel: θ ≤ π
    step = kl.dual_quat_from_screw(-l, -m, t * (2 * np.pi - theta), -t * d)
    return kl.dual_quat_multiply(dq0, step)


def _wrong_side(dq0, dq1, t):
    """(q̂0* q̂1)^t applied before q̂0 instead of after it."""
    ident = np.r_[1.0, np.zeros(7)]
    rel = _relative(dq0, dq1)
    return kl.dual_quat_multiply(kl.dual_quat_sclerp(ident, rel, t), dq0)


SCLERP_MISTAKES = [
    Mistake("long way", "you took the long way round: when the relative motion q̂0* q̂1 has "
                        "w < 0, negate it first (the same motion), so that θ ≤ π",
            long_way_sclerp),
    Mistake("blend", "this is (1 − t) q̂0 + t q̂1 normalised (dual-quaternion blending): it "
                     "starts and ends right, but it is not the screw motion. ScLERP is "
                     "q̂0 (q̂0* q̂1)^t: the fraction t of the relative screw, tθ about its "
                     "axis and td along it", dlb),
    Mistake("blend", "this is (1 − t) q̂0 + t q̂1 normalised (dual-quaternion blending): it "
                     "starts and ends right, but it is not the screw motion. ScLERP is "
                     "q̂0 (q̂0* q̂1)^t: the fraction t of the relative screw, tθ about its "
                     "axis and td along it", dlb_plain),
    Mistake("decoupled", "you interpolated the rotation (slerp) and the translation (a "
                         "straight line) separately: same start and end, another path. "
                         "ScLERP moves along the relative screw: the origin follows a helix "
                         "about its axis", decoupled),
    Mistake("reversed", "your motion runs from q̂1 (t = 0) to q̂0 (t = 1): ScLERP starts at "
                        "q̂0, q̂(t) = q̂0 (q̂0* q̂1)^t",
            lambda dq0, dq1, t: kl.dual_quat_sclerp(dq1, dq0, t)),
    Mistake("order", "the fraction of the relative screw is on the wrong side: "
                     "q̂(t) = q̂0 (q̂0* q̂1)^t (the relative motion is measured in q̂0's "
                     "frame, so it acts after q̂0, on the right); you computed "
                     "(q̂0* q̂1)^t q̂0", _wrong_side),
]


def _sclerp_cases(rng):
    a, b = random_poses(rng, 36, 1.5), random_poses(rng, 36, 1.5)
    out = [(a[i], b[i], float(rng.uniform(0.0, 1.0))) for i in range(36)]
    ident = kl.dual_quat_from_transform(np.eye(4))
    T1 = kl.transform(kl.rotz(np.pi / 2), [1.0, -1.0, 1.0])  # kinlib's docstring example
    lift = kl.dual_quat_multiply(a[0], kl.dual_quat_from_transform(kl.transform(p=[0.3, -0.5,
                                                                                   0.8])))
    tiny = kl.dual_quat_multiply(a[1], kl.dual_quat_from_transform(kl.transform(
        kl.matrix_from_axis_angle([0.6, 0.0, 0.8], 1e-5), [0.2, 0.4, -0.1])))
    half = kl.dual_quat_multiply(a[2], kl.dual_quat_from_transform(kl.transform(
        kl.matrix_from_axis_angle([0.0, 0.6, 0.8], np.pi - 1e-3), [0.5, 0.0, 0.3])))
    about_origin = kl.dual_quat_from_transform(kl.transform(kl.rotx(2.0)))
    fixed = [(ident, kl.dual_quat_from_transform(T1), 0.5), (a[3], b[3], 0.0),
             (a[4], b[4], 1.0), (a[5], a[5], 0.4), (a[6], -a[6], 0.6), (a[0], lift, 0.3),
             (a[0], -lift, 0.7), (a[1], tiny, 0.5), (a[2], half, 0.5),
             (ident, about_origin, 0.25)]
    return [(np.asarray(x, dtype=float), np.asarray(y, dtype=float), float(t))
            for x, y, t in fixed] + out


def _sclerp_special(args, v):
    if v.key == "nan" and np.linalg.norm(_relative(*args[:2])[1:4]) < 1e-9:
        return Verdict(False, "no rotation", "the relative motion does not rotate (θ = 0): "
                                             "the screw axis is not defined (sin(θ/2) = 0, "
                                             "cot(θ/2) infinite). Then the motion is the "
                                             "translation p alone, and its fraction t is the "
                                             "translation t p", v.expected)
    return v


def _sclerp_accept(dq0, dq1, t):
    return [-kl.dual_quat_sclerp(dq0, dq1, t)]


def sclerp_check() -> Check:
    return Check("sclerp", 6, "screw linear interpolation q̂0 (q̂0* q̂1)^t", _sclerp_cases,
                 sclerp_model, SCLERP_MISTAKES, accept=_sclerp_accept,
                 judge=either_sign(Rule(sclerp_model, SCLERP_MISTAKES, _sclerp_accept),
                                   _sclerp_special))
