"""Notebook 14: wrong answers a student would write."""

import numpy as np
import sympy as sp

import kinlib as kl

phi1, phi2 = sp.symbols("phi_1 phi_2", real=True)
a1, a2 = sp.symbols("l_1 l_2", real=True)
t2 = sp.symbols("theta_2", real=True)
x = a1 * sp.cos(phi1) + a2 * sp.cos(phi2)
y = a1 * sp.sin(phi1) + a2 * sp.sin(phi2)
c12 = sp.cos(phi1 - phi2)

# J' with the columns in the order (φ2, φ1)
J_cols_swapped = sp.Matrix([x, y]).jacobian([phi2, phi1])
# J' by hand, copying seed 001's dy/dt line with its stray minus
J_seed_typo = sp.Matrix([[-a1 * sp.sin(phi1), -a2 * sp.sin(phi2)],
                         [-a1 * sp.cos(phi1), a2 * sp.cos(phi2)]])
# seed 001's DH matrix JᵀJ
G_dh = sp.Matrix([[a1**2 + a2**2 + 2 * a1 * a2 * sp.cos(t2), a2**2 + a1 * a2 * sp.cos(t2)],
                  [a2**2 + a1 * a2 * sp.cos(t2), a2**2]])

J_step = kl.planar_2r_jacobian(0.4, np.pi / 2, 1.0, 0.8)[:2]
step = np.array([0.01, -0.01])
h = 2 * np.pi / 96

WRONG = {
    "14.1": [("a", "link 1"), ("b", "theta2 alone")],
    "14.2": [
        (J_cols_swapped.T * J_cols_swapped, "swapped"),
        ((J_seed_typo.T * J_seed_typo).applyfunc(sp.trigsimp), "seed typo"),
        (sp.Matrix([[a1**2, a1 * a2 * sp.cos(phi1 + phi2)],
                    [a1 * a2 * sp.cos(phi1 + phi2), a2**2]]), "angle sum"),
        # read off the seed's (L1 δ1)² + (L2 δ2)² + 2 L1 L2 δ1 δ2 cos(θ1' − θ2')
        (sp.Matrix([[a1**2, 2 * a1 * a2 * c12], [2 * a1 * a2 * c12, a2**2]]), "doubled"),
        (sp.Matrix([[a1**2, 2 * a1 * a2 * c12], [0, a2**2]]), "symmetric"),
        (sp.Matrix([[a1**2, 0], [2 * a1 * a2 * c12, a2**2]]), "symmetric"),
        (sp.diag(a1**2, a2**2), "cross term"),
        (G_dh.subs(t2, phi2 - phi1), "coordinates"),
        (G_dh, "symbols"),                    # the DH answer, still in θ2
    ],
    "14.3": [
        (np.hypot(0.01, 0.01), "joint metric"),
        (0.8 * 0.01, "link 2"),
        (1.0 * 0.01 + 0.8 * 0.01, "both links"),
        (step @ J_step.T @ J_step @ step, "squared"),
        (np.linalg.norm(J_step @ [0.01, 0.01]), "step sign"),
    ],
    "14.4": [("a", "joint"), ("c", "same path")],
    "14.5": [
        ((93 - 2) * h, "long way"),
        (6 * h, "cells"),                     # 93, 94, 95, 0, 1, 2
        (4 * h, "rounded"),                   # cells 94 and 2
        (2 * np.pi - 6.0, "exact angle"),
        (6.0, "unwrapped"),
    ],
}
