"""Notebook 06: wrong answers a student would write."""

import numpy as np
import sympy as sp

import kinlib as kl

theta = sp.Symbol("theta", real=True)
x, y, z = sp.symbols("x y z", real=True)


def _conjugation_matrix(q, first_conjugate=False):
    """The Jacobian of the vector part of q p q̄ (or q̄ p q), as in the notebook."""
    p = sp.Quaternion(0, x, y, z)
    v = q.conjugate() * p * q if first_conjugate else q * p * q.conjugate()
    return sp.Matrix([v.b, v.c, v.d]).jacobian([x, y, z])


def plane_matrix(z_new, real_first=True):
    """The 2×2 matrix read off x' + i y' = z_new, as the notebook does it."""
    parts = [sp.re(z_new), sp.im(z_new)]
    return sp.Matrix(parts if real_first else parts[::-1]).jacobian([x, y])


z_turned = sp.expand(sp.exp(sp.I * theta) * (x + sp.I * y), complex=True)
z_half = sp.expand(sp.exp(sp.I * theta / 2) * (x + sp.I * y), complex=True)   # "as for q"
z_back = sp.expand(sp.exp(-sp.I * theta) * (x + sp.I * y), complex=True)      # e^{−iθ}

q_z_half = sp.Quaternion(sp.cos(theta / 2), 0, 0, sp.sin(theta / 2))
q_z_full = sp.Quaternion(sp.cos(theta), 0, 0, sp.sin(theta))          # the half angle forgotten

R_seed = kl.matrix_from_axis_angle([1.0, -2.0, 2.0], np.deg2rad(100))
eps4 = 0.5 * np.sqrt(1.0 + np.trace(R_seed))
eps = np.array([R_seed[2, 1] - R_seed[1, 2], R_seed[0, 2] - R_seed[2, 0],
                R_seed[1, 0] - R_seed[0, 1]]) / (4 * eps4)
eps_swapped = np.array([R_seed[1, 2] - R_seed[2, 1], R_seed[2, 0] - R_seed[0, 2],
                        R_seed[0, 1] - R_seed[1, 0]]) / (4 * eps4)   # r23 − r32: R[i, j] misread

h = np.sqrt(0.5)
right_rows = np.array([[1, 0, 0, 0], [0, 0, 0, 1], [h, 0, h, 0], [h, -h, 0, 0]])


def rows_by_hand(angles_deg, use_half=True, degrees=False):
    axes = [(1, 0, 0), (0, 0, 1), (0, 1, 0), (1, 0, 0)]
    out = []
    for a, u in zip(angles_deg, axes, strict=True):
        t = a if degrees else np.deg2rad(a)
        t = t / 2 if use_half else t
        out.append(np.r_[np.cos(t), np.sin(t) * np.array(u, float)])
    return np.array(out)


axis = np.ones(3) / np.sqrt(3)
q_perm = kl.quat_from_axis_angle([1.0, 1.0, 1.0], np.deg2rad(120))
q_z90 = kl.quat_from_axis_angle([0.0, 0.0, 1.0], np.pi / 2)

WRONG = {
    "06.0": [
        (plane_matrix(z_turned).T, "transposed"),            # (x', y') read down the columns
        (plane_matrix(z_back), "transposed"),                 # turned the other way
        (plane_matrix(z_turned, real_first=False), "re im"),
        (plane_matrix(z_half), "half angle"),
    ],
    "06.1": [("a", "dot product"), ("b", "symmetric"), ("d", "unit")],
    "06.2": [
        (_conjugation_matrix(q_z_half, first_conjugate=True), "conjugate"),   # q̄ p q
        (_conjugation_matrix(q_z_full), "half angle"),
    ],
    "06.3": [
        (np.r_[eps, eps4], "xyzw"),                       # (ε1, ε2, ε3, ε4) as it stands
        (np.r_[eps, eps4][::-1], "reversed"),
        (np.r_[eps4, eps_swapped], "conjugate"),
    ],
    "06.4": [
        (rows_by_hand([0, 180, 90, -90], use_half=False), "half angle"),
        (rows_by_hand([0, 180, 90, -90], degrees=True), "degrees"),      # np.cos(90 / 2)
        (np.array([[0, 0, 0, 1], [0, 0, 1, 0], [0, h, 0, h], [-h, 0, 0, h]]), "xyzw"),
        (np.array([[1, 0, 0, 0], [0, 0, 0, 1], [h, 0, h, 0], [h, h, 0, 0]]), "conjugate"),
        (np.array([[1, 0, 0, 0], [0, 0, 0, 1], [0.5, 0, 0.5, 0], [0.5, -0.5, 0, 0]]), "unit"),
    ],
    "06.5": [
        (np.r_[np.cos(np.deg2rad(120)), np.sin(np.deg2rad(120)) * axis], "half angle"),
        (np.r_[np.cos(120 / 2), np.sin(120 / 2) * axis], "degrees"),
        (np.r_[np.cos(np.deg2rad(60)), np.sin(np.deg2rad(60)) * np.ones(3)], "unit axis"),
    ],
    "06.6": [
        (kl.quat_multiply(q_perm, q_z90), "order"),
        (kl.quat_multiply(kl.quat_multiply(q_z90, q_perm), kl.quat_conjugate(q_z90)),
         "conjugated"),
    ],
}
