"""Robot trees and forward kinematics against closed forms, scipy and the Robotics Toolbox."""

import importlib.util
import os
import subprocess
import sys
import warnings

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from kinlib import KinlibError, Robot, load_urdf, planar_2r_fk
from kinlib.kinematics import _fk
from kinlib.models.tree import Joint, Link, Mimic
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
    """Building robots never imports numba; FK imports it on first use unless disabled."""
    code = ("import sys, numpy as np, kinlib.robots as r; p = r.puma560(); "
            "assert 'numba' not in sys.modules; T = p.fk([0.1] * 6); "
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
