"""Exercises of notebooks 06 (quaternions) and 07 (dual quaternions, screws): right answers
reached another way (scipy, sympy's own conversions, a closed form) are right, and the
options the checks call right follow from the mathematics, computed here independently."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
import sympy as sp
from scipy.spatial.transform import Rotation

import kinlib as kl
from kinlib.check import check, exercise

theta, d, eps = sp.symbols("theta d epsilon", real=True)


def _right(ex_id, answer):
    feedback = check(ex_id, answer)
    assert feedback.status == "right", str(feedback)


# --- notebook 06 ---------------------------------------------------------------------


def test_06_1_the_right_option_is_the_term_that_changes_sign():
    r1, r2 = sp.symbols("r1 r2", real=True)
    v1, v2 = sp.Matrix(sp.symbols("a1 b1 c1", real=True)), sp.Matrix(sp.symbols("a2 b2 c2",
                                                                                 real=True))
    p12 = sp.Quaternion(r1, *v1) * sp.Quaternion(r2, *v2)
    p21 = sp.Quaternion(r2, *v2) * sp.Quaternion(r1, *v1)
    difference = sp.Matrix([p12.a - p21.a, p12.b - p21.b, p12.c - p21.c, p12.d - p21.d])
    assert sp.expand(difference - sp.Matrix([0, *(2 * v1.cross(v2))])) == sp.zeros(4, 1)
    _right("06.1", "c")                       # the option "v1 × v2"
    assert all(check("06.1", o).status == "wrong" for o in "abd")
    assert check("06.1", " C ").status == "right"


def test_06_2_sympys_own_rotation_matrix_is_right():
    q = sp.Quaternion(sp.cos(theta / 2), 0, 0, sp.sin(theta / 2))
    _right("06.2", q.to_rotation_matrix())
    _right("06.2", sp.Matrix([[sp.cos(theta), -sp.sin(theta), 0],
                              [sp.sin(theta), sp.cos(theta), 0], [0, 0, 1]]))
    plain = sp.Symbol("theta")                # a symbol without assumptions, matched by name
    _right("06.2", sp.Quaternion(sp.cos(plain / 2), 0, 0, sp.sin(plain / 2)).to_rotation_matrix())
    assert check("06.2", sp.eye(3)).key == "wrong"


def test_06_3_scipys_quaternion_moved_to_scalar_first_is_right():
    R_seed = kl.matrix_from_axis_angle([1.0, -2.0, 2.0], np.deg2rad(100))
    xyzw = Rotation.from_matrix(R_seed).as_quat()
    _right("06.3", np.r_[xyzw[3], xyzw[:3]])
    _right("06.3", -np.r_[xyzw[3], xyzw[:3]])
    assert check("06.3", xyzw).key == "xyzw"


def test_06_4_every_sign_of_every_row_is_right_and_the_rows_are_seed_000s():
    h = np.sqrt(0.5)
    slide = np.array([[1, 0, 0, 0], [0, 0, 0, 1], [h, 0, h, 0], [h, -h, 0, 0]])  # seed 000
    for signs in itertools.product((1, -1), repeat=4):
        _right("06.4", np.array(signs)[:, None] * slide)
    # the same rotations from scipy, scalar moved first
    peers = Rotation.from_rotvec([[0, 0, 0], [0, 0, np.pi], [0, np.pi / 2, 0],
                                  [-np.pi / 2, 0, 0]]).as_quat()
    _right("06.4", np.roll(peers, 1, axis=1))
    assert check("06.4", slide.T).status == "wrong"
    assert check("06.4", slide[:, :3]).key == "shape"


def test_06_5_and_06_6_quaternions_from_matrices_are_right():
    R_perm = np.roll(np.eye(3), 1, axis=0)    # x → y → z → x, typed from the hint
    q_perm = kl.quat_from_matrix(R_perm)
    _right("06.5", q_perm)
    _right("06.5", -q_perm)
    Rz = np.array([[0.0, -1, 0], [1, 0, 0], [0, 0, 1]])
    _right("06.6", kl.quat_wxyz_from_xyzw(Rotation.from_matrix(Rz @ R_perm).as_quat()))
    assert check("06.6", kl.quat_from_matrix(R_perm @ Rz)).key == "order"


# --- notebook 07 ---------------------------------------------------------------------


def test_07_1_the_slide_from_scipys_rotation_vector_is_right():
    T_try = kl.transform(kl.matrix_from_axis_angle([1.0, 2.0, 2.0], 1.2), [0.4, -0.2, 0.7])
    rotvec = Rotation.from_matrix(T_try[:3, :3]).as_rotvec()
    _right("07.1", rotvec / np.linalg.norm(rotvec) @ T_try[:3, 3])
    assert np.isclose(rotvec / np.linalg.norm(rotvec) @ [1.0, 2.0, 2.0], 3.0)


@pytest.mark.parametrize("c", [[1.0, 0.0, 0.0], [3.0, 1.0, -2.0], [0.0, -5.0, 0.2]])
def test_07_2_a_rotation_about_any_line_has_no_slide(c):
    R = kl.matrix_from_axis_angle([0.3, -0.4, 0.866], 1.9)
    c = np.asarray(c)
    t = c - R @ c
    axis = Rotation.from_matrix(R).as_rotvec()
    assert np.linalg.norm(t) > 0.5 and abs(axis @ t) < 1e-12
    _right("07.2", "a")


def test_07_3_and_07_4_answers_built_another_way_are_right():
    _right("07.3", np.r_[1.0, 0, 0, 0, 0.5 * np.array([0.0, 1, 2, 3])])
    _right("07.3", -np.r_[1.0, 0, 0, 0, 0.5 * np.array([0.0, 1, 2, 3])])

    def through_the_matrix(q_rot, t):       # kinlib's converter, sign kept as given
        dq = kl.dual_quat_from_transform(kl.transform(kl.matrix_from_quat(q_rot), t))
        return dq if dq[:4] @ q_rot > 0 else -dq

    def always_w_positive(q_rot, t):
        return kl.dual_quat_from_transform(kl.transform(kl.matrix_from_quat(q_rot), t))

    def sympy_product(q_rot, t):
        q = sp.Quaternion(*q_rot)
        qd = sp.Quaternion(0, *t) * q * sp.Rational(1, 2)
        return np.array([*q_rot, qd.a, qd.b, qd.c, qd.d], dtype=float)

    for f in (through_the_matrix, always_w_positive, sympy_product):
        _right("07.4", f)
    assert len(exercise("07.4").cases) >= 5
    assert any(q[0] < 0 for q, _ in exercise("07.4").cases)


def test_07_5_every_way_of_writing_the_expansion_is_right():
    _right("07.5", sp.cos(theta / 2) - sp.Rational(1, 2) * eps * d * sp.sin(theta / 2))
    t_, d_, e_ = sp.symbols("theta d epsilon")   # no assumptions: matched by name
    _right("07.5", sp.cos(t_ / 2) - e_ * d_ * sp.sin(t_ / 2) / 2)
    # cos(a + εb) = cos a − ε b sin a, from the derivative, with a = θ/2, b = d/2
    a = sp.Symbol("a")
    expansion = sp.cos(a) + eps * (d / 2) * sp.diff(sp.cos(a), a)
    _right("07.5", expansion.subs(a, theta / 2))


def test_07_6_the_origin_moves_on_the_helix_of_the_relative_screw():
    T1 = kl.transform(kl.matrix_from_axis_angle([0, 0, 1.0], np.deg2rad(150)), [1.0, 2.2, 1.0])
    ts = np.linspace(0.0, 1.0, 7)
    path = kl.transform_from_dual_quat(kl.dual_quat_sclerp(
        kl.dual_quat_from_transform(np.eye(4)), kl.dual_quat_from_transform(T1), ts))[:, :3, 3]
    # closed form: a rotation about z by tθ about the vertical line through c, a rise t·d;
    # c solves (I − Rz) c = t_xy (the horizontal part of the translation)
    angle, lift = np.deg2rad(150), 1.0
    Rz = kl.rotz(angle)
    c = np.r_[np.linalg.solve((np.eye(3) - Rz)[:2, :2], [1.0, 2.2]), 0.0]
    helix = np.array([kl.rotz(s * angle) @ (-c) + c + [0, 0, s * lift] for s in ts])
    assert np.allclose(path, helix)
    _right("07.6", "b")
