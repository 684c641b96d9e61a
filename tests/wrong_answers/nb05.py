"""Notebook 05: wrong answers a student would write."""

import numpy as np
import sympy as sp

import kinlib as kl

kx, ky, kz = sp.symbols("k_x k_y k_z", real=True)
k = sp.Matrix([kx, ky, kz])
b = sp.Matrix(sp.symbols("b_x b_y b_z", real=True))

# 05.3: the formulas for the notebook's R_try
R_try = kl.matrix_from_euler([0.7, -1.1, 0.4], "ZYX")
theta = np.arccos((np.trace(R_try) - 1) / 2)
skew_part = np.array([R_try[2, 1] - R_try[1, 2], R_try[0, 2] - R_try[2, 0],
                      R_try[1, 0] - R_try[0, 1]])

# 05.4: the notebook's R_cay_try, by both routes
R_cay = kl.matrix_from_euler(np.deg2rad([30.0, -50.0, 80.0]), "ZYX")
I3 = np.eye(3)
theta_cay = np.arccos((np.trace(R_cay) - 1) / 2)
k_cay = np.array([R_cay[2, 1] - R_cay[1, 2], R_cay[0, 2] - R_cay[2, 0],
                  R_cay[1, 0] - R_cay[0, 1]]) / (2 * np.sin(theta_cay))
S_wrong_side = (I3 - R_cay) @ np.linalg.inv(I3 + R_cay)    # solved with the sign flipped
S_cay = (R_cay - I3) @ np.linalg.inv(R_cay + I3)

WRONG = {
    "05.1": [
        (-k * k.dot(b), "sign"),
        (k.dot(b) * b, "along b"),                 # projected onto the wrong vector
        (b - k * k.dot(b), "perpendicular"),       # answered b⊥
        (k * k.T, "operator"),                     # the projection matrix, not applied
        (k.dot(b), "scalar"),                      # the length only
        (k.cross(b), "wrong"),
    ],
    "05.2": [
        (k.cross(k.cross(b)), "sign"),             # the minus sign forgotten
        (k.cross(b), "quarter turn"),
        (k.cross(k).cross(b), "associative"),      # brackets in the wrong place
        (k * k.dot(b), "parallel"),
        (b - k * k.dot(b), "dot product"),         # right, but not with cross products
        (b - k * (k.T * b), "dot product"),        # b minus b∥ written as k kᵀ b
    ],
    "05.3": [
        # the skew part read as R_ij − R_ji: the axis of Rᵀ
        ((-skew_part / (2 * np.sin(theta)), theta), "axis sign"),
        ((skew_part / (2 * np.sin(theta)), np.rad2deg(theta)), "degrees"),
        ((skew_part, theta), "unit"),              # forgot to divide by 2 sin θ
    ],
    "05.4": [
        (np.array([S_wrong_side[2, 1], S_wrong_side[0, 2], S_wrong_side[1, 0]]), "transposed"),
        (np.array([S_cay[1, 0], S_cay[0, 2], S_cay[2, 1]]), "swapped"),   # seed 002's layout
        (np.tan(theta_cay) * k_cay, "half angle"),
        (np.sin(theta_cay / 2) * k_cay, "quaternion"),
        (kl.vee(R_cay - R_cay.T) / 2, "skew part"),    # the skew part of R taken for S
    ],
}
