"""The references of notebooks 08 and 09's exercises, checked against what they stand for,
computed another way (scipy, the rows the cases are built from, a second robot)."""

import numpy as np
from scipy.spatial.transform import Rotation

import kinlib as kl
from kinlib.check.notebooks import nb08, nb09
from kinlib.robots import autorob_test_robot, three_dof_arm
from kinlib.robots.autorob import urdf_path


def test_08_1_a_urdf_origin_is_scipys_fixed_axis_rpy_then_the_translation():
    for xyz, rpy in nb08._origin_cases():
        T = nb08._origin(xyz, rpy)
        assert np.allclose(T[:3, :3], Rotation.from_euler("xyz", rpy).as_matrix())  # extrinsic
        assert np.allclose(T[:3, 3], xyz) and np.allclose(T[3], [0, 0, 0, 1])


def test_08_2_and_08_4_the_products_on_the_stack_are_kinlibs_poses():
    robot = autorob_test_robot()
    assert np.allclose(nb08._stack("joint2", "joint3"), robot.fk(nb08.Q_LINK4, link="link4"))
    text = urdf_path().read_text().replace(
        '<joint name="joint1" type="continuous">',
        '<joint name="joint1" type="prismatic"><limit lower="-1" upper="2" effort="1" '
        'velocity="1"/>')
    slider = kl.load_urdf(text)
    assert slider.joint("joint1").type == "prismatic"
    T = nb08._base() @ slider.fk([nb08.Q_SLIDE, 0.0, 0.0], link="link2")
    assert np.allclose(nb08._link2(), T)


def test_09_2_reading_back_gives_the_rows_the_frames_were_built_from():
    for (T_prev, T), row in zip(nb09._read_back_cases(), nb09.READ_BACK_ROWS, strict=True):
        assert np.allclose(nb09._read_back(T_prev, T), row)


def test_09_4_a3_is_seed_001s_row_3_multiplied_out():
    c, s = np.cos(0.6), np.sin(0.6)
    a, ca, sa = -20.32 / 1000, np.cos(np.deg2rad(90)), np.sin(np.deg2rad(90))
    A = np.array([[c, -s * ca, s * sa, a * c], [s, c * ca, -c * sa, a * s],
                  [0, sa, ca, 0.0], [0, 0, 0, 1]])          # seed 001's matrix, by hand
    assert np.allclose(nb09._puma_row3(), A)


def test_09_5_the_modified_table_builds_the_same_arm():
    table = nb09._modified_table()
    rows = [kl.DHRow(a=a, alpha=al, d=d) for a, al, d in table[:3]]
    rows.append(kl.DHRow(a=table[3, 0], alpha=table[3, 1], d=table[3, 2], joint="fixed"))
    modified = kl.Robot.from_dh(rows, "modified")
    q = np.random.default_rng(9).uniform(-np.pi, np.pi, (200, 3))
    assert np.allclose(modified.fk(q), three_dof_arm().fk(q))


def test_09_3_the_tip_is_the_planar_arm_turned_by_the_base_as_the_explanation_says():
    import sympy as sp

    t1, t2, t3, d1, a2, a3 = sp.symbols("theta_1 theta_2 theta_3 d_1 a_2 a_3", real=True)
    r = a2 * sp.cos(t2) + a3 * sp.cos(t2 + t3)                 # reach in the arm's plane
    by_hand = sp.Matrix([r * sp.cos(t1), r * sp.sin(t1),
                         d1 + a2 * sp.sin(t2) + a3 * sp.sin(t2 + t3)])
    assert sp.simplify(sp.expand_trig(nb09._tip() - by_hand)) == sp.zeros(3, 1)


def test_09_5_the_table_is_the_one_the_explanation_writes_out():
    written = np.array([[0.0, 0.0, 0.4], [0.0, np.pi / 2, 0.0], [0.5, 0.0, 0.0],
                        [0.4, 0.0, 0.0]])
    assert np.allclose(nb09._modified_table(), written)
    assert "(0, π/2, 0)" in next(e for e in nb09.EXERCISES if e.id == "09.5").explain
