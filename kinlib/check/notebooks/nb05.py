"""Notebook 05 · angle-axis and Cayley: the split b = b∥ + b⊥ (seed 000), the inverse
problem (angle from the trace, axis from the skew part), Cayley's parameters of a matrix."""

import numpy as np

from .._symbolic import expression_judge
from .._verdict import Mistake, Verdict
from ..judges import axis_angle_judge
from ..mistakes import DEGREES, HALF_ANGLE, SIGN, SWAPPED, TRANSPOSED
from ._make import judged, value


def _symbols():
    import sympy as sp

    k = sp.Matrix(sp.symbols("k_x k_y k_z", real=True))
    b = sp.Matrix(sp.symbols("b_x b_y b_z", real=True))
    return k, b


def _b_par():
    k, b = _symbols()
    return k * k.dot(b)


def _b_perp():
    k, b = _symbols()
    return b - k * k.dot(b)


def _split_judge(expected, near, form=None):
    """An exact sympy judge (k a unit vector) that also names the mistakes ``near``. With
    ``form = (key, message, allowed, forbidden)``, a right answer that is, as a polynomial
    (without |k| = 1), the ``forbidden`` model and not the ``allowed`` one is written in a
    way the exercise excludes, and named so."""
    k, _ = _symbols()
    base = expression_judge(expected, unit=[list(k)], what="a 3×1 sympy Matrix in k and b",
                            mistakes=near)
    if form is None:
        return base
    key, message, allowed, forbidden = form

    def judge(args, got):
        verdict = base(args, got)
        if not verdict.ok:
            return verdict
        import sympy as sp

        from ...symbolic import sym_equal

        try:
            g = sp.Matrix(got) if isinstance(got, list | tuple | np.ndarray) else got
            names = {s.name: s for s in expected().free_symbols}
            g = g.xreplace({s: names[s.name] for s in g.free_symbols if s.name in names})
            excluded = not sym_equal(g, allowed()) and sym_equal(g, forbidden())
        except Exception:  # outside what the exact reduction decides: it is right
            excluded = False
        return Verdict(False, key, message, expected()) if excluded else verdict
    return judge


def _sym(f):
    """A model built from the notebook's k and b."""
    return lambda: f(*_symbols())


_PAR_NEAR = [
    Mistake("along b", "(k·b) b points along b; b∥ lies along the axis: (k·b) k",
            _sym(lambda k, b: b * k.dot(b))),
    Mistake("perpendicular", "that is b⊥ = b − (k·b) k, the part across the axis; b∥ is the "
                             "part you subtracted", _sym(lambda k, b: b - k * k.dot(b))),
    Mistake("operator", "that is the operator k kᵀ itself (the projection onto the axis): "
                        "apply it to b, b∥ = k kᵀ b = (k·b) k", _sym(lambda k, b: k * k.T)),
    Mistake("scalar", "k·b is a number, the length of b∥ along the unit axis; b∥ is that "
                      "number times the direction k", _sym(lambda k, b: k.dot(b))),
]

_PERP_NEAR = [
    Mistake("quarter turn", "k × b is b⊥ turned by 90° about k (perpendicular to b⊥, of the "
                            "same length); one more cross product with k turns it on, to "
                            "−b⊥: so b⊥ = −k × (k × b)", _sym(lambda k, b: k.cross(b))),
    Mistake("associative", "(k × k) × b is zero, since k × k = 0: the cross product is not "
                           "associative, and the brackets must be k × (k × b)",
            _sym(lambda k, b: k.cross(k).cross(b))),
    Mistake("parallel", "that is b∥ = (k·b) k, the part along the axis; b⊥ is the rest",
            _sym(lambda k, b: k * k.dot(b))),
]

_PERP_FORM = ("dot product", "that is b⊥ indeed, but written as b − (k·b) k, with a dot product "
                             "(or as b minus your b∥): the exercise asks for cross products "
                             "only. What does k × b do to b⊥, and what does one more cross "
                             "product with k do to that?",
              _sym(lambda k, b: -k.cross(k.cross(b))), _sym(lambda k, b: b - k * k.dot(b)))


# 05.3: the inverse problem for the notebook's R_try
def _R_try():
    from ...spatial.euler import matrix_from_euler

    return matrix_from_euler([0.7, -1.1, 0.4], "ZYX")


def _axis_angle_of_R_try(args, got):
    return axis_angle_judge((_R_try(),), got)


# 05.4: Cayley's parameters of the notebook's R_cay_try, a product of three turns
def _R_cay():
    from ...spatial.euler import matrix_from_euler

    return matrix_from_euler(np.deg2rad([30.0, -50.0, 80.0]), "ZYX")


def _s_cay():
    from ...spatial.cayley import cayley_from_matrix

    return cayley_from_matrix(_R_cay())


def _axis_angle_cay():
    from ...spatial.axis_angle import axis_angle_from_matrix

    return axis_angle_from_matrix(_R_cay())


def _skew_part():
    from ...spatial.rotations import vee

    R = _R_cay()
    return vee(R - R.T) / 2


EXERCISES = [
    judged("05.1", "derive", "b∥, the part of b along the axis",
           _split_judge(_b_par, _PAR_NEAR),
           diagnoses=(SIGN.key, "along b", "perpendicular", "operator", "scalar"),
           explain="the operator is the projection matrix k kᵀ: b∥ = (k·b) k = k (kᵀ b) = "
                   "(k kᵀ) b, and the rest is b⊥ = b − b∥"),
    judged("05.2", "derive", "b⊥ with cross products",
           _split_judge(_b_perp, _PERP_NEAR, _PERP_FORM),
           diagnoses=(SIGN.key, "quarter turn", "associative", "parallel", "dot product"),
           explain="k × b is b⊥ turned a quarter turn about k (k × b∥ = 0); one more cross "
                   "product with k turns it another quarter, to −b⊥. So b⊥ = −k × (k × b), "
                   "which is b − (k·b) k by the rule a × (b × c) = b (a·c) − c (a·b) and "
                   "|k| = 1"),
    judged("05.3", "compute", "angle from the trace, axis from the skew part",
           _axis_angle_of_R_try, diagnoses=("axis sign", DEGREES.key, "unit"),
           explain="the trace gives cos θ and the skew part sin θ k: for an angle well away "
                   "from 0 and 180° that is all you need. Below: what happens near them"),
    value("05.4", "compute", "Cayley's parameters of a rotation matrix", _s_cay,
          TRANSPOSED.of(lambda: -_s_cay(), "that is −s, the parameters of Rᵀ, the opposite "
                                           "turn: (I − S) R = I + S gives R − I = S (I + R), "
                                           "so S = (R − I)(I + R)⁻¹, not (I − R)(I + R)⁻¹; "
                                           "by the other route, the axis points the wrong way"),
          SWAPPED.of(lambda: _s_cay()[::-1], "s_x and s_z are swapped: that is S read the way "
                                             "seed 002 prints it (S₁₂ = −s_x); the skew matrix "
                                             "of s, as kl.skew builds it, has S₃₂ = s_x, "
                                             "S₁₃ = s_y, S₂₁ = s_z"),
          HALF_ANGLE.of(lambda: np.tan(_axis_angle_cay()[1]) * _axis_angle_cay()[0],
                        "that is tan θ k: Cayley's parameters use the half angle, "
                        "s = tan(θ/2) k"),
          Mistake("quaternion", "sin(θ/2) k is the vector part of the unit quaternion; "
                                "Cayley's parameters divide it by the scalar part cos(θ/2): "
                                "s = tan(θ/2) k",
                  lambda: np.sin(_axis_angle_cay()[1] / 2) * _axis_angle_cay()[0]),
          Mistake("skew part", "that is sin θ k, the skew part (R − Rᵀ)/2 of R read as a "
                               "vector: Cayley's S is not the skew part of R. Solve "
                               "(I − S) R = I + S for S", _skew_part),
          what="a 3-vector",
          explain="from (I − S) R = I + S: R − I = S (I + R), so S = (R − I)(I + R)⁻¹ "
                  "(R and S commute, so the order does not matter), and tan(θ/2) k gives the "
                  "same. Both need a rotation that is not a half turn: I + R must be "
                  "invertible, tan(θ/2) finite"),
]
