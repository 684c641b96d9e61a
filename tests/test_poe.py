"""Product of exponentials: the screw axes read off any Robot (DH, modified DH, URDF, with
prismatic joints and branches) give robot.fk's poses; the space and body Jacobians agree
with the Modern Robotics library (screw axes reordered to its [ω; v]), with finite
differences of the pose, and with robot.jacobian through their closed-form relations."""

from importlib import resources

import modern_robotics as mr
import numpy as np
import pytest

import kinlib as kl
from kinlib.grade.assignments.jacobian_ik import prismatic_robots
from kinlib.robots import autorob_test_robot, panda, planar_2r, puma560, three_dof_arm, ur5

REAL = sorted((resources.files("rtbdata") / "xacro").rglob("*.urdf"))
MODELS = [planar_2r(1.0, 0.6), three_dof_arm(), puma560(), ur5(), panda(), *prismatic_robots()]


def mr_order(S):
    return np.concatenate([S[3:], S[:3]])


def random_q(robot, rng, n):
    lim = np.clip(robot.limits, -np.pi, np.pi)
    return rng.uniform(lim[:, 0], lim[:, 1], (n, robot.dof))


def check_robot(robot, link=None, n=8, seed=0):
    rng = np.random.default_rng(seed)
    S, M = kl.screw_axes(robot, link)
    B, M_b = kl.screw_axes(robot, link, frame="body")
    np.testing.assert_array_equal(M, M_b)
    np.testing.assert_allclose(M, robot.fk(np.zeros(robot.dof), link), atol=1e-15)
    qs = random_q(robot, rng, n)
    T = robot.fk(qs, link)
    np.testing.assert_allclose(kl.poe_fk(M, S, qs), T, atol=1e-12)
    np.testing.assert_allclose(kl.poe_fk(M, B, qs, frame="body"), T, atol=1e-12)
    Js, Jb = kl.space_jacobian(S, qs), kl.body_jacobian(B, qs)
    J = robot.jacobian(qs, link)
    p, R = T[:, :3, 3], T[:, :3, :3]
    # J = [[I, −[p]], [0, I]] J_s = diag(R, R) J_b
    np.testing.assert_allclose(J[:, :3], Js[:, :3] - kl.skew(p) @ Js[:, 3:], atol=1e-12)
    np.testing.assert_allclose(J[:, 3:], Js[:, 3:], atol=1e-12)
    np.testing.assert_allclose(J[:, :3], R @ Jb[:, :3], atol=1e-12)
    np.testing.assert_allclose(J[:, 3:], R @ Jb[:, 3:], atol=1e-12)
    for q, Ti, Jsi, Jbi in zip(qs[:3], T, Js, Jb, strict=False):
        np.testing.assert_allclose(kl.poe_fk(M, S, q), mr.FKinSpace(M, mr_order(S), q),
                                   atol=1e-12)
        np.testing.assert_allclose(kl.poe_fk(M, B, q, frame="body"),
                                   mr.FKinBody(M, mr_order(B), q), atol=1e-12)
        np.testing.assert_allclose(mr_order(Jsi), mr.JacobianSpace(mr_order(S), q), atol=1e-12)
        np.testing.assert_allclose(mr_order(Jbi), mr.JacobianBody(mr_order(B), q), atol=1e-12)
        np.testing.assert_allclose(Jbi, kl.adjoint(kl.transform_inverse(Ti)) @ Jsi, atol=1e-12)
    return S, B


@pytest.mark.parametrize("robot", MODELS, ids=lambda r: r.name)
def test_poe_of_kinlibs_models(robot):
    check_robot(robot)


@pytest.mark.parametrize("path", REAL, ids=lambda p: p.name)
def test_poe_of_real_urdf_files(path):
    robot = kl.load_urdf(path)
    q = np.full(robot.dof, 0.3)  # the link moved by the most joints (the flange or tool)
    link = max(robot.link_names, key=lambda k: np.count_nonzero(robot.jacobian(q, k).any(0)))
    check_robot(robot, link, n=4)


def test_a_branched_tree_needs_the_link_and_zeroes_other_branches():
    robot = autorob_test_robot()
    with pytest.raises(kl.KinlibError, match="link="):
        kl.screw_axes(robot)
    for link in robot.link_names:
        S, _ = check_robot(robot, link, n=3)
        on_path = np.any(robot.jacobian(np.full(robot.dof, 0.3), link) != 0, axis=0)
        assert not S[:, ~on_path].any()


def test_screw_axes_of_the_puma_by_hand():
    """Joint 1 turns about the base z axis through the origin: S_1 = [0; z]; joint 2's axis
    (DH z_1) is horizontal: ω_2 ⟂ z and S_2 = [−ω_2 × o_1; ω_2] with o_1 DH frame 1's origin."""
    robot = puma560()
    S, _ = kl.screw_axes(robot)
    np.testing.assert_allclose(S[:, 0], [0, 0, 0, 0, 0, 1], atol=1e-15)
    T1 = robot.fk(np.zeros(6), link="link1")
    w, o = T1[:3, 2], T1[:3, 3]
    np.testing.assert_allclose(S[:, 1], np.concatenate([-np.cross(w, o), w]), atol=1e-15)
    assert abs(S[5, 1]) < 1e-15


def test_jacobians_are_finite_differences_of_the_pose():
    robot, rng, h = ur5(), np.random.default_rng(2), 1e-6
    S, M = kl.screw_axes(robot)
    B, _ = kl.screw_axes(robot, frame="body")
    q, qdot = random_q(robot, rng, 1)[0], rng.normal(size=robot.dof)
    T = kl.poe_fk(M, S, q)
    Tdot = (kl.poe_fk(M, S, q + h * qdot) - kl.poe_fk(M, S, q - h * qdot)) / (2 * h)
    spatial = kl.vee_se3(Tdot @ kl.transform_inverse(T), tol=1e-6)
    body = kl.vee_se3(kl.transform_inverse(T) @ Tdot, tol=1e-6)
    np.testing.assert_allclose(spatial, kl.space_jacobian(S, q) @ qdot, atol=1e-8)
    np.testing.assert_allclose(body, kl.body_jacobian(B, q) @ qdot, atol=1e-8)


def test_a_mimic_joint_on_the_chain_is_an_error():
    xml = """<robot name="m"><link name="a"/><link name="b"/><link name="c"/>
      <joint name="j1" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>
        <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
      <joint name="j2" type="revolute"><parent link="b"/><child link="c"/><axis xyz="0 0 1"/>
        <mimic joint="j1" multiplier="2"/><limit lower="-1" upper="1" effort="1" velocity="1"/>
      </joint></robot>"""
    robot = kl.load_urdf(xml)
    with pytest.raises(kl.KinlibError, match=r"'j2'.*mimics 'j1'"):
        kl.screw_axes(robot)
    S, M = kl.screw_axes(robot, "b")  # the chain to b has no mimic joint
    np.testing.assert_allclose(kl.poe_fk(M, S, [0.4]), robot.fk([0.4], "b"), atol=1e-15)


@pytest.mark.parametrize("call, match", [
    (lambda S, M: kl.poe_fk(M, S, [0.1, 0.2]), "expected 6 joint values"),
    (lambda S, M: kl.poe_fk(M, S[:3], np.zeros(6)), "\\(6, n\\)"),
    (lambda S, M: kl.poe_fk(M[:3], S, np.zeros(6)), "4, 4|4×4"),
    (lambda S, M: kl.poe_fk(M, S, np.zeros(6), frame="world"), "'space' or 'body'"),
    (lambda S, M: kl.space_jacobian(S, np.full(6, np.nan)), "NaN"),
    (lambda S, M: kl.body_jacobian(S[:, :5].T, np.zeros(6)), "\\(6, n\\)"),
    (lambda S, M: kl.screw_axes(puma560(), "link9"), "no link 'link9'"),
    (lambda S, M: kl.screw_axes(puma560(), frame="tool"), "'space' or 'body'"),
])
def test_bad_input_is_a_kinlib_error(call, match):
    S, M = kl.screw_axes(puma560())
    with pytest.raises(kl.KinlibError, match=match):
        call(S, M)
