r"""Screw axes in a 3-D scene: each column ``[v; ω]`` of a screw-axis matrix (the output of
:func:`kinlib.screw_axes`, or the columns of :func:`kinlib.space_jacobian`) drawn as an
arrow along its line.

A twist ``[v; ω]`` with :math:`\omega \ne 0` is a screw about the line with direction
:math:`\hat\omega = \omega/|\omega|` through the point
:math:`c = \omega \times v / |\omega|^2` (the point of the line nearest the origin: for a
revolute joint's :math:`S = [-\omega\times q;\ \omega]` it is the foot of the
perpendicular from the origin to the joint's axis). With :math:`\omega = 0` (a prismatic
joint) only the direction :math:`v/|v|` is fixed; the arrow is then drawn through the
point given for it, or the origin. Twists are ``[v; ω]``, linear part first (Modern
Robotics stacks ``[ω; v]``).
"""

from __future__ import annotations

import numpy as np

from .._validate import as_array
from ..errors import KinlibError
from . import _scene
from ._geometry import rotation_y_to

__all__ = ["screw_axis_lines", "draw_screw_axes", "SCREW_COLOR"]

#: the arrows' default colour (purple: apart from the robot's blue links and its orange
#: and green joint axes)
SCREW_COLOR = 0x8E44AD
_TOL = 1e-9


def _screw_matrix(S) -> np.ndarray:
    a = as_array(S, "S")
    if a.ndim == 1:
        a = a[:, None]
    if a.ndim != 2 or a.shape[0] != 6:
        raise KinlibError(f"S: expected screw axes as a (6, n) array, one column [v; ω] per "
                          f"axis (or one 6-vector), got shape {a.shape}")
    return a


def screw_axis_lines(S, through=None) -> tuple[np.ndarray, np.ndarray]:
    """The line of each screw axis: ``(points, directions)``, both ``(n, 3)``.

    ``directions[i]`` is ω/|ω| of column i (v/|v| when ω = 0); ``points[i]`` the point of
    its line nearest ``through[i]`` (``(n, 3)`` or one point for all; default: the origin).
    A zero column is no screw axis: :class:`~kinlib.KinlibError`.

    >>> S = np.array([[0.0, -1.0, 0.0, 0.0, 0.0, 1.0],   # about z through (1, 0, 0)
    ...               [0.0, 0.0, 1.0, 0.0, 0.0, 0.0]]).T  # a slide along z
    >>> points, directions = screw_axis_lines(S, through=[1.0, 2.0, 3.0])
    >>> points + 0.0, directions + 0.0
    (array([[1., 0., 3.],
           [1., 2., 3.]]), array([[0., 0., 1.],
           [0., 0., 1.]]))
    """
    a = _screw_matrix(S)
    v, w = a[:3].T, a[3:].T
    n_w, n_v = np.linalg.norm(w, axis=1), np.linalg.norm(v, axis=1)
    zero = (n_w <= _TOL) & (n_v <= _TOL)
    if zero.any():
        raise KinlibError(f"S: column {int(np.argmax(zero))} is zero, not a screw axis")
    turns = n_w > _TOL
    safe = np.where(turns, n_w, 1.0)[:, None]
    directions = np.where(turns[:, None], w / safe, v / np.where(turns, 1.0, n_v)[:, None])
    n = a.shape[1]
    if through is None:
        p = np.zeros((n, 3))
    else:
        p = as_array(through, "through", (3,))
        if p.shape not in ((3,), (n, 3)):
            raise KinlibError(f"through: expected one point (3,) or one per axis ({n}, 3), "
                              f"got shape {p.shape}")
        p = np.broadcast_to(p, (n, 3))
    on_line = np.where(turns[:, None], np.cross(w, v) / safe**2, p)  # a slide: through p
    along = np.sum((p - on_line) * directions, axis=1, keepdims=True)
    return on_line + along * directions, directions


def _positive(x, name: str) -> float:
    a = as_array(x, name)
    if a.ndim or not (np.isfinite(a) and a > 0):
        raise KinlibError(f"{name}: expected one positive number, got {x!r}")
    return float(a)


def draw_screw_axes(viz, S, *, through=None, length=None, radius=None, color=SCREW_COLOR,
                    prefix: str = "screws") -> tuple[np.ndarray, np.ndarray]:
    """Draw each screw axis (column of ``S``, in the robot's base frame) as an arrow.

    ``viz`` is a :class:`~kinlib.viz.RobotVisualizer` (the axes are placed with its
    ``base``) or a :class:`~kinlib.viz.Scene`. Arrow ``i`` is a thin cylinder of ``length``
    centred on the point of the axis nearest ``through[i]`` (see :func:`screw_axis_lines`)
    and a cone at its end that points along ω (along v for ω = 0): the right-hand sense of
    the joint's positive motion. They are drawn under the scene path ``prefix`` as
    ``<prefix>/<i>/shaft`` and ``<prefix>/<i>/head``, replacing what was there, so drawing
    again gives the same picture. Defaults: ``length`` 30 link radii of the visualizer
    (0.5 in a bare scene), ``radius`` 1/80 of the length.

    Returns ``(points, directions)`` of the arrows in the world frame, ``(n, 3)`` each.
    """
    from ._widget import Scene
    from .visualizer import RobotVisualizer

    if isinstance(viz, RobotVisualizer):
        scene, base, unit = viz.vis, viz.base, 30.0 * viz.link_radius
    elif isinstance(viz, Scene):
        scene, base, unit = viz, np.eye(4), 0.5
    else:
        raise KinlibError(f"draw_screw_axes: expected a RobotVisualizer or a Scene, got "
                          f"{type(viz).__name__}")
    if not isinstance(prefix, str) or not prefix.strip("/"):
        raise KinlibError(f"prefix: expected a non-empty scene path, got {prefix!r}")
    points, directions = screw_axis_lines(S, through)
    L = unit if length is None else _positive(length, "length")
    r = L / 80.0 if radius is None else _positive(radius, "radius")
    points = points @ base[:3, :3].T + base[:3, 3]
    directions = directions @ base[:3, :3].T
    head = min(8.0 * r, 0.25 * L)
    mat = _scene.material(color)
    shaft_geom = _scene.cylinder(L, r)
    head_geom = _scene.mg.Cylinder(head, radiusTop=0.0, radiusBottom=2.5 * r)
    head_geom.radialSegments = _scene.CYLINDER_SEGMENTS
    R = rotation_y_to(directions)  # (n, 3, 3): the cylinders' y onto each direction
    root = prefix.strip("/")
    with scene.batch():
        scene[root].delete()
        poses = {}
        for i in range(len(points)):
            shaft, tip = np.eye(4), np.eye(4)
            shaft[:3, :3] = tip[:3, :3] = R[i]
            shaft[:3, 3] = points[i]
            tip[:3, 3] = points[i] + (0.5 * L + 0.5 * head) * directions[i]
            scene[f"{root}/{i}/shaft"].set_object(shaft_geom, mat)
            scene[f"{root}/{i}/head"].set_object(head_geom, mat)
            poses[scene[f"{root}/{i}/shaft"].path.lower()] = shaft
            poses[scene[f"{root}/{i}/head"].path.lower()] = tip
        scene.set_poses(poses)
    return points, directions
