"""kinlib.viz: what a visualizer puts in its scene widget.

Expected values come from ``robot.link_poses`` and the joints' data, never from the
visualizer's own helpers; what the widget really holds is read back from the state it
sends to the browser (``Scene.get_state()``: meshcat's msgpack commands and the pose
buffer), and what an exported page holds from the page itself.
"""

import base64
import json
import re
import uuid

import numpy as np
import pytest
import umsgpack

from kinlib import KinlibError, load_urdf, matrix_from_quat, rotx, transform
from kinlib.kinematics.holonomic import base_pose
from kinlib.robots import autorob_test_robot, puma560
from kinlib.viz import RobotVisualizer, Scene

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


def decoded(commands, paths, poses):
    """Scene commands as dicts with 'type' and 'path' (meshcat's msgpack decoded), then
    one ``set_transform`` per pose (column-major 'matrix', as meshcat sends it)."""
    out = [umsgpack.unpackb(bytes(c)) for c in commands]
    mats = np.frombuffer(bytes(poses), dtype=np.float32).reshape(-1, 16)
    assert len(mats) == len(paths), (len(mats), len(paths))
    out += [{"type": "set_transform", "path": p, "matrix": m.astype(float).tolist()}
            for p, m in zip(paths, mats, strict=True)]
    return out


def page_commands(page):
    """Every command the scenes of an exported page replay (``kl-scene-static`` holders)."""
    found = []
    for text in re.findall(r'<div class="kl-scene-static"[^>]*><script type="application/json">'
                           r"(.*?)</script>", page, re.S):
        data = json.loads(text)
        found += decoded([base64.b64decode(c) for c in data["commands"]], data["paths"],
                         base64.b64decode(data["poses"]))
    return found


def server_commands(viz):
    """Every command the widget state of ``viz``'s scene holds: what the browser gets."""
    state = viz.vis.get_state()
    return decoded(state["_commands"], state["_pose_paths"], state["_poses"])


def column_major(matrix):
    return np.array(matrix, dtype=float).reshape(4, 4).T


def random_q(robot, seed):
    lim = np.clip(robot.limits, -np.pi, np.pi)
    return np.random.default_rng(seed).uniform(lim[:, 0], lim[:, 1])


BASE = base_pose(0.4, -0.3, 0.9) @ transform(rotx(0.3), [0.0, 0.0, 0.2])  # tilted too


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


MIRRORED_URDF = """<robot name="mirrored">
  <link name="left">
    <visual><origin xyz="0 0.2 0" rpy="0.3 -0.2 0.5"/>
      <geometry><mesh filename="tri.stl" scale="1 -1 1"/></geometry></visual>
    <visual><geometry><mesh filename="tri.stl" scale="-0.001 -0.002 -0.001"/></geometry></visual>
  </link>
</robot>"""


def test_mirrored_mesh_is_drawn_mirrored(make_viz):
    """A negative mesh scale (real robots' left arm is the right one mirrored) reaches the
    scene as a transform of negative determinant; three.js splits such a matrix into a
    rotation and a negative x scale (Matrix4.decompose), and so does kinlib's decompose."""
    from kinlib.viz._geometry import decompose

    robot = load_urdf(MIRRORED_URDF)
    viz = make_viz(robot)
    root = f"/meshcat/{viz.prefix}/links/left"
    moves = {c["path"]: column_major(c["matrix"]) for c in server_commands(viz)
             if c["type"] == "set_transform"}
    assert viz.skipped_meshes == []
    for i, scale in enumerate([(1.0, -1.0, 1.0), (-0.001, -0.002, -0.001)]):
        M = moves[f"{root}/visual_{i}"]
        expected = np.array(robot.link("left").visuals[i].origin) @ np.diag([*scale, 1.0])
        np.testing.assert_allclose(M, expected, rtol=1e-6, atol=1e-7)  # sent as float32
        assert np.linalg.det(M[:3, :3]) < 0
        _, R, s = decompose(expected)
        np.testing.assert_allclose(R.T @ R, np.eye(3), atol=1e-12)
        assert np.linalg.det(R) == pytest.approx(1.0)
        np.testing.assert_allclose(R * s, expected[:3, :3], atol=1e-15)
        np.testing.assert_allclose(np.abs(s), np.abs(scale), rtol=1e-12)
        assert s[0] < 0 < s[1] * s[2]
    _, R, s = decompose(np.diag([2.0, 3.0, 4.0, 1.0]))  # no mirror: every scale positive
    np.testing.assert_allclose(s, [2, 3, 4])
    np.testing.assert_array_equal(R, np.eye(3))


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
    viz.set_configuration(viz.robot.poses["ready"])
    page = viz.static_html()
    assert len(page) > 500_000  # the meshcat bundle is inline
    assert "MeshCat" in page and "kinlibStaticScenes(MeshCat, document)" in page
    assert not re.findall(r'(?:src|href)="https?:', page)  # nothing fetched
    assert page_commands(page) == server_commands(viz)  # the scene as it is now
    viz.save_html(tmp_path / "puma.html")
    assert (tmp_path / "puma.html").read_text(encoding="utf-8") == page


def test_jupyter_cell_is_the_live_scene_and_snapshot_a_frozen_copy(make_viz):
    viz = make_viz(puma560())
    viz.set_configuration(viz.robot.poses["ready"])
    cell = viz.jupyter_cell(height=300)
    assert cell is viz.vis and cell.height == 300
    bundle = cell._repr_mimebundle_()
    assert bundle[0]["application/vnd.jupyter.widget-view+json"]["model_id"] == cell.model_id
    snap = viz.snapshot(height=321)
    assert isinstance(snap, Scene) and snap is not viz.vis and snap.height == 321
    assert snap._bundle is viz.vis._bundle  # one copy of the meshcat bundle per kernel
    at_ready = server_commands(viz)
    snap_state = snap.get_state()
    assert decoded(snap_state["_commands"], snap_state["_pose_paths"],
                   snap_state["_poses"]) == at_ready
    viz.set_configuration(np.zeros(6))  # the live scene follows, the snapshot does not
    assert server_commands(viz) != at_ready
    snap_state = snap.get_state()
    assert decoded(snap_state["_commands"], snap_state["_pose_paths"],
                   snap_state["_poses"]) == at_ready
    with pytest.raises(KinlibError, match="frozen"):
        snap["x"].set_object(__import__("meshcat.geometry").geometry.Box([1, 1, 1]))
    for bad in (0, -5, 2.5, "400", True, None):
        with pytest.raises(KinlibError, match="height"):
            viz.snapshot(height=bad)
        with pytest.raises(KinlibError, match="height"):
            viz.jupyter_cell(height=bad)


def test_same_prefix_replaces_the_robot(make_viz):
    """Re-running a cell: a new visualizer of the same prefix closes the old scene widget
    (nothing left behind in the kernel); in one shared scene it redraws in place."""
    prefix = f"test_{uuid.uuid4().hex[:8]}"
    first = make_viz(puma560(), prefix=prefix)
    again = make_viz(puma560(), prefix=prefix)
    assert first.vis.comm is None and again.vis.comm is not None  # the old widget closed
    root = f"/meshcat/{prefix}/"
    shared = make_viz(puma560(), prefix="shared_" + prefix)

    def drawn():
        return sorted(c["path"] for c in server_commands(shared)
                      if c["type"] == "set_object" and c["path"].startswith(root))

    in_shared = RobotVisualizer(puma560(), prefix=prefix, scene=shared.vis)
    puma_objects = drawn()
    assert f"{root}links/link6/origin" in puma_objects
    RobotVisualizer(puma560(), prefix=prefix, scene=shared.vis)
    assert drawn() == puma_objects  # same picture, no duplicates
    assert set(in_shared.scene_transforms(np.zeros(6))) == set(
        again.scene_transforms(np.zeros(6)))
    RobotVisualizer(autorob_test_robot(), prefix=prefix, scene=shared.vis)
    now = drawn()
    assert f"{root}links/link6/origin" not in now  # the PUMA was deleted, not kept
    assert f"{root}links/link4/origin" in now
    assert not any("link0" in p or "link5" in p or "link6" in p for p in now)
    assert shared.vis.comm is not None  # drawing into a scene never closes it


def test_bad_constructor_arguments():
    with pytest.raises(KinlibError, match="Robot"):
        RobotVisualizer("puma")
    with pytest.raises(KinlibError, match="prefix"):
        RobotVisualizer(puma560(), prefix="/")
    with pytest.raises(KinlibError, match="link_radius"):
        RobotVisualizer(puma560(), link_radius=-1.0)
    with pytest.raises(KinlibError, match="color"):
        RobotVisualizer(puma560(), color="magenta")
    with pytest.raises(KinlibError, match="scene"):
        RobotVisualizer(puma560(), scene="a scene")
