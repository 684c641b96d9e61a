"""The first two functions of assignment 04 (configuration-space planning) and what the A*
judge shares with them: kinlib's cost table of the 8 moves on the torus (:func:`_costs`,
:func:`_move`, :func:`edge_cost_reference`), the check that an answer is a list of cells,
the neighbours' judge and mistake models, and the cost of one move with its mistake models
(:func:`edge_cost_model`) and cases; A* and ``assignment()`` are in :mod:`.planning`, which
imports these.
"""

from __future__ import annotations

from functools import lru_cache, partial

import numpy as np

import kinlib as kl
from kinlib.planning.cspace import NEIGHBOURS

from .._checks import RIGHT, Mistake, Verdict, fmt
from .._wire import Odd

__all__ = ["EIGHT", "MOVE_INDEX", "_cells", "_costs", "_edge_cases", "_edge_mistakes",
           "_empty_grid", "_judge_neighbors", "_key", "_move", "_neighbor_cases",
           "edge_cost_model", "edge_cost_reference"]

MOVE_INDEX = {(int(a), int(b)): k for k, (a, b) in enumerate(NEIGHBOURS)}
GL_X, GL_W = np.polynomial.legendre.leggauss(8)


@lru_cache(maxsize=64)
def _empty_grid(l1: float, l2: float, n1: int, n2: int) -> kl.CSpaceGrid:
    return kl.planar_2r_cspace(l1, l2, [], n=(n1, n2))


@lru_cache(maxsize=128)
def _costs(l1: float, l2: float, n1: int, n2: int, metric: str) -> np.ndarray:
    """kinlib's cost of each of the 8 moves from each cell, (n1, n2, 8)."""
    return _empty_grid(l1, l2, n1, n2).edge_costs(metric)


def _key(shape, l1, l2, metric) -> tuple:
    return float(l1), float(l2), int(shape[0]), int(shape[1]), metric


def _move(a, b, shape):
    """The move (di, dj) that takes cell a to its 8-neighbour b on the torus, or None."""
    d = tuple((int(b[k]) - int(a[k]) + 1) % int(shape[k]) - 1 for k in (0, 1))
    return d if d in MOVE_INDEX else None


def edge_cost_reference(cell_a, cell_b, shape, l1, l2, metric) -> float:
    """kinlib's cost of the move between neighbouring cells a and b."""
    k = MOVE_INDEX[_move(cell_a, cell_b, shape)]
    return float(_costs(*_key(shape, l1, l2, metric))[int(cell_a[0]), int(cell_a[1]), k])


# -- neighbours -----------------------------------------------------------------------------
def _cells(got, what: str):
    """``got`` as a list of (i, j) int pairs, or None and the verdict saying why not."""
    if got is None:
        return None, Verdict(False, "none", f"returned None, expected {what}: is there a "
                                            "`return` at the end of your function?")
    if isinstance(got, Odd):
        hint = " (a list, e.g. list(your_set))" if got.type in ("set", "frozenset") else ""
        return None, Verdict(False, "type", f"returned a {got.type} ({got.repr[:60]}), "
                                            f"expected {what}{hint}")
    if isinstance(got, str | bool | dict | int | float):
        return None, Verdict(False, "type", f"returned {fmt(got, 60)}, expected {what}")
    try:
        a = np.asarray(got, dtype=float)
    except (TypeError, ValueError):
        return None, Verdict(False, "type", f"returned {fmt(got, 80)}: expected {what}")
    if a.size == 0:
        return None, Verdict(False, "type", f"returned an empty list, expected {what}")
    if a.ndim == 2 and a.shape[0] == 2 and a.shape[1] != 2:
        return None, Verdict(False, "type", f"returned two rows of {a.shape[1]} numbers (all "
                                            f"i, then all j): expected {what}")
    if a.ndim != 2 or a.shape[1] != 2 or not np.isfinite(a).all() or (a != np.round(a)).any():
        return None, Verdict(False, "type", f"returned {fmt(got, 80)}: expected {what}, "
                                            "integer indices")
    return [(int(x), int(y)) for x, y in a], RIGHT


def _around(cell, shape, moves, wrap=True):
    (i, j), (n1, n2) = cell, shape
    out = [(i + di, j + dj) for di, dj in moves]
    if wrap == "filter":
        return [(x, y) for x, y in out if 0 <= x < n1 and 0 <= y < n2]
    return [(x % n1, y % n2) for x, y in out] if wrap else out


EIGHT = [tuple(int(x) for x in m) for m in NEIGHBOURS]
FOUR = EIGHT[:4]
NO_WRAP = ("the grid wraps around (a torus): at the border the neighbours are on the other "
           "side, e.g. (0, j) and (n1 − 1, j) are neighbours. Wrap with ((i + di) % n1, "
           "(j + dj) % n2)")
NEIGHBOUR_MODELS = [  # (key, message, model)
    ("wrap", NO_WRAP, lambda c, s: _around(c, s, EIGHT, "filter")),
    ("wrap", "indices outside the grid (−1 or n): " + NO_WRAP,
     lambda c, s: _around(c, s, EIGHT, False)),
    ("four", "only the 4 edge neighbours: the grid is 8-connected, the diagonal moves "
             "(±1, ±1) count too", lambda c, s: _around(c, s, FOUR)),
    ("four", "only the 4 edge neighbours, and no wrap-around: the grid is 8-connected and "
             "wraps (use % n)", lambda c, s: _around(c, s, FOUR, "filter")),
    ("self", "the cell itself is not its own neighbour: leave out (di, dj) = (0, 0)",
     lambda c, s: _around(c, s, EIGHT + [(0, 0)])),
    ("shape", "you wrapped i with n2 and j with n1: i runs along θ1 and wraps at "
              "n1 = shape[0], j along θ2 at n2 = shape[1]",
     lambda c, s: _around(c, s[::-1], EIGHT)),
]


def _judge_neighbors(args, got):
    cell, shape = args
    cells, bad = _cells(got, "a list of 8 cells (i, j)")
    if cells is None:
        return bad
    ref = sorted(_around(cell, shape, EIGHT))
    if sorted(cells) == ref:
        return RIGHT
    for key, message, model in NEIGHBOUR_MODELS:
        wrong = sorted(model(cell, shape))
        if sorted(cells) == wrong and wrong != ref:
            return Verdict(False, key, message, ref)
    if set(cells) == set(ref):
        return Verdict(False, "duplicates", "some cells appear twice: list each of the 8 "
                                            "neighbours once", ref)
    n1, n2 = shape
    outside = [c for c in cells if not (0 <= c[0] < n1 and 0 <= c[1] < n2)]
    if outside:
        return Verdict(False, "wrap", f"cell {outside[0]} is outside the grid (0 ≤ i < {n1}, "
                                      f"0 ≤ j < {n2}): " + NO_WRAP, ref)
    missing, extra = sorted(set(ref) - set(cells)), sorted(set(cells) - set(ref))
    return Verdict(False, "wrong", f"missing {fmt(missing, 80)}, not neighbours "
                                   f"{fmt(extra, 80)}", ref)


SHAPES = [(3, 3), (3, 5), (5, 3), (8, 8), (8, 6), (16, 16), (10, 7), (32, 64), (64, 32)]


def _neighbor_cases(rng):
    out = []
    for n1, n2 in SHAPES:  # the four corners, two border cells and an inner cell of each
        out += [((i, j), (n1, n2)) for i, j in ((0, 0), (0, n2 - 1), (n1 - 1, 0),
                                                (n1 - 1, n2 - 1), (0, n2 // 2),
                                                (n1 // 2, n2 - 1), (n1 // 2, n2 // 2))]
    for _ in range(47):
        n1, n2 = (int(k) for k in rng.integers(3, 70, 2))
        i, j = int(rng.integers(n1)), int(rng.integers(n2))
        side = rng.integers(5)  # put most of them on a border
        i = (0, n1 - 1, i, i, i)[side]
        j = (j, j, 0, n2 - 1, j)[side]
        out.append(((i, j), (n1, n2)))
    return out


# -- the cost of one move -------------------------------------------------------------------
def _speed(t1, t2, d1, d2, l1, l2, kind="dh"):
    """|J δθ| (DH angles), or the old slide's formula wrongly fed DH angles."""
    if kind == "dh":
        d12 = d1 + d2
        return np.hypot(l1 * d1 + l2 * d12 * np.cos(t2), l2 * d12 * np.sin(t2))
    return np.sqrt((l1 * d1) ** 2 + (l2 * d2) ** 2 + 2 * l1 * l2 * d1 * d2 * np.cos(t1 - t2))


RULES = {"gl8": ((GL_X + 1) / 2, GL_W / 2), "start": ([0.0], [1.0]), "end": ([1.0], [1.0]),
         "mid": ([0.5], [1.0]), "trapezoid": ([0.0, 1.0], [0.5, 0.5]),
         "unmapped": (GL_X, GL_W), "unmapped, halved": (GL_X, GL_W / 2),
         "unhalved": ((GL_X + 1) / 2, GL_W)}


def _tip(t1, t2, l1, l2):
    return np.array([l1 * np.cos(t1) + l2 * np.cos(t1 + t2),
                     l1 * np.sin(t1) + l2 * np.sin(t1 + t2)])


def edge_cost_model(cell_a, cell_b, shape, l1, l2, metric, *, steps="right", wrap=True,
                    centre=(-np.pi, 0.5), rule="gl8", speed="dh", floor=True,
                    ee_as_joint=False, squared=False):
    """The cost of a move as the notebook defines it, or with one mistake (the keywords)."""
    n1, n2 = shape
    h1, h2 = {"right": (2 * np.pi / n1, 2 * np.pi / n2),
              "swapped": (2 * np.pi / n2, 2 * np.pi / n1),
              "n-1": (2 * np.pi / (n1 - 1), 2 * np.pi / (n2 - 1))}[steps]
    di, dj = _move(cell_a, cell_b, shape)
    if wrap in (False, "i"):  # the raw index difference, n − 1 across the seam
        di = cell_b[0] - cell_a[0]
    if wrap in (False, "j"):
        dj = cell_b[1] - cell_a[1]
    d1, d2 = di * h1, dj * h2
    if squared:
        if metric != "joint":
            raise ValueError("a joint-metric mistake")
        return d1 * d1 + d2 * d2
    if metric == "joint" or ee_as_joint:
        if metric == "joint" and ee_as_joint:
            raise ValueError("an 'ee' mistake")
        return float(np.hypot(d1, d2))
    origin, half = centre
    t1, t2 = origin + (cell_a[0] + half) * h1, origin + (cell_a[1] + half) * h2
    chord = float(np.linalg.norm(_tip(t1 + d1, t2 + d2, l1, l2) - _tip(t1, t2, l1, l2)))
    if rule == "chord":
        return chord
    s, w = (np.asarray(x) for x in RULES[rule])
    arc = float(np.sum(w * _speed(t1 + s * d1, t2 + s * d2, d1, d2, l1, l2, speed)))
    return max(arc, chord) if floor else arc


GL_HINT = ("arc = Σ (w_k / 2)·|J(θa + s_k δθ) δθ| with s_k = (x_k + 1)/2 and (x, w) = "
           "np.polynomial.legendre.leggauss(8)")


def _edge_mistakes():
    """Most specific first. A wrong arc is modelled without the chord floor: where the floor
    lifts it, the answer is the chord and the "chord" diagnosis says so."""
    m = partial(partial, edge_cost_model)
    return [
        Mistake("metric", "for metric 'ee' you returned the joint-space length: 'ee' is the "
                          "end-effector path length, " + GL_HINT, m(ee_as_joint=True)),
        *[Mistake("wrap", "the move across the seam is one cell, not n − 1: from (0, j) to "
                          "(n1 − 1, j) is di = −1 (wrap: di = (i_b − i_a + 1) % n1 − 1, "
                          "dj likewise)", m(wrap=w)) for w in (False, "i", "j")],
        *[Mistake("gauss", "map the Gauss–Legendre nodes x ∈ [−1, 1] to s = (x + 1)/2 on "
                           "[0, 1] and halve the weights (they sum to 2): " + GL_HINT,
                  m(rule=r, floor=False)) for r in ("unmapped", "unmapped, halved", "unhalved")],
        Mistake("absolute", "that is the old slide's formula in absolute link angles (θ2' = "
                            "θ1 + θ2); with DH angles |J δθ|² = (l1² + l2² + 2 l1 l2 c2) δθ1² "
                            "+ 2 (l2² + l1 l2 c2) δθ1 δθ2 + l2² δθ2²",
                m(speed="absolute", floor=False)),
        *[Mistake("centre", "cell (i, j) is the configuration θ1 = −π + (i + ½)·2π/n1, "
                            "θ2 = −π + (j + ½)·2π/n2 (the cell's centre)", m(centre=c))
          for c in ((-np.pi, 0.0), (0.0, 0.5), (0.0, 0.0))],
        Mistake("step", "the cell size is 2π/n (n cells make the full turn, −π and π are the "
                        "same angle), not 2π/(n − 1)", m(steps="n-1")),
        Mistake("shape", "h1 = 2π/n1 goes with θ1 (index i, n1 = shape[0]) and h2 = 2π/n2 "
                         "with θ2", m(steps="swapped")),
        Mistake("sqrt", "you returned δθ1² + δθ2²: the joint cost is the length "
                        "sqrt(δθ1² + δθ2²)", m(squared=True)),
        *[Mistake("quadrature", f"you evaluated the speed |J δθ| once, {where}: the cost "
                                f"integrates it along the move, {GL_HINT}",
                  m(rule=rule, floor=False))
          for rule, where in (("start", "at cell a"), ("end", "at cell b"), ("mid", "halfway"))],
        Mistake("quadrature", "the trapezoid rule is not accurate enough: " + GL_HINT,
                m(rule="trapezoid", floor=False)),
        Mistake("chord", "your cost is the chord |p(θb) − p(θa)|, the straight line: either "
                         "you returned only the chord, or your arc came out shorter than it "
                         "and max(arc, chord) hid it. Then the arc is wrong (a path is never "
                         "shorter than the straight line): check the speed |J δθ| (with DH "
                         "angles JᵀJ depends on cos θ2; the old slide's cos(θ1' − θ2') is for "
                         "absolute link angles) and " + GL_HINT, m(rule="chord")),
    ]


def _edge_cases(rng):
    out = [((0, 3), (7, 3), (8, 8), 1.0, 1.0, "joint"), ((0, 0), (7, 7), (8, 8), 1.0, 1.0, "ee"),
           ((3, 0), (3, 7), (8, 8), 1.0, 0.5, "ee"), ((7, 7), (0, 0), (8, 8), 0.8, 1.0, "ee"),
           ((5, 0), (6, 15), (16, 16), 1.0, 0.8, "joint"), ((2, 5), (3, 6), (16, 16), 1.0, 0.8,
                                                             "ee")]
    shapes = [(16, 16), (32, 32), (64, 64), (24, 16), (16, 40), (12, 20), (48, 36), (5, 7),
              (3, 4), (96, 64)]
    for n in range(144):
        n1, n2 = shapes[n % len(shapes)]
        l1, l2 = (float(x) for x in np.round(rng.uniform(0.3, 1.5, 2), 3))
        metric = "joint" if n % 3 == 0 else "ee"
        di, dj = EIGHT[int(rng.integers(8))]
        i, j = int(rng.integers(n1)), int(rng.integers(n2))
        if n % 2:  # half of them cross a seam
            i = (n1 - 1 if di > 0 else 0) if di else i
            j = (n2 - 1 if dj > 0 else 0) if dj and (not di or n % 4 == 1) else j
        out.append(((i, j), ((i + di) % n1, (j + dj) % n2), (n1, n2), l1, l2, metric))
    return out
