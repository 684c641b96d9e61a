"""Screw axes drawn in a 3-D scene (kinlib.viz.draw_screw_axes), read back from the
scene's own state: the objects in its command list, the poses from its binary buffer.

The lines are checked by geometry, not by the helper that computes them: every drawn
point c lies on its axis (v = −ω × c for a revolute axis [v; ω]), the arrow runs along ω,
and for the UR5 each arrow lies on the joint axis the visualizer itself draws from the
link frames (its orange cylinders)."""

import numpy as np
import pytest
import umsgpack

import kinlib as kl
from kinlib import KinlibError
from kinlib.robots import ur5
from kinlib.viz import RobotVisualizer, Scene, draw_screw_axes


def objects(scene):
    cmds = [umsgpack.unpackb(c) for c in scene._commands]
    return {c["path"]: c["object"] for c in cmds if c["type"] == "set_object"}


def pose(scene, path):
    k = scene._pose_paths.index(path)
    return np.frombuffer(scene._poses, np.float32).reshape(-1, 4, 4)[k].T.astype(float)


def arrow(scene, root, i):
    """(centre, unit direction, shaft length, tip point) of arrow i, from the scene state."""
    obj = objects(scene)
    shaft = obj[f"/meshcat/{root}/{i}/shaft"]["geometries"][0]
    head = obj[f"/meshcat/{root}/{i}/head"]["geometries"][0]
    assert shaft["type"] == head["type"] == "CylinderGeometry"
    assert head["radiusTop"] == 0 and head["radiusBottom"] > shaft["radiusTop"]  # a cone
    T, H = pose(scene, f"/meshcat/{root}/{i}/shaft"), pose(scene, f"/meshcat/{root}/{i}/head")
    y = T[:3, :3] @ [0.0, 1.0, 0.0]                       # three.js cylinders lie along y
    np.testing.assert_allclose(H[:3, :3] @ [0.0, 1.0, 0.0], y, atol=1e-6)
    tip = H[:3, 3] + 0.5 * head["height"] * y             # the cone's apex (radiusTop 0)
    return T[:3, 3], y, shaft["height"], tip


def test_arrows_lie_on_their_axes_and_point_along_omega():
    rng = np.random.default_rng(5)
    w = rng.normal(size=(4, 3))
    w /= np.linalg.norm(w, axis=1, keepdims=True)
    q = rng.uniform(-1, 1, (4, 3))                        # a point on each axis
    S = np.vstack([-np.cross(w, q).T, w.T])               # revolute: [−ω × q; ω]
    S[:, 3] = [0.3, -0.4, 1.2, 0.0, 0.0, 0.0]             # and a slide along (0.3, −0.4, 1.2)
    hint = rng.uniform(-1, 1, (4, 3))
    scene = Scene()
    try:
        points, _ = draw_screw_axes(scene, S, through=hint, length=0.8)
        for i in range(4):
            c, y, L, tip = arrow(scene, "screws", i)
            assert L == pytest.approx(0.8)
            np.testing.assert_allclose(c, points[i], atol=1e-6)
            if i < 3:
                np.testing.assert_allclose(y, w[i], atol=1e-6)
                np.testing.assert_allclose(-np.cross(w[i], c), S[:3, i], atol=1e-6)  # on it
                np.testing.assert_allclose((hint[i] - c) @ w[i], 0.0, atol=1e-6)   # nearest
            else:
                np.testing.assert_allclose(y, S[:3, 3] / np.linalg.norm(S[:3, 3]), atol=1e-6)
                np.testing.assert_allclose(c, hint[3], atol=1e-6)  # through the given point
            assert (tip - c) @ y > 0.5 * L                # the head at the +ω end
        draw_screw_axes(scene, S[:, :2], length=0.8)      # again: replaced, not added
        assert sorted(p for p in objects(scene) if p.startswith("/meshcat/screws")) == [
            f"/meshcat/screws/{i}/{part}" for i in range(2) for part in ("head", "shaft")]
    finally:
        scene.close()


def test_the_ur5s_screw_axes_lie_on_its_drawn_joint_axes():
    """J_s(q)'s columns are the joints' screw axes at q: each arrow lies on the joint-axis
    cylinder the visualizer draws for that joint, whose pose comes from the link frames;
    a base pose moves both alike."""
    robot = ur5()
    q = np.array([0.4, -1.1, 1.3, -0.7, 0.9, 0.2])
    base = kl.transform(kl.rotz(0.7), [0.5, -0.2, 0.1])
    viz = RobotVisualizer(robot, prefix="test_viz_screws/ur5")
    try:
        viz.set_configuration(q, base=base)
        S, _ = kl.screw_axes(robot)
        points, _ = draw_screw_axes(viz, kl.space_jacobian(S, q), prefix="test_viz_screws/axes")
        axes = viz.scene_transforms(q)
        for i, joint in enumerate(robot.joint_names):
            c, y, L, _ = arrow(viz.vis, "test_viz_screws/axes", i)
            A = axes[f"/meshcat/test_viz_screws/ur5/axes/{joint}"]
            a, u = A[:3, 3], A[:3, :3] @ [0.0, 1.0, 0.0]  # the orange cylinder: centre, axis
            np.testing.assert_allclose(y, u, atol=1e-6)   # same direction (not reversed)
            off = (a - c) - ((a - c) @ u) * u
            np.testing.assert_allclose(off, 0.0, atol=1e-6)   # the same line
            assert L == pytest.approx(30 * viz.link_radius)
            np.testing.assert_allclose(points[i], c, atol=1e-6)   # returned in the world
        np.testing.assert_allclose(points[0], base[:3, 3], atol=1e-12)  # nearest the base
    finally:
        viz.close()


def test_bad_screw_axes_are_a_clear_error():
    scene = Scene()
    try:
        with pytest.raises(KinlibError, match=r"\(6, n\)"):
            draw_screw_axes(scene, np.zeros((5, 2)))
        with pytest.raises(KinlibError, match="column 1 is zero"):
            draw_screw_axes(scene, np.c_[[0, 0, 0, 0, 0, 1.0], np.zeros(6)])
        with pytest.raises(KinlibError, match="through"):
            draw_screw_axes(scene, np.eye(6), through=np.zeros((2, 3)))
        for bad in (0, -1.0, np.nan, [1.0, 2.0]):
            with pytest.raises(KinlibError, match="length"):
                draw_screw_axes(scene, np.eye(6), length=bad)
        with pytest.raises(KinlibError, match="RobotVisualizer or a Scene"):
            draw_screw_axes("scene", np.eye(6))
        with pytest.raises(KinlibError, match="prefix"):
            draw_screw_axes(scene, np.eye(6), prefix="/")
    finally:
        scene.close()
