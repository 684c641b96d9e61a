"""kinlib.viz.Scene, the 3-D viewer widget: what it keeps as state and what it sends.

The messages are caught where ipywidgets hands them to the comm (the kernel's
connection to the page); the poses are decoded from the bytes sent and compared with
``robot.link_poses``, never with the visualizer's own helpers.
"""

import numpy as np
import pytest
import umsgpack

from kinlib import KinlibError
from kinlib.robots import puma560
from kinlib.viz import RobotVisualizer, Scene
from kinlib.viz._scene import mg  # meshcat.geometry, imported with its warnings filtered
from kinlib.viz._widget import BUNDLE_FILE, MeshcatBundle, bundle


@pytest.fixture
def scene():
    s = Scene()
    yield s
    s.close()


def sent_messages(widget):
    """Start recording what ``widget`` sends; the list fills as it sends."""
    seen = []
    send = widget.comm.send

    def record(data=None, buffers=None, **kw):
        seen.append((data, [bytes(b) for b in (buffers or [])]))
        return send(data=data, buffers=buffers, **kw)

    widget.comm.send = record
    return seen


def kinds(scene):
    return [(c["type"], c["path"]) for c in map(umsgpack.unpackb, scene._commands)]


def test_the_state_is_the_scene_compacted(scene):
    scene["a/b"].set_object(mg.Box([1, 1, 1]))
    scene["a/b"].set_object(mg.Sphere(1.0))  # replaced, not added
    scene["ab"].set_object(mg.Sphere(2.0))  # a sibling whose name starts like "a"
    scene["a/b"].set_property("visible", False)
    assert kinds(scene) == [("set_object", "/meshcat/a/b"), ("set_object", "/meshcat/ab"),
                            ("set_property", "/meshcat/a/b")]
    scene["a/b"].set_object(mg.Box([1, 2, 3]))  # a new object starts without properties
    assert ("set_property", "/meshcat/a/b") not in kinds(scene)
    scene["a/b"].set_transform(np.diag([1.0, 2.0, 3.0, 1.0]))
    scene["ab"].set_transform(np.eye(4))
    assert scene._pose_paths == ["/meshcat/a/b", "/meshcat/ab"]
    scene["a"].delete()  # everything under /meshcat/a goes, /meshcat/ab stays
    assert kinds(scene) == [("set_object", "/meshcat/ab"), ("delete", "/meshcat/a")]
    assert scene._pose_paths == ["/meshcat/ab"]
    box = umsgpack.unpackb(scene._commands[0])["object"]["geometries"][0]
    assert box["type"] == "SphereGeometry" and box["radius"] == 2.0  # meshcat's own encoding


def test_set_configuration_is_one_message_of_poses():
    robot = puma560()
    viz = RobotVisualizer(robot, prefix="test_scene_msgs")
    try:
        seen = sent_messages(viz.vis)
        q = robot.poses["ready"]
        viz.set_configuration(q)
        assert len(seen) == 1, [m[0] for m in seen]
        data, buffers = seen[0]
        assert set(data["state"]) == {"_seq"}  # the paths are unchanged: not sent again
        assert data["buffer_paths"] == [["_poses"]] and len(buffers) == 1  # one binary buffer
        poses = np.frombuffer(buffers[0], dtype=np.float32).reshape(-1, 4, 4).transpose(0, 2, 1)
        paths = viz.vis._pose_paths
        world = robot.link_poses(q)
        for name, T in world.items():
            k = paths.index(f"/meshcat/test_scene_msgs/links/{name}")
            np.testing.assert_allclose(poses[k], T, atol=1e-6)  # float32 on the wire
        # a new robot is drawn in one message too: objects, poses and camera together
        seen.clear()
        RobotVisualizer(robot, prefix="test_scene_msgs", scene=viz.vis)
        assert len(seen) == 1 and "_commands" in seen[0][0]["state"]
    finally:
        viz.vis.close()


def test_every_scene_shares_one_bundle_per_kernel(scene):
    other = Scene()
    try:
        assert scene._bundle is other._bundle is bundle()
        assert isinstance(scene._bundle, MeshcatBundle)
        assert scene._bundle.source == BUNDLE_FILE.read_text(encoding="utf-8")
        assert "_bundle" in scene.get_state() and "source" not in scene.get_state()
        old = bundle()
        old.close()
        fresh = bundle()  # a closed bundle is made again for the next scene
        assert fresh is not old and fresh.comm is not None and Scene()._bundle is fresh
    finally:
        other.close()


def test_bad_scene_input_is_a_clear_error(scene):
    for bad in (0, -1, 2.5, "300", True, None):
        with pytest.raises(KinlibError, match="height"):
            Scene(height=bad)
    with pytest.raises(KinlibError, match="4x4"):
        scene["x"].set_transform(np.eye(3))

    class Odd:
        def lower(self):
            return {"type": "capture_image", "path": ""}

    with pytest.raises(KinlibError, match="capture_image"):
        scene.send_command(Odd())
    frozen = scene.copy()
    for change in (lambda: frozen["x"].set_object(mg.Box([1, 1, 1])),
                   lambda: frozen["x"].set_transform(np.eye(4)), lambda: frozen["x"].delete()):
        with pytest.raises(KinlibError, match="frozen"):
            change()


def test_running_a_viewer_cell_again_leaves_nothing_behind():
    """A new visualizer of the same prefix closes the old one's scene (and its layout) and
    panels; a new panel for a visualizer closes its old panel: the kernel's widget count
    stays where the first run left it. The control: ipywidgets alone keeps every widget."""
    import ipywidgets
    from ipywidgets.widgets.widget import _instances

    from kinlib.viz import joint_panel

    counts = []
    for _ in range(4):
        viz = RobotVisualizer(puma560(), prefix="test_scene_rerun")
        joint_panel(viz)
        joint_panel(viz)
        counts.append(len(_instances))
    assert counts[1:] == counts[:-1], counts
    viz.close()
    before = len(_instances)
    for _ in range(3):
        ipywidgets.VBox([ipywidgets.FloatSlider()])
    assert len(_instances) > before  # without closing, widgets pile up
