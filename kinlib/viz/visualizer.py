"""``RobotVisualizer``: a kinlib robot drawn in a 3-D scene widget (meshcat's three.js
viewer, reached through the notebook's own connection: see :mod:`kinlib.viz._widget`).

The scene under ``/meshcat/<prefix>`` is flat, so every transform it sends is a pose in
the world frame (meshcat's world is z-up, like kinlib's):

==============================  ===========================================================
``<prefix>/links/<link>``       ``T_world_link = base @ robot.link_poses(q)[link]``; holds
                                the link's origin sphere, URDF visuals and frame triad
``<prefix>/segments/<joint>``   a unit-height cylinder stretched from the parent link's
                                origin to the child link's origin
``<prefix>/axes/<joint>``       a short cylinder on each movable joint's axis
==============================  ===========================================================

meshcat (three.js) cylinders lie along their local **y** axis; see
:mod:`kinlib.viz._geometry` for how they are turned onto segments and axes.
"""

from __future__ import annotations

import weakref
from typing import ClassVar

import numpy as np

from .._validate import as_array
from ..errors import KinlibError
from ..kinematics.robot import Robot
from ..spatial.quaternions import quat_from_matrix
from ..spatial.transforms import check_transform, transform_inverse
from . import _scene
from ._geometry import axis_transforms, decompose, segment_transforms
from ._scene import mg
from ._widget import Scene, check_height, static_page

__all__ = ["RobotVisualizer", "REVOLUTE_COLOR", "PRISMATIC_COLOR", "LINK_COLOR"]

LINK_COLOR = 0x3B7DD8
REVOLUTE_COLOR = 0xE8A317
PRISMATIC_COLOR = 0x2CA02C
_VISUAL_COLOR = (0.7, 0.7, 0.7, 1.0)
_ROTX_90 = np.array([[1.0, 0, 0, 0], [0, 0, -1, 0], [0, 1, 0, 0], [0, 0, 0, 1]])


def _clean(name: str) -> str:
    return str(name).replace("/", "_") or "_"


def _robot_reach(robot: Robot, q0: np.ndarray) -> float:
    """The robot's size: the longest chain of joint-origin distances from the root at q0."""
    poses = robot.link_poses(q0)
    along = {robot.root: 0.0}
    for jt in robot.traversal():
        step = np.linalg.norm(poses[jt.child][:3, 3] - poses[jt.parent][:3, 3])
        along[jt.child] = along[jt.parent] + step
    reach = max(along.values())
    return reach if reach > 1e-9 else 1.0


class RobotVisualizer:
    """Draw ``robot`` in a meshcat viewer and move it.

    Parameters
    ----------
    robot : kinlib.Robot
    prefix : str, optional
        Scene path of this robot (default: the robot's name). A new visualizer of the
        same prefix replaces the old one: re-running a notebook cell redraws the picture
        (the old scene widget is closed) instead of adding a copy.
    scene : kinlib.viz.Scene, optional
        Draw into this scene (several robots in one viewer); default: a new scene.
    frames : bool
        Draw a frame triad (x red, y green, z blue) at every link origin.
    link_radius : float, optional
        Radius of the link cylinders; default 2 % of the robot's reach.
    color : colour
        Link colour: ``0xRRGGBB``, ``"#rrggbb"`` or ``(r, g, b)`` in [0, 1].
    mesh_dir : path, optional
        Where relative (and ``package://``) URDF mesh file names are looked up. Meshes not
        found or of an unknown format are left out and listed in :attr:`skipped_meshes`.

    Attributes
    ----------
    q : ndarray (dof,)
        The configuration last sent (starts at 0, clipped into the joint limits).
    base : ndarray (4, 4)
        ``T_world_base``: where the robot's root link sits (starts at identity).
    vis : kinlib.viz.Scene
        The scene widget (``vis["path"].set_object(...)`` as in meshcat).

    Examples
    --------
    >>> from kinlib.robots import puma560
    >>> viz = RobotVisualizer(puma560(), prefix="doctest_puma")  # doctest: +SKIP
    >>> viz.set_configuration(puma560().poses["ready"])          # doctest: +SKIP
    >>> viz.jupyter_cell()                                      # doctest: +SKIP
    """

    #: prefix -> the visualizer that made its own scene for it (closed when replaced)
    _made: ClassVar[weakref.WeakValueDictionary] = weakref.WeakValueDictionary()

    def __init__(self, robot, *, prefix=None, scene=None, frames=False, link_radius=None,
                 color=LINK_COLOR, mesh_dir=None):
        if not isinstance(robot, Robot):
            raise KinlibError(f"RobotVisualizer: expected a kinlib.Robot, got "
                              f"{type(robot).__name__}")
        prefix = robot.name if prefix is None else prefix
        if not isinstance(prefix, str) or not prefix.strip("/"):
            raise KinlibError(f"prefix: expected a non-empty scene path, got {prefix!r}")
        self.robot = robot
        self.prefix = prefix.strip("/")
        self.color = _scene.color_int(color)
        lim = robot.limits
        q0 = np.clip(np.zeros(robot.dof), lim[:, 0], lim[:, 1])
        reach = _robot_reach(robot, q0)
        if link_radius is None:
            link_radius = 0.02 * reach
        r = as_array(link_radius, "link_radius")
        if r.ndim or r <= 0:
            raise KinlibError(f"link_radius: expected one positive number, got {link_radius!r}")
        self.link_radius = float(r)
        if scene is not None and not isinstance(scene, Scene):
            raise KinlibError(f"scene: expected a kinlib.viz.Scene, got {type(scene).__name__}")
        self.skipped_meshes = []
        self.panels = []  # the joint panels made for this visualizer (closed with it)
        if scene is None:
            old = RobotVisualizer._made.get(self.prefix)
            if old is not None:
                old.close()  # the same cell run again: its old scene and panels go
            scene = Scene()
            RobotVisualizer._made[self.prefix] = self
        self.vis = scene
        self.node = self.vis[self.prefix]
        self._root = self.node.path.lower()
        with self.vis.batch():
            self.node.delete()
            self._draw(frames, mesh_dir)
            self.base = np.eye(4)
            self.q = q0
            self.set_configuration(q0)
            # frame the robot: the camera looks at the origin from the front right, above
            self.set_camera_position(max(reach, 0.1) * np.array([0.65, -0.8, 0.55]))

    # -- drawing --------------------------------------------------------------------------
    def _path(self, group: str, name: str) -> str:
        return f"{self._root}/{group}/{_clean(name)}"

    def _draw(self, frames: bool, mesh_dir) -> None:
        r = self.link_radius
        link_mat = _scene.material(self.color)
        for link in self.robot.links:
            node = self.vis[self._path("links", link.name)]
            node["origin"].set_object(_scene.sphere(1.6 * r), link_mat)
            if frames:
                node["frame"].set_object(mg.triad(12 * r))
            for i, visual in enumerate(link.visuals):
                self._draw_visual(node[f"visual_{i}"], link.name, visual, mesh_dir)
        segment = _scene.cylinder(1.0, r)
        for jt in self.robot.traversal():
            self.vis[self._path("segments", jt.name)].set_object(segment, link_mat)
        axis_mats = {"prismatic": _scene.material(PRISMATIC_COLOR),
                     "revolute": _scene.material(REVOLUTE_COLOR)}
        for jt in self.robot.traversal():
            if jt.movable:
                kind = "prismatic" if jt.type == "prismatic" else "revolute"
                self.vis[self._path("axes", jt.name)].set_object(
                    _scene.cylinder(10 * r, 1.25 * r), axis_mats[kind])

    def _draw_visual(self, node, link_name, visual, mesh_dir) -> None:
        mat = _scene.material(visual.rgba or _VISUAL_COLOR,
                              opacity=(visual.rgba or _VISUAL_COLOR)[3])
        T = np.array(visual.origin)
        if visual.kind == "box":
            geom = mg.Box(list(visual.size))
        elif visual.kind == "sphere":
            geom = _scene.sphere(visual.size[0])
        elif visual.kind == "cylinder":  # URDF: along z; three.js: along y -> turn y onto z
            geom = _scene.cylinder(visual.size[1], visual.size[0])
            T = T @ _ROTX_90
        else:
            path = _scene.resolve_mesh(visual.filename, mesh_dir)
            geom = None if path is None else _scene.mesh_geometry(path)
            if geom is None:
                self.skipped_meshes.append((link_name, visual.filename))
                return
            T = T @ np.diag(list(visual.size) + [1.0])
        node.set_object(geom, mat)
        node.set_transform(T)

    # -- configuration ---------------------------------------------------------------------
    def _check_base(self, base, batch=None) -> np.ndarray:
        if base is None:
            return self.base
        b = check_transform(base, "base")
        if b.ndim != 2 and (batch is None or b.shape[:-2] != batch):
            want = "(4, 4)" if batch is None else f"(4, 4) or {batch + (4, 4)}"
            raise KinlibError(f"base: expected a transform of shape {want}, got {b.shape}")
        return b

    def _world(self, q, base) -> dict[str, np.ndarray]:
        poses = self.robot.link_poses(q)
        W = {name: base @ T for name, T in poses.items()}
        out = {self._path("links", n): W[n] for n in self.robot.link_names}
        for jt in self.robot.traversal():
            out[self._path("segments", jt.name)] = segment_transforms(
                W[jt.parent][..., :3, 3], W[jt.child][..., :3, 3])
        for jt in self.robot.traversal():
            if jt.movable:  # the axis lives in origin @ motion(q) = child frame @ inv(post)
                T_joint = W[jt.child] @ transform_inverse(jt.post)
                out[self._path("axes", jt.name)] = axis_transforms(T_joint, jt.axis)
        return out

    def _check_one_q(self, q) -> np.ndarray:
        a = self.robot.check_q(q)
        if a.ndim != 1:
            raise KinlibError(f"q: expected one configuration of {self.robot.dof} values, got "
                              f"shape {a.shape}; use animate() for a sequence")
        return a

    def scene_transforms(self, q, base=None) -> dict[str, np.ndarray]:
        """Every transform :meth:`set_configuration` would send: scene path → 4×4 (world).

        Pure: nothing is sent and :attr:`q`, :attr:`base` stay as they are. ``base``
        defaults to the current :attr:`base`.
        """
        return self._world(self._check_one_q(q), self._check_base(base))

    def set_configuration(self, q, base=None) -> None:
        """Show the robot at ``q`` (length ``dof``, or a dict joint → value) on ``base``.

        ``base`` (``T_world_base``, 4×4) defaults to the current :attr:`base`.
        """
        a = self._check_one_q(q)
        b = self._check_base(base)
        self.vis.set_poses(self._world(a, b))
        self.q = np.array(a)
        self.base = np.array(b)

    def animate(self, qs, fps=30, base=None):
        """Send a trajectory ``qs`` (T, dof) to the viewer as a meshcat animation.

        ``base`` is one 4×4 pose or one per frame (T, 4, 4). Returns the
        ``meshcat.animation.Animation`` (the viewer shows play controls).
        """
        from meshcat.animation import Animation, AnimationClip, AnimationTrack

        a = self.robot.check_q(qs, "qs")
        if a.ndim != 2 or a.shape[0] < 1:
            raise KinlibError(f"qs: expected a sequence of configurations, shape (T, "
                              f"{self.robot.dof}) with T >= 1, got shape {a.shape}")
        rate = as_array(fps, "fps")
        if rate.ndim or rate <= 0:
            raise KinlibError(f"fps: expected one positive number, got {fps!r}")
        b = self._check_base(base, batch=a.shape[:1])
        anim = Animation(default_framerate=float(rate))  # meshcat's own animation objects
        frames = list(range(a.shape[0]))
        for path, M in self._world(a, b).items():
            p, R, s = decompose(M)
            wxyz = quat_from_matrix(R)
            tracks = {"position": AnimationTrack("position", "vector3", frames, p.tolist()),
                      "quaternion": AnimationTrack("quaternion", "quaternion", frames,
                                                   wxyz[:, [1, 2, 3, 0]].tolist()),
                      "scale": AnimationTrack("scale", "vector3", frames, s.tolist())}
            clip = AnimationClip(tracks=tracks, fps=float(rate))
            anim.clips[self.vis[path].path] = clip
        self.vis.set_animation(anim)
        return anim

    # -- viewer --------------------------------------------------------------------------
    def set_camera_position(self, position) -> None:
        """Put the viewer's camera at ``position`` (world, z-up, metres); it looks at 0."""
        p = as_array(position, "position", (3,))
        if p.ndim != 1:
            raise KinlibError(f"position: expected one point (3,), got shape {p.shape}")
        # the default camera sits in a y-up frame turned by +90° about x: (x, y, z)_world
        # = (x, -z, y)_camera frame
        self.vis["/Cameras/default/rotated/<object>"].set_property(
            "position", [float(p[0]), float(p[2]), float(-p[1])])

    def static_html(self) -> str:
        """A self-contained HTML page of the scene as it is now (three.js, meshcat and the
        scene inline; about 1 MB), which needs no kernel and no network."""
        return static_page([self.vis.state()], title=self.robot.name)

    def save_html(self, path) -> None:
        """Write :meth:`static_html` to ``path``."""
        with open(path, "w", encoding="utf-8") as fh:
            fh.write(self.static_html())

    def jupyter_cell(self, height: int = 400):
        """The viewer in a notebook cell (make it the cell's last expression): the scene
        widget, ``height`` pixels tall, which follows every later change. Saved with the
        notebook's widget state, it shows again in an exported page."""
        self.vis.height = check_height(height)
        return self.vis

    def snapshot(self, height: int = 400):
        """The scene as it is now, as a frozen copy (a widget that later changes do not
        reach): for a picture that should stay, e.g. before the robot moves on."""
        copy = self.vis.copy(frozen=True)
        copy.height = check_height(height)
        return copy

    def _repr_mimebundle_(self, **kwargs):
        return self.vis._repr_mimebundle_(**kwargs)

    def delete(self) -> None:
        """Remove this robot from the scene."""
        self.node.delete()

    def close(self) -> None:
        """Close the scene widget and this visualizer's joint panels: their views leave the
        page and the kernel keeps nothing of them. (A scene passed in as ``scene=`` is
        closed too: close it yourself to keep it for other robots.)"""
        from ._widget import close_tree

        for panel in self.panels:
            close_tree(panel)
        self.panels = []
        self.vis.close()

    def __repr__(self) -> str:
        return f"RobotVisualizer({self.robot.name!r}, prefix={self.prefix!r})"
