"""What notebook 14 (configuration-space planning) relies on, tested against independent routes.

The lesson's scene (l1 = 1, l2 = 0.8, two discs and a triangle) is planned with kinlib;
here its grid, its paths and their costs are checked with the plain scalar geometry and the
plain Dijkstra of tests/planning_reference.py, the exercises' answers with closed forms,
and the drawing helpers of kinlib.plot.cspace against what they were given.
"""

import functools
import math

import matplotlib
import matplotlib.pyplot as plt
import numpy as np
import pytest
from matplotlib.colors import to_rgb
from planning_reference import (
    MOVES,
    arm_clearance,
    dense,
    occupancy_disagreements,
    ref_cost,
    ref_dijkstra,
    theta,
)

import kinlib as kl
from kinlib import KinlibError
from kinlib.plot.cspace import (
    CSPACE_EXTENT,
    cspace_image,
    plot_cspace,
    plot_obstacles,
    wrap_path,
)

matplotlib.use("agg")

L1, L2 = 1.0, 0.8
SCENE = [("c", (0.4, 1.45), 0.2), ("c", (1.2, -0.75), 0.25),
         ("p", [(-1.7, -0.5), (-1.2, -0.5), (-1.2, 0.2)])]


def obstacles():
    return [kl.Circle(o[1], o[2]) if o[0] == "c" else kl.Polygon(o[1]) for o in SCENE]


@functools.cache
def lesson():
    """The notebook's grid, start, goal and the two optimal plans."""
    grid = kl.planar_2r_cspace(L1, L2, obstacles(), n=96)
    ik_s = kl.planar_2r_ik(-1.0, 0.9, L1, L2, elbow="down")
    ik_g = kl.planar_2r_ik(1.4, -0.1, L1, L2, elbow="down")
    start, goal = (ik_s.theta1, ik_s.theta2), (ik_g.theta1, ik_g.theta2)
    plans = {m: kl.astar(grid, start, goal, metric=m) for m in ("joint", "ee")}
    return grid, start, goal, plans


def cell(n, q):
    """The cell of angle q on n cells, by the documented rule ⌊(q + π)/h⌋ mod n."""
    return math.floor((q + math.pi) / (2 * math.pi / n)) % n


# --------------------------------------------------------------------------- the lesson's grid


def test_lesson_grid_matches_plain_geometry_in_every_cell():
    grid, *_ = lesson()
    n1, n2 = grid.shape
    margin = 0.5 * ((L1 + L2) * 2 * math.pi / n1 + L2 * 2 * math.pi / n2)
    assert grid.margin == pytest.approx(margin)
    checked, wrong = occupancy_disagreements(grid, SCENE, L1, L2, margin)
    assert not wrong and checked > 0.99 * n1 * n2, wrong[:5]


def test_only_link_2_reaches_the_lesson_obstacles():
    """Every point of every obstacle is farther from the base than l1 + margin."""
    grid, *_ = lesson()
    for o in SCENE:
        if o[0] == "c":
            nearest = math.hypot(*o[1]) - o[2]
        else:  # the triangle does not contain the base: its nearest point is on an edge
            V = o[1]
            nearest = min(math.hypot(*p) for k in range(len(V))
                          for p in [np.array(V[k]) + s * (np.array(V[k - 1]) - V[k])
                                    for s in np.linspace(0, 1, 2001)])
        assert nearest > L1 + grid.margin


def test_a_disc_only_link_2_reaches_is_a_blob_one_link_1_reaches_a_band():
    """Exercise 14.1's answer from geometry: no θ1 column or θ2 row is all red; the disc
    link 1 passes through fills every θ2 of the column at its direction."""
    n = 48
    red = kl.planar_2r_cspace(L1, L2, [kl.Circle((0.4, 1.45), 0.2)], n=n)
    near = kl.planar_2r_cspace(L1, L2, [kl.Circle((0.35, -0.35), 0.12)], n=n)
    occ = np.array([[arm_clearance((theta(n, i), theta(n, j)), L1, L2,
                                   [("c", (0.4, 1.45), 0.2)]) < red.margin
                     for j in range(n)] for i in range(n)])
    assert occ.any() and not occ.all(axis=1).any() and not occ.all(axis=0).any()
    np.testing.assert_array_equal(red.occupied, occ)
    i = cell(n, -math.pi / 4)                       # link 1 points at the disc's centre
    assert all(arm_clearance((theta(n, i), theta(n, j)), L1, L2,
                             [("c", (0.35, -0.35), 0.12)]) == 0 for j in range(n))
    assert near.occupied[i].all()


# --------------------------------------------------------------------------- the lesson's paths


@pytest.mark.parametrize("metric", ["joint", "ee"])
def test_lesson_plans_are_optimal(metric):
    grid, start, goal, plans = lesson()
    s = (cell(96, start[0]), cell(96, start[1]))
    t = (cell(96, goal[0]), cell(96, goal[1]))
    # an "ee" move costs the same at every θ1 (turning θ1 rotates the whole arm): one per (j, k)
    per_move = functools.cache(lambda j, k: ref_cost(grid, metric, 0, j, k))
    want = ref_dijkstra(grid, metric, s, t, cost=lambda i, j, k: per_move(j, k))
    plan = plans[metric]
    assert plan.success and plan.cost == pytest.approx(want, rel=1e-9)
    assert tuple(plan.cells[0]) == s and tuple(plan.cells[-1]) == t
    if metric == "joint":  # and with every move charged at its own θ1
        assert ref_dijkstra(grid, metric, s, t) == pytest.approx(want, rel=1e-12)


@pytest.mark.parametrize("metric", ["joint", "ee"])
def test_lesson_paths_are_free_neighbour_moves(metric):
    grid, _, _, plans = lesson()
    plan = plans[metric]
    assert not grid.occupied[plan.cells[:, 0], plan.cells[:, 1]].any()
    steps = np.round(np.diff(plan.q, axis=0) / grid.step).astype(int)
    assert all(tuple(m) in MOVES for m in steps)
    np.testing.assert_allclose(np.diff(plan.q, axis=0), steps * grid.step, atol=1e-12)
    for q in dense(plan.q, 10):                     # in between the cells too
        assert arm_clearance(q, L1, L2, SCENE) > 0
    tip = np.array([(L1 * math.cos(a) + L2 * math.cos(a + b),
                     L1 * math.sin(a) + L2 * math.sin(a + b)) for a, b in plan.q])
    np.testing.assert_allclose(plan.xy, tip, atol=1e-12)


# --------------------------------------------------------------------------- the exercises


@pytest.mark.parametrize(("n", "a", "b"), [(96, (3.0, 0.0), (-3.0, 0.0)),
                                           ((40, 24), (-3.0, 2.9), (2.5, -3.1)),
                                           ((30, 50), (0.3, -1.0), (2.0, 0.4))])
def test_joint_cost_on_an_empty_torus_is_the_wrapped_octile_distance(n, a, b):
    n1, n2 = (n, n) if np.ndim(n) == 0 else n
    h1, h2 = 2 * math.pi / n1, 2 * math.pi / n2
    di = abs(cell(n1, a[0]) - cell(n1, b[0]))
    dj = abs(cell(n2, a[1]) - cell(n2, b[1]))
    di, dj = min(di, n1 - di), min(dj, n2 - dj)
    diag = min(di, dj)
    want = diag * math.hypot(h1, h2) + (di - diag) * h1 + (dj - diag) * h2
    plan = kl.astar(kl.planar_2r_cspace(L1, L2, [], n=n), a, b, metric="joint")
    assert plan.cost == pytest.approx(want, rel=1e-12)
    if n == 96:
        assert plan.cost == pytest.approx(5 * h1)        # exercise 14.5: 93 → … → 2
        assert list(plan.cells[:, 0]) == [93, 94, 95, 0, 1, 2]


def test_the_end_moves_with_the_elbow_when_link_2_keeps_its_direction():
    """Exercise 14.3: δθ1 + δθ2 = 0 turns link 1 only; the end moves l1·|δθ1|."""
    rng = np.random.default_rng(14)
    for th, d in zip(rng.uniform(-math.pi, math.pi, (50, 2)), rng.uniform(-1, 1, 50),
                     strict=True):
        assert kl.planar_2r_metric(th, [d, -d], L1, L2) == pytest.approx(L1 * abs(d), rel=1e-12)
        h = 1e-6
        p0 = kl.planar_2r_fk(*th, L1, L2)[:2, 3]
        p1 = kl.planar_2r_fk(th[0] + h * d, th[1] - h * d, L1, L2)[:2, 3]
        assert np.linalg.norm(p1 - p0) / h == pytest.approx(L1 * abs(d), rel=1e-5, abs=1e-9)


def test_the_metric_in_absolute_link_angles():
    """Exercise 14.2: G' = [[l1², l1 l2 cos(φ1 − φ2)], [·, l2²]] with φ = (θ1, θ1 + θ2)."""
    rng = np.random.default_rng(2)
    for th, dth in zip(rng.uniform(-4, 4, (50, 2)), rng.uniform(-2, 2, (50, 2)), strict=True):
        p1, p2 = th[0], th[0] + th[1]
        dphi = np.array([dth[0], dth[0] + dth[1]])
        c = L1 * L2 * math.cos(p1 - p2)
        G = np.array([[L1**2, c], [c, L2**2]])
        assert math.sqrt(dphi @ G @ dphi) == pytest.approx(
            float(kl.planar_2r_metric(th, dth, L1, L2)), rel=1e-10, abs=1e-12)


# --------------------------------------------------------------------------- the pictures


def test_cspace_image_tints_each_obstacles_cells():
    n1, n2 = 18, 14
    scene = [SCENE[0], ("c", (0.35, -0.35), 0.12)]
    grid = kl.planar_2r_cspace(L1, L2, [kl.Circle(o[1], o[2]) for o in scene], n=(n1, n2))
    colors = ["tab:red", "tab:cyan"]
    img = cspace_image(grid, colors)
    assert img.shape == (n2, n1, 3)
    for i in range(n1):
        for j in range(n2):
            hit = [arm_clearance((theta(n1, i), theta(n2, j)), L1, L2, [o]) < grid.margin
                   for o in scene]
            want = np.ones(3)
            for c, h in zip(colors, hit, strict=True):
                if h:
                    want = 0.55 * np.array(to_rgb(c)) + 0.45
            np.testing.assert_allclose(img[j, i], want, err_msg=str((i, j)))
    assert ((img != 1).any(axis=2).T == grid.occupied).all()


def test_plot_cspace_puts_theta1_right_and_theta2_up():
    grid = kl.planar_2r_cspace(L1, L2, [kl.Circle((1.5, 0.0), 0.2)], n=(20, 10))
    fig, ax = plt.subplots()
    shown = plot_cspace(ax, cspace_image(grid))
    assert shown.get_extent() == list(CSPACE_EXTENT) and shown.origin == "lower"
    for i, j in np.argwhere(grid.occupied):
        x, y = grid.q_of([i, j])                    # the cell's centre, read off the axes
        col = int((x + math.pi) / (2 * math.pi) * 20)
        row = int((y + math.pi) / (2 * math.pi) * 10)
        assert (shown.get_array()[row, col] != 1).any()
    plt.close(fig)


def test_plot_obstacles_draws_what_it_is_given():
    fig, ax = plt.subplots()
    obs = obstacles()
    drawn = plot_obstacles(ax, obs, ["red", "orange", "purple"], reach=L1 + L2, lim=2.5)
    assert len(drawn) == 3 and len(ax.patches) == 4           # and the reach
    assert drawn[0].center == (0.4, 1.45) and drawn[0].radius == 0.2
    np.testing.assert_allclose(drawn[2].get_xy()[:3], SCENE[2][1])
    assert matplotlib.colors.same_color(drawn[1].get_facecolor()[:3], "orange")
    assert ax.get_xlim() == (-2.5, 2.5) and ax.patches[-1].radius == pytest.approx(1.8)
    plt.close(fig)


def test_wrap_path_folds_into_the_square_and_breaks_at_seams():
    rng = np.random.default_rng(5)
    q = np.cumsum(rng.uniform(-0.4, 0.4, (300, 2)), axis=0) + [3.0, -3.0]
    w = wrap_path(q)
    breaks = np.isnan(w).all(axis=1)
    pts = w[~breaks]
    assert ((pts >= -math.pi) & (pts < math.pi)).all()
    np.testing.assert_allclose(np.cos(pts), np.cos(q), atol=1e-12)
    np.testing.assert_allclose(np.sin(pts), np.sin(q), atol=1e-12)
    turns = np.floor((q + math.pi) / (2 * math.pi))   # which copy of the square each row is in
    crossings = int((np.diff(turns, axis=0) != 0).any(axis=1).sum())
    assert crossings > 3 and breaks.sum() == crossings


BAD = [
    (lambda ax: plot_obstacles(ax, [(0.0, 1.0)]), "obstacles"),
    (lambda ax: plot_obstacles(ax, obstacles(), ["red"]), "colors"),
    (lambda ax: plot_obstacles(ax, obstacles(), ["red", "nocolour", "blue"]), "colors"),
    (lambda ax: plot_obstacles(ax, obstacles(), lim=-1.0), "lim"),
    (lambda ax: cspace_image(np.zeros((4, 4))), "grid"),
    (lambda ax: plot_cspace(ax, np.zeros((4, 4, 2))), "image"),
    (lambda ax: wrap_path([1.0, 2.0, 3.0]), "q"),
    (lambda ax: wrap_path([[np.nan, 0.0]]), "q"),
]


@pytest.mark.parametrize(("call", "name"), BAD, ids=[b[1] + str(k) for k, b in enumerate(BAD)])
def test_bad_input_to_the_pictures(call, name):
    fig, ax = plt.subplots()
    with pytest.raises(KinlibError) as info:
        call(ax)
    plt.close(fig)
    msg = str(info.value)
    assert msg.startswith(name) and ("expected" in msg or "NaN or infinity" in msg), msg
