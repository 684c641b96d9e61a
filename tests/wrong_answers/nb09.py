"""Notebook 09: wrong answers a student would write."""

import numpy as np
import sympy as sp

import kinlib as kl
from kinlib.symbolic import simplify_rotation

# 09.2: a row read back from two frames


def with_arccos(T_prev, T):          # the size of each angle, not its sign
    o0, x0, z0 = T_prev[:3, 3], T_prev[:3, 0], T_prev[:3, 2]
    o1, x1, z1 = T[:3, 3], T[:3, 0], T[:3, 2]
    theta = np.arccos(np.clip(x0 @ x1, -1, 1))
    alpha = np.arccos(np.clip(z0 @ z1, -1, 1))
    return np.array([theta, (o1 - o0) @ z0, (o1 - o0) @ x1, alpha])


def measure(T_prev, T):
    """The pieces a student computes: signed angles, and the origin step o_i − o_{i−1}."""
    x0, z0, x1, z1 = T_prev[:3, 0], T_prev[:3, 2], T[:3, 0], T[:3, 2]
    step = T[:3, 3] - T_prev[:3, 3]
    theta = np.arctan2(np.cross(x0, x1) @ z0, x0 @ x1)
    alpha = np.arctan2(np.cross(z0, z1) @ x1, z0 @ z1)
    return theta, alpha, step, x0, z0, x1


def a_along_old_x(T_prev, T):
    theta, alpha, step, x0, z0, _ = measure(T_prev, T)
    return np.array([theta, step @ z0, step @ x0, alpha])


def d_as_distance(T_prev, T):
    theta, alpha, step, _, _, x1 = measure(T_prev, T)
    return np.array([theta, np.linalg.norm(step), step @ x1, alpha])


def in_degrees(T_prev, T):
    theta, alpha, step, _, z0, x1 = measure(T_prev, T)
    return np.array([np.degrees(theta), step @ z0, step @ x1, np.degrees(alpha)])


def table_columns(T_prev, T):        # θ, α, a, d: the PUMA table's column order
    theta, alpha, step, _, z0, x1 = measure(T_prev, T)
    return np.array([theta, alpha, step @ x1, step @ z0])


# 09.3: the 3-DOF arm's tip
t1, t2, t3, d1, a2, a3 = sp.symbols("theta_1 theta_2 theta_3 d_1 a_2 a_3", real=True)


def tip(f, alpha1=sp.pi / 2, reverse=False, thetas=(t1, t2, t3)):
    A = [f(theta=thetas[0], d=d1, a=0, alpha=alpha1), f(theta=thetas[1], d=0, a=a2, alpha=0),
         f(theta=thetas[2], d=0, a=a3, alpha=0)]
    if reverse:
        A = A[::-1]
    return simplify_rotation((A[0] * A[1] * A[2])[:3, 3])


right_tip = tip(kl.dh_transform)

# 09.4: the PUMA's A_3 at q_3 = 0.6
c, s = np.cos(0.6), np.sin(0.6)

WRONG = {
    "09.1": [("a", "revolute"), ("c", "link length"), ("d", "twist")],
    "09.2": [(with_arccos, "arccos"), (a_along_old_x, "x axis"), (d_as_distance, "distance"),
             (in_degrees, "degrees"), (table_columns, "swapped")],
    "09.3": [
        (tip(kl.mdh_transform), "modified"),                     # Craig's product
        (tip(kl.dh_transform, alpha1=-sp.pi / 2), "sign"),       # α1 = −90°
        (-right_tip, "sign"),
        (tip(kl.dh_transform, reverse=True), "order"),           # A3 A2 A1
        (tip(kl.dh_transform, thetas=(t1, t3, t2)), "swapped"),  # θ2 and θ3 in the wrong rows
        (right_tip.T, "transposed"),                              # a row, not a column
    ],
    "09.4": [
        (kl.mdh_transform(theta=0.6, d=0.0, a=-0.02032, alpha=np.pi / 2), "modified"),
        (np.array([[c, -s * np.cos(90), s * np.sin(90), -0.02032 * c],      # cos(90) in radians
                   [s, c * np.cos(90), -c * np.sin(90), -0.02032 * s],
                   [0, np.sin(90), np.cos(90), 0], [0, 0, 0, 1]]), "degrees"),
        (kl.dh_transform(theta=0.6 + np.pi / 2, d=0.0, a=-0.02032, alpha=np.pi / 2), "table pose"),
        (kl.dh_transform(theta=0.6, d=0.0, a=-20.32, alpha=np.pi / 2), "millimetres"),
        (kl.dh_transform(theta=0.6, d=0.0, a=-0.02032, alpha=-np.pi / 2), "sign"),
        (kl.dh_transform(theta=0.6, d=0.0, a=0.02032, alpha=np.pi / 2), "sign"),
        (kl.dh_transform(np.pi / 2, 0.0, -0.02032, 0.6), "swapped"),
    ],
    "09.5": [
        # the standard table copied, a tool row of zeros added
        (np.array([[0.0, np.pi / 2, 0.4], [0.5, 0.0, 0.0], [0.4, 0.0, 0.0], [0.0, 0.0, 0.0]]),
         "standard rows"),
        # everything moved down a row, d included
        (np.array([[0.0, 0.0, 0.0], [0.0, np.pi / 2, 0.4], [0.5, 0.0, 0.0], [0.4, 0.0, 0.0]]),
         "d moved"),
        (np.array([[0.0, 0.0, 0.4], [0.0, 90.0, 0.0], [0.5, 0.0, 0.0], [0.4, 0.0, 0.0]]),
         "degrees"),
    ],
}
