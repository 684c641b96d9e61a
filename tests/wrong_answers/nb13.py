"""Notebook 13: wrong answers a student would write."""

import numpy as np
import sympy as sp

import kinlib as kl

t1, t2 = sp.symbols("theta_1 theta_2", real=True)
l1s, l2s = sp.symbols("l_1 l_2", positive=True)
x = l1s * sp.cos(t1) + l2s * sp.cos(t1 + t2)
y = l1s * sp.sin(t1) + l2s * sp.sin(t1 + t2)
l1, l2 = 1.0, 0.8
J_tip = np.array([[-0.8, -0.8], [1.0, 0.0]])          # J at (0, π/2), by hand
J_w = kl.planar_2r_jacobian(0.3, np.pi / 2, l1, l2)    # all three rows
J_w2 = J_w[:2]

WRONG = {
    "13.1": [
        (sp.simplify(sp.Matrix([x, y]).jacobian([t2, t1]).det()), "sign"),     # columns swapped
        (l1s * l2s * sp.sin(t1), "swapped"),
    ],
    "13.2": [("b", "across"), ("c", "rank")],
    "13.3": [
        (J_tip.T @ [-1.0, 0.0], "transposed"),                # "the inverse of a rotation"
        (np.array([1.25, 0.0]), "swapped"),
        (np.linalg.pinv(kl.planar_2r_jacobian(0.0, np.pi / 2, l1, l2)) @ [-1.0, 0.0, 0.0],
         "phi row"),
    ],
    "13.4": [
        (np.linalg.det(J_w2 @ J_w2.T), "squared"),
        (np.sqrt(np.linalg.det(J_w.T @ J_w)), "phi row"),
        (abs(np.linalg.det(J_w @ J_w.T)) ** 0.5, "phi row"),
        (l1 * l2 * abs(np.sin(90)), "degrees"),
    ],
}
