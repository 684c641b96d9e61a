"""Notebook 07: wrong answers a student would write."""

import numpy as np
import sympy as sp

import kinlib as kl

T_try = kl.transform(kl.matrix_from_axis_angle([1.0, 2.0, 2.0], 1.2), [0.4, -0.2, 0.7])
R_try, t_try = T_try[:3, :3], T_try[:3, 3]
axis, angle = kl.axis_angle_from_matrix(R_try)
skew = np.array([R_try[2, 1] - R_try[1, 2], R_try[0, 2] - R_try[2, 0], R_try[1, 0] - R_try[0, 1]])
skew_flipped = -skew / np.linalg.norm(skew)          # r23 − r32, …: the indices swapped

theta, d, eps = sp.symbols("theta d epsilon", real=True)


def dual(expr):
    e = sp.expand(sp.series(expr, eps, 0, 2).removeO())
    return e.coeff(eps, 0) + eps * e.coeff(eps, 1)


def dq_other_order(q_rot, t):
    return np.r_[q_rot, 0.5 * kl.quat_multiply(q_rot, np.r_[0.0, t])]


def dq_without_half(q_rot, t):
    return np.r_[q_rot, kl.quat_multiply(np.r_[0.0, t], q_rot)]


def dq_without_rotation(q_rot, t):
    return np.r_[q_rot, 0.0, 0.5 * np.asarray(t)]


def dq_scalar_last(q_rot, t):
    return np.r_[q_rot, 0.5 * kl.quat_multiply(np.r_[t, 0.0], q_rot)]


WRONG = {
    "07.1": [
        (np.linalg.norm(t_try), "norm"),
        (t_try[2], "z component"),                               # the old axis-is-z habit
        (skew @ t_try, "unit axis"),
        (skew_flipped @ t_try, "sign"),
    ],
    "07.2": [("b", "norm"), ("c", "distance")],
    "07.3": [
        (np.array([1.0, 0, 0, 0, 0, 1, 2, 3]), "half"),
        (np.array([1.0, 0, 0, 0, 0.5, 1, 1.5, 0]), "xyzw"),
        (np.array([0.0, 0, 0, 1, 0.5, 1, 1.5, 0]), "xyzw"),
        (np.array([0.0, 0.5, 1, 1.5, 1, 0, 0, 0]), "parts swapped"),
    ],
    "07.4": [
        (dq_other_order, "order"),
        (dq_without_half, "half"),
        (dq_without_rotation, "no q_r"),
        (dq_scalar_last, "xyzw"),
    ],
    "07.5": [
        (sp.cos(theta / 2) - eps * d * sp.sin(theta / 2), "chain rule"),
        (sp.cos(theta / 2) + eps * d / 2 * sp.sin(theta / 2), "derivative sign"),
        (dual(sp.cos(theta + eps * d)), "half angle"),
        (sp.cos((theta + eps * d) / 2), "not expanded"),
    ],
    "07.6": [("a", "straight"), ("c", "sphere")],
}
