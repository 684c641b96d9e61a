"""The first functions of assignment 02 (forward kinematics): the standard DH matrix
(:func:`dh`, its mistake models :data:`DH_MISTAKES` and its cases), the same matrix derived
with sympy (:func:`dh_symbolic_check`) and the pose of a DH table's last frame
(:func:`fk_dh_reference`, the mistake models of the product of the A_i, the DH tables of
kinlib robots and the random tables of the cases); the matrix stack and ``assignment()``
are in :mod:`.forward_kinematics`, which imports these.
"""

from __future__ import annotations

from collections.abc import Callable
from functools import reduce

import numpy as np

import kinlib as kl

from .._checks import Check, Mistake
from .._symbolic import symbolic_check
from .common import DEGREES

__all__ = ["CRAIG", "DH_MISTAKES", "_dh_cases", "_fk_dh_cases", "_fk_mistakes", "_rot_transposed",
           "_row", "dh", "dh_symbolic_check", "dh_table_of", "fk_dh_reference"]

CRAIG = ("this is Craig's modified DH, A = Rx(α) Tx(a) Rz(θ) Tz(d) (the same as multiplying "
         "the four factors in reverse order): standard DH, used here, is "
         "A = Rz(θ) Tz(d) Tx(a) Rx(α), first about and along z, then along and about the new x")


# -- the DH matrix --------------------------------------------------------------------------
def dh(theta, d, a, alpha) -> np.ndarray:
    return kl.dh_transform(theta=theta, d=d, a=a, alpha=alpha)


def _rot_transposed(T) -> np.ndarray:
    T = np.array(T, dtype=float)
    T[:3, :3] = T[:3, :3].T.copy()
    return T


def _with_p(T, p) -> np.ndarray:
    T = np.array(T, dtype=float)
    T[:3, 3] = p
    return T


DH_MISTAKES = [  # (key, message, model(theta, d, a, alpha))
    ("modified", CRAIG, lambda t, d, a, al: kl.mdh_transform(theta=t, d=d, a=a, alpha=al)),
    ("transposed", "the rotation part is transposed (Rᵀ: the frames are mixed up, or the "
                   "signs of the sines swapped): R = Rz(θ) Rx(α), whose first column is "
                   "(cos θ, sin θ, 0) and third row (0, sin α, cos α)",
     lambda t, d, a, al: _rot_transposed(dh(t, d, a, al))),
    ("layout", "you returned the transpose of the whole 4×4: the translation "
               "(a cos θ, a sin θ, d) is the last column, and the last row is [0, 0, 0, 1]",
     lambda t, d, a, al: dh(t, d, a, al).T),
    ("degrees", DEGREES.message, lambda t, d, a, al: dh(np.deg2rad(t), d, a, np.deg2rad(al))),
    ("theta sign", "the signs of sin θ are flipped (you built Rz(−θ)): Rz(θ)'s first column "
                   "is (cos θ, sin θ, 0) and the translation is (a cos θ, a sin θ, d)",
     lambda t, d, a, al: dh(-t, d, a, al)),
    ("theta sign", "the signs of sin θ in the rotation part are flipped (Rz(−θ)): Rz(θ)'s "
                   "first column is (cos θ, sin θ, 0)",
     lambda t, d, a, al: _with_p(dh(-t, d, a, al), dh(t, d, a, al)[:3, 3])),
    ("alpha sign", "the signs of sin α are flipped (you built Rx(−α)): the third row of A is "
                   "(0, sin α, cos α, d), the second (sin θ, cos θ cos α, −cos θ sin α, a sin θ)",
     lambda t, d, a, al: dh(t, d, a, -al)),
    ("translation", "a cos θ and a sin θ are swapped: the translation is "
                    "(a cos θ, a sin θ, d), the point a along the x axis turned by θ",
     lambda t, d, a, al: _with_p(dh(t, d, a, al), [a * np.sin(t), a * np.cos(t), d])),
    ("translation", "the translation must be (a cos θ, a sin θ, d): the length a is measured "
                    "along the x axis after the rotation by θ about z, not before it",
     lambda t, d, a, al: _with_p(dh(t, d, a, al), [a, 0.0, d])),
    ("d axis", "d and a are swapped: d is the offset along z (the translation's third entry), "
               "a the length along the turned x axis", lambda t, d, a, al: dh(t, a, d, al)),
    ("d axis", "d slides along the old z axis, before the twist α: A = Rz(θ) Tz(d) Tx(a) "
               "Rx(α), so the translation is (a cos θ, a sin θ, d), not along the twisted z",
     lambda t, d, a, al: dh(t, 0.0, a, al) @ dh(0.0, d, 0.0, 0.0)),
]


def _dh_cases(rng):
    h = np.pi / 2
    fixed = [(0.0, 0.0, 0.0, 0.0), (h, 0.0, 2.0, 0.0), (0.0, 0.5, 1.0, h), (h, 0.3, 0.0, -h),
             (np.pi, 1.0, 1.0, np.pi), (0.3, 0.2, 0.1, 0.5), (-1.0, 0.0, 0.4318, 0.0),
             (0.0, 0.14909, 0.0, -h), (2.5, -0.7, -0.3, 1.2), (-h, 0.2, 0.6, h)]
    out = list(fixed)
    for _ in range(80):
        t, d, a = rng.uniform(-np.pi, np.pi), rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)
        al = rng.choice([0.0, h, -h, np.pi]) if rng.random() < 0.3 else rng.uniform(-np.pi,
                                                                                   np.pi)
        out.append(tuple(float(x) for x in (t, d, a, al)))
    return out


# -- the DH matrix derived with sympy -------------------------------------------------------
def _dh_symbols(rng):
    """The grader's symbols: plain, indexed (row i), a revolute row with an exact twist ±π/2,
    and a prismatic row (θ = π/2, d = q + an exact offset, a = 0)."""
    import sympy as sp

    i = int(rng.integers(1, 7))
    names = "theta d a alpha"
    sign = int(rng.choice([1, -1]))
    q, d, a, alpha = sp.symbols(f"q{i} d{i} a{i} alpha{i}", real=True)
    return [sp.symbols(names, real=True), sp.symbols(" ".join(f"{n}_{i}" for n in
                                                              names.split()), real=True),
            (q, d, a, sign * sp.pi / 2),
            (sp.pi / 2, q + sp.Rational(int(rng.integers(1, 10)), 10), 0, alpha)]


def dh_symbolic_check() -> Check:
    """``dh_symbolic(theta, d, a, alpha)``: A = Rz(θ) Tz(d) Tx(a) Rx(α) as a sympy Matrix."""
    message = {key: m for key, m, _ in reversed(DH_MISTAKES)}  # each key's first message

    def std(t, d, a, al):
        return kl.dh_transform(theta=t, d=d, a=a, alpha=al)
    return symbolic_check(
        "dh_symbolic", 3, "the DH matrix A = Rz(θ) Tz(d) Tx(a) Rx(α) derived with sympy",
        _dh_symbols, std, names=("theta", "d", "a", "alpha"),
        mistakes=[Mistake("modified", CRAIG, lambda t, d, a, al: kl.mdh_transform(
                      theta=t, d=d, a=a, alpha=al)),
                  Mistake("transposed", "each elementary rotation is transposed, the signs "
                                        "of its sines swapped (you built Rz(−θ) and Rx(−α)): "
                                        "Rz(θ)'s first column is (cos θ, sin θ, 0), Rx(α)'s "
                                        "third row (0, sin α, cos α)",
                          lambda t, d, a, al: std(-t, d, a, -al)),
                  Mistake("layout", message["layout"], lambda *p: std(*p).T),
                  Mistake("theta sign", message["theta sign"],
                          lambda t, d, a, al: std(-t, d, a, al)),
                  Mistake("alpha sign", message["alpha sign"],
                          lambda t, d, a, al: std(t, d, a, -al))],
        swaps=[(0, 3), (1, 2)])


# -- forward kinematics of a DH table -------------------------------------------------------
def _row_params(row, qi) -> tuple:
    """(θ, d, a, α) of one row at joint value qi."""
    if row["type"] == "prismatic":
        return row["theta"], qi + row["d"], row["a"], row["alpha"]
    return qi + row["theta"], row["d"], row["a"], row["alpha"]


def _chain(table, q, link: Callable, params: Callable = _row_params, reverse=False):
    mats = [link(*params(row, float(qi))) for row, qi in zip(table, q, strict=True)]
    return reduce(np.matmul, mats[::-1] if reverse else mats, np.eye(4))


def fk_dh_reference(table, q) -> np.ndarray:
    """T_0n = A_1(q_1) … A_n(q_n), standard DH."""
    return _chain(table, q, dh)


def _no_offsets(row, qi):
    if row["type"] == "prismatic":
        return row["theta"], qi, row["a"], row["alpha"]
    return qi, row["d"], row["a"], row["alpha"]


def _all_revolute(row, qi):
    return qi + row["theta"], row["d"], row["a"], row["alpha"]


def _fk_mistakes():
    out = [
        Mistake("order", "you multiplied in reverse order, A_n … A_1: the pose of the last "
                         "frame is T_0n = A_1(q_1) A_2(q_2) … A_n(q_n), the base's transform "
                         "leftmost", lambda tb, q: _chain(tb, q, dh, reverse=True)),
        Mistake("offsets", "the table's constants were dropped for the joint variable: "
                           "a revolute row has θ = q_i + theta (d from the table), a "
                           "prismatic row d = q_i + d (θ from the table)",
                lambda tb, q: _chain(tb, q, dh, _no_offsets)),
        Mistake("prismatic", "the prismatic rows were treated as revolute: for "
                             "type 'prismatic' q_i moves d (d = q_i + d), and θ is the "
                             "table's constant", lambda tb, q: _chain(tb, q, dh, _all_revolute)),
        Mistake("modified", "each A_i is " + CRAIG,
                lambda tb, q: _chain(tb, q, lambda *p: kl.mdh_transform(*p))),
        Mistake("transposed", "each row's matrix has its rotation part transposed: build "
                              "A_i = Rz(θ) Tz(d) Tx(a) Rx(α) as in dh_matrix",
                lambda tb, q: _chain(tb, q, lambda *p: _rot_transposed(dh(*p)))),
        Mistake("transposed", "each row's 4×4 matrix is transposed: the translation is the "
                              "last column of A_i, the last row is [0, 0, 0, 1]",
                lambda tb, q: _chain(tb, q, lambda *p: dh(*p).T)),
        Mistake("degrees", DEGREES.message,
                lambda tb, q: _chain(tb, q, lambda t, d, a, al: dh(np.deg2rad(t), d, a,
                                                                   np.deg2rad(al)))),
    ]
    for key, _, model in DH_MISTAKES[4:]:  # the sign and translation slips of dh_matrix
        out.append(Mistake("dh_matrix", f"each A_i has the mistake '{key}' of dh_matrix: "
                                        "make dh_matrix right first and build every A_i "
                                        "with it", lambda tb, q, m=model: _chain(tb, q, m)))
    return out


def _row(rtype, a, alpha, d, theta) -> dict:
    return {"a": float(a), "alpha": float(alpha), "d": float(d), "theta": float(theta),
            "type": rtype}


def dh_table_of(robot) -> list[dict]:
    """A kinlib DH robot's rows as the assignment's dicts (offset → theta or d)."""
    out = []
    for r in robot.dh_rows:
        pris = r.joint == "prismatic"
        out.append(_row(r.joint, r.a, r.alpha, r.offset if pris else r.d,
                        r.theta if pris else r.offset + r.theta))
    return out


def _random_table(rng, n):
    rows = []
    for _ in range(n):
        pris = rng.random() < 0.3
        alpha = rng.choice([0.0, np.pi / 2, -np.pi / 2]) if rng.random() < 0.4 \
            else rng.uniform(-np.pi, np.pi)
        a = 0.0 if rng.random() < 0.2 else rng.uniform(-1.0, 1.0)
        theta = rng.uniform(-np.pi, np.pi) if rng.random() < 0.8 else 0.0
        d = rng.uniform(-0.8, 0.8) if rng.random() < 0.8 else 0.0
        rows.append(_row("prismatic" if pris else "revolute", a, alpha, d, theta))
    return rows


def _random_q(rng, table):
    return np.array([rng.uniform(-1.0, 1.0) if r["type"] == "prismatic"
                     else rng.uniform(-np.pi, np.pi) for r in table])


def _fk_dh_cases(rng):
    from kinlib.robots import planar_2r, puma560

    puma = puma560()
    table = dh_table_of(puma)
    lo, hi = puma.limits.T
    out = [(table, np.array(puma.poses[k])) for k in ("zero", "table", "ready")]
    out += [(table, rng.uniform(lo, hi)) for _ in range(9)]
    for _ in range(8):
        l1, l2 = rng.uniform(0.3, 1.5, 2)
        out.append((dh_table_of(planar_2r(float(l1), float(l2))),
                    rng.uniform(-np.pi, np.pi, 2)))
    out.append(([_row("prismatic", 0.2, 0.0, 0.3, 0.5)], np.array([0.4])))
    out.append(([_row("revolute", 0.5, np.pi / 2, 0.2, 0.3),
                 _row("prismatic", 0.0, 0.0, 0.1, -np.pi / 2)], np.array([0.0, 0.0])))
    for i in range(80):
        tb = _random_table(rng, 2 + i % 5)
        if i % 4 == 0 and all(r["type"] == "revolute" for r in tb):
            tb[int(rng.integers(len(tb)))]["type"] = "prismatic"
        out.append((tb, _random_q(rng, tb)))
    return out
