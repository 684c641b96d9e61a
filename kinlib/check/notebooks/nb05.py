"""Notebook 05 · angle-axis and Cayley: the split b = b∥ + b⊥ (seed 000), the inverse
problem (angle from the trace, axis from the skew part), Cayley's parameters tan(θ/2) k."""

import numpy as np

from .._symbolic import expression_judge
from .._verdict import Mistake, Verdict
from ..judges import axis_angle_judge
from ..mistakes import DEGREES, HALF_ANGLE, SIGN, TRANSPOSED
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


def _split_judge(expected, near):
    """An exact sympy judge (k a unit vector) that also names the near misses ``near``:
    ``(key, message, model)``, tried when the answer is not right and not the negative."""
    k, _ = _symbols()
    unit = [list(k)]   # one unit vector (nested: the probe of a wrong answer normalises it)
    base = expression_judge(expected, unit=unit, what="a 3×1 sympy Matrix in k and b")

    def judge(args, got):
        import sympy as sp

        from ...symbolic import sym_equal

        verdict = base(args, got)
        if verdict.ok or verdict.key not in ("wrong", "shape", "type"):
            return verdict
        try:
            g = sp.Matrix(got) if isinstance(got, list | tuple | np.ndarray) else got
            g = g if isinstance(g, sp.MatrixBase) else sp.sympify(g, strict=True)
            names = {s.name: s for s in expected().free_symbols}
            g = g.xreplace({s: names[s.name] for s in g.free_symbols if s.name in names})
        except Exception:  # not something sympy reads: the base verdict stands
            return verdict
        for key, message, model in near:
            m = model()
            if isinstance(m, sp.MatrixBase) != isinstance(g, sp.MatrixBase):
                continue
            if isinstance(m, sp.MatrixBase) and m.shape != g.shape:
                continue
            try:
                same = sym_equal(g, m, unit)
            except Exception:  # outside what the exact reduction decides
                same = False
            if same:
                return Verdict(False, key, message, expected())
        return verdict
    return judge


def _sym(f):
    """A model built from the notebook's k and b."""
    return lambda: f(*_symbols())


_PAR_NEAR = [
    ("along b", "(k·b) b points along b; b∥ lies along the axis: (k·b) k",
     _sym(lambda k, b: b * k.dot(b))),
    ("perpendicular", "that is b⊥ = b − (k·b) k, the part across the axis; b∥ is the part "
                      "you subtracted", _sym(lambda k, b: b - k * k.dot(b))),
    ("operator", "that is the operator k kᵀ itself (the projection onto the axis): apply it "
                 "to b, b∥ = k kᵀ b = (k·b) k", _sym(lambda k, b: k * k.T)),
    ("scalar", "k·b is a number, the length of b∥ along the unit axis; b∥ is that number "
               "times the direction k", _sym(lambda k, b: k.dot(b))),
]

_PERP_NEAR = [
    ("quarter turn", "k × b is b⊥ turned by 90° about k (perpendicular to b⊥, of the same "
                     "length); one more cross product with k turns it on, to −b⊥: so "
                     "b⊥ = −k × (k × b)", _sym(lambda k, b: k.cross(b))),
    ("associative", "(k × k) × b is zero, since k × k = 0: the cross product is not "
                    "associative, and the brackets must be k × (k × b)",
     _sym(lambda k, b: k.cross(k).cross(b))),
    ("parallel", "that is b∥ = (k·b) k, the part along the axis; b⊥ is the rest",
     _sym(lambda k, b: k * k.dot(b))),
]


# 05.3: the inverse problem for the notebook's R_try
def _R_try():
    from ...axis_angle import matrix_from_axis_angle

    return matrix_from_axis_angle([0.0, 0.6, 0.8], 2.0)


def _axis_angle_of_R_try(args, got):
    return axis_angle_judge((_R_try(),), got)


# 05.4: Cayley's parameters of a 100° turn about (2, −1, 2)/3
K_CAY, DEG_CAY = np.array([2.0, -1.0, 2.0]) / 3.0, 100.0


def _s_cay():
    from ...axis_angle import matrix_from_axis_angle
    from ...cayley import cayley_from_matrix

    return cayley_from_matrix(matrix_from_axis_angle(K_CAY, np.deg2rad(DEG_CAY)))


EXERCISES = [
    judged("05.1", "derive", "b∥, the part of b along the axis",
           _split_judge(_b_par, _PAR_NEAR),
           diagnoses=(SIGN.key, "along b", "perpendicular", "operator", "scalar")),
    judged("05.2", "derive", "b⊥ with cross products",
           _split_judge(_b_perp, _PERP_NEAR),
           diagnoses=(SIGN.key, "quarter turn", "associative", "parallel")),
    judged("05.3", "compute", "angle from the trace, axis from the skew part",
           _axis_angle_of_R_try, diagnoses=("axis sign", DEGREES.key)),
    value("05.4", "compute", "Cayley's parameters s = tan(θ/2) k", _s_cay,
          HALF_ANGLE.of(lambda: np.tan(np.deg2rad(DEG_CAY)) * K_CAY,
                        "that is tan θ k: Cayley's parameters use the half angle, "
                        "s = tan(θ/2) k"),
          DEGREES.of(lambda: np.tan(DEG_CAY / 2) * K_CAY,
                     "np.tan took 50 as radians: convert the angle first, "
                     "np.tan(np.deg2rad(100) / 2)"),
          Mistake("quaternion", "sin(θ/2) k is the vector part of the unit quaternion; "
                                "Cayley's parameters divide it by the scalar part cos(θ/2): "
                                "s = tan(θ/2) k", lambda: np.sin(np.deg2rad(DEG_CAY) / 2) * K_CAY),
          TRANSPOSED.of(lambda: -_s_cay(), "that is s of Rᵀ, the opposite turn: the "
                                           "axis points the wrong way (vee(R − Rᵀ), not "
                                           "vee(Rᵀ − R))"),
          what="a 3-vector"),
]
