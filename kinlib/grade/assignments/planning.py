"""Assignment 04 · configuration-space planning (seed 001): the 8 neighbours of a cell on the
torus, the end-effector metric JᵀJ of the 2R arm derived with sympy, the cost of one move
under the joint and the end-effector metric, and A*.

The reference is kinlib: :meth:`kinlib.CSpaceGrid.edge_costs` for one move,
:func:`kinlib.astar` for the optimal cost. A path is judged by its own cost (kinlib's edge
costs summed along it), so any optimal path is right.
"""

from __future__ import annotations

import dataclasses
import heapq
from itertools import pairwise

import numpy as np

import kinlib as kl

from .._checks import RIGHT, Assignment, Check, Mistake, Verdict
from .._symbolic import symbolic_check
from ._planning_moves import (
    EIGHT,
    MOVE_INDEX,
    _cells,
    _costs,
    _edge_cases,
    _edge_mistakes,
    _empty_grid,
    _judge_neighbors,
    _key,
    _move,
    _neighbor_cases,
    edge_cost_reference,
)
from ._planning_moves import edge_cost_model as edge_cost_model
from .common import jacobian_2r, symbolic_2r_cases

LENGTHS = [(1.0, 0.8), (1.0, 1.0), (0.7, 1.1), (1.2, 0.6), (0.9, 0.4), (0.6, 1.3)]


# -- A* -------------------------------------------------------------------------------------
_PLANS: dict = {}


def _plan(free, start, goal, l1, l2, metric):
    """kinlib's A* on the grid ``free`` (remembered: the cases and the judge share them)."""
    free = np.asarray(free, dtype=bool)
    key = (free.shape, free.tobytes(), tuple(start), tuple(goal), float(l1), float(l2), metric)
    if key not in _PLANS:
        if len(_PLANS) > 500:
            _PLANS.clear()
        grid = dataclasses.replace(_empty_grid(float(l1), float(l2), *free.shape),
                                   occupied=~free)
        _PLANS[key] = kl.astar(grid, grid.q_of(start), grid.q_of(goal), metric=metric)
    return _PLANS[key]


def _path_cost(path, costs, shape) -> float:
    total = 0.0
    for a, b in pairwise(path):
        total += costs[a[0], a[1], MOVE_INDEX[_move(a, b, shape)]]
    return total


def _dijkstra(free, costs, start, goal, wrap=True) -> float:
    """Optimal cost (inf if unreachable), optionally on the grid without wrap-around."""
    n1, n2 = free.shape
    best, heap, done = {start: 0.0}, [(0.0, start)], set()
    while heap:
        d, u = heapq.heappop(heap)
        if u in done:
            continue
        if u == goal:
            return d
        done.add(u)
        for k, (di, dj) in enumerate(EIGHT):
            v = (u[0] + di, u[1] + dj)
            if not wrap and not (0 <= v[0] < n1 and 0 <= v[1] < n2):
                continue
            v = (v[0] % n1, v[1] % n2)
            if v in done or not free[v]:
                continue
            dv = d + costs[u[0], u[1], k]
            if dv < best.get(v, np.inf):
                best[v] = dv
                heapq.heappush(heap, (dv, v))
    return np.inf


def _crosses_seam(path) -> bool:
    return any(abs(a[k] - b[k]) > 1 for a, b in pairwise(path) for k in (0, 1))


def _validity(path, free, start, goal):
    """The first thing wrong with ``path`` as a path on ``free``, or None."""
    n1, n2 = free.shape
    for c in path:
        if not (0 <= c[0] < n1 and 0 <= c[1] < n2):
            return Verdict(False, "outside", f"cell {c} is outside the grid (0 ≤ i < {n1}, "
                                             f"0 ≤ j < {n2}): wrap the indices with % n1 and "
                                             "% n2 (numpy accepts −1, the grader does not)")
    if path[0] == goal and path[-1] == start and start != goal:
        return Verdict(False, "endpoints", "your path runs from the goal to the start: "
                                           "reverse it")
    if path[0] != start or path[-1] != goal:
        return Verdict(False, "endpoints", f"your path runs from {path[0]} to {path[-1]}; it "
                                           f"must start at {start} and end at {goal} (both "
                                           "included; start = goal gives [start])")
    for a, b in pairwise(path):
        if _move(a, b, free.shape) is None:
            why = "the same cell twice" if a == b else "not 8-neighbours on the torus"
            return Verdict(False, "jump", f"the step {a} → {b} is not a move: {why} (each step "
                                          "goes to one of the 8 neighbours, across the seams "
                                          "too)")
    hit = [c for c in path if not free[c]]
    if hit:
        return Verdict(False, "occupied", f"your path passes through the occupied cell {hit[0]} "
                                          "(free[i, j] is False): only free cells may be "
                                          "pushed on the open list")
    return None


SUBOPTIMAL = ("stop when the goal is popped from the heap, not when it is pushed; never let "
              "the heuristic overestimate (wrapped joint distance for 'joint', straight-line "
              "end-effector distance for 'ee'); when a cheaper way to a cell turns up, update "
              "its g and parent and push it again")


def _no_path(args) -> bool:
    """Whether the case has no path (its right answer, None, needs no search)."""
    return not _plan(*args).success


def _judge_astar(args, got):
    free, start, goal, l1, l2, metric = args
    plan = _plan(free, start, goal, l1, l2, metric)
    blocked = [name for name, c in (("start", start), ("goal", goal)) if not free[c]]
    if got is None:
        if not plan.success:
            return RIGHT
        costs = _costs(*_key(free.shape, l1, l2, metric))
        if start == goal:
            return Verdict(False, "missed", "start = goal: the path is [start], one cell")
        if not np.isfinite(_dijkstra(free, costs, start, goal, wrap=False)):
            return Verdict(False, "wrap", "you returned None, but a path exists: every path "
                                          "crosses the seam θ = ±π, where cells 0 and n − 1 "
                                          "are neighbours (wrap indices with % n)",
                           plan.cells.tolist())
        return Verdict(False, "missed", f"you returned None, but a path exists (optimal cost "
                                        f"{plan.cost:.6g})", plan.cells.tolist())
    if blocked:
        cell = start if blocked[0] == "start" else goal
        return Verdict(False, "blocked", f"the {blocked[0]} cell {cell} is occupied (free is "
                                         "False there): then there is no path, return None")
    path, bad = _cells(got, "a list of cells (i, j) from start to goal, or None")
    if path is None:
        return bad
    problem = _validity(path, free, start, goal)
    if not plan.success:
        why = f": {problem.message}" if problem else ""
        return Verdict(False, "phantom", "start and goal lie in different free regions, so no "
                                         "path exists and the answer is None; you returned a "
                                         "path" + why)
    if problem is not None:
        return Verdict(problem.ok, problem.key, problem.message, plan.cells.tolist())
    costs = _costs(*_key(free.shape, l1, l2, metric))
    cost = _path_cost(path, costs, free.shape)
    if cost <= plan.cost * (1 + 1e-9) + 1e-12:
        return RIGHT
    expected = plan.cells.tolist()
    flat = _dijkstra(free, costs, start, goal, wrap=False)
    if not _crosses_seam(path) and abs(cost - flat) <= 1e-9 * flat:
        return Verdict(False, "wrap", f"your path costs {cost:.6g}, the optimum is "
                                      f"{plan.cost:.6g}: yours is the best path that does not "
                                      "cross the seam θ = ±π; the grid wraps around (cells 0 "
                                      "and n − 1 are neighbours)", expected)
    if metric == "ee" and cost > 1.02 * plan.cost:  # (stopping at a push costs less)
        joint = _costs(*_key(free.shape, l1, l2, "joint"))
        best = _plan(free, start, goal, l1, l2, "joint").cost
        if abs(_path_cost(path, joint, free.shape) - best) <= 1e-9 * best:
            return Verdict(False, "metric", f"your path costs {cost:.6g}, the optimum is "
                                            f"{plan.cost:.6g}. Yours is a shortest path in "
                                            "joint space: for 'ee', does each move cost its "
                                            "end-effector path length (part 2), and is the "
                                            "heuristic the end-effector distance?", expected)
    return Verdict(False, "suboptimal", f"your path costs {cost:.6g}, the optimum is "
                                        f"{plan.cost:.6g}: {SUBOPTIMAL}", expected)


def _pair(rng, free, l1, l2, metric):
    """A start and a goal, free and joined by a path."""
    cells = np.argwhere(free)
    for _ in range(100):
        a, b = rng.choice(len(cells), 2, replace=False)
        start, goal = tuple(int(x) for x in cells[a]), tuple(int(x) for x in cells[b])
        if _plan(free, start, goal, l1, l2, metric).success:
            return start, goal
    raise RuntimeError("no connected pair of cells")  # pragma: no cover


def _scene(rng, k):
    obs = []
    for _ in range(k):
        r, phi = rng.uniform(0.9, 1.9), rng.uniform(-np.pi, np.pi)
        obs.append(kl.Circle((r * np.cos(phi), r * np.sin(phi)), rng.uniform(0.08, 0.25)))
    if rng.random() < 0.5:
        x, y = rng.uniform(-1.6, 1.2, 2)
        if np.hypot(x + 0.2, y + 0.2) < 1.0:  # keep it away from the base
            x, y = 1.1, -0.5
        obs.append(kl.Polygon([(x, y), (x + 0.4, y), (x + 0.2, y + 0.15), (x + 0.3, y + 0.4)]))
    return obs


def _random_free(rng, shape, p):
    return rng.random(shape) >= p


def _wall(free, k, axis):
    free = free.copy()
    if axis == 0:
        free[k, :] = False
    else:
        free[:, k] = False
    return free


def _astar_cases(rng):
    out = []
    sizes = [(16, 16), (24, 24), (32, 32), (48, 48), (64, 64), (32, 48), (48, 32)]
    for n in range(28):  # real obstacles, then random occupancy; both metrics
        l1, l2 = LENGTHS[n % len(LENGTHS)]
        metric = ("joint", "ee")[n % 2]
        shape = sizes[n % len(sizes)]
        if n < 14:
            free = ~kl.planar_2r_cspace(l1, l2, _scene(rng, 1 + n % 3), n=shape).occupied
        else:
            free = _random_free(rng, shape, rng.uniform(0.15, 0.35))
        out.append((free, *_pair(rng, free, l1, l2, metric), l1, l2, metric))
    for n in range(6):  # the best path crosses a seam (or both)
        shape = sizes[n % 5]
        n1, n2 = shape
        free = _random_free(rng, shape, 0.1)
        a = [int(rng.integers(1, 3)), int(rng.integers(n2))]
        b = [n1 - 1 - int(rng.integers(1, 3)), int(rng.integers(n2))]
        if n % 3 == 1:  # across the θ2 seam instead
            a, b = [a[1] % n1, a[0]], [b[1] % n1, n2 - 1 - (n1 - 1 - b[0])]
        elif n % 3 == 2:  # across both
            a[1], b[1] = 1, n2 - 2
        free[tuple(a)] = free[tuple(b)] = True
        l1, l2 = LENGTHS[n]
        out.append((free, tuple(a), tuple(b), l1, l2, ("joint", "ee")[n % 2]))
    for n in range(6):  # a wall across the grid: every path goes round through the seam
        shape = sizes[n % 5]
        axis = n % 2
        c = shape[axis] // 2
        l1, l2 = LENGTHS[(n + 2) % len(LENGTHS)]
        metric = ("ee", "joint")[n // 3]
        while True:
            free = _wall(_random_free(rng, shape, 0.08), c, axis)
            a = [int(rng.integers(shape[1 - axis]))] * 2
            a[axis] = c - 2
            b = [int(rng.integers(shape[1 - axis]))] * 2
            b[axis] = c + 2
            a, b = tuple(a), tuple(b)
            if free[a] and free[b] and _plan(free, a, b, l1, l2, metric).success:
                break
        out.append((free, a, b, l1, l2, metric))
    for n in range(3):  # start = goal
        free = _random_free(rng, sizes[n], 0.2)
        cell = tuple(int(x) for x in np.argwhere(free)[n * 7])
        out.append((free, cell, cell, *LENGTHS[n], ("ee", "joint", "ee")[n]))
    for n in range(4):  # blocked start or goal
        free = _random_free(rng, sizes[n + 1], 0.25)
        start, goal = _pair(rng, free, 1.0, 0.8, "joint")
        blocked = (start, goal)[n % 2]
        free[blocked] = False
        out.append((free, start, goal, *LENGTHS[n + 1], ("joint", "ee")[n // 2]))
    # no path: two walls cut the torus into two bands; an island; the walls of notebook 14
    for n, axis in enumerate((0, 1)):
        shape = sizes[n + 2]
        free = _wall(_wall(_random_free(rng, shape, 0.1), 4, axis), shape[axis] - 6, axis)
        a = [int(rng.integers(shape[1 - axis]))] * 2
        a[axis] = 8
        b = [int(rng.integers(shape[1 - axis]))] * 2
        b[axis] = 1
        free[tuple(a)] = free[tuple(b)] = True
        out.append((free, tuple(a), tuple(b), 1.0, 0.8, ("joint", "ee")[n]))
    free = _random_free(rng, (20, 20), 0.1)
    free[9:14, 4:9] = False
    free[11, 6] = free[3, 3] = True
    out.append((free, (3, 3), (11, 6), 0.7, 1.1, "ee"))
    walls = [kl.Polygon([(0.25, -0.05), (2.0, -0.05), (2.0, 0.05), (0.25, 0.05)]),
             kl.Polygon([(-2.0, -0.05), (-0.25, -0.05), (-0.25, 0.05), (-2.0, 0.05)])]
    for n, l1, l2, metric in ((48, 1.0, 0.8, "joint"), (40, 1.2, 0.6, "ee")):
        grid = kl.planar_2r_cspace(l1, l2, walls, n=n)
        up, down = (tuple(int(x) for x in grid.cell_of(q)) for q in ([np.pi / 2, 0.3],
                                                                      [-np.pi / 2, 0.3]))
        out.append((~grid.occupied, up, down, l1, l2, metric))
    for seed in (9, 125, 162, 188):  # A* that stops when the goal is pushed misses these
        fixed = np.random.default_rng(seed)
        n = int(fixed.choice([12, 16, 20]))
        l1, l2 = LENGTHS[seed % len(LENGTHS)]
        free = fixed.random((n, n)) >= fixed.uniform(0.1, 0.35)
        out.append((free, *_pair(fixed, free, l1, l2, "ee"), l1, l2, "ee"))
    return [(np.ascontiguousarray(f, dtype=bool), *rest) for f, *rest in out]


# -- the metric JᵀJ, derived with sympy -------------------------------------------------------
def _metric(*args, **kwargs):
    J = jacobian_2r(*args, **kwargs)
    return J.T * J


def metric_check() -> Check:
    """``metric_2r(theta1, theta2, l1, l2)``: JᵀJ of the 2R arm's 2×2 position Jacobian,
    seed 001's minimum end-effector-distance metric, a sympy Matrix."""
    import sympy as sp

    from kinlib.symbolic import simplify_rotation

    def order(*a):
        J = jacobian_2r(*a)
        return J * J.T
    return symbolic_check(
        "metric_2r", 3, "the end-effector metric JᵀJ of the 2R arm derived with sympy",
        symbolic_2r_cases, _metric, names=("theta1", "theta2", "l1", "l2"),
        show=simplify_rotation,
        mistakes=[Mistake("order", "this is J Jᵀ: the metric of a joint step δθ is JᵀJ, from "
                                   "|δp|² = (J δθ)ᵀ (J δθ) = δθᵀ (JᵀJ) δθ (J Jᵀ depends on θ1; "
                                   "the metric does not)", order),
                  Mistake("heading", "you used the 3×2 Jacobian with the heading row "
                                     "φ = θ1 + θ2: the end-effector metric measures how far "
                                     "the point (x, y) moves, J = ∂(x, y)/∂(θ1, θ2) is 2×2",
                          lambda *a: _metric(*a) + sp.ones(2, 2)),
                  Mistake("absolute", "θ2 is the angle of link 2 relative to link 1 (DH): "
                                      "link 2 points at θ1 + θ2 (seed 001's earlier metric, "
                                      "with cos(θ1 − θ2), used absolute angles)",
                          lambda *a: _metric(*a, absolute=True))])


def assignment() -> Assignment:
    checks = [Check("neighbors", 6, "the 8 neighbours of a cell on the torus", _neighbor_cases,
                    judge=_judge_neighbors),
              metric_check(),
              Check("edge_cost", 5, "the cost of one move, joint and end-effector metric",
                    _edge_cases, edge_cost_reference, _edge_mistakes()),
              Check("astar_2r", 20, "an optimal path by A*, or None", _astar_cases,
                    judge=_judge_astar, is_trivial=_no_path,
                    trivial="of None where there is no path")]
    return Assignment("04_planning", "Configuration-space planning", checks)
