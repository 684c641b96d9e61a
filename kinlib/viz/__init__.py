"""3-D views of kinlib robots in meshcat (three.js in the browser), and widget panels.

Not imported by ``import kinlib``: meshcat and ipywidgets load only when you ask::

    from kinlib.viz import RobotVisualizer, joint_panel
    viz = RobotVisualizer(puma560())   # the server: $KINLIB_MESHCAT_ZMQ_URL or a new one
    viz.jupyter_cell()                 # the viewer inside the notebook
    joint_panel(viz)                   # sliders and holonomic-base buttons
    viz.snapshot()                     # the scene now, self-contained (no server needed)

The "new one" is this process's own server, shared by its visualizers and ended with the
process even when the process is killed (a kernel restart leaves nothing behind). With
``KINLIB_STATIC_SCENES=1`` in the environment, ``jupyter_cell()`` embeds a snapshot
instead of the live viewer: set it when executing notebooks for export to HTML.

:class:`RobotVisualizer` draws each link as a cylinder from its parent's origin to its
own, a sphere at every link origin, a short coloured cylinder on each joint axis, the
URDF visuals (boxes, cylinders, spheres, meshes) and, if asked, frame triads.
"""

from .panel import BASE_MOVES, joint_panel, slider_bounds
from .visualizer import LINK_COLOR, PRISMATIC_COLOR, REVOLUTE_COLOR, STATIC_ENV, RobotVisualizer

__all__ = ["RobotVisualizer", "joint_panel", "slider_bounds", "BASE_MOVES", "LINK_COLOR",
           "REVOLUTE_COLOR", "PRISMATIC_COLOR", "STATIC_ENV"]
