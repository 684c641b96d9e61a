"""Assignment 04 (configuration-space planning): the grader's reference agrees with kinlib's
A*, its cases cover what they must, each classic mistake gets its diagnosis, and any right
answer (another order, another optimal path, an array) is accepted.

Submissions are built from the source notebook's own code with one mistake patched in per
function; ``astar_2r`` calls right copies of ``neighbors`` and ``edge_cost`` so that each
function carries exactly its own mistake.
"""

import dataclasses
import heapq
import itertools

import numpy as np
import pytest
import sympy as sp
from grading_helpers import (
    by_function,
    judge_notebooks,
    misdiagnosed,
    mistake_submissions,
    patched,
    solution_code,
    write_notebook,
)

import kinlib as kl
from kinlib.grade.assignments import planning as P
from kinlib.planning.cspace import NEIGHBOURS

NAME = "04_planning"


# -- the reference --------------------------------------------------------------------------
@pytest.mark.parametrize("metric", ["joint", "ee"])
@pytest.mark.parametrize("seed", range(4))
def test_edge_costs_summed_along_kinlibs_path_give_its_cost(metric, seed):
    rng = np.random.default_rng(seed)
    l1, l2 = rng.uniform(0.4, 1.4, 2)
    shape = [(32, 32), (24, 40), (48, 48), (16, 20)][seed]
    free = rng.random(shape) > 0.25
    start, goal = P._pair(rng, free, float(l1), float(l2), metric)
    plan = P._plan(free, start, goal, float(l1), float(l2), metric)
    assert plan.success and plan.cost > 0
    cells = [tuple(int(x) for x in c) for c in plan.cells]
    total = sum(P.edge_cost_reference(a, b, shape, l1, l2, metric)
                for a, b in itertools.pairwise(cells))
    assert total == pytest.approx(plan.cost, rel=1e-12)
    assert P._path_cost(cells, P._costs(*P._key(shape, l1, l2, metric)), shape) == plan.cost
    # and kinlib's optimum is the plain Dijkstra optimum of the grader's own search
    costs = P._costs(*P._key(shape, l1, l2, metric))
    assert P._dijkstra(free, costs, start, goal) == pytest.approx(plan.cost, rel=1e-12)


def test_the_notebooks_formula_is_kinlibs_edge_cost():
    """The formula the notebook states (and the mistake models build on) is kinlib's."""
    for shape, l1, l2 in (((16, 16), 1.0, 0.5), ((24, 40), 0.7, 1.3), ((5, 3), 1.1, 0.9)):
        for metric in ("joint", "ee"):
            costs = kl.planar_2r_cspace(l1, l2, [], n=shape).edge_costs(metric)
            for i, j in ((0, 0), (shape[0] - 1, 2), (3, shape[1] - 1), (2, 1)):
                for k, (di, dj) in enumerate(NEIGHBOURS):
                    b = ((i + di) % shape[0], (j + dj) % shape[1])
                    model = P.edge_cost_model((i, j), b, shape, l1, l2, metric)
                    assert model == pytest.approx(costs[i, j, k], rel=1e-13, abs=1e-15)
                    assert P.edge_cost_reference((i, j), b, shape, l1, l2, metric) == costs[i, j, k]


def test_metric_reference_is_seed_001s_and_kinlibs_jacobian():
    """The reference of metric_2r (kinlib's DH product, differentiated) is seed 001's JᵀJ
    (typed here), and at numbers JᵀJ of the first two rows of kinlib's planar_2r_jacobian;
    its mistake models differ from it."""
    check = next(c for c in P.assignment().checks if c.function == "metric_2r")
    rng = np.random.default_rng(5)
    for t1, t2, l1, l2 in check.make_cases(0):
        c2 = sp.cos(t2)
        seed = sp.Matrix([[l1**2 + l2**2 + 2 * l1 * l2 * c2, l2**2 + l1 * l2 * c2],
                          [l2**2 + l1 * l2 * c2, l2**2]])
        free = sorted(sp.Matrix([t1, t2, l1, l2]).free_symbols, key=str)
        for _ in range(3):  # (numbers at random points: exact identities are the judge's)
            at = {s: rng.uniform(0.3, 2.0) if s.is_positive else rng.uniform(-3, 3)
                  for s in free}
            num = [float(sp.sympify(x).subs(at)) for x in (t1, t2, l1, l2)]
            J = kl.planar_2r_jacobian(*num)[:2]
            M = np.array(P._metric(t1, t2, l1, l2).subs(at), dtype=float)
            assert np.allclose(M, J.T @ J) and np.allclose(M, np.array(seed.subs(at), float))
            absolute = P._metric(t1, t2, l1, l2, absolute=True).subs(at)
            assert not np.allclose(np.array(absolute, dtype=float), M)


def test_cases_cover_what_they_must():
    spec = P.assignment()
    cases = {c.function: c.make_cases(0) for c in spec.checks}
    assert sum(map(len, cases.values())) >= 300
    assert len(cases["neighbors"]) >= 100 and len(cases["edge_cost"]) >= 140
    seam = [c for c in cases["edge_cost"] if P._move(c[0], c[1], c[2]) != (c[1][0] - c[0][0],
                                                                          c[1][1] - c[0][1])]
    assert len(seam) >= 40 and {c[5] for c in cases["edge_cost"]} == {"joint", "ee"}
    kinds = {"only across the seam": 0, "no path": 0, "blocked": 0, "start = goal": 0,
             "best crosses the seam": 0, "non-square": 0, "ee": 0}
    for free, start, goal, l1, l2, metric in cases["astar_2r"]:
        assert free.dtype == bool and free.ndim == 2
        kinds["non-square"] += free.shape[0] != free.shape[1]
        kinds["ee"] += metric == "ee"
        if not (free[start] and free[goal]):
            kinds["blocked"] += 1
            continue
        plan = P._plan(free, start, goal, l1, l2, metric)
        if not plan.success:
            kinds["no path"] += 1
            continue
        kinds["start = goal"] += start == goal
        costs = P._costs(*P._key(free.shape, l1, l2, metric))
        flat = P._dijkstra(free, costs, start, goal, wrap=False)
        kinds["only across the seam"] += not np.isfinite(flat)
        kinds["best crosses the seam"] += bool(flat > plan.cost * (1 + 1e-9))
    assert 40 <= len(cases["astar_2r"]) <= 60
    traps = cases["astar_2r"][-4:]  # the goal is first pushed by a worse last move
    assert all(push_astar(*c) > P._plan(*c).cost * (1 + 1e-6) for c in traps)
    assert kinds["only across the seam"] >= 6 and kinds["best crosses the seam"] >= 20
    assert kinds["no path"] >= 5 and kinds["blocked"] == 4 and kinds["start = goal"] == 3
    assert kinds["non-square"] >= 6 and kinds["ee"] >= 20


def push_astar(free, start, goal, l1, l2, metric):
    """The cost found by A* that (wrongly) stops when the goal is pushed."""
    n1, n2 = free.shape
    costs = P._costs(*P._key(free.shape, l1, l2, metric))
    grid = P._empty_grid(l1, l2, n1, n2)
    T1, T2 = np.meshgrid(grid.theta1, grid.theta2, indexing="ij")
    xy = kl.planar_2r_fk(T1, T2, l1, l2)[..., :2, 3]
    assert metric == "ee" and start != goal
    g, closed, heap = {start: 0.0}, set(), [(0.0, start)]
    while heap:
        _, u = heapq.heappop(heap)
        if u in closed:
            continue
        closed.add(u)
        for k, (di, dj) in enumerate(P.EIGHT):
            v = ((u[0] + di) % n1, (u[1] + dj) % n2)
            if v in closed or not free[v]:
                continue
            gv = g[u] + costs[u[0], u[1], k]
            if gv < g.get(v, np.inf):
                g[v] = gv
                if v == goal:
                    return gv
                heapq.heappush(heap, (gv + float(np.hypot(*(xy[v] - xy[goal]))), v))
    return np.inf


# -- the judge of astar_2r, on answers made by hand -----------------------------------------
def _case(free, start, goal, metric="joint"):
    return (np.asarray(free, dtype=bool), start, goal, 1.0, 0.8, metric)


def test_astar_judge_on_hand_made_answers():
    empty = np.ones((16, 16), dtype=bool)
    args = _case(empty, (1, 5), (14, 5))
    ok = [(1, 5), (0, 5), (15, 5), (14, 5)]
    assert P._judge_astar(args, ok).ok
    assert P._judge_astar(args, np.array(ok)).ok and P._judge_astar(args, tuple(ok)).ok
    # two different optimal paths (diagonal first or last) are both right
    args = _case(empty, (2, 2), (5, 3))
    assert P._judge_astar(args, [(2, 2), (3, 3), (4, 3), (5, 3)]).ok
    assert P._judge_astar(args, [(2, 2), (3, 2), (4, 2), (5, 3)]).ok
    assert P._judge_astar(args, [(2, 2), (3, 2), (4, 3), (5, 3)]).ok
    key = lambda a, got: P._judge_astar(a, got).key  # noqa: E731
    assert key(args, [(2, 2), (3, 1), (4, 2), (5, 3)]) == "suboptimal"
    assert key(args, [(2, 2), (4, 2), (5, 3)]) == "jump"
    assert key(args, [(2, 2), (3, 2), (3, 2), (4, 2), (5, 3)]) == "jump"
    assert key(args, [(5, 3), (4, 2), (3, 2), (2, 2)]) == "endpoints"
    assert key(args, [(3, 2), (4, 2), (5, 3)]) == "endpoints"
    assert key(args, [[2, 3, 4, 5], [2, 2, 2, 3]]) == "type"
    assert key(args, []) == "type" and key(args, "path") == "type"
    assert key(args, [(2.5, 2), (5, 3)]) == "type"
    assert key(args, None) == "missed"
    across = _case(empty, (1, 5), (14, 5))
    assert key(across, [(1, 5), (0, 5), (-1, 5), (-2, 5)]) == "outside"
    assert key(across, [(1, 5), (0, 5), (15, 5), (14, 5)][::-1]) == "endpoints"
    # the best path that does not cross the seam: the wrap diagnosis
    assert key(across, [(1, 5)] + [(i, 5) for i in range(2, 15)]) == "wrap"
    wall = empty.copy()
    wall[8, :] = False
    assert key(_case(wall, (6, 0), (10, 0)), None) == "wrap"
    hole = empty.copy()
    hole[3, 2] = False
    assert key(_case(hole, (2, 2), (5, 3)), [(2, 2), (3, 2), (4, 2), (5, 3)]) == "occupied"
    assert key(_case(hole, (3, 2), (5, 3)), [(3, 2), (4, 2), (5, 3)]) == "blocked"
    assert P._judge_astar(_case(hole, (3, 2), (5, 3)), None).ok
    assert P._judge_astar(_case(hole, (5, 3), (3, 2)), None).ok
    two = empty.copy()
    two[4, :] = two[10, :] = False
    assert P._judge_astar(_case(two, (7, 0), (12, 0)), None).ok
    assert key(_case(two, (7, 0), (12, 0)), [(7, 0), (12, 0)]) == "phantom"
    assert key(_case(empty, (3, 3), (3, 3)), None) == "missed"
    assert P._judge_astar(_case(empty, (3, 3), (3, 3)), [(3, 3)]).ok
    assert key(_case(empty, (3, 3), (3, 3)), [(3, 3), (3, 3)]) == "jump"


def test_astar_judge_tells_the_joint_optimal_path_under_ee():
    empty = np.ones((32, 32), dtype=bool)
    start, goal = (16, 28), (2, 28)  # the arm nearly folded: 'ee' prefers another way
    args = _case(empty, start, goal, "ee")
    joint = P._plan(empty, start, goal, 1.0, 0.8, "joint")
    ee = P._plan(empty, start, goal, 1.0, 0.8, "ee")
    path = [tuple(int(x) for x in c) for c in joint.cells]
    ee_costs = P._costs(*P._key(empty.shape, 1.0, 0.8, "ee"))
    assert P._path_cost(path, ee_costs, empty.shape) > ee.cost * 1.01
    assert P._judge_astar(args, path).key == "metric"
    assert P._judge_astar(args, [tuple(int(x) for x in c) for c in ee.cells]).ok


def test_neighbors_judge_on_hand_made_answers():
    shape = (8, 6)
    ring = [(7, 5), (7, 0), (7, 1), (0, 5), (0, 1), (1, 5), (1, 0), (1, 1)]
    judge = P._judge_neighbors
    assert judge(((0, 0), shape), ring).ok and judge(((0, 0), shape), np.array(ring[::-1])).ok
    assert judge(((0, 0), shape), ring + [(0, 0)]).key == "self"
    assert judge(((0, 0), shape), ring + [(1, 1)]).key == "duplicates"
    assert judge(((0, 0), shape), [(1, 0), (0, 1), (1, 1)]).key == "wrap"
    assert judge(((0, 0), shape), [(7, 0), (1, 0), (0, 5), (0, 1)]).key == "four"
    assert judge(((0, 0), shape), set(ring)).key == "type"
    assert judge(((0, 0), shape), ring[:7] + [(3, 3)]).key == "wrong"
    assert judge(((0, 0), shape), None).key == "none"


# -- classic mistakes, graded for real ------------------------------------------------------
NB_RIGHT = ("return [((i + di) % n1, (j + dj) % n2)\n"
            "            for di in (-1, 0, 1) for dj in (-1, 0, 1) if (di, dj) != (0, 0)]")
NEIGHBOR_MISTAKES = [  # (edit, diagnosis)
    ((NB_RIGHT, "return [(i + di, j + dj) for di in (-1, 0, 1) for dj in (-1, 0, 1)\n"
                "            if (di, dj) != (0, 0) and 0 <= i + di < n1 and 0 <= j + dj < n2]"),
     "wrap"),
    ((NB_RIGHT, "return [(i + di, j + dj) for di in (-1, 0, 1) for dj in (-1, 0, 1)\n"
                "            if (di, dj) != (0, 0)]"), "wrap"),
    ((NB_RIGHT, "return [((i + di) % n1, (j + dj) % n2)\n"
                "            for di, dj in ((1, 0), (-1, 0), (0, 1), (0, -1))]"), "four"),
    ((" if (di, dj) != (0, 0)]", "]"), "self"),
    (("i, j = cell\n    n1, n2 = shape", "i, j = cell\n    n2, n1 = shape"), "shape"),
    ((NB_RIGHT, NB_RIGHT + " + [((i + 1) % n1, j)]"), "duplicates"),
    ((NB_RIGHT, "return set(" + NB_RIGHT[len("return "):] + ")"), "type"),
]
EC_STEP = "n1, n2 = shape\n    h1, h2 = 2 * np.pi / n1, 2 * np.pi / n2"
ABSOLUTE = ("speed = np.sqrt((l1 * d1) ** 2 + (l2 * d2) ** 2\n"
            "                    + 2 * l1 * l2 * d1 * d2 * np.cos(t1 + s * d1 - t2s))")
EDGE_MISTAKES = [
    (('if metric == "joint":\n        return float(np.hypot(d1, d2))',
      'if True:\n        return float(np.hypot(d1, d2))'), "metric"),
    (("di = (cell_b[0] - cell_a[0] + 1) % n1 - 1", "di = cell_b[0] - cell_a[0]"), "wrap"),
    (("s = (x + 1) / 2", "s, w = np.zeros(1), np.full(1, 2.0)"), "quadrature"),
    (("s = (x + 1) / 2", "s = x"), "gauss"),
    (("arc = np.sum(w / 2 * speed)", "arc = np.sum(w * speed)"), "gauss"),
    (("return float(max(arc, chord))", "return float(chord)"), "chord"),
    (("s = (x + 1) / 2", "x, w = np.array([-1.0, 1.0]), np.ones(2)\n    s = (x + 1) / 2"),
     "quadrature"),
    ((("speed = np.hypot(l1 * d1 + l2 * sigma * np.cos(t2s), l2 * sigma * np.sin(t2s))",
       ABSOLUTE), ("return float(max(arc, chord))", "return float(arc)")), "absolute"),
    # with the floor the answer is often the chord: both diagnoses show (see below)
    (("speed = np.hypot(l1 * d1 + l2 * sigma * np.cos(t2s), l2 * sigma * np.sin(t2s))",
      ABSOLUTE), "chord"),
    (("t2 = -np.pi + (cell_a[1] + 0.5) * h2", "t2 = -np.pi + cell_a[1] * h2"), "centre"),
    ((EC_STEP, "n1, n2 = shape\n    h1, h2 = 2 * np.pi / (n1 - 1), 2 * np.pi / (n2 - 1)"),
     "step"),
    ((EC_STEP, "n1, n2 = shape\n    h1, h2 = 2 * np.pi / n2, 2 * np.pi / n1"), "shape"),
    (("return float(np.hypot(d1, d2))", "return float(d1 ** 2 + d2 ** 2)"), "sqrt"),
]
ASTAR_MISTAKES = [
    (("                parent[v] = u\n",
      "                parent[v] = u\n"
      "                if v == goal:  # stops when the goal is pushed\n"
      "                    path = [v]\n"
      "                    while parent[path[-1]] is not None:\n"
      "                        path.append(parent[path[-1]])\n"
      "                    return path[::-1]\n"), "suboptimal"),
    (("(gv + heuristic(v), pushes, v)", "(gv + 3 * heuristic(v), pushes, v)"), "suboptimal"),
    (("for v in _nb(u, free.shape):",
      "for v in [(u[0] + a, u[1] + b) for a in (-1, 0, 1) for b in (-1, 0, 1)\n"
      "                  if (a, b) != (0, 0) and 0 <= u[0] + a < n1 and 0 <= u[1] + b < n2]:"),
     "wrap"),
    ((("_ec(u, v, free.shape, l1, l2, metric)", "_ec(u, v, free.shape, l1, l2, 'joint')"),
      ('if metric == "joint":\n            di, dj', 'if True:\n            di, dj')), "metric"),
    (("if v in closed or not free[v]:", "if v in closed:"), "occupied"),
    (("if not free[start] or not free[goal]:\n        return None", ""), "blocked"),
    (("return path[::-1]", "return path"), "endpoints"),
    (("    return None\n    ### END SOLUTION", "    return [start, goal]\n    ### END SOLUTION"),
     "phantom"),
    (("if not free[start] or not free[goal]:", "if not free[start] or not free[goal] or "
                                               "start == goal:"), "missed"),
    (("return path[::-1]", "return [list(c) for c in zip(*path[::-1])]"), "type"),
    (("return path[::-1]", "path = path[::-1]\n            return path[:1] + path[2:]"),
     "jump"),
    (("return path[::-1]",  # the path unwrapped, like kinlib's plan.q, instead of cells
      "path = path[::-1]\n            out = [path[0]]\n"
      "            for a, b in zip(path[:-1], path[1:]):\n"
      "                d = [(b[k] - a[k] + 1) % free.shape[k] - 1 for k in (0, 1)]\n"
      "                out.append((out[-1][0] + d[0], out[-1][1] + d[1]))\n"
      "            return out"), "outside"),
]


def _isolated(code: str) -> str:
    """astar_2r calling the right copies _nb and _ec (defined by an earlier cell)."""
    return patched(code, ("for v in neighbors(u, free.shape):", "for v in _nb(u, free.shape):"),
                   ("edge_cost(u, v, free.shape, l1, l2, metric)",
                    "_ec(u, v, free.shape, l1, l2, metric)"))


METRIC_X = "l1 * sp.cos(theta1) + l2 * sp.cos(theta1 + theta2)"
METRIC_Y = "l1 * sp.sin(theta1) + l2 * sp.sin(theta1 + theta2)"
METRIC_J = "J = p.jacobian([theta1, theta2])"
METRIC_MISTAKES = [  # the metric J^T J derived with sympy
    (("return J.T * J", "return J * J.T"), "order"),
    ((METRIC_Y + "])", METRIC_Y + ", theta1 + theta2])"), "heading"),
    (((METRIC_X, "l1 * sp.cos(theta1) + l2 * sp.cos(theta2)"),
      (METRIC_Y, "l1 * sp.sin(theta1) + l2 * sp.sin(theta2)")), "absolute"),
    ((METRIC_J, "J = sp.Matrix([[-l1 * sp.sin(theta1), -l2 * sp.sin(theta1 + theta2)],\n"
                "                   [p[0], l2 * sp.cos(theta1 + theta2)]])  # by hand"),
     "entries"),
    (("p = sp.Matrix([", "theta1, theta2 = sp.symbols('theta1 theta2')  # my own\n"
                         "    p = sp.Matrix(["), "symbols"),
]
TABLE = (("neighbors", NEIGHBOR_MISTAKES), ("metric_2r", METRIC_MISTAKES),
         ("edge_cost", EDGE_MISTAKES), ("astar_2r", ASTAR_MISTAKES))


def test_planning_mistakes_are_diagnosed(tmp_path):
    right = solution_code(NAME) + "\n\n_nb, _ec = neighbors, edge_cost\n"
    code = _isolated(solution_code(NAME))
    graded = judge_notebooks(mistake_submissions(tmp_path, NAME, code, TABLE, right))
    # the right copies keep astar_2r right, but its own mistakes spoil nothing else
    wrong = misdiagnosed(graded, TABLE, unaffected=("neighbors", "edge_cost"))
    results = [by_function(r) for r in graded]
    assert not wrong, wrong
    n = next(n for n, (e, key) in enumerate(EDGE_MISTAKES) if e[1] == ABSOLUTE)
    floored = {d["key"] for d in results[n]["edge_cost"]["diagnoses"]}  # absolute + floor
    assert floored == {"chord", "absolute"}
    # the rare mistakes fail only where they matter: 2 blocked starts, 3 start = goal, and
    # stopping when the goal is pushed (the first "suboptimal") at least on the 4 traps
    keys = [key for _, key in ASTAR_MISTAKES]
    fails = {key: results[keys.index(key)]["astar_2r"] for key in ("blocked", "missed",
                                                                   "suboptimal")}
    fails = {key: c["total"] - c["passed"] for key, c in fails.items()}
    assert fails["blocked"] == 2 and fails["missed"] == 3 and fails["suboptimal"] >= 4


def test_other_right_answers_are_accepted(tmp_path):
    """Neighbours in another order, as an array; the metric simplified (factored entries);
    the speed by the quadratic form sqrt(δθᵀJᵀJδθ); Dijkstra (no heuristic) with another
    neighbour order, returning an array."""
    right = solution_code(NAME) + "\n\n_nb, _ec = neighbors, edge_cost\n"
    code = patched(
        _isolated(solution_code(NAME)),
        (NB_RIGHT, "return np.array(" + NB_RIGHT[len("return "):] + "[::-1])"),
        ("return J.T * J", "return sp.factor(sp.trigsimp(J.T * J))"),
        ("speed = np.hypot(l1 * d1 + l2 * sigma * np.cos(t2s), l2 * sigma * np.sin(t2s))",
         "c = np.cos(t2s)\n"
         "    speed = np.sqrt((l1**2 + l2**2 + 2 * l1 * l2 * c) * d1**2\n"
         "                    + 2 * (l2**2 + l1 * l2 * c) * d1 * d2 + l2**2 * d2**2)"),
        ("def heuristic(c):\n", "def heuristic(c):\n        return 0.0\n"),
        ("for v in _nb(u, free.shape):", "for v in _nb(u, free.shape)[::-1]:"),
        ("return path[::-1]", "return np.array(path[::-1])"))
    result = by_function(judge_notebooks([write_notebook(tmp_path / "alt.ipynb", right, code,
                                                    assignment=NAME)])[0])
    for fn, check in result.items():
        assert check["passed"] == check["total"], (fn, check["diagnoses"])


def test_empty_grid_helper_is_kinlibs_grid():
    grid = P._empty_grid(1.0, 0.8, 16, 24)
    free = np.ones((16, 24), dtype=bool)
    free[3, :] = False
    plan = P._plan(free, (1, 1), (5, 1), 1.0, 0.8, "joint")
    assert plan.success and len(plan.cells) == 16 - 4 + 1
    assert dataclasses.replace(grid, occupied=~free).occupied[3].all()
