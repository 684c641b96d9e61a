"""``joint_panel``: ipywidgets sliders for the joints and buttons for the holonomic base.

The base controls are those of seed 000 (KinEval's keyboard base controls): move forward,
back, left, right along the base's own heading and lateral axes, turn left or right, and
show the heading and lateral vectors in world coordinates
(:mod:`kinlib.kinematics.holonomic`). ipywidgets is imported when a panel is made.
"""

from __future__ import annotations

import numpy as np

from ..errors import KinlibError
from ..kinematics.holonomic import base_heading_lateral, base_step

__all__ = ["joint_panel", "slider_bounds", "BASE_MOVES"]

#: button label → (forward, lateral, turn) in units of the step sizes
BASE_MOVES = {
    "forward": (1.0, 0.0, 0.0),
    "back": (-1.0, 0.0, 0.0),
    "left": (0.0, 1.0, 0.0),
    "right": (0.0, -1.0, 0.0),
    "turn left": (0.0, 0.0, 1.0),
    "turn right": (0.0, 0.0, -1.0),
}


def slider_bounds(robot) -> np.ndarray:
    """(dof, 2) slider ranges: the joint limits; unlimited sides ±π (revolute) or ±1 m.

    >>> from kinlib.robots import autorob_test_robot
    >>> slider_bounds(autorob_test_robot())[0].round(6)
    array([-3.141593,  3.141593])
    """
    lim = np.array(robot.limits, dtype=float)
    for i, name in enumerate(robot.joint_names):
        default = 1.0 if robot.joint(name).type == "prismatic" else np.pi
        lo, hi = lim[i]
        lim[i, 0] = lo if np.isfinite(lo) else min(-default, hi - default)
        lim[i, 1] = hi if np.isfinite(hi) else max(default, lim[i, 0] + default)
    return lim


def _vec(v) -> str:
    return "[" + ", ".join(f"{x:+.3f}" for x in np.asarray(v)) + "]"


def _base_text(T) -> str:
    heading, lateral = base_heading_lateral(T)
    p = T[:3, 3]
    return (f"<b>base</b> position {_vec(p)} &nbsp; heading {_vec(heading)} &nbsp; "
            f"lateral {_vec(lateral)} <i>(world coordinates)</i>")


def joint_panel(viz, *, step: float = 0.1, turn_step: float = np.pi / 12, base: bool = True):
    """A widget panel that drives ``viz`` (a :class:`~kinlib.viz.RobotVisualizer`).

    One ``FloatSlider`` per joint (in the order of q), bounded by :func:`slider_bounds` and
    starting at ``viz.q``; moving one calls ``viz.set_configuration``. Below them, the base
    controls: buttons ``forward``, ``back``, ``left``, ``right``, ``turn left``,
    ``turn right`` that move ``viz.base`` with :func:`kinlib.kinematics.holonomic.base_step` by
    ``step`` metres or ``turn_step`` radians (editable in the panel), and a line showing
    the base's heading and lateral vectors in world coordinates. ``base=False`` leaves
    the base controls out (a robot that stands still).

    Returns
    -------
    ipywidgets.VBox
        With attributes ``sliders`` (dict joint name → slider), ``buttons`` (dict label →
        button), ``step`` and ``turn_step`` (the step-size fields) and ``base_info`` (the
        HTML line), so code and tests can drive it:
        ``panel.sliders["joint1"].value = 0.3``, ``panel.buttons["forward"].click()``.

    A new panel for the same visualizer closes the previous one (running its cell again
    replaces the panel), and closing the visualizer closes its panel.
    """
    import ipywidgets as w

    robot = getattr(viz, "robot", None)
    if robot is None or not hasattr(viz, "set_configuration"):
        raise KinlibError(f"joint_panel: expected a RobotVisualizer, got {type(viz).__name__}")
    for name, value in (("step", step), ("turn_step", turn_step)):
        if isinstance(value, bool) or not isinstance(value, int | float | np.floating) \
                or not np.isfinite(value) or value <= 0:
            raise KinlibError(f"{name}: expected one positive number, got {value!r}")

    bounds = slider_bounds(robot)
    sliders = {}
    for i, name in enumerate(robot.joint_names):
        lo, hi = (float(x) for x in bounds[i])
        sliders[name] = w.FloatSlider(
            value=float(np.clip(viz.q[i], lo, hi)), min=lo, max=hi, step=(hi - lo) / 1000,
            description=name, readout_format=".3f", continuous_update=True,
            style={"description_width": "initial"}, layout=w.Layout(width="480px"))

    def on_slide(change, i):
        q = np.array(viz.q, dtype=float)
        q[i] = change["new"]
        viz.set_configuration(q)

    for i, s in enumerate(sliders.values()):
        s.observe(lambda change, i=i: on_slide(change, i), names="value")

    step_box = w.BoundedFloatText(value=float(step), min=1e-6, max=1e6, description="step (m)")
    turn_box = w.BoundedFloatText(value=float(turn_step), min=1e-6, max=2 * np.pi,
                                  description="turn (rad)")
    info = w.HTML(_base_text(viz.base))
    buttons = {label: w.Button(description=label, layout=w.Layout(width="90px"))
               for label in BASE_MOVES}

    def on_click(label):
        f, s, t = BASE_MOVES[label]
        T = base_step(viz.base, forward=f * step_box.value, lateral=s * step_box.value,
                      turn=t * turn_box.value)
        viz.set_configuration(viz.q, base=T)
        info.value = _base_text(viz.base)

    for label, b in buttons.items():
        b.on_click(lambda _b, label=label: on_click(label))

    b = buttons
    base_box = w.VBox([
        w.HTML("<b>holonomic base</b>"),
        w.HBox([b["turn left"], b["forward"], b["turn right"]]),
        w.HBox([b["left"], b["back"], b["right"]]),
        w.HBox([step_box, turn_box]),
        info,
    ])
    panel = w.VBox([w.HTML("<b>joints</b>"), *sliders.values()] + ([base_box] if base else []))
    panel.sliders = sliders
    panel.buttons = buttons
    panel.step = step_box
    panel.turn_step = turn_box
    panel.base_info = info
    made = getattr(viz, "panels", None)
    if isinstance(made, list):
        from ._widget import close_tree

        for old in made:
            close_tree(old)
        made[:] = [panel]
    return panel
