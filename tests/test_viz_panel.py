"""The widget panel of kinlib.viz: joint sliders and the holonomic base buttons."""

import numpy as np
import pytest

from kinlib import DHRow, KinlibError, Robot
from kinlib.kinematics.holonomic import base_pose
from kinlib.robots import autorob_test_robot, puma560
from kinlib.viz import joint_panel


def test_panel_sliders_have_joint_bounds(make_viz):
    viz = make_viz(puma560())
    panel = joint_panel(viz)
    assert list(panel.sliders) == [f"joint{i}" for i in range(1, 7)]
    s2 = panel.sliders["joint2"]
    assert (s2.min, s2.max) == pytest.approx((np.deg2rad(-225.0), np.deg2rad(45.0)))
    cont = joint_panel(make_viz(autorob_test_robot()))
    for s in cont.sliders.values():
        assert (s.min, s.max) == pytest.approx((-np.pi, np.pi))
    pris = Robot.from_dh([DHRow(a=0.0, alpha=0.0, joint="prismatic"),
                          DHRow(a=0.5, alpha=0.0, limits=(-1.0, 0.5))], name="pr")
    sl = joint_panel(make_viz(pris)).sliders
    assert (sl["joint1"].min, sl["joint1"].max) == (-1.0, 1.0)
    assert (sl["joint2"].min, sl["joint2"].max) == (-1.0, 0.5)


def test_panel_slider_moves_the_robot(make_viz):
    viz = make_viz(puma560())
    panel = joint_panel(viz)
    before = viz.scene_transforms(viz.q)
    panel.sliders["joint3"].value = 0.3
    np.testing.assert_allclose(viz.q, [0, 0, 0.3, 0, 0, 0])
    panel.sliders["joint1"].value = -0.2
    np.testing.assert_allclose(viz.q, [-0.2, 0, 0.3, 0, 0, 0])
    after = viz.scene_transforms(viz.q)
    link6 = f"/meshcat/{viz.prefix}/links/link6"
    assert not np.allclose(after[link6], before[link6])


def test_panel_base_buttons(make_viz):
    viz = make_viz(puma560())
    viz.set_configuration(viz.q, base=base_pose(1.0, 2.0, 0.6))
    panel = joint_panel(viz, step=0.25, turn_step=0.5)
    assert set(panel.buttons) == {"forward", "back", "left", "right", "turn left",
                                  "turn right"}
    panel.buttons["forward"].click()
    np.testing.assert_allclose(viz.base[:3, 3], [1 + 0.25 * np.cos(0.6),
                                                 2 + 0.25 * np.sin(0.6), 0], atol=1e-12)
    panel.buttons["back"].click()
    np.testing.assert_allclose(viz.base, base_pose(1.0, 2.0, 0.6), atol=1e-12)
    panel.buttons["left"].click()
    np.testing.assert_allclose(viz.base[:3, 3], [1 - 0.25 * np.sin(0.6),
                                                 2 + 0.25 * np.cos(0.6), 0], atol=1e-12)
    panel.buttons["right"].click()
    panel.buttons["turn left"].click()
    np.testing.assert_allclose(viz.base, base_pose(1.0, 2.0, 1.1), atol=1e-12)
    assert "+0.454" in panel.base_info.value  # heading x = cos(1.1)
    panel.turn_step.value = 1.1
    panel.buttons["turn right"].click()
    np.testing.assert_allclose(viz.base, base_pose(1.0, 2.0, 0.0), atol=1e-12)
    panel.sliders["joint2"].value = 0.1  # a slider keeps the base
    np.testing.assert_allclose(viz.base, base_pose(1.0, 2.0, 0.0), atol=1e-12)


def test_panel_rejects_bad_input(make_viz):
    with pytest.raises(KinlibError, match="RobotVisualizer"):
        joint_panel(puma560())
    with pytest.raises(KinlibError, match="step"):
        joint_panel(make_viz(puma560()), step=0)




def test_panel_without_base_controls(make_viz):
    viz = make_viz(puma560())
    panel = joint_panel(viz, base=False)
    assert len(panel.children) == 1 + 6  # the title and six sliders, no base box
    with_base = joint_panel(viz)
    assert len(with_base.children) == 1 + 6 + 1
    panel.sliders["joint1"].value = 0.25  # the sliders drive the robot
    assert viz.q[0] == pytest.approx(0.25)
