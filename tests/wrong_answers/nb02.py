"""Notebook 02: wrong answers a student would write."""

import numpy as np

import kinlib as kl

Q = np.array([0.3, -0.2, 0.5])
T_AB_e = kl.transform(kl.rotx(np.deg2rad(90)), [0.0, 1.0, 0.0])
T_BC_e = kl.transform(kl.rotz(np.deg2rad(30)), [2.0, 0.0, 0.5])
T_AB_num = kl.transform(kl.roty(np.deg2rad(60)), [2.0, 0.0, -1.0])
R_, p_ = T_AB_num[:3, :3], T_AB_num[:3, 3]
T_AB_grip = kl.transform(kl.matrix_from_euler(np.deg2rad([90, 30, 0]), "ZYX"), [0.5, 1.0, 0.8])
line_B = np.array([5.0, 0.0, -20.0, -2.0, 6.0, -0.5])
R_g, t_g = T_AB_grip[:3, :3], T_AB_grip[:3, 3]
f_A = R_g @ line_B[:3]


def with_column(R, p):
    T = np.eye(4)
    T[:3, :3], T[:3, 3] = R, p
    return T


def q_in_bottom_row():
    T = np.eye(4)
    T[3, :3] = Q            # rows for columns
    return T


WRONG = {
    "02.1": [
        (with_column(np.eye(3), -Q), "sign"),        # "the frame moves backward"
        (q_in_bottom_row(), "transposed"),
    ],
    "02.2": [("b", "order"), ("c", "commute")],
    "02.3": [
        (T_BC_e @ T_AB_e, "order"),
        (kl.transform(kl.rotx(90), [0.0, 1.0, 0.0])            # degrees into rotx
         @ kl.transform(kl.rotz(30), [2.0, 0.0, 0.5]), "degrees"),
        (T_AB_e * T_BC_e, "elementwise"),
        (with_column(T_AB_e[:3, :3] @ T_BC_e[:3, :3], T_AB_e[:3, 3] + T_BC_e[:3, 3]), "offset"),
    ],
    "02.4": [("b", "transposed"), ("c", "sign")],
    "02.5": [
        (with_column(R_.T, R_.T @ p_), "sign"),
        (with_column(R_.T, -p_), "unrotated"),
        (with_column(R_, -R_ @ p_), "transposed"),    # forgot to transpose R
        (T_AB_num.T, "transposed"),                   # transposed the whole 4×4
    ],
    "02.6": [
        ([80, 32], "swapped"),
        ([24, 60], "additions"),
        ((18, 36), "3×3"),
        ([32, 64], "final product"),
    ],
    "02.7": [
        (np.r_[f_A, R_g @ line_B[3:]], "free vector"),                  # m rotated only
        (np.r_[kl.transform_points(T_AB_grip, line_B[:3]),               # both as points
               kl.transform_points(T_AB_grip, line_B[3:])], "point"),
        (np.r_[f_A, R_g @ line_B[3:] + np.cross(f_A, t_g)], "cross order"),
        (np.r_[f_A, R_g @ line_B[3:] + np.cross(t_g, line_B[:3])], "unrotated"),
        (np.r_[R_g @ line_B[3:] + np.cross(t_g, f_A), f_A], "swapped"),  # moment first
    ],
}
