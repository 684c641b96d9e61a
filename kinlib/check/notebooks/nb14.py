"""Notebook 14 · configuration-space planning: C-space obstacles, seed 001's metric, A*."""

import numpy as np

from .._verdict import Mistake
from ._make import choice, expression, value

#: the notebook's arm (metres)
L1, L2 = 1.0, 0.8
#: exercise 14.3: the configuration and the joint step
THETA_STEP, DTHETA_STEP = (0.4, np.pi / 2), (0.01, -0.01)
#: exercise 14.5: the grid and the two configurations
N_EMPTY, FROM, TO = 96, (3.0, 0.0), (-3.0, 0.0)


def _symbols():
    import sympy as sp

    return (*sp.symbols("phi_1 phi_2", real=True), *sp.symbols("l_1 l_2", real=True))


def _g_abs():
    """J'ᵀJ' for the end x = l1 cos φ1 + l2 cos φ2, y = l1 sin φ1 + l2 sin φ2."""
    import sympy as sp

    p1, p2, a1, a2 = _symbols()
    x = a1 * sp.cos(p1) + a2 * sp.cos(p2)
    y = a1 * sp.sin(p1) + a2 * sp.sin(p2)
    J = sp.Matrix([x, y]).jacobian([p1, p2])
    return J.T * J


def _off_diagonal(upper, lower):
    import sympy as sp

    *_, a1, a2 = _symbols()
    return sp.Matrix([[a1**2, upper], [lower, a2**2]])


def _g_abs_near_misses():
    """(key, message, model) of the classic slips in J'ᵀJ', tried after sign/swap."""
    import sympy as sp

    p1, p2, a1, a2 = _symbols()
    cross = a1 * a2 * sp.cos(p1 - p2)
    c2 = sp.cos(p2 - p1)  # cos θ2, with θ2 = φ2 − φ1
    dh = sp.Matrix([[a1**2 + a2**2 + 2 * a1 * a2 * c2, a2**2 + a1 * a2 * c2],
                    [a2**2 + a1 * a2 * c2, a2**2]])
    return [
        ("seed typo", "your off-diagonal is −l1 l2 cos(φ1 + φ2): one entry of J' has the wrong "
                      "sign. ∂y/∂φ1 = +l1 cos φ1 (seed 001's line for dy/dt has a stray minus "
                      "in front of (l1 c1 + l2 c12); its matrix has it right)",
         _off_diagonal(-a1 * a2 * sp.cos(p1 + p2), -a1 * a2 * sp.cos(p1 + p2))),
        ("angle sum", "cos φ1 cos φ2 + sin φ1 sin φ2 is cos(φ1 − φ2), the cosine of the angle "
                      "between the two links, not cos(φ1 + φ2)",
         _off_diagonal(a1 * a2 * sp.cos(p1 + p2), a1 * a2 * sp.cos(p1 + p2))),
        ("doubled", "the off-diagonal entries are twice too big: in Δφᵀ G' Δφ each of the two "
                    "enters once, so the cross term 2 l1 l2 cos(φ1 − φ2) Δφ1 Δφ2 of (Δs)² is "
                    "shared between them",
         _off_diagonal(2 * cross, 2 * cross)),
        ("symmetric", "your matrix gives the right (Δs)², but J'ᵀJ' is symmetric: the cross term "
                      "2 l1 l2 cos(φ1 − φ2) Δφ1 Δφ2 is split evenly between the two "
                      "off-diagonal entries", _off_diagonal(2 * cross, 0)),
        ("symmetric", "your matrix gives the right (Δs)², but J'ᵀJ' is symmetric: the cross term "
                      "2 l1 l2 cos(φ1 − φ2) Δφ1 Δφ2 is split evenly between the two "
                      "off-diagonal entries", _off_diagonal(0, 2 * cross)),
        ("cross term", "the cross term is missing: the two links' velocities, l1 Δφ1 and "
                       "l2 Δφ2, are not perpendicular; their dot product gives the off-diagonal "
                       "entries l1 l2 cos(φ1 − φ2)", _off_diagonal(0, 0)),
        ("coordinates", "that is the DH matrix JᵀJ with θ2 = φ2 − φ1 put in: the matrix changes "
                        "too, because the step is measured in other coordinates (Δφ1 = Δθ1, "
                        "Δφ2 = Δθ1 + Δθ2). Differentiate x, y with respect to φ1 and φ2", dh),
    ]


def _g_abs_swapped():
    p1, p2, *_ = _symbols()
    return _g_abs().xreplace({p1: p2, p2: p1})


def _g_abs_mistakes():
    """The slips in J'ᵀJ' as mistakes: the columns of J' swapped, then the classic ones."""
    swapped = Mistake("swapped", "φ_1 and φ_2 are swapped in your answer: are the columns of "
                                 "J' in the order (φ2, φ1)? Column k is ∂(x, y)/∂φk, so G'11 "
                                 "belongs to link 1: l1²", _g_abs_swapped)
    return [swapped, *(Mistake(key, message, lambda m=model: m)
                       for key, message, model in _g_abs_near_misses())]


def _ee_step(dtheta=DTHETA_STEP):
    from ...planning.cspace import planar_2r_metric

    return float(planar_2r_metric(THETA_STEP, dtheta, L1, L2))


def _empty_grid():
    from ...planning.cspace import planar_2r_cspace

    return planar_2r_cspace(L1, L2, [], n=N_EMPTY)


def _seam_cost():
    from ...planning.astar import astar

    return astar(_empty_grid(), FROM, TO, metric="joint").cost


def _moves(rounding):
    """Moves from FROM's cell to TO's, the short way round and the long way, with the cells
    found by ``floor`` (as the grid does) or by ``round`` (the slip)."""
    h = 2 * np.pi / N_EMPTY
    i, j = (int(rounding((t + np.pi) / h)) % N_EMPTY for t in (FROM[0], TO[0]))
    across = (j - i) % N_EMPTY
    return min(across, N_EMPTY - across), max(across, N_EMPTY - across), h


EXERCISES = [
    choice("14.1", "predict", "the C-space region of a disc that only link 2 can reach",
           {"a": "a vertical band: a range of θ1, every θ2",
            "b": "a horizontal band: a range of θ2, every θ1",
            "c": "a bounded blob whose θ2 range shifts with θ1"}, "c",
           {"a": ("link 1", "a band over every θ2 is what an obstacle within reach of link 1 "
                            "makes: link 1's place depends on θ1 alone, so it collides whatever "
                            "θ2 is. This disc is farther from the base than l1 + margin; only "
                            "link 2 can touch it, and link 2 moves with both angles"),
            "b": ("theta2 alone", "a band over every θ1 would mean the arm collides at every "
                                  "turn about the base: only an obstacle all round the base "
                                  "(a ring) does that. Link 2 starts at the elbow, which "
                                  "moves with θ1, and points along θ1 + θ2: whether it hits "
                                  "the disc depends on both angles")}),
    expression("14.2", "the metric J'ᵀJ' in absolute link angles", _g_abs, *_g_abs_mistakes(),
               what="a 2×2 sympy Matrix",
               explain="G' = [[l1², l1 l2 cos(φ1 − φ2)], [l1 l2 cos(φ1 − φ2), l2²]]: again one "
                   "angle only, the angle between the two links (φ2 − φ1 = θ2). The end's "
                   "velocity is the sum of l1 δφ1 and l2 δφ2, each perpendicular to its link; "
                   "the off-diagonal entries are their dot product"),
    value("14.3", "compute", "how far the end moves for δθ = (0.01, −0.01) at θ = (0.4, π/2)",
          _ee_step,
          Mistake("joint metric", "that is the joint-space length √(δθ1² + δθ2²) of the step, "
                                  "in radians; the question is how far the end moves, in "
                                  "metres: |J δθ|", lambda: np.hypot(*DTHETA_STEP)),
          Mistake("link 2", "l2·0.01 is how far the end would move if only link 2 turned; here "
                            "link 1 turns by δθ1 = 0.01 and carries the elbow, while link 2 "
                            "keeps its direction (δφ2 = δθ1 + δθ2 = 0)", lambda: L2 * 0.01),
          Mistake("both links", "(l1 + l2)·0.01 adds up a motion for each link; but link 2 "
                                "keeps its direction (δθ1 + δθ2 = 0): it only translates with "
                                "the elbow, which moves l1·δθ1",
                  lambda: L1 * abs(DTHETA_STEP[0]) + L2 * abs(DTHETA_STEP[1])),
          Mistake("squared", "that is (Δs)² = δθᵀ JᵀJ δθ, the square of the distance: take its "
                             "square root", lambda: _ee_step() ** 2),
          Mistake("step sign", "you used δθ2 = +0.01: the step is (0.01, −0.01), link 2 turns "
                               "back at the elbow by as much as link 1 turns forward",
                  lambda: _ee_step((DTHETA_STEP[0], -DTHETA_STEP[1]))),
          what="a number (metres)",
          explain="l1·δθ1 = 0.01 m: link 2 keeps its direction (δφ2 = δθ1 + δθ2 = 0), so it "
                  "only translates with the elbow, which moves l1·δθ1. With G' and "
                  "δφ = (0.01, 0): Δs² = l1² δφ1²"),
    choice("14.4", "predict", "which optimal path bends the elbow further",
           {"a": "the joint-metric path", "b": "the end-effector-metric path",
            "c": "neither: both metrics find the same path"}, "b",
           {"a": ("joint", "the joint metric charges every radian the same wherever the arm "
                           "is, so bending the elbow out of the way and back is a detour it "
                           "pays for in full: its path heads straight for the goal round the "
                           "obstacles. The end-effector metric is the one for which a bent "
                           "elbow is cheap: the end, then close to the base, moves little when "
                           "θ1 turns"),
            "c": ("same path", "the two metrics weigh the same move differently: the joint "
                               "metric charges |δθ|, the end-effector metric √(δθᵀJᵀJδθ), "
                               "which depends on θ2. With the elbow bent, turning θ1 moves "
                               "the end on a small circle round the base: cheap for the "
                               "end-effector metric only")}),
    value("14.5", "compute", "the joint-metric cost across the seam θ1 = ±π",
          _seam_cost,
          Mistake("long way", "that is the long way round, through θ1 = 0; θ1 = π and −π are "
                              "the same angle, so the grid wraps: after cell 95 comes cell 0",
                  lambda: (lambda s, long, h: long * h)(*_moves(np.floor))),
          Mistake("cells", "you counted the cells on the path; the cost adds up the moves "
                           "between them, one fewer, each of length h = 2π/96",
                  lambda: (lambda s, long, h: (s + 1) * h)(*_moves(np.floor))),
          Mistake("rounded", "θ lies in cell ⌊(θ + π)/h⌋ (cell k covers [−π + kh, −π + (k+1)h)): "
                             "θ1 = 3.0 is in cell 93 ((3.0 + π)/h = 93.8, rounded down), not 94",
                  lambda: (lambda s, long, h: s * h)(*_moves(np.round))),
          Mistake("exact angle", "2π − 6 is the exact angle between 3.0 and −3.0 the short "
                                 "way round; the planner moves from cell centre to cell centre, "
                                 "so it charges a whole number of grid steps h = 2π/96",
                  lambda: 2 * np.pi - abs(FROM[0] - TO[0])),
          Mistake("unwrapped", "|3.0 − (−3.0)| = 6 rad is the long way round through θ1 = 0, "
                               "and off the grid; the short way crosses θ1 = ±π",
                  lambda: abs(FROM[0] - TO[0])),
          what="a number (radians)",
          explain="θ1 = 3.0 lies in cell ⌊(3.0 + π)/h⌋ = 93 and θ1 = −3.0 in cell 2; the "
                  "short way crosses the seam, 93 → 94 → 95 → 0 → 1 → 2: five moves of "
                  "h = 2π/96 each, 5h ≈ 0.327 rad"),
]
