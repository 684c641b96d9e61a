"""Planar obstacles (``kinlib.Circle``, ``kinlib.Polygon``) in a 3-D scene.

The planning notebook's obstacles live in the arm's plane (z = 0); here each becomes a
solid of ``height`` centred on that plane: a disc an upright cylinder, a polygon a prism
(its outline triangulated by ear clipping, so non-convex polygons work too).
"""

from __future__ import annotations

import numpy as np

from ..errors import KinlibError
from ..planning.cspace import Circle, Polygon
from . import _scene
from ._scene import mg

__all__ = ["draw_obstacles", "triangulate", "prism"]

_UPRIGHT = np.array([[1.0, 0, 0, 0], [0, 0, -1, 0], [0, 1, 0, 0], [0, 0, 0, 1]])  # y -> z


def _cross(o, a, b) -> float:
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])


def _signed_area(v: np.ndarray) -> float:
    """The shoelace area of the closed outline ``v`` (M, 2): > 0 counter-clockwise."""
    w = np.roll(v, -1, axis=0)
    return 0.5 * float(np.sum(v[:, 0] * w[:, 1] - w[:, 0] * v[:, 1]))


def triangulate(vertices) -> np.ndarray:
    """Triangles (K, 3) of vertex indices covering the simple polygon ``vertices`` (M, 2),
    counter-clockwise (ear clipping).

    >>> triangulate([(0, 0), (1, 0), (1, 1), (0, 1)]).tolist()
    [[3, 0, 1], [1, 2, 3]]
    """
    v = np.asarray(Polygon(vertices).vertices, dtype=float)
    idx = list(range(len(v)))
    if _signed_area(v) < 0:
        idx.reverse()
    out = []
    while len(idx) > 3:
        for k in range(len(idx)):
            i, j, m = idx[k - 1], idx[k], idx[(k + 1) % len(idx)]
            if _cross(v[i], v[j], v[m]) <= 1e-15:
                continue  # a reflex (or flat) corner is no ear
            inside = any(
                p not in (i, j, m) and _cross(v[i], v[j], v[p]) >= 0
                and _cross(v[j], v[m], v[p]) >= 0 and _cross(v[m], v[i], v[p]) >= 0
                for p in idx)
            if not inside:
                out.append([i, j, m])
                del idx[k]
                break
        else:  # pragma: no cover - a simple polygon always has an ear
            raise KinlibError("triangulate: found no ear; is the polygon simple?")
    out.append(idx)
    return np.array(out, dtype=np.int64)


def prism(vertices, height: float):
    """A meshcat triangle mesh: the polygon ``vertices`` extruded from z = -h/2 to +h/2."""
    v = np.asarray(Polygon(vertices).vertices, dtype=float)
    n = len(v)
    h = float(height) / 2
    points = np.vstack([np.c_[v, np.full(n, -h)], np.c_[v, np.full(n, h)]])
    tri = triangulate(v)
    faces = [tri[:, ::-1], tri + n]  # bottom facing down, top facing up
    ccw = _signed_area(v) > 0
    for i in range(n):
        j = (i + 1) % n
        a, b = (i, j) if ccw else (j, i)
        faces.append(np.array([[a, b, b + n], [a, b + n, a + n]]))
    return mg.TriangularMeshGeometry(points, np.vstack(faces))


def draw_obstacles(viz, obstacles, colors=None, *, height: float = 0.1,
                   prefix: str = "obstacles") -> None:
    """Draw ``obstacles`` (``kinlib.Circle`` / ``kinlib.Polygon``) into the scene of
    ``viz`` (a ``RobotVisualizer`` or a ``Scene``) under ``prefix``, replacing what was
    there. ``colors``: one colour per obstacle (default grey)."""
    from ._widget import Scene

    scene = viz if isinstance(viz, Scene) else getattr(viz, "vis", None)
    if not isinstance(scene, Scene):
        raise KinlibError(f"draw_obstacles: expected a RobotVisualizer or a Scene, got "
                          f"{type(viz).__name__}")
    obstacles = list(obstacles)
    colors = [0x888888] * len(obstacles) if colors is None else list(colors)
    if len(colors) != len(obstacles):
        raise KinlibError(f"colors: expected one per obstacle ({len(obstacles)}), got "
                          f"{len(colors)}")
    h = np.asarray(height, dtype=float)
    if h.ndim or not np.isfinite(h) or h <= 0:
        raise KinlibError(f"height: expected one positive number, got {height!r}")
    with scene.batch():
        scene[prefix].delete()
        for k, (ob, color) in enumerate(zip(obstacles, colors, strict=True)):
            node = scene[f"{prefix}/{k}"]
            mat = _scene.material(_named(color))
            if isinstance(ob, Circle):
                node.set_object(_scene.cylinder(float(h), ob.radius), mat)
                T = _UPRIGHT.copy()
                T[:2, 3] = ob.center
                node.set_transform(T)
            elif isinstance(ob, Polygon):
                node.set_object(prism(ob.vertices, float(h)), mat)
                node.set_transform(np.eye(4))
            else:
                raise KinlibError(f"obstacles[{k}]: expected a kinlib.Circle or "
                                  f"kinlib.Polygon, got {type(ob).__name__}")


def _named(color):
    """matplotlib colour names too ("tab:red"), when matplotlib is there."""
    if isinstance(color, str) and not color.startswith("#"):
        try:
            from matplotlib.colors import to_rgb
        except ImportError:  # pragma: no cover
            return color
        try:
            return to_rgb(color)
        except ValueError:
            raise KinlibError(f"colors: {color!r} is not a colour name") from None
    return color
