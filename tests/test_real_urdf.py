"""Real URDF files (shipped with the Robotics Toolbox's data package) and kinlib's own
models, loaded by kinlib and by pinocchio (urdfdom, an independent parser and FK), must
give the same pose for every link."""

import warnings
from importlib import resources

import numpy as np
import pytest

from kinlib import URDFError, load_urdf
from kinlib.robots import autorob_test_robot, panda, planar_2r, puma560, three_dof_arm, ur5

with warnings.catch_warnings():
    warnings.simplefilter("ignore")
    import pinocchio as pin

DATA = resources.files("rtbdata")
REAL = sorted(p for p in (DATA / "xacro").rglob("*.urdf"))


def pin_link_poses(model, data, robot, q):
    """Pinocchio's pose of each kinlib link for kinlib's q (continuous joints: cos, sin)."""
    x = pin.neutral(model)
    for name, value in zip(robot.joint_names, q, strict=True):
        jm = model.joints[model.getJointId(name)]
        if jm.nq == 2:  # unbounded revolute in pinocchio
            x[jm.idx_q], x[jm.idx_q + 1] = np.cos(value), np.sin(value)
        else:
            x[jm.idx_q] = value
    pin.framesForwardKinematics(model, data, x)
    return {name: data.oMf[model.getFrameId(name)].homogeneous for name in robot.link_names}


def compare(robot, model, seed):
    data = model.createData()
    lim = np.clip(robot.limits, -np.pi, np.pi)
    qs = np.random.default_rng(seed).uniform(lim[:, 0], lim[:, 1], (20, robot.dof))
    ours = robot.link_poses(qs)
    for i, q in enumerate(qs):
        theirs = pin_link_poses(model, data, robot, q)
        for name in robot.link_names:
            np.testing.assert_allclose(ours[name][i], theirs[name], atol=1e-12, err_msg=name)


def test_real_files_are_found():
    names = {p.name for p in REAL}
    assert {"puma560_robot.urdf", "lbr_iiwa_14_r820.urdf", "kr210l150.urdf"} <= names
    assert len(REAL) >= 6


@pytest.mark.parametrize("path", REAL, ids=lambda p: p.name)
def test_real_urdf_matches_pinocchio(path):
    robot = load_urdf(path)
    model = pin.buildModelFromXML(path.read_text())
    assert robot.dof == model.njoints - 1
    assert set(robot.joint_names) == set(model.names[1:])
    compare(robot, model, seed=len(path.name))
    bounded = np.isfinite(robot.limits).all(axis=1)
    for name, (lo, hi) in zip(robot.joint_names, robot.limits, strict=True):
        jm = model.joints[model.getJointId(name)]
        if jm.nq == 1 and np.isfinite(lo):
            assert model.lowerPositionLimit[jm.idx_q] == pytest.approx(lo)
            assert model.upperPositionLimit[jm.idx_q] == pytest.approx(hi)
    assert bounded.any()


@pytest.mark.parametrize("model_fn", [planar_2r, three_dof_arm, puma560, ur5, panda,
                                      autorob_test_robot])
def test_exported_models_match_pinocchio(model_fn):
    robot = model_fn()
    compare(robot, pin.buildModelFromXML(robot.to_urdf()), seed=3)


def test_not_xml_is_refused():
    with pytest.raises(URDFError, match=r"test\.urdf: line 1: XML syntax error"):
        load_urdf(DATA / "data" / "test.urdf")
