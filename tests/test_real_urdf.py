"""Real URDF files and kinlib's own models, loaded by kinlib and by pinocchio (urdfdom, an
independent parser, FK and Jacobian), must give the same pose and the same geometric
Jacobian for every link.

Two collections of real files: the Robotics Toolbox's data package (rtbdata) and every
URDF of example-robot-data (69 robots: quadrupeds, humanoids with mirrored meshes and
``<mimic>`` grippers, hands, arms). kinlib's Jacobian has rows ``[v; ω]`` in the base frame
for the link's origin, which is pinocchio's ``LOCAL_WORLD_ALIGNED`` frame Jacobian.
"""

import warnings
import xml.etree.ElementTree as ET
from importlib import metadata, resources

import numpy as np
import pytest

from kinlib import URDFError, load_urdf
from kinlib.robots import autorob_test_robot, panda, planar_2r, puma560, three_dof_arm, ur5

with warnings.catch_warnings():
    warnings.simplefilter("ignore")
    import pinocchio as pin

DATA = resources.files("rtbdata")
REAL = sorted(p for p in (DATA / "xacro").rglob("*.urdf"))

# example-robot-data is a cmeel package: its files live under the cmeel prefix
ERD_ROOT = metadata.distribution("example-robot-data").locate_file(
    "cmeel.prefix/share/example-robot-data/robots")
ERD = sorted(ERD_ROOT.rglob("*.urdf"))
# two files of the collection are not robots, and urdfdom or pinocchio refuse them too
ERD_REFUSED = {
    # <robot> without a name or a link (urdfdom: "No name given for the robot")
    "ur3.urdf": "ur3.urdf:6: <robot>: missing or empty attribute name",
    # a typo: its fingers mimic "index_q1", which is "Left_index_q1"; pinocchio's mimic
    # mode refuses it ("The parent joint of the mimic joint is not in the kinematic tree")
    "alex_psyonic_hands.urdf": "joint 'Left_index_q2' mimics 'index_q1', which does not exist",
}
ERD_LOADED = [p for p in ERD if p.name not in ERD_REFUSED]


def pin_model(xml: str):
    """``(model, mimic)``: pinocchio's model with its own mimic joints when it can build
    them (they then take no q of their own), else every joint independent."""
    try:
        return pin.buildModelFromXML(xml, True), True
    except (RuntimeError, ValueError):  # mimic of a joint later in the tree
        return pin.buildModelFromXML(xml), False


def drivers(xml: str):
    """For every movable joint of the URDF: (the joint whose value moves it, multiplier,
    offset), following its ``<mimic>`` elements (read here with ElementTree, not kinlib)."""
    joints = [j for j in ET.fromstring(xml).findall("joint") if j.get("type") != "fixed"]
    mimic = {j.get("name"): j.find("mimic") for j in joints}
    out = {}

    def follow(name):
        if name not in out:
            m = mimic[name]
            if m is None:
                out[name] = (name, 1.0, 0.0)
            else:
                src, a, b = follow(m.get("joint"))
                k, c = float(m.get("multiplier", 1)), float(m.get("offset", 0))
                out[name] = (src, k * a, k * b + c)
        return out[name]

    for name in mimic:
        follow(name)
    return out


def pin_q(model, robot, q, drive):
    """Pinocchio's configuration for kinlib's q (continuous joints: cos, sin); with
    ``drive`` (independent mimic joints) every joint gets the value its mimic rule says."""
    x = pin.neutral(model)
    named = dict(zip(robot.joint_names, q, strict=True))
    values = named if drive is None else {n: a * named[s] + b for n, (s, a, b) in drive.items()}
    for name, value in values.items():
        jm = model.joints[model.getJointId(name)]
        if jm.nq == 2:  # unbounded revolute in pinocchio
            x[jm.idx_q], x[jm.idx_q + 1] = np.cos(value), np.sin(value)
        else:
            x[jm.idx_q] = value
    return x


def pin_jacobian_columns(model, robot, drive):
    """(dof, nv) matrix C with kinlib's J = pinocchio's J @ C.T: column k of kinlib's J
    sums pinocchio's columns of the joints that q[k] moves, times their multipliers."""
    C = np.zeros((robot.dof, model.nv))
    rules = drive or {n: (n, 1.0, 0.0) for n in robot.joint_names}
    index = {n: k for k, n in enumerate(robot.joint_names)}
    for name, (src, a, _) in rules.items():
        C[index[src], model.joints[model.getJointId(name)].idx_v] += a
    return C


def compare(robot, xml, seed, n=3):
    """Poses and Jacobians of every link of ``robot`` at ``n`` seeded configurations
    against pinocchio's model of ``xml``; returns the largest difference."""
    model, mimic = pin_model(xml)
    movable = {jt.name for jt in robot.joints if jt.movable}
    assert set(model.names[1:]) == movable
    if mimic:  # pinocchio decides which joints take a q of their own
        assert set(robot.joint_names) == {nm for nm, jm in zip(model.names[1:],
                                                               model.joints[1:], strict=True)
                                          if jm.nv > 0}
    drive = None if mimic else drivers(xml)
    C = pin_jacobian_columns(model, robot, drive)
    data = model.createData()
    lim = np.clip(robot.limits, -np.pi, np.pi)
    qs = np.random.default_rng(seed).uniform(lim[:, 0], lim[:, 1], (n, robot.dof))
    poses = robot.link_poses(qs)
    jacobians = {name: robot.jacobian(qs, link=name) for name in robot.link_names}
    worst = 0.0
    for i, q in enumerate(qs):
        pin.computeJointJacobians(model, data, pin_q(model, robot, q, drive))
        pin.updateFramePlacements(model, data)
        for name in robot.link_names:
            fid = model.getFrameId(name, pin.BODY)
            T = data.oMf[fid].homogeneous
            np.testing.assert_allclose(poses[name][i], T, atol=1e-12, err_msg=name)
            worst = max(worst, np.abs(poses[name][i] - T).max())
            assert jacobians[name].shape == (n, 6, robot.dof)
            if robot.dof == 0:
                continue  # (pinocchio's frame Jacobian crashes on a model without joints)
            J = pin.getFrameJacobian(model, data, fid, pin.LOCAL_WORLD_ALIGNED) @ C.T
            np.testing.assert_allclose(jacobians[name][i], J, atol=1e-12, err_msg=name)
            worst = max(worst, np.abs(jacobians[name][i] - J).max())
    return worst


def test_real_files_are_found():
    names = {p.name for p in REAL}
    assert {"puma560_robot.urdf", "lbr_iiwa_14_r820.urdf", "kr210l150.urdf"} <= names
    assert len(REAL) >= 6
    names = {p.name for p in ERD}
    assert len(ERD) >= 69 and set(ERD_REFUSED) <= names
    assert {"talos_full_v2.urdf", "talos_left_arm.urdf", "centauro.urdf", "tiago_dual.urdf",
            "romeo.urdf", "pr2.urdf", "panda.urdf"} <= names


@pytest.mark.parametrize("path", REAL, ids=lambda p: p.name)
def test_real_urdf_matches_pinocchio(path):
    robot = load_urdf(path)
    model = pin.buildModelFromXML(path.read_text())
    assert robot.dof == model.njoints - 1
    assert set(robot.joint_names) == set(model.names[1:])
    compare(robot, path.read_text(), seed=len(path.name), n=20)
    bounded = np.isfinite(robot.limits).all(axis=1)
    for name, (lo, hi) in zip(robot.joint_names, robot.limits, strict=True):
        jm = model.joints[model.getJointId(name)]
        if jm.nq == 1 and np.isfinite(lo):
            assert model.lowerPositionLimit[jm.idx_q] == pytest.approx(lo)
            assert model.upperPositionLimit[jm.idx_q] == pytest.approx(hi)
    assert bounded.any()


@pytest.mark.parametrize("path", ERD_LOADED, ids=lambda p: f"{p.parts[-3]}/{p.name}")
def test_example_robot_data_matches_pinocchio(path):
    robot = load_urdf(path)
    assert compare(robot, path.read_text(), seed=len(path.name)) < 1e-12


@pytest.mark.parametrize("name", ERD_REFUSED)
def test_example_robot_data_that_is_no_robot_is_refused(name):
    (path,) = [p for p in ERD if p.name == name]
    with pytest.raises(URDFError, match=ERD_REFUSED[name]):
        load_urdf(path)


def test_what_the_collection_exercises():
    """The files hold what the issue was about, and kinlib keeps it: mirrored meshes
    (negative scale), mimic joints kinlib follows, a mimic on a fixed joint it ignores."""
    talos = load_urdf(ERD_ROOT / "talos_data/robots/talos_full_v2.urdf")
    mirrored = [v for lk in talos.links for v in lk.visuals if min(v.size) < 0]
    assert mirrored and all(v.kind == "mesh" for v in mirrored)
    assert (1.0, -1.0, 1.0) in {v.size for v in mirrored}
    assert any(jt.mimic is not None for jt in talos.joints)  # its grippers
    arm = load_urdf(ERD_ROOT / "talos_data/robots/talos_left_arm.urdf")
    jt = arm.joint("gripper_left_inner_double_joint")
    assert jt.type == "fixed" and jt.mimic is None
    assert "gripper_left_inner_double_joint" not in arm.joint_names
    for name in ("panda_description/urdf/panda.urdf", "pr2_description/urdf/pr2.urdf",
                 "romeo_description/urdf/romeo.urdf"):
        robot = load_urdf(ERD_ROOT / name)
        movable = [jt for jt in robot.joints if jt.movable]
        assert robot.dof < len(movable), name  # some joints follow others


@pytest.mark.parametrize("model_fn", [planar_2r, three_dof_arm, puma560, ur5, panda,
                                      autorob_test_robot])
def test_exported_models_match_pinocchio(model_fn):
    robot = model_fn()
    compare(robot, robot.to_urdf(), seed=3, n=20)


def test_not_xml_is_refused():
    with pytest.raises(URDFError, match=r"test\.urdf: line 1: XML syntax error"):
        load_urdf(DATA / "data" / "test.urdf")
