r"""Configuration space of the planar 2R arm: obstacles, occupancy grid, metric (seed 001).

Obstacles live in the arm's plane (base at the origin). The configuration space
``(θ1, θ2)`` of two continuous revolute joints is a torus; :func:`planar_2r_cspace`
samples it on an ``n1 × n2`` grid of cells and marks a cell occupied when a link comes
closer than ``margin`` to an obstacle. The search (A*, Dijkstra) is in :mod:`kinlib.planning.astar`.

The *minimum end-effector-distance metric* of seed 001 measures a small joint step by
how far the end moves: ``(Δs)² = δθᵀ JᵀJ δθ`` with

.. math:: J^T J = \begin{bmatrix} l_1^2 + l_2^2 + 2 l_1 l_2 c_2 & l_2^2 + l_1 l_2 c_2 \\
                                 l_2^2 + l_1 l_2 c_2 & l_2^2 \end{bmatrix}

(DH angles; the seed's earlier slide used absolute link angles ``θ2' = θ1 + θ2`` and so
wrote ``(L1 δθ1')² + (L2 δθ2')² + 2 L1 L2 δθ1' δθ2' cos(θ1' − θ2')``, the same thing).

>>> grid = planar_2r_cspace(1.0, 1.0, [Circle((1.2, 0.0), 0.3)], n=(32, 32))
>>> grid.occupied.shape, bool(grid.occupied[grid.cell_of([0.0, 0.0])[0], 16])
((32, 32), True)
>>> bool(grid.occupied[tuple(grid.cell_of([np.pi / 2, 0.0]))])
False
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._validate import as_array, broadcast, py_scalar
from ..errors import KinlibError
from ..kinematics.planar import _lengths, planar_2r_fk
from ._geometry2d import point_segment_distance as _point_segment
from ._geometry2d import segment_segment_distance as _segment_segment

__all__ = ["Circle", "Polygon", "CSpaceGrid", "NEIGHBOURS", "OPPOSITE", "default_margin",
           "planar_2r_cspace", "planar_2r_metric"]

#: The 8 grid moves ``(di, dj)`` of the 8-connected grid (their order numbers edge costs).
NEIGHBOURS = np.array([[1, 0], [0, 1], [-1, 0], [0, -1], [1, 1], [-1, 1], [-1, -1], [1, -1]])
NEIGHBOURS.setflags(write=False)
#: ``OPPOSITE[k]`` is the index of the move ``-NEIGHBOURS[k]``.
OPPOSITE = np.array([2, 3, 0, 1, 6, 7, 4, 5])
OPPOSITE.setflags(write=False)

_GL_NODES, _GL_WEIGHTS = np.polynomial.legendre.leggauss(8)


def _two_point_sets(a, b):
    pa, pb = as_array(a, "a", (2,)), as_array(b, "b", (2,))
    batch = broadcast((pa, 1, "a"), (pb, 1, "b"))
    return np.broadcast_to(pa, batch + (2,)), np.broadcast_to(pb, batch + (2,))


# --------------------------------------------------------------------------- obstacles


@dataclass(frozen=True)
class Circle:
    """A disc obstacle: ``center`` (x, y) in metres and ``radius > 0``.

    >>> c = Circle((1.0, 0.0), 0.5)
    >>> c.distance([[0.0, 0.0], [1.0, 0.25]])
    array([ 0.5 , -0.25])
    >>> c.segment_distance([[0.0, 1.0]], [[2.0, 1.0]])
    array([0.5])
    """

    center: tuple[float, float]
    radius: float

    def __post_init__(self):
        c = as_array(self.center, "Circle.center", (2,))
        if c.shape != (2,):
            raise KinlibError(f"Circle.center: expected one point (x, y), got shape {c.shape}")
        r = as_array(self.radius, "Circle.radius")
        if r.ndim or not r > 0:
            raise KinlibError(f"Circle.radius: expected one number > 0, got {self.radius!r}")
        object.__setattr__(self, "center", (float(c[0]), float(c[1])))
        object.__setattr__(self, "radius", float(r))

    def distance(self, points) -> np.ndarray:
        """Signed distance from ``points`` (..., 2) to the disc: < 0 inside, 0 on the rim."""
        p = as_array(points, "points", (2,))
        return np.hypot(p[..., 0] - self.center[0], p[..., 1] - self.center[1]) - self.radius

    def segment_distance(self, a, b) -> np.ndarray:
        """Distance (≥ 0) between segments ``a→b`` (each (..., 2)) and the disc."""
        pa, pb = _two_point_sets(a, b)
        d = _point_segment(np.asarray(self.center), pa, pb) - self.radius
        return np.maximum(d, 0.0)


@dataclass(frozen=True)
class Polygon:
    """A simple polygon obstacle (convex or not), vertices in either winding order.

    ``vertices`` is (M, 2) with M ≥ 3 distinct consecutive points, non-zero area and no
    self-intersection (the closing edge joins the last vertex to the first).

    >>> sq = Polygon([(1.0, -0.5), (2.0, -0.5), (2.0, 0.5), (1.0, 0.5)])
    >>> sq.distance([[0.0, 0.0], [1.5, 0.0]])
    array([ 1. , -0.5])
    >>> sq.segment_distance([[0.0, 0.0], [0.0, 0.0]], [[3.0, 0.0], [0.0, 2.0]])
    array([0., 1.])
    """

    vertices: tuple[tuple[float, float], ...]

    def __post_init__(self):
        v = as_array(self.vertices, "Polygon.vertices", (2,))
        if v.ndim != 2 or len(v) < 3:
            raise KinlibError(
                f"Polygon.vertices: expected (M, 2) with M >= 3 vertices, got shape {v.shape}"
            )
        w = np.roll(v, -1, axis=0)
        if (np.hypot(*(w - v).T) == 0).any():
            k = int(np.argmax(np.hypot(*(w - v).T) == 0))
            raise KinlibError(f"Polygon.vertices: vertex {k} repeats the next one: {v[k]}")
        area = 0.5 * float(np.sum(v[:, 0] * w[:, 1] - w[:, 0] * v[:, 1]))
        scale = float(np.abs(v).max()) or 1.0
        if abs(area) <= 1e-12 * scale * scale:
            raise KinlibError(f"Polygon.vertices: expected non-zero area, got {v.tolist()}")
        m = len(v)
        i, j = np.triu_indices(m, 2)
        keep = ~((i == 0) & (j == m - 1))  # edges 0 and m-1 share vertex 0
        i, j = i[keep], j[keep]
        touch = _segment_segment(v[i], w[i], v[j], w[j]) == 0
        if touch.any():
            k = int(np.argmax(touch))
            raise KinlibError(
                f"Polygon.vertices: expected a simple polygon, but edge {i[k]} meets edge {j[k]}"
            )
        object.__setattr__(self, "vertices", tuple((float(x), float(y)) for x, y in v))

    def _edges(self):
        v = np.asarray(self.vertices)
        return v, np.roll(v, -1, axis=0)

    def _inside(self, p):
        """Even–odd rule (crossing number) for points p (N, 2) → (N,) bool."""
        a, b = self._edges()
        px, py = p[:, None, 0], p[:, None, 1]
        straddle = (a[:, 1] > py) != (b[:, 1] > py)
        dy = np.where(straddle, b[:, 1] - a[:, 1], 1.0)
        x_cross = a[:, 0] + (py - a[:, 1]) * (b[:, 0] - a[:, 0]) / dy
        return (np.count_nonzero(straddle & (px < x_cross), axis=1) % 2) == 1

    def distance(self, points) -> np.ndarray:
        """Signed distance from ``points`` (..., 2) to the polygon: < 0 inside."""
        p = as_array(points, "points", (2,))
        flat = p.reshape(-1, 2)
        a, b = self._edges()
        d = _point_segment(flat[:, None, :], a, b).min(axis=1)
        return np.where(self._inside(flat), -d, d).reshape(p.shape[:-1])

    def segment_distance(self, a, b) -> np.ndarray:
        """Distance (≥ 0) between segments ``a→b`` (each (..., 2)) and the polygon."""
        pa, pb = _two_point_sets(a, b)
        shape = pa.shape[:-1]
        fa, fb = pa.reshape(-1, 2), pb.reshape(-1, 2)
        c, d = self._edges()
        dist = _segment_segment(fa[:, None, :], fb[:, None, :], c, d).min(axis=1)
        return np.where(self._inside(fa), 0.0, dist).reshape(shape)


# --------------------------------------------------------------------------- the metric


def planar_2r_metric(theta, dtheta, l1, l2) -> float | np.ndarray:
    r"""Seed 001's minimum end-effector-distance metric ``c = sqrt(δθᵀ JᵀJ δθ)``.

    ``c`` is the speed of the end for joint velocity ``δθ`` at configuration ``θ``: the
    length of ``J[:2] δθ``. It depends on θ2 only (turning θ1 rotates the whole arm):
    ``c = |l1 δθ1 + l2 (δθ1 + δθ2) e^{iθ2}|``, which expands to the seed's
    ``(l1² + l2² + 2 l1 l2 c2) δθ1² + 2 (l2² + l1 l2 c2) δθ1 δθ2 + l2² δθ2²``.

    Parameters
    ----------
    theta, dtheta : array_like, shape (..., 2)
        Configurations ``(θ1, θ2)`` and joint steps ``(δθ1, δθ2)`` (radians); they broadcast.
    l1, l2 : float
        Link lengths (> 0).

    Returns
    -------
    float or ndarray, shape (...)
        End-effector distance per step (metres): a Python float for one step.

    Examples
    --------
    >>> planar_2r_metric([0.3, 0.0], [1.0, 0.0], 1.0, 0.5)  # stretched: l1 + l2
    1.5
    >>> planar_2r_metric([0.3, np.pi / 2], [0.0, 2.0], 1.0, 0.5)  # only link 2 turns
    1.0
    """
    th = as_array(theta, "theta", (2,))
    d = as_array(dtheta, "dtheta", (2,))
    a1, a2 = _lengths(l1, l2)
    broadcast((th, 1, "theta"), (d, 1, "dtheta"), (a1, 0, "l1"), (a2, 0, "l2"))
    t2, d1, d12 = th[..., 1], d[..., 0], d[..., 0] + d[..., 1]
    return py_scalar(np.hypot(a1 * d1 + a2 * d12 * np.cos(t2), a2 * d12 * np.sin(t2)))


# --------------------------------------------------------------------------- the grid


@dataclass(frozen=True, eq=False)
class CSpaceGrid:
    """An occupancy grid over the 2R arm's torus of configurations; see :func:`planar_2r_cspace`.

    Attributes: ``l1, l2, obstacles, margin``; ``theta1`` (n1,), ``theta2`` (n2,): cell
    centres; ``occupied`` (n1, n2) bool; ``clearance`` (n1, n2): the smallest distance
    between a link and an obstacle at each cell centre (inf without obstacles).
    """

    l1: float
    l2: float
    obstacles: tuple
    margin: float
    theta1: np.ndarray
    theta2: np.ndarray
    occupied: np.ndarray
    clearance: np.ndarray

    @property
    def shape(self) -> tuple[int, int]:
        """``(n1, n2)``."""
        return self.occupied.shape

    @property
    def step(self) -> tuple[float, float]:
        """Cell size ``(2π/n1, 2π/n2)`` in radians."""
        return 2 * np.pi / self.shape[0], 2 * np.pi / self.shape[1]

    def cell_of(self, q) -> np.ndarray:
        """Index ``(i, j)`` of the cell whose centre is nearest to ``q`` (..., 2), wrapped.

        >>> g = planar_2r_cspace(1.0, 1.0, [], n=(8, 4))
        >>> g.cell_of([[0.1, 0.1], [np.pi + 0.1, -4.0]])
        array([[4, 2],
               [0, 3]])
        """
        qa = as_array(q, "q", (2,))
        n, h = np.array(self.shape), np.array(self.step)
        return (np.floor((qa + np.pi) / h).astype(np.int64)) % n

    def q_of(self, cells) -> np.ndarray:
        """Configuration (cell centre) of cells ``(i, j)`` (..., 2); indices wrap."""
        c = as_array(cells, "cells", (2,))
        if (c != np.round(c)).any():
            raise KinlibError(f"cells: expected integer indices, got {c.tolist()!r}")
        n, h = np.array(self.shape), np.array(self.step)
        return -np.pi + ((c.astype(np.int64) % n) + 0.5) * h

    def edge_costs(self, metric: str = "joint") -> np.ndarray:
        """Cost of each of the 8 moves :data:`NEIGHBOURS` from each cell, (n1, n2, 8).

        ``"joint"``: the Euclidean length ``|(Δθ1, Δθ2)|`` of the step. ``"ee"``: the length
        of the end-effector path while the joints move straight from cell to cell,
        ``∫₀¹ |J(θ + s δθ) δθ| ds`` (8-point Gauss–Legendre), but never less than the
        chord ``|fk(θ + δθ) − fk(θ)|``. That floor makes the straight-line end-effector
        distance a lower bound on every edge, so by the triangle inequality it is an
        admissible and consistent A* heuristic (quadrature error cannot break it).
        """
        metric = _check_metric(metric)
        n1, n2 = self.shape
        dq = NEIGHBOURS * np.array(self.step)  # (8, 2)
        if metric == "joint":
            per_cell = np.broadcast_to(np.hypot(dq[:, 0], dq[:, 1]), (n2, 8))
        else:  # both the integral and the chord depend on θ2 only: evaluate at θ1 = 0
            s = 0.5 * (_GL_NODES + 1.0)  # nodes on [0, 1], weights sum to 1 after halving
            t2 = self.theta2[:, None, None] + s[None, None, :] * dq[None, :, 1, None]
            theta = np.stack([np.zeros_like(t2), t2], axis=-1)  # (n2, 8, 8, 2)
            speed = planar_2r_metric(theta, dq[None, :, None, :], self.l1, self.l2)
            arc = 0.5 * (speed * _GL_WEIGHTS).sum(axis=-1)
            p0 = planar_2r_fk(0.0, self.theta2, self.l1, self.l2)[:, :2, 3]
            p1 = planar_2r_fk(dq[None, :, 0], self.theta2[:, None] + dq[None, :, 1],
                              self.l1, self.l2)[..., :2, 3]
            chord = np.linalg.norm(p1 - p0[:, None, :], axis=-1)
            per_cell = np.maximum(arc, chord)
        return np.broadcast_to(per_cell, (n1, n2, 8)).copy()


def _check_metric(metric) -> str:
    if metric not in ("joint", "ee"):
        raise KinlibError(f"metric: expected 'joint' or 'ee', got {metric!r}")
    return metric


def _grid_size(n) -> tuple[int, int]:
    pair = (n, n) if np.ndim(n) == 0 else n
    try:
        ok = len(pair) == 2 and all(
            isinstance(k, int | np.integer) and not isinstance(k, bool) and k >= 3 for k in pair
        )
    except TypeError:
        ok = False
    if not ok:
        raise KinlibError(f"n: expected an integer >= 3 or a pair (n1, n2) of them, got {n!r}")
    return int(pair[0]), int(pair[1])


def _obstacle_tuple(obstacles) -> tuple:
    if isinstance(obstacles, Circle | Polygon):
        return (obstacles,)
    try:
        obs = tuple(obstacles)
    except TypeError:
        obs = None
    if obs is None or not all(isinstance(o, Circle | Polygon) for o in obs):
        raise KinlibError(
            f"obstacles: expected a list of Circle and Polygon objects, got {obstacles!r}"
        )
    return obs


def default_margin(l1: float, l2: float, n1: int, n2: int) -> float:
    """Half of the largest distance a point of the arm travels between neighbouring cells.

    ``((l1 + l2)·2π/n1 + l2·2π/n2) / 2``; see :func:`planar_2r_cspace`.

    >>> round(default_margin(1.0, 1.0, 128, 128), 6)
    0.073631
    """
    return 0.5 * ((l1 + l2) * 2 * np.pi / n1 + l2 * 2 * np.pi / n2)


def planar_2r_cspace(l1, l2, obstacles, n=(128, 128), margin=None) -> CSpaceGrid:
    r"""Occupancy grid of the planar 2R arm's configuration space (a torus).

    Cell ``(i, j)`` is the configuration ``θ1 = −π + (i + ½)·2π/n1``,
    ``θ2 = −π + (j + ½)·2π/n2``; both joints are continuous, so the grid wraps in both
    directions. A cell is occupied when either link (base→elbow ``l1 (c1, s1)``,
    elbow→end) comes closer than ``margin`` to an obstacle (or touches it, for
    ``margin = 0``).

    **Default margin.** Moving the joints straight between two 8-neighbouring cell
    centres (``|Δθ1| ≤ 2π/n1``, ``|Δθ2| ≤ 2π/n2``), every point of the arm travels at most
    ``D = (l1 + l2)·2π/n1 + l2·2π/n2``: a point of link 1 moves at speed ≤ ``l1 |θ̇1|``, a
    point of link 2 at ≤ ``l1 |θ̇1| + l2 |θ̇1 + θ̇2|``, and the straight distance (chord)
    is at most the path (arc). Every intermediate configuration is within half the move
    of one of the two end cells, so each point is within ``D/2`` of where it was at a free
    cell, whose clearance is ≥ margin. With ``margin = D/2`` the clearance along the whole
    move stays ≥ 0, and in fact > 0: the points move on curves, so their chords are
    strictly shorter than the bound. A smaller ``margin`` loses this guarantee.

    Parameters
    ----------
    l1, l2 : float
        Link lengths (> 0).
    obstacles : sequence of Circle or Polygon
        Obstacles in the arm's plane.
    n : int or (int, int)
        Cells along θ1 and θ2 (each ≥ 3).
    margin : float, optional
        Required clearance (≥ 0, metres); default :func:`default_margin`.

    Returns
    -------
    CSpaceGrid

    Examples
    --------
    >>> grid = planar_2r_cspace(1.0, 0.5, [Polygon([(0.5, 2), (2, 2), (2, 3)])], n=16)
    >>> grid.shape, int(grid.occupied.sum()), round(grid.margin, 4)
    ((16, 16), 0, 0.3927)
    """
    a1, a2 = _lengths(l1, l2)
    if a1.ndim or a2.ndim:
        raise KinlibError(f"l1, l2: expected one number each, got {l1!r}, {l2!r}")
    a1, a2 = float(a1), float(a2)
    obs = _obstacle_tuple(obstacles)
    n1, n2 = _grid_size(n)
    if margin is None:
        margin = default_margin(a1, a2, n1, n2)
    m = as_array(margin, "margin")
    if m.ndim or m < 0:
        raise KinlibError(f"margin: expected one number >= 0, got {margin!r}")
    t1 = -np.pi + (np.arange(n1) + 0.5) * (2 * np.pi / n1)
    t2 = -np.pi + (np.arange(n2) + 0.5) * (2 * np.pi / n2)
    T1, T2 = np.meshgrid(t1, t2, indexing="ij")
    elbow = a1 * np.stack([np.cos(T1), np.sin(T1)], axis=-1)
    end = planar_2r_fk(T1, T2, a1, a2)[..., :2, 3]
    base = np.zeros_like(elbow)
    clearance = np.full((n1, n2), np.inf)
    for o in obs:
        clearance = np.minimum(clearance, o.segment_distance(base, elbow))
        clearance = np.minimum(clearance, o.segment_distance(elbow, end))
    occupied = (clearance < m) | (clearance <= 0.0)  # margin 0: touching counts
    for arr in (t1, t2, occupied, clearance):
        arr.setflags(write=False)
    return CSpaceGrid(a1, a2, obs, float(m), t1, t2, occupied, clearance)
