"""Plain reference implementations for tests/test_planning.py (independent of
kinlib.planning.cspace).

Scalar 2-D geometry, the 8 grid moves, the documented edge costs and a plain-heapq Dijkstra,
written from the formulas in the docstrings of kinlib.planning.cspace / kinlib.planning.astar,
not from their code.
"""

import heapq
import itertools
import math

import numpy as np

from kinlib import planar_2r_fk
from kinlib.planning.cspace import Circle, Polygon

MOVES = [(1, 0), (0, 1), (-1, 0), (0, -1), (1, 1), (-1, 1), (-1, -1), (1, -1)]

# --------------------------------------------------------------------------- plain geometry


def pt_seg(p, a, b):
    ax, ay = a
    bx, by = b
    px, py = p
    dx, dy = bx - ax, by - ay
    L2 = dx * dx + dy * dy
    t = 0.0 if L2 == 0 else max(0.0, min(1.0, ((px - ax) * dx + (py - ay) * dy) / L2))
    return math.hypot(px - ax - t * dx, py - ay - t * dy)


def orient(o, a, b):
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])


def seg_seg(a, b, c, d):
    d1, d2, d3, d4 = orient(c, d, a), orient(c, d, b), orient(a, b, c), orient(a, b, d)
    if ((d1 > 0 > d2) or (d1 < 0 < d2)) and ((d3 > 0 > d4) or (d3 < 0 < d4)):
        return 0.0
    return min(pt_seg(a, c, d), pt_seg(b, c, d), pt_seg(c, a, b), pt_seg(d, a, b))


def inside_poly(p, verts):
    x, y = p
    inside = False
    for k in range(len(verts)):
        (x1, y1), (x2, y2) = verts[k], verts[(k + 1) % len(verts)]
        if (y1 > y) != (y2 > y) and x < x1 + (y - y1) * (x2 - x1) / (y2 - y1):
            inside = not inside
    return inside


def seg_obstacle(a, b, obs):
    """Exact distance between segment a→b and an obstacle given as ('c', c, r) / ('p', V)."""
    if obs[0] == "c":
        return max(0.0, pt_seg(obs[1], a, b) - obs[2])
    V = obs[1]
    if inside_poly(a, V):
        return 0.0
    return min(seg_seg(a, b, V[k], V[(k + 1) % len(V)]) for k in range(len(V)))


def arm_clearance(q, l1, l2, scene):
    e = (l1 * math.cos(q[0]), l1 * math.sin(q[0]))
    p = (e[0] + l2 * math.cos(q[0] + q[1]), e[1] + l2 * math.sin(q[0] + q[1]))
    return min(
        (min(seg_obstacle((0.0, 0.0), e, o), seg_obstacle(e, p, o)) for o in scene),
        default=math.inf,
    )


def to_kinlib(scene):
    return [Circle(o[1], o[2]) if o[0] == "c" else Polygon(o[1]) for o in scene]


def random_scene(rng, n_circles=3, polygon=True):
    scene = []
    for _ in range(n_circles):
        r, phi = rng.uniform(0.9, 2.0), rng.uniform(-np.pi, np.pi)
        scene.append(("c", (r * math.cos(phi), r * math.sin(phi)), rng.uniform(0.1, 0.3)))
    if polygon:
        cx, cy = rng.uniform(-1.5, 1.5, 2)
        if math.hypot(cx + 0.2, cy + 0.2) < 1.0:  # keep it away from the base
            cx, cy = 1.2, -0.6
        scene.append(("p", [(cx, cy), (cx + 0.4, cy), (cx + 0.2, cy + 0.15), (cx + 0.4, cy + 0.4),
                            (cx, cy + 0.4)]))  # not convex
    return scene


def theta(n, k):
    return -math.pi + (k + 0.5) * 2 * math.pi / n


def ref_cost(grid, metric, i, j, k):
    n1, n2 = grid.shape
    di, dj = MOVES[k]
    h1, h2 = 2 * math.pi / n1, 2 * math.pi / n2
    if metric == "joint":
        return math.hypot(di * h1, dj * h2)
    t1, t2 = theta(n1, i), theta(n2, j)
    x, w = np.polynomial.legendre.leggauss(8)
    s = (x + 1) / 2
    c = np.cos(t2 + s * dj * h2)
    d1, d2, l1, l2 = di * h1, dj * h2, grid.l1, grid.l2
    sq = (l1**2 + l2**2 + 2 * l1 * l2 * c) * d1**2 + 2 * (l2**2 + l1 * l2 * c) * d1 * d2 + (
        l2**2 * d2**2)
    arc = float(np.sum(w / 2 * np.sqrt(np.maximum(sq, 0))))
    a = planar_2r_fk(t1, t2, l1, l2)[:2, 3]
    b = planar_2r_fk(t1 + d1, t2 + d2, l1, l2)[:2, 3]
    return max(arc, float(np.linalg.norm(b - a)))


def occupancy_disagreements(grid, scene, l1, l2, margin) -> tuple[int, list]:
    """Every cell of ``grid`` against plain geometry (the arm's clearance from ``scene``):
    the number of cells decided (not within 1e-9 of the margin) and the cells where the
    grid says otherwise."""
    n1, n2 = grid.shape
    decided, wrong = 0, []
    for i in range(n1):
        for j in range(n2):
            d = arm_clearance((theta(n1, i), theta(n2, j)), l1, l2, scene)
            if abs(d - margin) > 1e-9:
                decided += 1
                if grid.occupied[i, j] != (d < margin):
                    wrong.append((i, j, d))
    return decided, wrong


def ref_dijkstra(grid, metric, s, t, cost=None):
    """The cheapest cost from cell s to cell t over free cells of the 8-connected torus;
    a move costs ``cost(i, j, k)`` (default: :func:`ref_cost` of ``metric``)."""
    cost = cost or (lambda i, j, k: ref_cost(grid, metric, i, j, k))
    n1, n2 = grid.shape
    dist = {s: 0.0}
    heap, done = [(0.0, s)], set()
    while heap:
        d, u = heapq.heappop(heap)
        if u in done:
            continue
        done.add(u)
        if u == t:
            return d
        for k, (di, dj) in enumerate(MOVES):
            v = ((u[0] + di) % n1, (u[1] + dj) % n2)
            if grid.occupied[v] or v in done:
                continue
            nd = d + cost(u[0], u[1], k)
            if nd < dist.get(v, math.inf):
                dist[v] = nd
                heapq.heappush(heap, (nd, v))
    return math.inf


def free_cells(grid, rng, k):
    free = np.argwhere(~grid.occupied)
    return [tuple(int(x) for x in free[m]) for m in rng.choice(len(free), k, replace=False)]


def dense(q, m=20):
    """m configurations per step along the straight joint moves (plus the last one)."""
    s = np.arange(m)[:, None] / m
    parts = [a + s * (b - a) for a, b in itertools.pairwise(q)]
    return np.vstack(parts + [q[-1:]])


def ee_length(q, l1, l2, m=64):
    p = planar_2r_fk(*dense(q, m).T, l1, l2)[:, :2, 3]
    return float(np.sum(np.linalg.norm(np.diff(p, axis=0), axis=1)))


def joint_length(q):
    return float(np.sum(np.linalg.norm(np.diff(q, axis=0), axis=1)))
