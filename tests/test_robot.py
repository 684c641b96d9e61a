"""Robot trees and forward kinematics against closed forms, scipy and the Robotics Toolbox."""

import importlib.util
import os
import subprocess
import sys
import warnings

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from kinlib import DHRow, KinlibError, Robot, URDFError, load_urdf, planar_2r_fk
from kinlib.kinematics import _fk
from kinlib.models.tree import Joint, Link, Mimic, origin_from_xyz_rpy, xyz_rpy_from_origin
from kinlib.robots import autorob_test_robot, panda, planar_2r, puma560, three_dof_arm, ur5

ALL_MODELS = [planar_2r, three_dof_arm, puma560, ur5, panda, autorob_test_robot]


def hom(R=None, p=(0, 0, 0)):
    T = np.eye(4)
    T[:3, :3] = np.eye(3) if R is None else R
    T[:3, 3] = p
    return T


def rot(axis, angle):
    """Rotation about a (not necessarily unit) axis, by scipy's rotation vector."""
    u = np.asarray(axis, float) / np.linalg.norm(axis)
    return hom(Rotation.from_rotvec(u * angle).as_matrix())


def rz(t):
    return rot([0, 0, 1], t)


# -- closed forms ---------------------------------------------------------------------
def test_planar_2r_equals_eq_5_4():
    l1, l2 = 0.7, 0.4
    rng = np.random.default_rng(1)
    q = rng.uniform(-np.pi, np.pi, (200, 2))
    t1, t2 = q[:, 0], q[:, 1]
    x = l1 * np.cos(t1) + l2 * np.cos(t1 + t2)
    y = l1 * np.sin(t1) + l2 * np.sin(t1 + t2)
    for T in (planar_2r(l1, l2).fk(q), planar_2r_fk(t1, t2, l1, l2)):
        np.testing.assert_allclose(T[:, 0, 3], x, atol=1e-14)
        np.testing.assert_allclose(T[:, 1, 3], y, atol=1e-14)
        np.testing.assert_allclose(T[:, 0, 0], np.cos(t1 + t2), atol=1e-14)
        np.testing.assert_allclose(T[:, 1, 0], np.sin(t1 + t2), atol=1e-14)
        np.testing.assert_allclose(T[:, 2:, :], np.broadcast_to(np.eye(4)[2:], (200, 2, 4)),
                                   atol=0)


def test_planar_2r_fk_bad_lengths():
    with pytest.raises(KinlibError, match="positive"):
        planar_2r_fk(0.0, 0.0, -1.0, 1.0)


def test_autorob_test_robot_matrix_stack():
    """Seed 000: link2 = D(5,3,0) R(joint1), link3 = D(-2,5,0) Rz(1.57) R(joint2), ..."""
    robot = autorob_test_robot()
    rng = np.random.default_rng(2)
    for q in rng.uniform(-3, 3, (20, 3)):
        link2 = hom(p=(5, 3, 0)) @ rot([-0.9, 0.15, 0], q[0])
        link3 = hom(p=(-2, 5, 0)) @ rz(1.57) @ rot([-0.707, 0.707, 0], q[1])
        link4 = link3 @ hom(p=(5, 0, 0)) @ rz(-1.57) @ rot([0.707, -0.707, 0], q[2])
        poses = robot.link_poses(q)
        np.testing.assert_allclose(poses["link1"], np.eye(4), atol=0)
        for name, T in (("link2", link2), ("link3", link3), ("link4", link4)):
            np.testing.assert_allclose(poses[name], T, atol=1e-13)
            np.testing.assert_allclose(robot.fk(q, link=name), T, atol=1e-13)
    assert [j.name for j in robot.traversal()] == ["joint1", "joint2", "joint3"]


FETCH_LIKE = """<robot name="fetch_torso">
  <link name="base_link"/> <link name="torso_lift_link"/> <link name="shoulder_pan_link"/>
  <link name="finger_l"/> <link name="finger_r"/>
  <joint name="torso_lift_joint" type="prismatic">
    <origin rpy="-6.123E-17 0 0" xyz="-0.086875 0 0.37743" />
    <parent link="base_link" /> <child link="torso_lift_link" />
    <axis xyz="0 0 1" /> <limit effort="450.0" lower="0" upper="0.4" velocity="0.1" />
  </joint>
  <joint name="shoulder_pan_joint" type="revolute">
    <origin rpy="0 0 0" xyz="0.119525 0 0.34858" />
    <parent link="torso_lift_link" /> <child link="shoulder_pan_link" />
    <axis xyz="0 0 1" /> <dynamics damping="1.0" />
    <limit effort="33.82" lower="-1.6056" upper="1.6056" velocity="1.256" />
  </joint>
  <joint name="finger_l_joint" type="prismatic">
    <parent link="shoulder_pan_link" /> <child link="finger_l" /> <origin xyz="0.2 0 0"/>
    <axis xyz="0 1 0" /> <limit lower="0" upper="0.05" effort="1" velocity="1"/>
  </joint>
  <joint name="finger_r_joint" type="prismatic">
    <parent link="shoulder_pan_link" /> <child link="finger_r" /> <origin xyz="0.2 0 0"/>
    <axis xyz="0 -1 0" /> <limit lower="0" upper="0.05" effort="1" velocity="1"/>
    <mimic joint="finger_l_joint" multiplier="1.0" offset="0.01"/>
  </joint>
</robot>"""


def test_seed_prismatic_and_revolute_joints_with_mimic():
    robot = load_urdf(FETCH_LIKE)
    assert robot.joint_names == ["torso_lift_joint", "shoulder_pan_joint", "finger_l_joint"]
    np.testing.assert_allclose(robot.limits, [[0, 0.4], [-1.6056, 1.6056], [0, 0.05]])
    assert robot.tip is None
    lift, pan, grip = 0.25, 0.8, 0.03
    poses = robot.link_poses([lift, pan, grip])
    torso = hom(Rotation.from_euler("x", -6.123e-17).as_matrix(), (-0.086875, 0, 0.37743))
    torso = torso @ hom(p=(0, 0, lift))
    shoulder = torso @ hom(p=(0.119525, 0, 0.34858)) @ rz(pan)
    np.testing.assert_allclose(poses["torso_lift_link"], torso, atol=1e-15)
    np.testing.assert_allclose(poses["shoulder_pan_link"], shoulder, atol=1e-15)
    np.testing.assert_allclose(poses["finger_l"], shoulder @ hom(p=(0.2, grip, 0)), atol=1e-15)
    np.testing.assert_allclose(poses["finger_r"], shoulder @ hom(p=(0.2, -(grip + 0.01), 0)),
                               atol=1e-15)


def test_mimic_chain_and_cycle():
    links = [Link(n) for n in "abcd"]

    def j(name, p, c, mimic=None):
        return Joint(name, "continuous", p, c, axis=(0, 0, 1), mimic=mimic)

    robot = Robot("m", links, [j("j1", "a", "b"), j("j2", "b", "c", Mimic("j1", 2.0, 0.1)),
                               j("j3", "c", "d", Mimic("j2", -1.0, 0.5))])
    assert robot.joint_names == ["j1"]
    q1 = 0.3
    angles = [q1, 2 * q1 + 0.1, -(2 * q1 + 0.1) + 0.5]
    np.testing.assert_allclose(robot.fk([q1]), rz(sum(angles)), atol=1e-15)
    with pytest.raises(KinlibError, match="cycle"):
        Robot("m", links, [j("j1", "a", "b", Mimic("j3")), j("j2", "b", "c", Mimic("j1")),
                           j("j3", "c", "d", Mimic("j2"))])


FIXED_MIMIC = """<robot name="gripper">
  <link name="palm"/> <link name="finger"/> <link name="pad"/> <link name="tip"/>
  <joint name="grip" type="revolute"> <parent link="palm"/> <child link="finger"/>
    <origin xyz="0.1 0 0"/> <axis xyz="0 0 1"/> <limit lower="-1" upper="1"/> </joint>
  <joint name="pad_joint" type="fixed"> <parent link="finger"/> <child link="pad"/>
    <origin xyz="0 0.05 0" rpy="0.2 0 0"/> <axis xyz="1 0 0"/>
    <limit lower="-1.05" upper="0"/> <mimic joint="grip" multiplier="3" offset="0.5"/> </joint>
  <joint name="tip_joint" type="fixed"> <parent link="pad"/> <child link="tip"/>
    <origin xyz="0 0 0.02"/> <mimic joint="no_such_joint"/> </joint>
</robot>"""


def test_mimic_on_a_fixed_joint_is_ignored():
    """As urdfdom (talos_left_arm.urdf has one): a fixed joint moves nothing, so its
    ``<mimic>`` changes nothing, even one naming a joint that does not exist."""
    robot = load_urdf(FIXED_MIMIC)
    assert robot.joint_names == ["grip"]
    assert robot.joint("pad_joint").mimic is None and robot.joint("tip_joint").mimic is None
    q = 0.4
    finger = hom(p=(0.1, 0, 0)) @ rz(q)
    pad = finger @ hom(Rotation.from_euler("x", 0.2).as_matrix(), (0, 0.05, 0))
    poses = robot.link_poses([q])
    np.testing.assert_allclose(poses["finger"], finger, atol=1e-15)
    np.testing.assert_allclose(poses["pad"], pad, atol=1e-15)
    np.testing.assert_allclose(poses["tip"], pad @ hom(p=(0, 0, 0.02)), atol=1e-15)
    # the same text without the two mimics is the same robot
    plain = load_urdf(FIXED_MIMIC.replace('<mimic joint="grip" multiplier="3" offset="0.5"/>',
                                          "").replace('<mimic joint="no_such_joint"/>', ""))
    for name, T in plain.link_poses([q]).items():
        np.testing.assert_array_equal(poses[name], T)
    # built by hand, a fixed joint with a mimic is still a mistake worth a message
    with pytest.raises(KinlibError, match="a fixed joint cannot mimic"):
        Joint("j", "fixed", "a", "b", mimic=Mimic("k"))


# -- export: URDF text that any XML reader reads back -----------------------------------
AWKWARD = {  # what names and file names may hold: XML's special characters, quotes, Unicode
    "robot": 'R&D "lab" <arm>',
    "base": "base & <co>",
    "arm": "arm 'A' \"B\"",
    "hand": "händ_日本\ttab",
    "j1": "j1 & <j>",
    "j2": 'j2 "follows"',
    "mesh": "meshes/R&D.stl",
    "mirror": "package://ünï/meshes/<left> \"arm\".dae",
}


def awkward_robot():
    n = AWKWARD
    from kinlib.models.tree import Visual

    links = [Link(n["base"], (Visual("box", (0.1, 0.2, 0.3), rgba=(1, 0, 0, 1)),)),
             Link(n["arm"], (Visual("mesh", (0.001, 0.001, 0.001), filename=n["mesh"]),)),
             Link(n["hand"], (Visual("mesh", (1, -1, 1), filename=n["mirror"],
                                     origin=hom(rz(0.3)[:3, :3], (0, 0.1, 0))),))]
    joints = [Joint(n["j1"], "revolute", n["base"], n["arm"], origin=hom(p=(0.1 + 0.2, 0, 1 / 3)),
                    axis=(0, 1, 1), limits=(-0.1 - 0.2, 2 / 3)),
              Joint(n["j2"], "revolute", n["arm"], n["hand"], origin=rot([1, 2, 3], 0.7),
                    axis=(1, 0, 0), limits=(-4, 4), mimic=Mimic(n["j1"], -1.5, 0.25))]
    return Robot(n["robot"], links, joints)


def test_urdf_export_escapes_names_and_reads_back(tmp_path):
    import xml.etree.ElementTree as ET

    robot = awkward_robot()
    text = robot.to_urdf(tmp_path / "awkward.urdf")
    # well-formed XML whose attributes are the names, as written
    root = ET.fromstring(text.encode("utf-8"))
    assert root.get("name") == AWKWARD["robot"]
    assert [el.get("name") for el in root.findall("link")] == robot.link_names
    assert [el.get("name") for el in root.findall("joint")] == [AWKWARD["j1"], AWKWARD["j2"]]
    assert [el.get("filename") for el in root.iter("mesh")] == [AWKWARD["mesh"],
                                                                 AWKWARD["mirror"]]
    assert root.find("joint/mimic").get("joint") == AWKWARD["j1"]
    assert [el.get("scale") for el in root.iter("mesh")] == ["0.001 0.001 0.001", "1.0 -1.0 1.0"]
    # numbers as repr writes them: the same floats come back
    assert root.find("joint/origin").get("xyz") == f"{0.1 + 0.2!r} 0.0 {1 / 3!r}"
    assert root.find("joint/limit").get("lower") == repr(-0.1 - 0.2)
    for back in (load_urdf(text), load_urdf(tmp_path / "awkward.urdf")):
        assert back.name == robot.name and back.link_names == robot.link_names
        assert back.joint_names == robot.joint_names == [AWKWARD["j1"]]
        for a, b in zip(robot.joints, back.joints, strict=True):
            assert (a.name, a.type, a.parent, a.child, a.mimic, a.limits) == \
                (b.name, b.type, b.parent, b.child, b.mimic, b.limits)
            np.testing.assert_array_equal(a.axis, b.axis)
            np.testing.assert_array_equal(a.origin[:3, 3], b.origin[:3, 3])
            np.testing.assert_allclose(a.origin, b.origin, atol=1e-15)
        for a, b in zip(robot.links, back.links, strict=True):
            assert [(v.kind, v.size, v.filename, v.rgba) for v in a.visuals] == \
                [(v.kind, v.size, v.filename, v.rgba) for v in b.visuals]
            for va, vb in zip(a.visuals, b.visuals, strict=True):
                np.testing.assert_allclose(va.origin, vb.origin, atol=1e-15)
        qs = random_q(robot, 5, 7)
        ours, theirs = robot.link_poses(qs), back.link_poses(qs)
        for name in robot.link_names:
            np.testing.assert_allclose(theirs[name], ours[name], atol=1e-14)


def test_urdf_export_matches_a_second_xml_reader():
    """urdfdom (tinyxml2, through pinocchio) reads the same names and poses."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        import pinocchio as pin

    robot = awkward_robot()
    model = pin.buildModelFromXML(robot.to_urdf(), True)
    assert list(model.names[1:]) == [AWKWARD["j1"], AWKWARD["j2"]]
    data = model.createData()
    for q in random_q(robot, 3, 8):
        pin.framesForwardKinematics(model, data, np.array(q))
        for name, T in robot.link_poses(q).items():
            M = data.oMf[model.getFrameId(name, pin.BODY)].homogeneous
            np.testing.assert_allclose(M, T, atol=1e-14, err_msg=name)


@pytest.mark.parametrize("field, value, phrase", [
    ("link", "arm\x01", "link name 'arm\\x01' holds the character '\\x01'"),
    ("robot", "r\ud800", "robot name"),
    ("joint", "j\x0c", "joint name"),
    ("mesh", "meshes/a\x00.stl", "link 'a': mesh filename"),
    ("link", "   ", "link name '   ' is blank"),
])
def test_urdf_export_refuses_what_xml_cannot_hold(field, value, phrase):
    from kinlib.models.tree import Visual

    names = {"robot": "r", "link": "b", "joint": "j", "mesh": "m.stl"} | {field: value}
    links = [Link("a", (Visual("mesh", (1, 1, 1), filename=names["mesh"]),)),
             Link(names["link"])]
    robot = Robot(names["robot"], links,
                  [Joint(names["joint"], "continuous", "a", names["link"])])
    with pytest.raises(KinlibError, match="cannot export") as info:
        robot.to_urdf()
    assert phrase in str(info.value)


# -- peers: the Robotics Toolbox ------------------------------------------------------
def rtb():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        import roboticstoolbox

    return roboticstoolbox


def rtb_from_rows(robot, modified=False):
    """An RTB DHRobot typed from kinlib's DH rows (RTB does its own FK)."""
    r = rtb()
    cls = r.RevoluteMDH if modified else r.RevoluteDH
    links = [cls(d=row.d, a=row.a, alpha=row.alpha, offset=row.offset)
             for row in robot.dh_rows if row.joint == "revolute"]
    return r.DHRobot(links)


def random_q(robot, n, seed):
    lim = np.clip(robot.limits, -np.pi, np.pi)
    return np.random.default_rng(seed).uniform(lim[:, 0], lim[:, 1], (n, robot.dof))


@pytest.mark.parametrize("model", [puma560, ur5])
def test_standard_dh_arms_against_robotics_toolbox(model):
    robot = model()
    peer = rtb_from_rows(robot)
    q = random_q(robot, 50, 3)
    ours = robot.fk(q)
    for i in range(len(q)):
        np.testing.assert_allclose(ours[i], peer.fkine(q[i]).A, atol=1e-12)


def test_puma_table_in_metres_matches_seed():
    """The seed's table typed once more here, in millimetres and degrees."""
    robot = puma560()
    seed = [(-90, 0, 0), (0, 431.8, 149.09), (90, -20.32, 0), (-90, 0, 433.07), (90, 0, 0),
            (0, 0, 56.25)]
    ranges = [(-160, 160), (-225, 45), (-45, 225), (-110, 170), (-100, 100), (-266, 266)]
    for row, (alpha, a, d) in zip(robot.dh_rows, seed, strict=True):
        assert (np.rad2deg(row.alpha), row.a * 1000, row.d * 1000) == pytest.approx((alpha, a, d))
    np.testing.assert_allclose(np.rad2deg(robot.limits), ranges)
    np.testing.assert_allclose(np.rad2deg(robot.poses["table"]), [90, 0, 90, 0, 0, 0])


def test_panda_against_robotics_toolbox_model():
    """RTB's own Panda model (its own parameter entry, flange inside row 7, hand as tool)."""
    peer = rtb().models.DH.Panda()
    robot = panda()
    np.testing.assert_allclose(robot.limits, peer.qlim.T, atol=1e-4)
    q = random_q(robot, 50, 4)
    ours = robot.fk(q)
    tool_inv = np.linalg.inv(peer.tool.A)
    for i in range(len(q)):
        np.testing.assert_allclose(ours[i], peer.fkine(q[i]).A @ tool_inv, atol=1e-12)


@pytest.mark.parametrize("model", ALL_MODELS)
def test_models_are_data_with_poses_and_reference(model):
    robot = model()
    assert robot.reference and len(robot.reference) > 20
    assert "zero" in robot.poses
    for name, q in robot.poses.items():
        assert q.shape == (robot.dof,), name
    poses = robot.link_poses(robot.poses["zero"])
    for T in poses.values():
        np.testing.assert_allclose(T[:3, :3] @ T[:3, :3].T, np.eye(3), atol=1e-12)


# -- batching and the two FK paths -----------------------------------------------------
@pytest.mark.parametrize("model", ALL_MODELS)
def test_batched_equals_looped(model):
    robot = model()
    q = random_q(robot, 300, 5).reshape(3, 100, robot.dof)
    batched = robot.link_poses(q)
    for name in robot.link_names:
        assert batched[name].shape == (3, 100, 4, 4)
    for idx in [(0, 0), (1, 57), (2, 99)]:
        single = robot.link_poses(q[idx])
        for name in robot.link_names:
            np.testing.assert_allclose(batched[name][idx], single[name], atol=1e-14)


@pytest.mark.parametrize("model", ALL_MODELS)
def test_compiled_kernel_equals_numpy(model):
    if _fk._compiled() is None:
        pytest.skip("numba is not installed or KINLIB_NUMBA=0")
    robot = model()
    q = random_q(robot, 64, 6)
    a = _fk.run(robot._table, q, robot._all, compiled=True)
    b = _fk.run(robot._table, q, robot._all, compiled=False)
    np.testing.assert_allclose(a, b, atol=1e-14)


def test_chain_kernel_all_axis_cases():
    """fk's chain form (axis rotated onto z) against the tree's numpy path, every axis case,
    serial and parallel batches."""
    axes = [(0, 0, 1), (0, 0, -1), (1, 0, 0), (0, -1, 0), (0.3, -0.2, 0.9), (1e-9, 0, -1),
            (-0.5, 0.5, -0.7)]
    rng = np.random.default_rng(8)
    links, joints = [Link("base")], []
    for i, u in enumerate(axes * 2):
        links.append(Link(f"l{i}"))
        origin = hom(Rotation.random(random_state=i).as_matrix(), rng.normal(size=3))
        kind = ["revolute", "prismatic", "fixed", "continuous"][i % 4]
        joints.append(Joint(f"j{i}", kind, links[-2].name, f"l{i}", origin=origin, axis=u,
                            limits=None if kind in ("fixed", "continuous") else (-2, 2)))
    robot = Robot("axes", links, joints)
    q = rng.uniform(-2, 2, (_fk.PARALLEL_MIN + 3, robot.dof))
    reference = _fk.run(robot._table, q, robot._all, compiled=False)
    for link in ("l3", "l6", "l13"):
        expected = reference[:, robot._frame[link]]
        np.testing.assert_allclose(robot.fk(q, link=link), expected, atol=1e-12)
        np.testing.assert_allclose(robot.fk(q[:7], link=link), expected[:7], atol=1e-12)
    np.testing.assert_allclose(robot.fk(q[0], link="base"), np.eye(4), atol=0)


def test_compiled_sincos_matches_libm():
    if _fk._compiled() is None:
        pytest.skip("numba is not installed or KINLIB_NUMBA=0")
    sincos = _fk._compiled().sincos
    x = np.concatenate([np.linspace(-20, 20, 40_001), np.pi / 4 * np.arange(-40, 41),
                        [0.0, -0.0, 1e-300, 5e-324, 0.855, 2.426, 99_999.9, -1e5, 3e5, 1e300]])
    got = np.array([sincos(v) for v in x])
    np.testing.assert_allclose(got[:, 0], np.sin(x), rtol=0, atol=2.3e-16)
    np.testing.assert_allclose(got[:, 1], np.cos(x), rtol=0, atol=2.3e-16)


def test_numba_is_optional_and_lazy():
    """Building robots never imports numba; the first FK starts preparing its kernel (in
    the background thread, which imports numba) unless disabled."""
    code = ("import sys, threading, numpy as np, kinlib.robots as r; p = r.puma560(); "
            "assert 'numba' not in sys.modules; T = p.fk([0.1] * 6); "
            "[t.join() for t in threading.enumerate() if t.name == 'kinlib-kernels']; "
            "print('numba' in sys.modules, np.round(T[0, 3], 12))")
    results = {}
    for flag in ("0", "1"):
        env = dict(os.environ, KINLIB_NUMBA=flag)
        out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                             env=env, check=False)
        assert out.returncode == 0, out.stderr
        results[flag] = out.stdout.split()
    assert results["0"][0] == "False"
    has_numba = importlib.util.find_spec("numba") is not None
    assert results["1"][0] == str(has_numba)
    assert results["0"][1] == results["1"][1]


def test_deep_chain_has_no_recursion_limit():
    n = 3000
    links = [Link(f"l{i}") for i in range(n + 1)]
    joints = [Joint(f"j{i}", "prismatic", f"l{i}", f"l{i + 1}", axis=(1, 0, 0),
                    limits=(-1, 1)) for i in range(n)]
    robot = Robot("long", links, joints)
    T = robot.fk(np.full(n, 0.001))
    assert T[0, 3] == pytest.approx(3.0)


# -- bad input --------------------------------------------------------------------------
def test_wrong_q_is_a_clear_error():
    robot = puma560()
    with pytest.raises(KinlibError, match=r"expected 6 joint values.*puma560.*got shape \(5,\)"):
        robot.fk([0.0] * 5)
    with pytest.raises(KinlibError, match="shape"):
        robot.fk(0.0)
    with pytest.raises(KinlibError, match="NaN"):
        robot.fk([0, 0, np.nan, 0, 0, 0])
    with pytest.raises(KinlibError, match="real numbers"):
        robot.fk(["a"] * 6)
    with pytest.raises(KinlibError, match="no link 'hand'"):
        robot.fk(np.zeros(6), link="hand")
    with pytest.raises(KinlibError, match="unknown joints"):
        robot.fk({"elbow": 0.3})
    with pytest.raises(KinlibError, match="several leaf links"):
        autorob_test_robot().fk([0, 0, 0])


def test_q_as_dict():
    robot = puma560()
    np.testing.assert_allclose(robot.fk({"joint2": 0.3}), robot.fk([0, 0.3, 0, 0, 0, 0]))


def test_check_limits_names_joint_and_batch_index():
    robot = puma560()
    q = np.zeros((4, 6))
    q[2, 1] = np.deg2rad(50)  # joint2 range is [-225°, 45°]
    robot.fk(q)  # no check by default
    with pytest.raises(KinlibError) as exc:
        robot.fk(q, check_limits=True)
    msg = str(exc.value)
    assert "q[2]" in msg and "'joint2'" in msg and "0.872665" in msg and "0.785398" in msg
    with pytest.raises(KinlibError, match="joint2"):
        robot.link_poses(q, check_limits=True)
    robot.check_limits(np.zeros(6))


def test_tree_errors():
    L = [Link("a"), Link("b")]
    with pytest.raises(KinlibError, match="duplicate link"):
        Robot("r", [Link("a"), Link("a")], [])
    with pytest.raises(KinlibError, match="several root links"):
        Robot("r", L, [])
    with pytest.raises(KinlibError, match="expected Link"):
        Robot("r", ["a"], [])
    with pytest.raises(KinlibError, match="parent link 'x' does not exist"):
        Robot("r", L, [Joint("j", "fixed", "x", "b")])
    with pytest.raises(KinlibError, match="no root link"):
        Robot("r", L, [Joint("j", "fixed", "a", "b"), Joint("k", "fixed", "b", "a")])
    with pytest.raises(KinlibError, match="unsupported joint type 'floating'"):
        Joint("j", "floating", "a", "b")
    with pytest.raises(KinlibError, match="axis"):
        Joint("j", "revolute", "a", "b", axis=(0, 0, 0))
    with pytest.raises(KinlibError, match="no joint 'q'"):
        Robot("r", L, [Joint("j", "fixed", "a", "b")]).joint("q")


def test_tree_errors_name_the_element_and_which_one():
    """The tree checks raise a TreeError that says which element is at fault (kind, name,
    which of the elements of that name); load_urdf turns it into the line of that element."""
    from kinlib.errors import TreeError

    cases = [
        (([Link("a"), Link("b"), Link("a")], []), ("link", "a"), 1),
        (([Link("a"), Link("b"), Link("c")], [Joint("j", "fixed", "a", "b"),
                                              Joint("j", "fixed", "a", "c")]), ("joint", "j"), 1),
        (([Link("a"), Link("b")], [Joint("j", "fixed", "a", "x")]), ("joint", "j"), 0),
        (([Link("a"), Link("b"), Link("c")], [Joint("j", "fixed", "a", "b")]), ("link", "c"), 0),
        (([], []), None, 0),
    ]
    for (links, joints), element, nth in cases:
        with pytest.raises(TreeError) as info:
            Robot("r", links, joints)
        assert (info.value.element, info.value.nth) == (element, nth), info.value
        assert isinstance(info.value, KinlibError)
    urdf = """<robot name="r">
  <link name="a"/>
  <link name="b"/>
  <link name="c"/>
  <joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint>
  <joint name="j" type="fixed"><parent link="a"/><child link="c"/></joint>
</robot>"""
    with pytest.raises(URDFError, match=r"^<urdf string>:6: duplicate joint name 'j'$"):
        load_urdf(urdf)
    with pytest.raises(URDFError, match=r"^<urdf string>:4: duplicate link name 'b'$"):
        load_urdf(urdf.replace('name="c"', 'name="b"', 1))


def test_the_dh_table_is_kept_by_the_constructor():
    rows = [DHRow(a=0.4, alpha=np.pi / 2, d=0.1), DHRow(a=0.3, alpha=0.0, joint="prismatic")]
    arm = Robot.from_dh(rows, "modified", name="arm")
    assert arm.dh_convention == "modified" and arm.dh_rows == tuple(rows)
    plain = Robot("p", arm.links, arm.joints)
    assert plain.dh_rows is None and plain.dh_convention is None
    np.testing.assert_allclose(plain.fk([0.2, 0.1]), arm.fk([0.2, 0.1]), atol=0)
    with pytest.raises(AttributeError):
        arm.dh_rows[0].a = 1.0  # the rows are frozen data, like the links and joints


def test_public_helpers_that_ik_and_the_viewer_use():
    arm = Robot.from_dh([DHRow(a=1.0, alpha=0.0), DHRow(a=0.5, alpha=0.0)])
    assert arm.resolve_link() == "link2" and arm.resolve_link("link1") == "link1"
    with pytest.raises(KinlibError, match="has no link 'nope'"):
        arm.resolve_link("nope")
    assert arm.check_q({"joint2": 0.5}).tolist() == [0.0, 0.5]
    with pytest.raises(KinlibError, match="expected 2 joint values"):
        arm.check_q([1.0, 2.0, 3.0])
    assert arm.chain_table() is arm.chain_table("link2")  # built once per link


def test_origins_are_checked_unless_kinlib_built_them():
    """URDF origins are built from checked numbers and taken as they are; an origin given
    by hand is still checked, and what a joint stores is a plain read-only array, so a
    product with it is never taken unchecked."""
    bad = np.diag([2.0, 1.0, 1.0, 1.0])
    with pytest.raises(KinlibError, match="joint 'j' origin"):
        Joint("j", "continuous", "a", "b", origin=bad)
    with pytest.raises(KinlibError, match="joint 'j' post"):
        Joint("j", "continuous", "a", "b", post=bad)
    robot = load_urdf("""<robot name="r"><link name="a"/><link name="b"/>
        <joint name="j" type="continuous"><parent link="a"/><child link="b"/>
        <origin xyz="1 2 3" rpy="0.1 0.2 0.3"/></joint></robot>""")
    origin = robot.joint("j").origin
    assert type(origin) is np.ndarray and not origin.flags.writeable
    assert type(origin @ bad) is np.ndarray
    with pytest.raises(KinlibError, match="joint 'j' origin"):
        Joint("j", "continuous", "a", "b", origin=origin @ bad)
    expected = np.eye(4)
    expected[:3, :3] = Rotation.from_euler("xyz", [0.1, 0.2, 0.3]).as_matrix()  # extrinsic
    expected[:3, 3] = [1, 2, 3]
    assert np.allclose(origin, expected, atol=1e-15)


def test_urdf_origin_is_scipys_extrinsic_xyz_and_round_trips():
    """A URDF ``<origin rpy>`` is roll about x, then pitch about the fixed y, then yaw about
    the fixed z: scipy's extrinsic "xyz"; back through xyz_rpy_from_origin away from lock."""
    rng = np.random.default_rng(7)
    for _ in range(200):
        xyz = rng.normal(size=3)
        rpy = rng.uniform(-np.pi, np.pi, 3) * [1, 0.49, 1]
        T = origin_from_xyz_rpy(xyz, rpy)
        np.testing.assert_allclose(T[:3, :3], Rotation.from_euler("xyz", rpy).as_matrix(),
                                   atol=1e-15)
        assert T[:3, 3].tolist() == xyz.tolist() and T[3].tolist() == [0, 0, 0, 1]
        back_xyz, back_rpy = xyz_rpy_from_origin(T)
        np.testing.assert_allclose(back_rpy, rpy, atol=1e-12)
        np.testing.assert_array_equal(back_xyz, xyz)
    with pytest.raises(KinlibError, match="rpy"):
        origin_from_xyz_rpy([0, 0, 0], [0, float("nan"), 0])
    with pytest.raises(KinlibError, match="xyz"):
        origin_from_xyz_rpy([0, 0], [0, 0, 0])
