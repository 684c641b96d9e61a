"""3-D views of kinlib robots (meshcat's three.js viewer in a Jupyter widget), and panels.

Not imported by ``import kinlib``: meshcat, anywidget and ipywidgets load only when asked::

    from kinlib.viz import RobotVisualizer, joint_panel
    viz = RobotVisualizer(puma560())   # a new scene widget (no server, no port)
    viz.jupyter_cell()                 # the viewer inside the notebook
    joint_panel(viz)                   # sliders and holonomic-base buttons
    viz.snapshot()                     # the scene now, as a frozen copy

The viewer is a widget (:class:`Scene`): its scene travels over the notebook's own
connection to the kernel, so it works wherever Jupyter runs (JupyterHub, Binder, a remote
kernel), and the notebook's saved widget state shows it again in exported pages.

:class:`RobotVisualizer` draws each link as a cylinder from its parent's origin to its
own, a sphere at every link origin, a short coloured cylinder on each joint axis, the
URDF visuals (boxes, cylinders, spheres, meshes) and, if asked, frame triads.
:func:`draw_screw_axes` adds screw axes ``[v; ω]`` (a robot's joints, as lines) as arrows.
"""

from ._widget import Scene, SceneNode, static_page
from .obstacles import draw_obstacles
from .panel import BASE_MOVES, joint_panel, slider_bounds
from .screws import SCREW_COLOR, draw_screw_axes
from .visualizer import LINK_COLOR, PRISMATIC_COLOR, REVOLUTE_COLOR, RobotVisualizer

__all__ = ["RobotVisualizer", "Scene", "SceneNode", "static_page", "draw_obstacles", "joint_panel",
           "slider_bounds", "BASE_MOVES", "LINK_COLOR", "REVOLUTE_COLOR", "PRISMATIC_COLOR",
           "draw_screw_axes", "SCREW_COLOR"]
