"""Notebook 15: wrong answers a student would write."""

import numpy as np
import sympy as sp

import kinlib as kl
from kinlib.robots import ur5

# -- 15.2: the bead on the turntable on the conveyor
R_table = kl.rotz(0.6)
w_table, d_dot = np.array([0.0, 0.0, 0.5]), np.array([0.2, 0.0, 0.0])
p1, p1_dot = np.array([0.3, 0.0, 0.1]), np.array([0.1, 0.0, 0.0])
d_table = np.array([1.2, 0.4, 0.3])

# -- 15.3: the revolute joint about the vertical line through (a, b, 0)
a, b, theta = sp.symbols("a b theta", real=True)
w_z, q_ab = sp.Matrix([0, 0, 1]), sp.Matrix([a, b, 0])


def screw_exp(v, w, th):
    """e^{[S]θ} for a unit ω by the closed form, as a student types it."""
    W = kl.skew(w)
    T = sp.eye(4)
    T[:3, :3] = sp.eye(3) + sp.sin(th) * W + (1 - sp.cos(th)) * W * W
    T[:3, 3] = (sp.eye(3) * th + (1 - sp.cos(th)) * W + (th - sp.sin(th)) * W * W) * v
    return T


# -- 15.4: the UR5's fifth axis at home
F4 = ur5().link_poses(np.zeros(6))["link4"]
F5 = ur5().link_poses(np.zeros(6))["link5"]
M_ur5 = ur5().fk(np.zeros(6))
w5, q5 = F4[:3, 2], F4[:3, 3]


# -- 15.5: PoE forward kinematics, as students write it
def poe_reversed(M, S, q):                   # the last joint's exponential leftmost
    T = np.eye(4)
    for i in reversed(range(len(q))):
        T = T @ kl.exp_se3(S[:, i], q[i])
    return T @ M


def poe_reversed_loop(M, S, q):               # the same slip: T = e^{S_i q_i} T, from i = 1
    T = np.eye(4)
    for i in range(len(q)):
        T = kl.exp_se3(S[:, i] * q[i]) @ T
    return T @ M


def poe_m_first(M, S, q):                     # the body form with the space axes
    T = M.copy()
    for i in range(len(q)):
        T = T @ kl.exp_se3(S[:, i] * q[i])
    return T


def poe_no_home(M, S, q):                     # forgot M
    T = np.eye(4)
    for i in range(len(q)):
        T = T @ kl.exp_se3(S[:, i] * q[i])
    return T


def poe_mr_order(M, S, q):                    # ported from Modern Robotics' FKinSpace
    T = np.eye(4)
    for i in range(len(q)):
        w, v = S[:3, i], S[3:, i]             # MR: S = [ω; v]
        T = T @ kl.exp_se3(np.r_[v, w] * q[i])
    return T @ M


def poe_rows(M, S, q):                        # S[i] is a row, not joint i's axis
    T = np.eye(4)
    for i in range(len(q)):
        T = T @ kl.exp_se3(S[i] * q[i])
    return T @ M


WRONG = {
    "15.1": [("a", "seed 004"), ("c", "zero row"), ("d", "translation")],
    "15.2": [
        (np.cross(w_table, R_table @ p1) + R_table @ p1_dot, "carried"),       # no ḋ
        (kl.point_velocity(R_table, d_dot, w_table, p1), "sliding"),           # no R ṗ1
        (kl.point_velocity(R_table, d_dot, w_table, p1) + p1_dot, "frame"),    # ṗ1 unrotated
        (np.cross(w_table, p1) + d_dot + R_table @ p1_dot, "frame"),           # ω × p1
        (np.cross(w_table, R_table @ p1 + d_table) + d_dot + R_table @ p1_dot, "lever arm"),
    ],
    "15.3": [
        (screw_exp(w_z.cross(q_ab), w_z, theta), "moment"),             # v = ω × q
        (screw_exp(sp.zeros(3, 1), w_z, theta), "origin"),              # forgot v
        (kl.transform(kl.rotz(theta), -theta * w_z.cross(q_ab)), "no V"),   # [R, θ v]
        (kl.transform(kl.rotz(theta), (kl.rotz(theta) - sp.eye(3)) * q_ab), "moment"),
    ],
    "15.4": [
        (np.r_[w5, -np.cross(w5, q5)], "rows"),                         # MR's [ω; v]
        (np.r_[np.cross(w5, q5), w5], "sign"),                          # v = ω × q
        (np.r_[q5, w5], "point"),                                        # v = q
        (np.r_[-np.cross(F5[:3, 2], F5[:3, 3]), F5[:3, 2]], "next frame"),   # z5, o5
        (kl.adjoint(kl.transform_inverse(M_ur5)) @ np.r_[-np.cross(w5, q5), w5], "frame"),
    ],
    "15.5": [
        (poe_reversed, "order"),
        (poe_reversed_loop, "order"),
        (poe_m_first, "body form"),
        (poe_no_home, "home"),
        (poe_mr_order, "rows"),
        (poe_rows, "columns"),
    ],
    "15.6": [("a", "all"), ("b", "space"), ("d", "column 1")],
}
