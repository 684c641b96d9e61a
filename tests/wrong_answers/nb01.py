"""Notebook 01: wrong answers a student would write."""

import numpy as np
import sympy as sp

import kinlib as kl

theta = sp.Symbol("theta", real=True)
c, s = sp.cos(theta), sp.sin(theta)
c45, s45 = np.cos(np.deg2rad(-45)), np.sin(np.deg2rad(-45))
R_AB = kl.matrix_from_euler([0.4, -0.3, 1.1], "ZYX")
R_x = np.array([[1, 0, 0], [0, c45, -s45], [0, s45, c45]])   # written out by hand

WRONG = {
    "01.1": [("a", "translation"), ("c", "rotation axis")],
    "01.2": [
        # X_B = (cos θ, 0, sin θ): the usual sign slip of R_Y, which is the transpose
        (sp.Matrix([[c, 0, -s], [0, 1, 0], [s, 0, c]]), "transposed"),
        (-kl.roty(theta), "sign"),
    ],
    "01.3": [(9, "symmetric"), (3, "right angles")],
    "01.4": [("a", "handedness"), ("c", "orthonormal")],
    "01.5": [
        ([True, False, True, False], "determinant"),     # "det = 1 makes it a rotation"
        ([True, False, False, False], "reflection"),     # rotations only
        ([True, True, False, True], "unit columns"),     # d's columns are unit vectors
    ],
    "01.6": [(R_AB[:, 1], "transposed")],
    "01.7": [
        (R_x @ [0, 1, 1], "translation"),
        (R_x.T @ [0, 1, 1] + [0, 0, 2], "transposed"),
        (R_x @ ([0, 1, 1] + np.array([0, 0, 2])), "order"),
        (np.array([[1, 0, 0], [0, np.cos(-45), -np.sin(-45)], [0, np.sin(-45), np.cos(-45)]])
         @ [0, 1, 1] + [0, 0, 2], "degrees"),
    ],
    "01.8": [
        (kl.rotz(np.deg2rad(30)) @ [1.0, 0.0, 0.0], "transposed"),     # the operator
        (np.array([np.cos(30), -np.sin(30), 0.0]), "degrees"),
    ],
}
