"""Notebook 10 · inverse kinematics I, the planar 2R arm: c2 from the law of cosines, seed
001's closed form, the number of solutions across the workspace, equal links at the base."""

import numpy as np

from .._verdict import RIGHT, Mistake, Verdict, as_numeric, close
from ..mistakes import DEGREES, OTHER_ELBOW, SIGN, SWAPPED
from ._make import choice, expression, judged, value

# --- 10.1 · c2 from the law of cosines ------------------------------------------------------


def _c2(factor, precedence=False):
    """c2 times ``factor``; with ``precedence``, typed as ``(...) / 2 * l1 * l2``."""
    def model():
        import sympy as sp

        x, y = sp.symbols("x y", real=True)
        l1, l2 = sp.symbols("l_1 l_2", positive=True)
        if precedence:
            return factor * (x**2 + y**2 - l1**2 - l2**2) / 2 * l1 * l2
        return factor * (x**2 + y**2 - l1**2 - l2**2) / (2 * l1 * l2)
    return model


_C2_MISTAKES = (
    SIGN.of(_c2(-1), "that is −c2 = cos(π − θ2): the cosine of the triangle's angle at the "
                     "elbow. The forward kinematics gives x² + y² = l1² + l2² + 2 l1 l2 c2, "
                     "with a plus, because θ2 is measured from link 1, not inside the "
                     "triangle"),
    Mistake("factor 2", "the 2 of 2 l1 l2 c2 is missing: divide by 2 l1 l2", _c2(2)),
    Mistake("precedence", "`/ 2 * L1 * L2` divides by 2 and then multiplies by l1 l2: write "
                          "`/ (2 * L1 * L2)`", _c2(1, precedence=True)),
)


# --- 10.2 · seed 001's inverse kinematics, elbow "down" --------------------------------------


def _wrap(a):
    from ..._validate import wrap_angle  # kinlib's one wrap: into (−π, π]

    return wrap_angle(a)


def _down(x, y, l1, l2):
    from ...kinematics.planar import planar_2r_ik

    sol = planar_2r_ik(x, y, l1, l2, elbow="down")
    return np.array([sol.theta1, sol.theta2], dtype=float)


def _formula(x, y, l1, l2, *, sign=1.0, phi=None, beta=None, plus=False):
    """Seed 001's formulas with one piece replaced by a mistake."""
    c2 = (x * x + y * y - l1 * l1 - l2 * l2) / (2 * l1 * l2)
    s2 = sign * np.sqrt(1 - c2 * c2)
    phi = np.arctan2(y, x) if phi is None else phi(x, y)
    beta = np.arctan2(l2 * s2, l1 + l2 * c2) if beta is None else beta(l2 * s2, l1 + l2 * c2)
    return np.array([phi + beta if plus else phi - beta, np.arctan2(s2, c2)])


_IK_MISTAKES = [
    OTHER_ELBOW.of(lambda x, y, l1, l2: _formula(x, y, l1, l2, sign=-1.0),
                   'this is the elbow "up": s2 = −√(1 − c2²), θ2 ≤ 0. The exercise asks for '
                   '"down", s2 = +√(1 − c2²), θ2 ≥ 0'),
    Mistake("acos", "wrong for targets below the x axis, which come out mirrored above it: "
                    "arccos(x / r) only returns angles in [0, π]. The polar angle of (x, y) "
                    "is atan2(y, x)",
            lambda x, y, l1, l2: _formula(x, y, l1, l2, phi=lambda x, y: np.arccos(
                x / np.hypot(x, y)))),
    Mistake("atan", "arctan(y / x) only returns angles in (−π/2, π/2): it cannot tell (x, y) "
                    "from (−x, −y). Use np.arctan2(y, x), which sees both signs",
            lambda x, y, l1, l2: _formula(x, y, l1, l2, phi=lambda x, y: np.arctan(y / x))),
    Mistake("atan", "arctan(l2 s2 / (l1 + l2 c2)) loses the quadrant when l1 + l2 c2 < 0 "
                    "(the elbow folded far back): use np.arctan2(l2 s2, l1 + l2 c2)",
            lambda x, y, l1, l2: _formula(x, y, l1, l2, beta=lambda s, c: np.arctan(s / c))),
    Mistake("beta sign", "θ1 = atan2(y, x) − atan2(l2 s2, l1 + l2 c2), with a minus: the "
                         "polar angle of the target is θ1 plus the angle of the tip seen "
                         "from link 1",
            lambda x, y, l1, l2: _formula(x, y, l1, l2, plus=True)),
    SWAPPED.of(lambda x, y, l1, l2: _down(x, y, l1, l2)[::-1],
               "you returned (θ2, θ1): return (theta1, theta2)"),
    DEGREES.of(lambda x, y, l1, l2: np.rad2deg(_down(x, y, l1, l2)),
               "you returned degrees: np.arctan2 gives radians, and the course's angles "
               "stay in radians"),
]


def _same(a, b, atol=1e-6) -> bool:
    """The same angles, modulo 2π."""
    return close(_wrap(a - b), np.zeros(np.shape(b)), atol)


def _ik_judge(args, got):
    """(θ1, θ2) is right when it equals kinlib's elbow-"down" solution modulo 2π."""
    expected = _down(*args)
    a, bad = as_numeric(got, (2,), "(theta1, theta2)")
    if a is None:
        return Verdict(False, bad.key, bad.message, expected)
    if _same(a, expected):
        return RIGHT
    for m in _IK_MISTAKES:
        try:
            with np.errstate(all="ignore"):
                wrong = np.asarray(m.model(*args), dtype=float)
        except Exception:  # a model that does not apply to this case
            continue
        if (wrong.shape == a.shape and np.isfinite(wrong).all() and _same(a, wrong)
                and not _same(wrong, expected)):
            return Verdict(False, m.key, m.message, expected)
    err = float(np.abs(_wrap(a - expected)).max())
    return Verdict(False, "wrong", f"differs from the right angles by up to {err:.3g} rad "
                                   "(modulo 2π)", expected)


def _ik_cases():
    """Reachable targets, well inside the annulus, in every quadrant, for three arms."""
    rng = np.random.default_rng(10)
    out = []
    for l1, l2 in ((0.6, 0.9), (1.0, 0.7), (0.8, 0.8)):
        lo, hi = abs(l1 - l2) + 0.05, l1 + l2 - 0.05
        angles = (np.arange(8) + 0.5) * np.pi / 4 - np.pi + rng.uniform(-0.3, 0.3, 8)
        radii = np.sqrt(rng.uniform(lo**2, hi**2, 8))
        radii[:2] = lo + 0.02, lo + 0.1   # near the inner circle: l1 + l2 c2 < 0 for 0.6/0.9
        out += [(float(r * np.cos(a)), float(r * np.sin(a)), l1, l2)
                for r, a in zip(radii, angles, strict=True)]
    return out


# --- 10.3 · how many solutions, on the outer circle, inside, outside -------------------------

L1, L2 = 1.0, 0.7


def _n_solutions(r, l1=L1, l2=L2, tol=1e-6):
    """Distinct IK solutions of a target at distance r on the x axis, counted with kinlib."""
    from ...kinematics.planar import planar_2r_ik

    up, down = (planar_2r_ik(r, 0.0, l1, l2, elbow=e) for e in ("up", "down"))
    if not up.success:
        return 0
    same = abs(_wrap(up.theta1 - down.theta1)) < tol and abs(up.theta2 - down.theta2) < tol
    return 1 if same else 2


def _counts():
    return np.array([_n_solutions(L1 + L2), _n_solutions(1.0), _n_solutions(1.9)], dtype=float)


# --- 10.4 · equal links, the target at the base ----------------------------------------------

_BASE = {"a": "none: the base is not in the workspace", "b": "one, the arm folded",
         "c": "two, folded one way or the other", "d": "infinitely many"}


def _base_option() -> str:
    """The option the mathematics gives: folded, the tip is at the base for every θ1."""
    from ...kinematics.planar import planar_2r_fk

    theta1 = np.linspace(-np.pi, np.pi, 13)
    tips = planar_2r_fk(theta1, np.pi, 0.8, 0.8)[:, :2, 3]
    return "d" if np.abs(tips).max() < 1e-12 else "b"


EXERCISES = [
    expression("10.1", "c2 from the law of cosines", _c2(1), *_C2_MISTAKES, swaps=(),
               what="a sympy expression in x, y, l_1, l_2 (the expression, not sympy's list)",
               explain="c2 = (x² + y² − l1² − l2²) / (2 l1 l2): the law of cosines solved for "
                   "the cosine of θ2. A real θ2 needs −1 ≤ c2 ≤ 1, which is the condition for "
                   "the target to be reachable (section 4)"),
    judged("10.2", "implement", 'seed 001\'s 2R inverse kinematics, elbow "down"', _ik_judge,
           cases=_ik_cases(),
           diagnoses=("other elbow", "acos", "atan", "beta sign", "swapped", "degrees"),
           explain='for elbow "up" change one sign only, s2 = −√(1 − c2²): θ2 and β change '
                   "sign with it. kinlib's `planar_2r_ik(x, y, l1, l2, elbow=\"down\")` is "
                   "this function, for arrays of targets too"),
    value("10.3", "predict", "how many solutions on the outer circle, inside, outside", _counts,
          Mistake("boundary", "on the outer circle c2 = 1 and s2 = 0: the two elbows "
                              "coincide (the arm stretched straight, θ2 = 0), one solution",
                  lambda: [2, 2, 0]),
          Mistake("boundary reachable", "the outer circle belongs to the workspace: the arm "
                                        "stretched straight (θ2 = 0) reaches it, once",
                  lambda: [0, 2, 0]),
          Mistake("one inside", "inside the annulus |c2| < 1, so s2 = ±√(1 − c2²) has two "
                                "values: two elbows", lambda: [1, 1, 0]),
          Mistake("closest", "outside the annulus there is no solution: kinlib returns the "
                             "closest configuration, but with success=False — it does not "
                             "reach the target", lambda: [1, 2, 1]),
          what="three numbers",
          explain="inside the annulus |c2| < 1 gives two values of s2, two elbows; on a circle "
                  "s2 = 0 and they coincide; outside no θ2 exists"),
    choice("10.4", "predict", "equal links, the target at the base", _BASE, _base_option(),
           {"a": ("excluded", "with l1 = l2 the inner circle has radius |l1 − l2| = 0: the "
                              "base is in the workspace, reached with the arm folded"),
            "b": ("theta1 free", "folded, θ2 = π, yes — but then the tip is at the base "
                                 "whatever θ1 is: θ1 is free"),
            "c": ("theta1 free", "θ2 = π and θ2 = −π are the same fold, and for it θ1 is "
                                 "free: every θ1 puts the tip at the base")},
           explain="folded (θ2 = π) with l1 = l2 the tip sits on the base whatever θ1 is: a "
                   "whole circle of solutions (the formula for θ1 meets atan2(0, 0) twice)"),
]
