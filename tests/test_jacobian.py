"""The geometric Jacobian against finite differences of forward kinematics."""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from kinlib import KinlibError, Robot, planar_2r_jacobian
from kinlib.kinematics import _fk
from kinlib.models.tree import Joint, Link, Mimic
from kinlib.robots import autorob_test_robot, panda, planar_2r, puma560, three_dof_arm, ur5


def vee(S):
    return np.array([S[2, 1] - S[1, 2], S[0, 2] - S[2, 0], S[1, 0] - S[0, 1]]) / 2


def numeric_jacobian(robot, q, link, h=1e-6):
    """Central differences: v = dp/dq, ω from dR/dq Rᵀ (written out here, not kinlib's)."""
    J = np.zeros((6, robot.dof))
    R = robot.fk(q, link=link)[:3, :3]
    for i in range(robot.dof):
        dq = np.zeros(robot.dof)
        dq[i] = h
        Tp, Tm = robot.fk(q + dq, link=link), robot.fk(q - dq, link=link)
        J[:3, i] = (Tp[:3, 3] - Tm[:3, 3]) / (2 * h)
        J[3:, i] = vee((Tp[:3, :3] - Tm[:3, :3]) / (2 * h) @ R.T)
    return J


def tree_robot():
    """Branches, arbitrary axes (incl. ±z), a prismatic joint, a fixed joint and a mimic."""
    rng = np.random.default_rng(3)

    def origin(i):
        T = np.eye(4)
        T[:3, :3] = Rotation.random(random_state=i).as_matrix()
        T[:3, 3] = rng.normal(size=3) * 0.3
        return T

    links = [Link(n) for n in ["base", "a", "b", "c", "d", "e"]]
    joints = [
        Joint("j1", "revolute", "base", "a", origin(1), (0, 0, -1), (-3, 3)),
        Joint("j2", "prismatic", "a", "b", origin(2), (0.3, 0.4, 0.5), (-1, 1)),
        Joint("j3", "continuous", "b", "c", origin(3), (1, 0, 0)),
        Joint("fix", "fixed", "c", "d", origin(4)),
        Joint("j4", "revolute", "a", "e", origin(5), (0, 1, 1), (-2, 2)),
        Joint("j5", "continuous", "d", "f", origin(6), (0.2, -1, 0.1),
              mimic=Mimic("j1", -1.5, 0.2)),
    ]
    links.append(Link("f"))
    return Robot("tree", links, joints)


MODELS = [planar_2r, three_dof_arm, puma560, ur5, panda, autorob_test_robot, tree_robot]


def tips(robot):
    """The tip, or for a branched tree every link that is not the root."""
    return [robot.tip] if robot.tip else [n for n in robot.link_names if n != robot.root]


def sample(robot, n, seed):
    lim = np.clip(robot.limits, -np.pi, np.pi)
    return np.random.default_rng(seed).uniform(lim[:, 0], lim[:, 1], (n, robot.dof))


@pytest.mark.parametrize("model", MODELS, ids=lambda m: m.__name__)
def test_jacobian_matches_finite_differences(model):
    robot = model()
    for link in tips(robot):
        Q = sample(robot, 8, 1)
        J = robot.jacobian(Q, link=link)
        assert J.shape == (8, 6, robot.dof)
        for q, Jq in zip(Q, J, strict=True):
            np.testing.assert_allclose(Jq, numeric_jacobian(robot, q, link), atol=1e-8)


SINGULAR = [
    (planar_2r, [0.4, 0.0]), (planar_2r, [-1.0, np.pi]),
    (puma560, [0.1, -0.5, 0.7, 0.3, 0.0, 0.2]),                  # wrist: θ5 = 0
    # elbow stretched: the forearm vector (a3, d4) = (−20.32, 433.07) mm in line with link 2
    (puma560, [0.3, -1.2, -np.pi / 2 + np.arctan2(20.32, 433.07), 0.0, 0.4, 0.0]),
    (ur5, [0.0, -np.pi / 2, 0.0, -np.pi / 2, 0.0, 0.0]),           # upright, θ5 = 0
    (panda, [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]),                 # joints 1, 3, 5 aligned
]


@pytest.mark.parametrize("model, q", SINGULAR, ids=lambda x: getattr(x, "__name__", ""))
def test_jacobian_at_singular_configurations(model, q):
    robot = model()
    q = np.asarray(q, float)
    J = robot.jacobian(q)
    np.testing.assert_allclose(J, numeric_jacobian(robot, q, robot.tip), atol=1e-8)
    rows = [0, 1] if robot.dof == 2 else slice(None)  # the 2R arm: its position part
    assert np.linalg.matrix_rank(J[rows], tol=1e-9) < min(J[rows].shape)


def test_planar_2r_robot_rows_equal_the_closed_form():
    l1, l2 = 0.8, 0.35
    Q = sample(planar_2r(l1, l2), 50, 4)
    J = planar_2r(l1, l2).jacobian(Q)
    closed = planar_2r_jacobian(Q[:, 0], Q[:, 1], l1, l2)
    np.testing.assert_allclose(J[:, [0, 1, 5]], closed, atol=1e-14)
    np.testing.assert_allclose(J[:, [2, 3, 4]], 0.0, atol=1e-15)


def test_joints_off_the_path_give_zero_columns():
    robot = autorob_test_robot()
    J = robot.jacobian([0.3, -0.2, 0.5], link="link2")
    np.testing.assert_array_equal(J[:, 1:], 0.0)
    assert np.abs(J[:, 0]).max() > 0.1
    J4 = robot.jacobian([0.3, -0.2, 0.5], link="link4")
    np.testing.assert_array_equal(J4[:, 0], 0.0)
    np.testing.assert_array_equal(robot.jacobian([0.3, -0.2, 0.5], link="link1"), 0.0)


def test_prismatic_and_mimic_columns():
    robot = tree_robot()
    q = np.array([0.4, 0.2, -0.7, 0.9])
    J = robot.jacobian(q, link="f")
    # j2 is prismatic: its column has no angular part
    np.testing.assert_allclose(J[3:, 1], 0.0, atol=1e-15)
    # j1 drives j5 too (mimic, multiplier −1.5): column 0 holds both contributions
    np.testing.assert_allclose(J, numeric_jacobian(robot, q, "f"), atol=1e-8)


def test_expressed_in_another_frame():
    robot = puma560()
    q = sample(robot, 3, 5)
    J = robot.jacobian(q)
    for frame in ("link0", "link3", "link6"):
        R = robot.fk(q, link=frame)[:, :3, :3]
        Jf = robot.jacobian(q, frame=frame)
        for i in range(3):
            np.testing.assert_allclose(Jf[i, :3], R[i].T @ J[i, :3], atol=1e-14)
            np.testing.assert_allclose(Jf[i, 3:], R[i].T @ J[i, 3:], atol=1e-14)
    with pytest.raises(KinlibError, match="no link 'hand'"):
        robot.jacobian(q, frame="hand")


@pytest.mark.parametrize("model", MODELS, ids=lambda m: m.__name__)
def test_compiled_and_numpy_paths_and_batches_agree(model):
    robot = model()
    link = tips(robot)[-1]
    Q = sample(robot, _fk.PARALLEL_MIN + 5, 6)  # the parallel kernel too
    T, J = robot.fk_and_jacobian(Q, link)
    path = robot._path(link)
    T0, J0 = _fk.run_chain_jacobian(robot.chain_table(link), Q, compiled=False)
    np.testing.assert_allclose(J, J0, atol=1e-12)
    np.testing.assert_allclose(T, T0, atol=1e-12)
    # the chain's numpy path against the tree's (joint by joint, no constants folded)
    tree = _fk.run(robot._table, Q, path, compiled=False)
    np.testing.assert_allclose(T0, tree[:, path[-1] + 1], atol=1e-12)
    np.testing.assert_allclose(_fk.run_chain(robot.chain_table(link), Q, compiled=False), T0,
                               atol=0)
    np.testing.assert_allclose(T, robot.fk(Q, link=link), atol=1e-13)
    for i in (0, 7):
        np.testing.assert_allclose(robot.jacobian(Q[i], link=link), J[i], atol=1e-13)
    assert robot.jacobian(Q[:6].reshape(2, 3, -1), link=link).shape == (2, 3, 6, robot.dof)


def test_bad_input():
    robot = puma560()
    with pytest.raises(KinlibError, match="expected 6 joint values"):
        robot.jacobian([0.0] * 7)
    with pytest.raises(KinlibError, match="several leaf links"):
        autorob_test_robot().jacobian([0, 0, 0])
