"""Configuration-space planning for the planar 2R arm (seed 001): kinlib.planning.cspace,
kinlib.planning.astar.

Reference values are recomputed from the documented formulas with independent, plain
(scalar) geometry, a plain-heapq Dijkstra (tests/planning_reference.py) and the seed's
expanded metric.
"""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from planning_reference import (
    MOVES,
    arm_clearance,
    dense,
    ee_length,
    free_cells,
    inside_poly,
    joint_length,
    occupancy_disagreements,
    pt_seg,
    random_scene,
    ref_cost,
    ref_dijkstra,
    seg_obstacle,
    theta,
    to_kinlib,
)

from kinlib import KinlibError, planar_2r_fk, planar_2r_jacobian
from kinlib.planning.astar import astar, cost_to_go
from kinlib.planning.cspace import Circle, Polygon, planar_2r_cspace, planar_2r_metric

# --------------------------------------------------------------------------- the metric

angles = st.floats(-math.pi, math.pi)
steps = st.floats(-2.0, 2.0)
lengths = st.floats(0.1, 3.0)


@settings(max_examples=150, deadline=None)
@given(angles, angles, steps, steps, lengths, lengths)
def test_metric_is_jacobian_norm_and_seed_formula(t1, t2, d1, d2, l1, l2):
    c = planar_2r_metric([t1, t2], [d1, d2], l1, l2)
    J = planar_2r_jacobian(t1, t2, l1, l2)[:2]
    assert c == pytest.approx(np.linalg.norm(J @ [d1, d2]), rel=1e-9, abs=1e-12)
    c2 = math.cos(t2)
    seed = ((l1**2 + l2**2 + 2 * l1 * l2 * c2) * d1**2 + 2 * (l2**2 + l1 * l2 * c2) * d1 * d2
            + l2**2 * d2**2)
    assert c**2 == pytest.approx(seed, rel=1e-9, abs=1e-9)
    # the earlier slide's absolute angles θ1' = θ1, θ2' = θ1 + θ2 give the same number
    a1, a2, da1, da2 = t1, t1 + t2, d1, d1 + d2
    old = (l1 * da1) ** 2 + (l2 * da2) ** 2 + 2 * l1 * da1 * l2 * da2 * math.cos(a1 - a2)
    assert c**2 == pytest.approx(old, rel=1e-9, abs=1e-9)


@settings(max_examples=150, deadline=None)
@given(angles, angles, steps, steps, lengths, lengths)
def test_metric_is_the_limit_of_end_effector_displacements(t1, t2, d1, d2, l1, l2):
    c = float(planar_2r_metric([t1, t2], [d1, d2], l1, l2))
    p0 = planar_2r_fk(t1, t2, l1, l2)[:2, 3]
    # second derivative of the end along the line is at most l1 d1² + l2 (d1 + d2)²
    bound = l1 * d1**2 + l2 * (d1 + d2) ** 2
    for h in (1e-2, 1e-3, 1e-4):
        p = planar_2r_fk(t1 + h * d1, t2 + h * d2, l1, l2)[:2, 3]
        assert abs(np.linalg.norm(p - p0) / h - c) <= 0.5 * h * bound + 1e-9
        if c > 0.05:
            assert abs(np.linalg.norm(p - p0) / (h * c) - 1) <= 0.5 * h * bound / c + 1e-8


def test_metric_batches():
    th = np.array([[0.0, 0.0], [0.0, np.pi]])
    np.testing.assert_allclose(planar_2r_metric(th, [1.0, 0.0], 1.0, 0.5), [1.5, 0.5])
    assert planar_2r_metric(np.zeros((4, 3, 2)), np.ones((3, 2)), 1.0, 1.0).shape == (4, 3)


# --------------------------------------------------------------------------- obstacles


def test_obstacle_distances_match_plain_geometry():
    rng = np.random.default_rng(1)
    V = [(0.0, 0.0), (2.0, 0.0), (1.0, 0.5), (2.0, 1.0), (0.0, 1.0)]  # a notch: not convex
    for verts in (V, V[::-1]):
        poly = Polygon(verts)
        P = rng.uniform(-1, 3, (300, 2))
        d = poly.distance(P)
        for p, dk in zip(P, d, strict=True):
            edge = min(pt_seg(p, verts[k], verts[(k + 1) % 5]) for k in range(5))
            assert dk == pytest.approx(-edge if inside_poly(p, verts) else edge, abs=1e-12)
        A, B = rng.uniform(-1, 3, (300, 2)), rng.uniform(-1, 3, (300, 2))
        got = poly.segment_distance(A, B)
        want = [seg_obstacle(a, b, ("p", verts)) for a, b in zip(A, B, strict=True)]
        np.testing.assert_allclose(got, want, atol=1e-12)
    assert Polygon(V).distance([1.5, 0.5]) > 0  # in the notch: outside
    circ = Circle((0.5, -0.2), 0.7)
    A, B = rng.uniform(-2, 2, (300, 2)), rng.uniform(-2, 2, (300, 2))
    want = [seg_obstacle(a, b, ("c", (0.5, -0.2), 0.7)) for a, b in zip(A, B, strict=True)]
    np.testing.assert_allclose(circ.segment_distance(A, B), want, atol=1e-12)
    np.testing.assert_allclose(circ.distance(A), np.hypot(A[:, 0] - 0.5, A[:, 1] + 0.2) - 0.7)


# --------------------------------------------------------------------------- occupancy


NEAR_BASE = [("c", (0.45, 0.0), 0.08), ("p", [(-0.5, 0.3), (-0.3, 0.3), (-0.4, 0.5)]),
             ("p", [(1.4, 1.2), (1.8, 1.2), (1.6, 1.3), (1.8, 1.5), (1.4, 1.5)])]


@pytest.mark.parametrize(("seed", "margin"), [(0, None), (1, None), ("near base", 0.03)])
def test_occupancy_matches_brute_force(seed, margin):
    l1, l2, n1, n2 = 1.0, 0.8, 24, 20
    if margin is None:
        scene = random_scene(np.random.default_rng(seed))
        margin = 0.5 * ((l1 + l2) * 2 * math.pi / n1 + l2 * 2 * math.pi / n2)
        grid = planar_2r_cspace(l1, l2, to_kinlib(scene), n=(n1, n2))
    else:  # link 1 alone hits the obstacles near the base
        scene = NEAR_BASE
        grid = planar_2r_cspace(l1, l2, to_kinlib(scene), n=(n1, n2), margin=margin)
    assert grid.margin == pytest.approx(margin)
    assert grid.occupied.shape == (n1, n2)
    checked, wrong = occupancy_disagreements(grid, scene, l1, l2, margin)
    assert not wrong and checked > 0.95 * n1 * n2, wrong[:5]
    assert 0 < grid.occupied.sum() < n1 * n2


def test_zero_margin_means_touching():
    grid = planar_2r_cspace(1.0, 1.0, [Circle((1.5, 0.0), 0.2)], n=16, margin=0.0)
    assert grid.occupied.any()
    for i, j in zip(*np.nonzero(grid.occupied), strict=True):
        assert arm_clearance((theta(16, i), theta(16, j)), 1, 1, [("c", (1.5, 0), 0.2)]) == 0


def test_cells_wrap_around():
    grid = planar_2r_cspace(1.0, 1.0, [], n=(12, 10))
    np.testing.assert_array_equal(grid.cell_of([np.pi + 0.01, -np.pi - 0.01]), [0, 9])
    np.testing.assert_array_equal(grid.cell_of([3 * np.pi + 0.01, 2 * np.pi]), [0, 5])
    np.testing.assert_allclose(grid.q_of([12, -1]), grid.q_of([0, 9]))
    np.testing.assert_allclose(grid.q_of([0, 9]), [theta(12, 0), theta(10, 9)])
    np.testing.assert_allclose(grid.theta1, [theta(12, k) for k in range(12)])
    cells = np.array([[3, 7], [11, 0]])
    np.testing.assert_array_equal(grid.cell_of(grid.q_of(cells)), cells)


# --------------------------------------------------------------------------- optimality


@pytest.mark.parametrize("metric", ["joint", "ee"])
@pytest.mark.parametrize("seed", [3, 4, 5])
def test_astar_is_optimal(metric, seed):
    rng = np.random.default_rng(seed)
    n = (16, 20) if seed % 2 else (22, 18)
    grid = planar_2r_cspace(1.0, 0.7, to_kinlib(random_scene(rng)), n=n)
    s, t = free_cells(grid, rng, 2)
    want = ref_dijkstra(grid, metric, s, t)
    qs, qt = grid.q_of(s), grid.q_of(t)
    plan = astar(grid, qs, qt, metric=metric)
    dijk = astar(grid, qs, qt, metric=metric, heuristic=False)
    assert plan.success == dijk.success == (want < math.inf)
    assert want < math.inf or seed == 5  # these scenes are connected (checked once)
    if want < math.inf:
        assert plan.cost == pytest.approx(want, rel=1e-9)
        assert dijk.cost == pytest.approx(want, rel=1e-9)
        assert plan.expanded <= dijk.expanded
        assert tuple(plan.cells[0]) == s and tuple(plan.cells[-1]) == t
        steps = [ref_cost(grid, metric, *c, MOVES.index(tuple(m)))
                 for c, m in zip(plan.cells[:-1], np.diff(plan.q, axis=0) / grid.step,
                                 strict=True)
                 for m in [np.round(m).astype(int)]]
        assert sum(steps) == pytest.approx(want, rel=1e-9)
    ctg = cost_to_go(grid, qt, metric)
    if want < math.inf:
        assert ctg.cost[s] == pytest.approx(want, rel=1e-9)
    else:
        assert np.isinf(ctg.cost[s])


def test_cost_to_go_arrows_follow_optimal_moves():
    rng = np.random.default_rng(7)
    grid = planar_2r_cspace(1.0, 1.0, to_kinlib(random_scene(rng)), n=16)
    (t,) = free_cells(grid, rng, 1)
    ctg = cost_to_go(grid, grid.q_of(t), "ee")
    assert ctg.cost[t] == 0 and not ctg.next_step[t].any()
    assert np.isinf(ctg.cost[grid.occupied]).all()
    for i, j in np.argwhere(np.isfinite(ctg.cost)):
        if (i, j) == t:
            continue
        u = ctg.next_step[i, j]
        assert np.linalg.norm(u) == pytest.approx(1.0)
        k = MOVES.index(tuple(int(x) for x in np.sign(np.round(u, 9))))
        v = ((i + MOVES[k][0]) % 16, (j + MOVES[k][1]) % 16)
        step = ref_cost(grid, "ee", i, j, k)
        assert ctg.cost[i, j] == pytest.approx(step + ctg.cost[v], rel=1e-9)


# --------------------------------------------------------------------------- paths


@pytest.mark.parametrize("seed", [10, 11, 12, 13])
def test_paths_never_touch_obstacles(seed):
    rng = np.random.default_rng(seed)
    scene = random_scene(rng, n_circles=4)
    l1, l2 = 1.0, 0.9
    grid = planar_2r_cspace(l1, l2, to_kinlib(scene), n=32)
    for _ in range(50):  # a start and goal that are connected and far apart
        s, t = free_cells(grid, rng, 2)
        if len(astar(grid, grid.q_of(s), grid.q_of(t)).q) > 12:
            break
    for metric in ("joint", "ee"):
        plan = astar(grid, grid.q_of(s), grid.q_of(t), metric=metric)
        assert plan.success and len(plan.q) > 12, plan.message
        assert plan.xy.shape == plan.q.shape == plan.cells.shape
        for q in dense(plan.q):
            assert arm_clearance(q, l1, l2, scene) > 0, (metric, q)


def test_path_across_the_seam_is_short_and_continuous():
    grid = planar_2r_cspace(1.0, 1.0, [Circle((0.0, 1.6), 0.3)], n=64)
    plan = astar(grid, [3.0, 0.5], [-3.0, 0.5])
    h = 2 * math.pi / 64
    assert plan.success
    assert plan.cost == pytest.approx(3 * h)  # 62 → 63 → 0 → 1 across θ1 = ±π
    assert plan.cost < 2 * math.pi - 6.0 + 2 * h
    steps = np.diff(plan.q, axis=0)
    assert np.all(np.abs(steps) <= h + 1e-12)
    assert plan.q[-1, 0] == pytest.approx(plan.q[0, 0] + 3 * h)
    np.testing.assert_allclose(np.cos(plan.q[-1]), np.cos(grid.q_of(plan.cells[-1])))
    np.testing.assert_allclose(plan.xy, planar_2r_fk(plan.q[:, 0], plan.q[:, 1], 1, 1)[:, :2, 3])


@pytest.mark.parametrize("with_obstacles", [False, True])
def test_ee_metric_gives_shorter_end_effector_paths(with_obstacles):
    scene = [("c", (0.2, 1.5), 0.25), ("p", [(-1.6, -0.3), (-1.1, -0.3), (-1.1, 0.2)])]
    obstacles = to_kinlib(scene) if with_obstacles else []
    l1, l2 = 1.0, 0.8
    grid = planar_2r_cspace(l1, l2, obstacles, n=48)
    start, goal = [-0.4, 1.9], [2.4, -1.2]
    pj = astar(grid, start, goal, metric="joint")
    pe = astar(grid, start, goal, metric="ee")
    assert pj.success and pe.success
    ej, ee = ee_length(pj.q, l1, l2), ee_length(pe.q, l1, l2)
    assert ee <= ej * (1 + 1e-5)
    assert ee < 0.98 * ej  # and really shorter in these scenes
    assert joint_length(pj.q) <= joint_length(pe.q) + 1e-9
    # the polyline through the cells is the chord sum: a lower bound of the ee cost
    chords = float(np.sum(np.linalg.norm(np.diff(pe.xy, axis=0), axis=1)))
    assert chords <= pe.cost + 1e-12 and pe.cost == pytest.approx(ee, rel=1e-4)


# --------------------------------------------------------------------------- failures


def test_blocked_start_or_goal():
    grid = planar_2r_cspace(1.0, 1.0, [Circle((1.5, 0.0), 0.3)], n=32)
    assert grid.occupied[tuple(grid.cell_of([0.0, 0.0]))]
    for metric in ("joint", "ee"):
        bad_goal = astar(grid, [np.pi / 2, 0.0], [0.0, 0.0], metric=metric)
        assert not bad_goal.success and "goal" in bad_goal.message
        assert bad_goal.cells.shape == (0, 2) and bad_goal.cost == math.inf
        bad_start = astar(grid, [0.0, 0.0], [np.pi / 2, 0.0], metric=metric)
        assert not bad_start.success and "start" in bad_start.message
    ctg = cost_to_go(grid, [0.0, 0.0], "joint")
    assert np.isinf(ctg.cost).all() and not ctg.next_step.any()


def test_wall_separates_start_from_goal():
    walls = [("p", [(0.25, -0.05), (3.0, -0.05), (3.0, 0.05), (0.25, 0.05)]),
             ("p", [(-3.0, -0.05), (-0.25, -0.05), (-0.25, 0.05), (-3.0, 0.05)])]
    grid = planar_2r_cspace(1.0, 1.0, to_kinlib(walls), n=64)
    start, goal = [np.pi / 2, 0.0], [-np.pi / 2, 0.0]
    assert not grid.occupied[tuple(grid.cell_of(start))]
    assert not grid.occupied[tuple(grid.cell_of(goal))]
    for metric in ("joint", "ee"):
        for heuristic in (True, False):
            plan = astar(grid, start, goal, metric=metric, heuristic=heuristic)
            assert not plan.success and "no path" in plan.message
            assert 0 < plan.expanded <= (~grid.occupied).sum()
    ctg = cost_to_go(grid, goal, "ee")
    assert np.isinf(ctg.cost[tuple(grid.cell_of(start))])


# --------------------------------------------------------------------------- bad input

GRID = planar_2r_cspace(1.0, 1.0, [], n=8)

BAD = [
    ("start NaN", lambda: astar(GRID, [np.nan, 0.0], [0.0, 0.0]), "start"),
    ("start shape", lambda: astar(GRID, [0.0, 0.0, 0.0], [0.0, 0.0]), "start"),
    ("start batch", lambda: astar(GRID, [[0.0, 0.0]], [0.0, 0.0]), "start"),
    ("goal text", lambda: astar(GRID, [0.0, 0.0], "up"), "goal"),
    ("metric", lambda: astar(GRID, [0.0, 0.0], [1.0, 0.0], metric="manhattan"), "metric"),
    ("heuristic", lambda: astar(GRID, [0.0, 0.0], [1.0, 0.0], heuristic="yes"), "heuristic"),
    ("grid", lambda: astar(np.zeros((8, 8)), [0.0, 0.0], [1.0, 0.0]), "grid"),
    ("ctg metric", lambda: cost_to_go(GRID, [0.0, 0.0], "euclid"), "metric"),
    ("ctg goal", lambda: cost_to_go(GRID, [0.0], "joint"), "goal"),
    ("polygon 2", lambda: Polygon([(0.0, 0.0), (1.0, 0.0)]), "Polygon"),
    ("polygon flat", lambda: Polygon([(0.0, 0.0), (1.0, 0.0), (2.0, 0.0)]), "Polygon"),
    ("polygon bowtie", lambda: Polygon([(0, 0), (1, 1), (1, 0), (0, 1)]), "Polygon"),
    ("polygon NaN", lambda: Polygon([(0, 0), (1, np.nan), (1, 1)]), "Polygon"),
    ("radius < 0", lambda: Circle((0.0, 0.0), -1.0), "Circle.radius"),
    ("radius 0", lambda: Circle((0.0, 0.0), 0.0), "Circle.radius"),
    ("center", lambda: Circle((0.0, 0.0, 1.0), 1.0), "Circle.center"),
    ("l1 0", lambda: planar_2r_cspace(0.0, 1.0, []), "l1"),
    ("l2 < 0", lambda: planar_2r_cspace(1.0, -1.0, []), "l1, l2"),
    ("n 2", lambda: planar_2r_cspace(1.0, 1.0, [], n=2), "n"),
    ("n (8, 2)", lambda: planar_2r_cspace(1.0, 1.0, [], n=(8, 2)), "n"),
    ("n float", lambda: planar_2r_cspace(1.0, 1.0, [], n=8.5), "n"),
    ("margin", lambda: planar_2r_cspace(1.0, 1.0, [], n=8, margin=-0.1), "margin"),
    ("obstacles", lambda: planar_2r_cspace(1.0, 1.0, [(1.0, 1.0)], n=8), "obstacles"),
    ("metric theta", lambda: planar_2r_metric([0.0], [1.0, 0.0], 1.0, 1.0), "theta"),
    ("metric dtheta", lambda: planar_2r_metric([0.0, 0.0], [np.inf, 0], 1.0, 1.0), "dtheta"),
    ("metric l2", lambda: planar_2r_metric([0.0, 0.0], [1.0, 0.0], 1.0, 0.0), "l1, l2"),
    ("cells", lambda: GRID.q_of([0.5, 1.0]), "cells"),
]


@pytest.mark.parametrize(("call", "name"), [b[1:] for b in BAD], ids=[b[0] for b in BAD])
def test_bad_input(call, name):
    with pytest.raises(KinlibError) as info:
        call()
    msg = str(info.value)
    assert msg.startswith(name), msg
    assert "expected" in msg or "must be" in msg or "NaN or infinity" in msg, msg
