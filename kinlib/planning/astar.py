r"""A* and Dijkstra on the planar 2R arm's configuration-space grid (seed 001).

The grid of :func:`kinlib.planar_2r_cspace` is 8-connected and wraps in both joints (a
torus). Edge costs come from :meth:`kinlib.CSpaceGrid.edge_costs`:

- ``metric="joint"``: the joint-space length of each step, with the heuristic "wrapped
  Euclidean joint distance" (a lower bound: the flat torus distance obeys the triangle
  inequality and every move costs its own Euclidean length);
- ``metric="ee"``: seed 001's minimum end-effector-distance metric, with the heuristic
  "straight-line distance between the two end-effector positions" (every edge costs at
  least its end-effector chord, so this is admissible and consistent).

:func:`cost_to_go` runs Dijkstra backwards from the goal over the whole grid: the optimal
cost from every cell and the direction of its first move — seed 001's "field of arrows".

>>> from kinlib.planning.cspace import Circle, planar_2r_cspace
>>> grid = planar_2r_cspace(1.0, 1.0, [Circle((0.0, 1.5), 0.3)], n=32)
>>> plan = astar(grid, [0.0, 0.0], [np.pi, 0.0])
>>> plan.success, plan.q.shape[1], bool(np.all(np.abs(np.diff(plan.q, axis=0)) < 0.2))
(True, 2, True)
"""

from __future__ import annotations

import heapq
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from .._validate import as_array
from ..errors import KinlibError
from ..kinematics.planar import planar_2r_fk
from .cspace import NEIGHBOURS, OPPOSITE, CSpaceGrid, _check_metric

__all__ = ["PlanResult", "CostToGo", "astar", "cost_to_go"]


@dataclass(frozen=True, eq=False)
class PlanResult:
    """Result of :func:`astar`.

    Attributes
    ----------
    success : bool
        Whether a path was found (a Python bool, the flag of every kinlib result).
    message : str
        What happened (which of start/goal is blocked, or that no path exists).
    cells : ndarray (K, 2) int
        Grid cells from start to goal (empty when ``success`` is False).
    q : ndarray (K, 2)
        Their configurations, unwrapped: consecutive rows differ by one grid step
        (multiples of 2π are added where the path crosses θ = ±π), so ``q`` is continuous.
    xy : ndarray (K, 2)
        End-effector positions along the path.
    cost : float
        Sum of the edge costs (inf on failure).
    expanded : int
        Number of nodes taken from the open list and expanded.
    metric : str
        ``"joint"`` or ``"ee"``.
    """

    success: bool
    message: str
    cells: np.ndarray
    q: np.ndarray
    xy: np.ndarray
    cost: float
    expanded: int
    metric: str


class CostToGo(NamedTuple):
    """Result of :func:`cost_to_go`: ``cost`` (n1, n2), inf where the goal cannot be
    reached; ``next_step`` (n1, n2, 2), the unit C-space direction of the optimal first
    move (zero at the goal and where unreachable).

    ``success`` (a Python bool, the flag of every kinlib result) is whether a field was
    computed: the goal cell is free. Then ``cost`` is 0 at the goal and finite wherever
    the goal can be reached from; when the goal cell is occupied nothing reaches it,
    ``cost`` is inf everywhere and ``success`` is False. (Whether one particular start
    reaches the goal is ``np.isfinite(cost[cell])``.) It is derived from ``cost``, so the
    result still unpacks as ``cost, next_step = cost_to_go(...)``.
    """

    cost: np.ndarray
    next_step: np.ndarray

    @property
    def success(self) -> bool:
        """Whether the goal cell is free (its cost, 0, is finite): see the class."""
        return bool(np.isfinite(self.cost).any())


def _check_grid(grid) -> CSpaceGrid:
    if not isinstance(grid, CSpaceGrid):
        raise KinlibError(
            f"grid: expected a CSpaceGrid from planar_2r_cspace, got {type(grid).__name__}"
        )
    return grid


def _config(q, name: str) -> np.ndarray:
    a = as_array(q, name, (2,))
    if a.shape != (2,):
        raise KinlibError(f"{name}: expected one configuration (θ1, θ2), got shape {a.shape}")
    return a


def _graph(grid: CSpaceGrid, metric: str):
    """Flat neighbour table (N, 8) and edge costs (N, 8) as Python lists (fast to index)."""
    n1, n2 = grid.shape
    i, j = np.meshgrid(np.arange(n1), np.arange(n2), indexing="ij")
    ni = (i[..., None] + NEIGHBOURS[:, 0]) % n1
    nj = (j[..., None] + NEIGHBOURS[:, 1]) % n2
    nbr = (ni * n2 + nj).reshape(-1, 8)
    costs = grid.edge_costs(metric).reshape(-1, 8)
    return nbr.tolist(), costs.tolist()


def _heuristic(grid: CSpaceGrid, goal: tuple[int, int], metric: str) -> np.ndarray:
    """Lower bound on the cost from every cell to ``goal``, flat (N,)."""
    n1, n2 = grid.shape
    h1, h2 = grid.step
    if metric == "joint":
        di = np.abs(np.arange(n1) - goal[0])
        dj = np.abs(np.arange(n2) - goal[1])
        di, dj = np.minimum(di, n1 - di) * h1, np.minimum(dj, n2 - dj) * h2
        return np.hypot(di[:, None], dj[None, :]).ravel()
    T1, T2 = np.meshgrid(grid.theta1, grid.theta2, indexing="ij")
    xy = planar_2r_fk(T1, T2, grid.l1, grid.l2)[..., :2, 3]
    g = xy[goal]
    return np.hypot(xy[..., 0] - g[0], xy[..., 1] - g[1]).ravel()


def _failure(message: str, metric: str, expanded: int = 0) -> PlanResult:
    empty = np.zeros((0, 2))
    return PlanResult(False, message, empty.astype(np.int64), empty, empty.copy(), np.inf,
                      expanded, metric)


def astar(grid, start, goal, metric: str = "joint", heuristic: bool = True) -> PlanResult:
    """Optimal path on the configuration-space grid by A* (or Dijkstra).

    Parameters
    ----------
    grid : CSpaceGrid
        From :func:`kinlib.planar_2r_cspace`.
    start, goal : array_like, shape (2,)
        Configurations ``(θ1, θ2)`` in radians; each is mapped to its cell.
    metric : {"joint", "ee"}
        Edge cost: joint-space step length, or end-effector path length (seed 001).
    heuristic : bool
        True: A* with the metric's consistent heuristic; False: Dijkstra (h = 0).

    Returns
    -------
    PlanResult
        ``success=False`` with a ``message`` when the start or goal cell is occupied or no
        path exists (this never raises; malformed input raises :class:`KinlibError`).
        At most n1·n2 nodes are expanded.

    Examples
    --------
    >>> from kinlib.planning.cspace import planar_2r_cspace
    >>> grid = planar_2r_cspace(1.0, 1.0, [], n=64)
    >>> plan = astar(grid, [3.0, 0.0], [-3.0, 0.0])  # the short way is across ±π
    >>> len(plan.q), round(plan.cost, 4), bool(plan.q[-1, 0] > np.pi)
    (4, 0.2945, True)
    >>> astar(grid, [0.0, 0.0], [1.0, 0.0], metric="ee").success
    True
    """
    grid = _check_grid(grid)
    metric = _check_metric(metric)
    if not isinstance(heuristic, bool | np.bool_):
        raise KinlibError(f"heuristic: expected True or False, got {heuristic!r}")
    s_cell = tuple(int(k) for k in grid.cell_of(_config(start, "start")))
    g_cell = tuple(int(k) for k in grid.cell_of(_config(goal, "goal")))
    occ = grid.occupied
    if occ[s_cell]:
        return _failure(f"start cell {s_cell} is occupied (in collision)", metric)
    if occ[g_cell]:
        return _failure(f"goal cell {g_cell} is occupied (in collision)", metric)
    n1, n2 = grid.shape
    nbr, costs = _graph(grid, metric)
    h = _heuristic(grid, g_cell, metric).tolist() if heuristic else [0.0] * (n1 * n2)
    blocked = occ.ravel().tolist()
    s, t = s_cell[0] * n2 + s_cell[1], g_cell[0] * n2 + g_cell[1]
    g = [np.inf] * (n1 * n2)
    parent_move = [-1] * (n1 * n2)
    closed = bytearray(n1 * n2)
    g[s] = 0.0
    heap = [(h[s], h[s], 0, s)]  # (f, h, tie-breaker, node): lower h first among equal f
    pushes, expanded = 0, 0
    while heap:
        _, _, _, u = heapq.heappop(heap)
        if closed[u]:
            continue
        closed[u] = 1
        expanded += 1
        if u == t:
            break
        gu, nu, cu = g[u], nbr[u], costs[u]
        for k in range(8):
            v = nu[k]
            if closed[v] or blocked[v]:
                continue
            gv = gu + cu[k]
            if gv < g[v]:
                g[v] = gv
                parent_move[v] = k
                pushes += 1
                heapq.heappush(heap, (gv + h[v], h[v], pushes, v))
    if not closed[t]:
        return _failure(
            f"no path: the goal cell {g_cell} cannot be reached from the start cell "
            f"{s_cell} (obstacles separate them in C-space; {expanded} cells explored)",
            metric,
            expanded,
        )
    moves = []
    v = t
    while v != s:
        k = parent_move[v]
        moves.append(k)
        v = nbr[v][OPPOSITE[k]]
    steps = NEIGHBOURS[np.array(moves[::-1], dtype=np.int64)].reshape(-1, 2)
    offsets = np.vstack([np.zeros((1, 2), dtype=np.int64), np.cumsum(steps, axis=0)])
    cells = (np.array(s_cell) + offsets) % np.array([n1, n2])
    q = grid.q_of(s_cell) + offsets * np.array(grid.step)
    xy = planar_2r_fk(q[:, 0], q[:, 1], grid.l1, grid.l2)[:, :2, 3]
    return PlanResult(True, f"path of {len(moves)} steps found", cells, q, xy, float(g[t]),
                      expanded, metric)


def cost_to_go(grid, goal, metric: str = "joint") -> CostToGo:
    """Optimal cost from every cell to ``goal`` and the first move of each optimal path.

    Dijkstra run backwards from the goal cell over the whole grid (the edge from ``u`` to
    ``v`` costs what :func:`astar` charges for it). ``next_step`` holds unit C-space
    directions ``(δθ1, δθ2)`` — the "field of arrows" of seed 001's figure.

    Parameters
    ----------
    grid : CSpaceGrid
    goal : array_like, shape (2,)
        Goal configuration (radians), mapped to its cell.
    metric : {"joint", "ee"}

    Returns
    -------
    CostToGo
        ``(cost, next_step)``: (n1, n2), inf where unreachable or occupied (everywhere if
        the goal cell is occupied, and then ``success`` is False); (n1, n2, 2), zero at the
        goal and where unreachable.

    Examples
    --------
    >>> from kinlib.planning.cspace import planar_2r_cspace
    >>> grid = planar_2r_cspace(1.0, 1.0, [], n=8)
    >>> ctg = cost_to_go(grid, [0.1, 0.1])
    >>> ctg.success, float(ctg.cost[4, 4]), ctg.next_step[6, 4].tolist()
    (True, 0.0, [-1.0, 0.0])
    """
    grid = _check_grid(grid)
    metric = _check_metric(metric)
    g_cell = tuple(int(k) for k in grid.cell_of(_config(goal, "goal")))
    n1, n2 = grid.shape
    cost = np.full(n1 * n2, np.inf)
    move = np.full(n1 * n2, -1)
    if not grid.occupied[g_cell]:
        nbr, costs = _graph(grid, metric)
        blocked = grid.occupied.ravel().tolist()
        opposite = OPPOSITE.tolist()
        g = [np.inf] * (n1 * n2)
        first = [-1] * (n1 * n2)
        closed = bytearray(n1 * n2)
        t = g_cell[0] * n2 + g_cell[1]
        g[t] = 0.0
        heap = [(0.0, 0, t)]
        pushes = 0
        while heap:
            _, _, v = heapq.heappop(heap)
            if closed[v]:
                continue
            closed[v] = 1
            gv, nv = g[v], nbr[v]
            for k in range(8):
                u = nv[k]  # u = v + move k, so u reaches v by the opposite move
                if closed[u] or blocked[u]:
                    continue
                back = opposite[k]
                gu = gv + costs[u][back]
                if gu < g[u]:
                    g[u] = gu
                    first[u] = back
                    pushes += 1
                    heapq.heappush(heap, (gu, pushes, u))
        cost, move = np.array(g), np.array(first)
    step = NEIGHBOURS * np.array(grid.step)
    unit = step / np.linalg.norm(step, axis=1, keepdims=True)
    next_step = np.where((move >= 0)[:, None], unit[np.maximum(move, 0)], 0.0)
    return CostToGo(cost.reshape(n1, n2), next_step.reshape(n1, n2, 2))
