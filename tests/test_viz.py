"""kinlib.viz against the session's meshcat server (started by the root conftest.py).

Expected values come from ``robot.link_poses`` and the joints' data, never from the
visualizer's own helpers; what the server really holds is read back from its scene
(``static_html`` replays every stored command as base64 msgpack).
"""

import base64
import html
import os
import re
import uuid

import numpy as np
import pytest
import umsgpack

from kinlib import KinlibError, load_urdf, matrix_from_quat, rotx, transform
from kinlib.holonomic import base_pose
from kinlib.robots import autorob_test_robot, puma560
from kinlib.viz import STATIC_ENV, RobotVisualizer

ZMQ_ENV, WEB_ENV = "KINLIB_MESHCAT_ZMQ_URL", "KINLIB_MESHCAT_WEB_URL"
EY = np.array([0.0, 1.0, 0.0])

SHAPES_URDF = """<?xml version="1.0"?>
<robot name="shapes">
  <material name="red"><color rgba="1 0 0 1"/></material>
  <link name="base">
    <visual><origin xyz="0 0 0.05"/><geometry><box size="0.2 0.2 0.1"/></geometry>
      <material name="red"/></visual>
  </link>
  <link name="arm">
    <visual><origin xyz="0 0 0.25"/><geometry><cylinder radius="0.03" length="0.5"/></geometry>
    </visual>
    <visual><origin xyz="0.1 0 0" rpy="0.4 -0.7 1.1"/>
      <geometry><cylinder radius="0.02" length="0.2"/></geometry></visual>
    <visual><geometry><mesh filename="package://nowhere/meshes/missing.stl"/></geometry></visual>
    <visual><geometry><mesh filename="tri.stl" scale="2 2 2"/></geometry></visual>
  </link>
  <link name="down"><visual><geometry><sphere radius="0.05"/></geometry></visual></link>
  <link name="up"/>
  <link name="slide"/>
  <joint name="j_arm" type="revolute">
    <parent link="base"/><child link="arm"/>
    <origin xyz="0 0 0.1" rpy="0.3 0 0.2"/><axis xyz="0 1 1"/>
    <limit lower="-2" upper="2" effort="1" velocity="1"/>
  </joint>
  <joint name="j_down" type="fixed">
    <parent link="base"/><child link="down"/><origin xyz="0 -0.4 0"/>
  </joint>
  <joint name="j_up" type="continuous">
    <parent link="base"/><child link="up"/><origin xyz="0 0.3 0"/><axis xyz="0 -1 0"/>
  </joint>
  <joint name="j_slide" type="prismatic">
    <parent link="arm"/><child link="slide"/><origin xyz="0 0 0.5"/><axis xyz="1 1 0"/>
    <limit lower="-0.3" upper="0.4" effort="1" velocity="1"/>
  </joint>
</robot>
"""

ROBOTS = {"puma560": puma560, "autorob": autorob_test_robot,
          "shapes": lambda: load_urdf(SHAPES_URDF)}


def page_commands(page):
    """Every command a static meshcat page replays, decoded: dicts with 'type' and 'path'."""
    blobs = re.findall(r"fetch\(\"data:application/octet-binary;base64,([A-Za-z0-9+/=]+)\"\)",
                       page)
    return [umsgpack.unpackb(base64.b64decode(b)) for b in blobs]


def server_commands(viz):
    """Every command the server holds (see :func:`page_commands`)."""
    return page_commands(viz.static_html())


def column_major(matrix):
    return np.array(matrix, dtype=float).reshape(4, 4).T


def random_q(robot, seed):
    lim = np.clip(robot.limits, -np.pi, np.pi)
    return np.random.default_rng(seed).uniform(lim[:, 0], lim[:, 1])


BASE = base_pose(0.4, -0.3, 0.9) @ transform(rotx(0.3), [0.0, 0.0, 0.2])  # tilted too


def test_the_session_server_is_configured():
    assert os.environ.get(ZMQ_ENV, "").startswith("tcp://")
    assert os.environ.get(WEB_ENV, "").startswith("http")


@pytest.mark.parametrize("name", ROBOTS)
def test_scene_paths_and_link_transforms(make_viz, name):
    robot = ROBOTS[name]()
    viz = make_viz(robot)
    q = random_q(robot, 1)
    T = viz.scene_transforms(q, base=BASE)
    root = f"/meshcat/{viz.prefix}"
    expected = {f"{root}/links/{n}" for n in robot.link_names}
    expected |= {f"{root}/segments/{j.name}" for j in robot.joints}
    expected |= {f"{root}/axes/{j.name}" for j in robot.joints if j.type != "fixed"}
    assert set(T) == expected
    poses = robot.link_poses(q)
    for n in robot.link_names:
        np.testing.assert_allclose(T[f"{root}/links/{n}"], BASE @ poses[n], atol=1e-12)


@pytest.mark.parametrize("name", ROBOTS)
def test_segments_join_the_link_origins(make_viz, name):
    robot = ROBOTS[name]()
    viz = make_viz(robot)
    for seed in range(3):
        q = random_q(robot, seed)
        T = viz.scene_transforms(q, base=BASE)
        W = {n: BASE @ P for n, P in robot.link_poses(q).items()}
        for jt in robot.joints:
            M = T[f"/meshcat/{viz.prefix}/segments/{jt.name}"]
            assert np.isfinite(M).all()
            p0, p1 = W[jt.parent][:3, 3], W[jt.child][:3, 3]
            if np.linalg.norm(p1 - p0) < 1e-9:  # hidden, not NaN
                assert np.abs(M[:3, :3]).max() < 1e-6
                continue
            np.testing.assert_allclose(M @ [0, 0.5, 0, 1], np.append(p1, 1), atol=1e-12)
            np.testing.assert_allclose(M @ [0, -0.5, 0, 1], np.append(p0, 1), atol=1e-12)
            # the cross-section keeps the cylinder's radius: x, z columns unit and ⟂ axis
            A = M[:3, :3]
            np.testing.assert_allclose(np.linalg.norm(A[:, [0, 2]], axis=0), 1.0)
            np.testing.assert_allclose((p1 - p0) @ A[:, [0, 2]], 0.0, atol=1e-12)
            assert np.linalg.det(A) > 0


def test_segments_along_minus_y_and_plus_y(make_viz):
    robot = load_urdf(SHAPES_URDF)
    viz = make_viz(robot)
    T = viz.scene_transforms(np.zeros(robot.dof), base=np.eye(4))
    for joint, end in (("j_down", [0.0, -0.4, 0.0]), ("j_up", [0.0, 0.3, 0.0])):
        M = T[f"/meshcat/{viz.prefix}/segments/{joint}"]
        assert np.isfinite(M).all()
        np.testing.assert_allclose(M @ [0, 0.5, 0, 1], end + [1.0], atol=1e-15)
        np.testing.assert_allclose(M @ [0, -0.5, 0, 1], [0, 0, 0, 1], atol=1e-15)
        assert np.linalg.det(M[:3, :3]) > 0


def test_zero_length_segment_is_hidden_without_nan(make_viz):
    robot = puma560()  # joint1 joins link0 and link1, both at the origin
    viz = make_viz(robot)
    M = viz.scene_transforms(np.zeros(6))[f"/meshcat/{viz.prefix}/segments/joint1"]
    assert np.isfinite(M).all() and np.abs(M[:3, :3]).max() < 1e-6


@pytest.mark.parametrize("name", ROBOTS)
def test_joint_axis_cylinders_lie_on_the_axes(make_viz, name):
    robot = ROBOTS[name]()
    viz = make_viz(robot)
    q = random_q(robot, 5)
    T = viz.scene_transforms(q, base=BASE)
    W = {n: BASE @ P for n, P in robot.link_poses(q).items()}
    for jt in robot.joints:
        if not jt.movable:
            continue
        # the motion rotates about (or slides along) the axis, so the axis direction is
        # already fixed by the parent frame and the joint origin
        F = W[jt.parent] @ jt.origin
        axis = F[:3, :3] @ jt.axis
        point = F[:3, 3]
        if jt.type == "prismatic":
            point = point + q[robot.joint_names.index(jt.name)] * axis
        # the same from the child side: the joint frame is child @ inv(post)
        G = W[jt.child] @ np.linalg.inv(jt.post)
        np.testing.assert_allclose(G[:3, :3] @ jt.axis, axis, atol=1e-12)
        M = T[f"/meshcat/{viz.prefix}/axes/{jt.name}"]
        np.testing.assert_allclose(M[:3, :3] @ EY, axis, atol=1e-12)
        np.testing.assert_allclose(M[:3, 3], point, atol=1e-12)
        np.testing.assert_allclose(M[:3, :3] @ M[:3, :3].T, np.eye(3), atol=1e-12)


def test_puma_axis_i_is_z_of_frame_i_minus_1(make_viz):
    robot = puma560()
    viz = make_viz(robot)
    q = robot.poses["ready"]
    T = viz.scene_transforms(q, base=np.eye(4))
    for i in range(1, 7):
        F = robot.link_poses(q)[f"link{i - 1}"]
        M = T[f"/meshcat/{viz.prefix}/axes/joint{i}"]
        np.testing.assert_allclose(M[:3, :3] @ EY, F[:3, 2], atol=1e-12)
        np.testing.assert_allclose(M[:3, 3], F[:3, 3], atol=1e-12)


def test_urdf_visuals_on_the_server(make_viz):
    robot = load_urdf(SHAPES_URDF)
    viz = make_viz(robot)
    root = f"/meshcat/{viz.prefix}"
    cmds = server_commands(viz)
    objects = {c["path"]: c for c in cmds if c["type"] == "set_object"}
    moves = {c["path"]: column_major(c["matrix"]) for c in cmds if c["type"] == "set_transform"}
    kinds = {p: objects[p]["object"]["geometries"][0]["type"] for p in objects}
    assert kinds[f"{root}/links/base/visual_0"] == "BoxGeometry"
    assert kinds[f"{root}/links/down/visual_0"] == "SphereGeometry"
    assert kinds[f"{root}/links/arm/visual_0"] == "CylinderGeometry"
    assert kinds[f"{root}/links/arm/visual_3"] == "_meshfile"  # tri.stl found in mesh_dir
    assert f"{root}/links/arm/visual_2" not in objects
    assert viz.skipped_meshes == [("arm", "package://nowhere/meshes/missing.stl")]
    assert objects[f"{root}/links/base/visual_0"]["object"]["materials"][0]["color"] == 0xFF0000
    # URDF cylinders are along the link's z (or their origin's z); three.js's along y
    arm = robot.link("arm")
    for i in (0, 1):
        M = moves[f"{root}/links/arm/visual_{i}"]
        np.testing.assert_allclose(M[:3, :3] @ EY, arm.visuals[i].origin[:3, 2], atol=1e-12)
        np.testing.assert_allclose(M[:3, 3], arm.visuals[i].origin[:3, 3], atol=1e-12)
    np.testing.assert_allclose(moves[f"{root}/links/arm/visual_0"][:3, :3] @ EY, [0, 0, 1],
                               atol=1e-12)
    np.testing.assert_allclose(np.diag(moves[f"{root}/links/arm/visual_3"]), [2, 2, 2, 1])
    # and in the world, after a move: the link's z
    q = random_q(robot, 3)
    viz.set_configuration(q)
    T_link = robot.link_poses(q)["arm"]
    moves = {c["path"]: column_major(c["matrix"]) for c in server_commands(viz)
             if c["type"] == "set_transform"}
    world = moves[f"{root}/links/arm"] @ moves[f"{root}/links/arm/visual_0"]
    np.testing.assert_allclose(world[:3, :3] @ EY, T_link[:3, 2], atol=1e-12)


def test_set_configuration_sends_and_stores(make_viz):
    robot = puma560()
    viz = make_viz(robot)
    q = robot.poses["ready"]
    viz.set_configuration(q, base=BASE)
    np.testing.assert_array_equal(viz.q, q)
    np.testing.assert_array_equal(viz.base, BASE)
    sent = {c["path"]: column_major(c["matrix"]) for c in server_commands(viz)
            if c["type"] == "set_transform" and c["path"].startswith(f"/meshcat/{viz.prefix}/")}
    for path, M in viz.scene_transforms(q).items():
        np.testing.assert_allclose(sent[path], M, atol=1e-12)
    viz.set_configuration(np.zeros(6))  # base=None keeps the base
    np.testing.assert_array_equal(viz.base, BASE)


def test_set_configuration_rejects_bad_input(make_viz):
    viz = make_viz(puma560())
    for bad in (np.zeros(5), np.zeros(7), np.zeros((2, 6)), "q", [np.nan] * 6):
        with pytest.raises(KinlibError, match="q"):
            viz.set_configuration(bad)
    with pytest.raises(KinlibError, match="base"):
        viz.set_configuration(np.zeros(6), base=np.eye(3))
    with pytest.raises(KinlibError, match="base"):
        viz.set_configuration(np.zeros(6), base=np.diag([1.0, 2.0, 1.0, 1.0]))
    with pytest.raises(KinlibError, match="q"):
        viz.scene_transforms(np.zeros(4))
    np.testing.assert_array_equal(viz.q, np.zeros(6))  # nothing changed


def test_animate_tracks_match_scene_transforms(make_viz):
    robot = puma560()
    viz = make_viz(robot)
    qs = np.linspace(robot.poses["zero"], robot.poses["ready"], 7)
    anim = viz.animate(qs, fps=10, base=BASE)
    clips = {path.lower(): clip for path, clip in anim.clips.items()}
    for k in (0, 3, 6):
        expected = viz.scene_transforms(qs[k], base=BASE)
        assert set(clips) == set(expected)
        for path, M in expected.items():
            tr = clips[path].tracks
            assert tr["position"].frames[k] == k and clips[path].fps == 10
            x, y, z, w = tr["quaternion"].values[k]
            R = matrix_from_quat([w, x, y, z]) * np.array(tr["scale"].values[k])
            np.testing.assert_allclose(R, M[:3, :3], atol=1e-9)
            np.testing.assert_allclose(tr["position"].values[k], M[:3, 3], atol=1e-12)
    stored = [c for c in server_commands(viz) if c["type"] == "set_animation"]
    assert stored, "the animation was not sent to the server"


def test_animate_validates(make_viz):
    viz = make_viz(puma560())
    with pytest.raises(KinlibError, match="qs"):
        viz.animate(np.zeros(6))
    with pytest.raises(KinlibError, match="qs"):
        viz.animate(np.zeros((4, 5)))
    with pytest.raises(KinlibError, match="qs"):
        viz.animate(np.zeros((0, 6)))
    with pytest.raises(KinlibError, match="fps"):
        viz.animate(np.zeros((3, 6)), fps=0)
    with pytest.raises(KinlibError, match="base"):
        viz.animate(np.zeros((3, 6)), base=np.tile(np.eye(4), (2, 1, 1)))
    moving = base_pose(np.linspace(0, 1, 3), 0.0, 0.0)
    anim = viz.animate(np.zeros((3, 6)), base=moving)
    link0 = anim.clips[viz.vis[f"{viz.prefix}/links/link0"].path]
    np.testing.assert_allclose(link0.tracks["position"].values, moving[:, :3, 3])


def test_static_html_is_self_contained(make_viz, tmp_path):
    viz = make_viz(puma560())
    html = viz.static_html()
    assert len(html) > 100_000
    assert "MeshCat.Viewer" in html and "handle_command_bytearray" in html
    assert "http://" not in html.split("<script>")[0]  # nothing fetched from the server
    viz.save_html(tmp_path / "puma.html")
    assert (tmp_path / "puma.html").read_text(encoding="utf-8") == html
    assert viz.url() == os.environ[WEB_ENV]
    assert viz.url() in viz.jupyter_cell().data


def test_snapshot_embeds_the_current_scene(make_viz, monkeypatch):
    viz = make_viz(puma560())
    viz.set_configuration(viz.robot.poses["ready"])
    cell = viz.snapshot(height=321)
    m = re.fullmatch(r'<div class="kinlib-scene"><iframe srcdoc="([^"]*)" style="width: 100%; '
                     r'height: 321px; border: none"></iframe></div>', cell.data)
    assert m, cell.data[:300]
    page = html.unescape(m.group(1))
    assert "MeshCat.Viewer" in page and viz.url() not in page
    ours = {c["path"].lower(): column_major(c["matrix"]) for c in page_commands(page)
            if c["type"] == "set_transform" and f"/{viz.prefix}/" in c["path"].lower()}
    expected = viz.scene_transforms(viz.robot.poses["ready"])
    assert set(ours) == set(expected)
    for path, M in expected.items():
        np.testing.assert_allclose(ours[path], M, atol=1e-12)

    monkeypatch.delenv(STATIC_ENV, raising=False)
    assert viz.url() in viz.jupyter_cell(height=300).data  # live
    monkeypatch.setenv(STATIC_ENV, "1")
    static = viz.jupyter_cell(height=300).data
    assert static.startswith('<div class="kinlib-scene"><iframe srcdoc=')
    assert viz.url() not in static
    for bad in (0, -5, 2.5, "400", True, None):
        with pytest.raises(KinlibError, match="height"):
            viz.snapshot(height=bad)
        with pytest.raises(KinlibError, match="height"):
            viz.jupyter_cell(height=bad)


def test_same_prefix_replaces_the_robot(make_viz):
    prefix = f"test_{uuid.uuid4().hex[:8]}"
    first = make_viz(puma560(), prefix=prefix)
    root = f"/meshcat/{prefix}/"

    def drawn():
        return sorted(c["path"] for c in server_commands(first)
                      if c["type"] == "set_object" and c["path"].startswith(root))

    puma_objects = drawn()
    assert f"{root}links/link6/origin" in puma_objects
    again = make_viz(puma560(), prefix=prefix)
    assert drawn() == puma_objects  # same picture, no duplicates
    assert set(again.scene_transforms(np.zeros(6))) == set(first.scene_transforms(np.zeros(6)))
    make_viz(autorob_test_robot(), prefix=prefix)
    now = drawn()
    assert f"{root}links/link6/origin" not in now  # the PUMA was deleted, not kept
    assert f"{root}links/link4/origin" in now
    assert not any("link0" in p or "link5" in p or "link6" in p for p in now)


def test_bad_constructor_arguments():
    with pytest.raises(KinlibError, match="Robot"):
        RobotVisualizer("puma")
    with pytest.raises(KinlibError, match="prefix"):
        RobotVisualizer(puma560(), prefix="/")
    with pytest.raises(KinlibError, match="link_radius"):
        RobotVisualizer(puma560(), link_radius=-1.0)
    with pytest.raises(KinlibError, match="color"):
        RobotVisualizer(puma560(), color="magenta")


def test_unreachable_server_is_a_clear_error():
    with pytest.raises(KinlibError, match="no meshcat server"):
        from kinlib.viz._scene import connect

        connect("tcp://127.0.0.1:1", timeout=0.3)
