"""Notebook 08: wrong answers a student would write."""

import numpy as np

import kinlib as kl
from kinlib.robots import autorob_test_robot

robot = autorob_test_robot()
j1, j2, j3 = (robot.joint(n) for n in ("joint1", "joint2", "joint3"))
q_try = np.array([0.6, 0.9, -0.4])
base = kl.transform(kl.rotz(0.3), [1.0, 2.0, 0.0])


def R_u(jt, q):
    return kl.transform(kl.matrix_from_axis_angle(jt.axis, q))


# 08.1: URDF origins, each written by hand as a student would get it wrong
def intrinsic(xyz, rpy):            # "roll, pitch, yaw" multiplied in the order they are read
    r, p, y = rpy
    return kl.transform(kl.rotx(r) @ kl.roty(p) @ kl.rotz(y), xyz)


def letters_read_backwards(xyz, rpy):  # Rz(roll) Ry(pitch) Rx(yaw)
    r, p, y = rpy
    return kl.transform(kl.rotz(r) @ kl.roty(p) @ kl.rotx(y), xyz)


def in_degrees(xyz, rpy):           # "angles in a file are degrees"
    r, p, y = np.deg2rad(rpy)
    return kl.transform(kl.rotz(y) @ kl.roty(p) @ kl.rotx(r), xyz)


def rotate_then_translate(xyz, rpy):  # R @ D: the translation taken in the rotated frame
    r, p, y = rpy
    R = kl.transform(kl.rotz(y) @ kl.roty(p) @ kl.rotx(r))
    return R @ kl.transform(p=xyz)


def translation_in_last_row(xyz, rpy):
    r, p, y = rpy
    T = np.eye(4)
    T[:3, :3] = kl.rotz(y) @ kl.roty(p) @ kl.rotx(r)
    T[3, :3] = xyz
    return T.T


def rotation_transposed(xyz, rpy):  # R(rpy)ᵀ: the parent's axes in the child frame
    r, p, y = rpy
    return kl.transform((kl.rotz(y) @ kl.roty(p) @ kl.rotx(r)).T, xyz)


# 08.6: a cylinder along y turned onto an axis u, each with one slip
E_Y = np.array([0.0, 1.0, 0.0])


def _along_y(u_hat):
    return np.eye(3) if u_hat[1] > 0 else kl.rotx(np.pi)


def turned_backwards(u):            # û × e_y: the turn from û to e_y
    u_hat = np.asarray(u, float) / np.linalg.norm(u)
    k = np.cross(u_hat, E_Y)
    if np.linalg.norm(k) < 1e-12:
        return _along_y(u_hat)
    return kl.matrix_from_axis_angle(k, np.arccos(u_hat @ E_Y))


def not_normalised(u):              # the file's axis taken as a unit vector
    u = np.asarray(u, float)
    k = np.cross(E_Y, u)
    if np.linalg.norm(k) < 1e-12:
        return _along_y(u)
    return kl.matrix_from_axis_angle(k, np.arccos(np.clip(u[1], -1, 1)))


def angle_from_arcsin(u):           # |e_y × û| = sin θ, so θ = arcsin(...)
    u_hat = np.asarray(u, float) / np.linalg.norm(u)
    k = np.cross(E_Y, u_hat)
    if np.linalg.norm(k) < 1e-12:
        return _along_y(u_hat)
    return kl.matrix_from_axis_angle(k, np.arcsin(np.linalg.norm(k)))


def forgot_minus_y(u):              # "no cross product, no turn"
    u_hat = np.asarray(u, float) / np.linalg.norm(u)
    k = np.cross(E_Y, u_hat)
    if np.linalg.norm(k) < 1e-12:
        return np.eye(3)
    return kl.matrix_from_axis_angle(k, np.arctan2(np.linalg.norm(k), u_hat @ E_Y))


def rodrigues_unnormalised(u):      # Rodrigues by hand with K of e_y × û, |e_y × û| = sin θ
    u_hat = np.asarray(u, float) / np.linalg.norm(u)
    k = np.cross(E_Y, u_hat)
    if np.linalg.norm(k) < 1e-12:
        return _along_y(u_hat)
    c = u_hat @ E_Y
    K = kl.skew(k)
    return np.eye(3) + np.sin(np.arccos(c)) * K + (1 - c) * K @ K


def divides_by_zero(u):             # the axis normalised without a look at u ∥ y
    u_hat = np.asarray(u, float) / np.linalg.norm(u)
    k = np.cross(E_Y, u_hat)
    with np.errstate(invalid="ignore", divide="ignore"):
        k = k / np.linalg.norm(k)
    theta = np.arctan2(np.linalg.norm(np.cross(E_Y, u_hat)), u_hat @ E_Y)
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + np.sin(theta) * K + (1 - np.cos(theta)) * K @ K


WRONG = {
    "08.1": [(intrinsic, "extrinsic"), (letters_read_backwards, "sequence"),
             (in_degrees, "degrees"), (rotate_then_translate, "order"),
             (translation_in_last_row, "transposed"), (rotation_transposed, "transposed")],
    "08.2": [
        # the motion before the origin, joint by joint
        (R_u(j2, q_try[1]) @ j2.origin @ R_u(j3, q_try[2]) @ j3.origin, "order"),
        # from link4 back to the root
        (j3.origin @ R_u(j3, q_try[2]) @ j2.origin @ R_u(j2, q_try[1]), "order"),
        # joint1 left on the stack: the branch to link2 included
        (j1.origin @ R_u(j1, q_try[0]) @ j2.origin @ R_u(j2, q_try[1])
         @ j3.origin @ R_u(j3, q_try[2]), "branch"),
    ],
    "08.3": [("a", "revolute"), ("c", "order")],
    "08.4": [
        (base @ j1.origin @ kl.transform(p=0.7 * np.array([-0.9, 0.15, 0.0])), "unit axis"),
        (base @ j1.origin @ R_u(j1, 0.7), "revolute"),
        (kl.transform(p=0.7 * j1.axis) @ base @ j1.origin, "order"),
        (j1.origin @ kl.transform(p=0.7 * j1.axis), "base"),
    ],
    "08.5": [("a", "limits"), ("c", "continuous")],
    "08.6": [(turned_backwards, "transposed"), (not_normalised, "unit"),
             (angle_from_arcsin, "arcsin"), (forgot_minus_y, "antiparallel"),
             (rodrigues_unnormalised, "rotation"), (divides_by_zero, "parallel")],
}
