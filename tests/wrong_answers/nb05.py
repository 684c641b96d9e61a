"""Notebook 05: wrong answers a student would write."""

import numpy as np
import sympy as sp

import kinlib as kl

kx, ky, kz = sp.symbols("k_x k_y k_z", real=True)
k = sp.Matrix([kx, ky, kz])
b = sp.Matrix(sp.symbols("b_x b_y b_z", real=True))

R_try = kl.matrix_from_axis_angle([0.0, 0.6, 0.8], 2.0)
theta = np.arccos((np.trace(R_try) - 1) / 2)
skew_part = np.array([R_try[2, 1] - R_try[1, 2], R_try[0, 2] - R_try[2, 0],
                      R_try[1, 0] - R_try[0, 1]])
k_cay = np.array([2.0, -1.0, 2.0]) / 3.0

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
    ],
    "05.3": [
        # the skew part read as R_ij − R_ji: the axis of Rᵀ
        ((-skew_part / (2 * np.sin(theta)), theta), "axis sign"),
        ((skew_part / (2 * np.sin(theta)), np.rad2deg(theta)), "degrees"),
        ((skew_part, theta), "unit"),              # forgot to divide by 2 sin θ
    ],
    "05.4": [
        (np.tan(np.deg2rad(100)) * k_cay, "half angle"),
        (np.tan(100 / 2) * k_cay, "degrees"),
        (np.sin(np.deg2rad(100) / 2) * k_cay, "quaternion"),
        (-np.tan(np.deg2rad(100) / 2) * k_cay, "transposed"),
    ],
}
