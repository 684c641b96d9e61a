"""Notebook 03: wrong answers a student would write."""

import numpy as np
import sympy as sp

import kinlib as kl

a, b, g = sp.symbols("alpha beta gamma", real=True)
c, s = sp.cos, sp.sin
R_try = kl.matrix_from_axis_angle([1.0, -1.0, 2.0], 1.0)


def zyx_generic(R):
    return np.array([np.arctan2(R[1, 0], R[0, 0]), np.arctan2(-R[2, 0], np.hypot(R[0, 0], R[1, 0])),
                     np.arctan2(R[2, 1], R[2, 2])])


def zyx_plus_branch_everywhere(R):
    """The lock handled, but with the β = +90° formula at both locks."""
    cb = np.hypot(R[0, 0], R[1, 0])
    beta = np.arctan2(-R[2, 0], cb)
    if cb < 1e-9:
        return np.array([0.0, beta, np.arctan2(R[0, 1], R[1, 1])])
    return zyx_generic(R)


def zyx_no_lock(R):
    """The formulas of seed 002 as written, dividing by cos β: NaN at the lock."""
    cb = np.hypot(R[0, 0], R[1, 0])
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.array([np.arctan2(R[1, 0] / cb, R[0, 0] / cb), np.arctan2(-R[2, 0], cb),
                         np.arctan2(R[2, 1] / cb, R[2, 2] / cb)])


def zyx_gamma_first(R):
    """Returns (γ, β, α): the fixed-angle order."""
    return zyx_plus_branch_fixed(R)[::-1]


def zyx_plus_branch_fixed(R):
    cb = np.hypot(R[0, 0], R[1, 0])
    beta = np.arctan2(-R[2, 0], cb)
    if cb < 1e-9:
        return np.array([0.0, beta, np.sign(-R[2, 0]) * np.arctan2(R[0, 1], R[1, 1])])
    return zyx_generic(R)


def zyx_degrees(R):
    return np.rad2deg(zyx_plus_branch_fixed(R))


def similarity_backwards():
    first = kl.rotx(g)
    second = first * (first * kl.roty(b) * first.T)
    return second * (second * kl.rotz(a) * second.T)


# R_Y(β) written out by hand with the sines the wrong way round
Ry_by_hand = sp.Matrix([[c(b), 0, -s(b)], [0, 1, 0], [s(b), 0, c(b)]])

# 03.1: (1, 0, 1) turned by 90° about x then y, and about y then x, worked out by hand
x_then_y, y_then_x = [0, -1, -1], [1, 1, 0]

WRONG = {
    "03.1": [
        ([y_then_x, x_then_y], "order"),                    # R_X R_Y p for "x, then y"
        ([[0, 1, 1], [-1, 1, 0]], "sense"),                 # both turns clockwise
        ([x_then_y, x_then_y], "commute"),                  # "the order does not matter"
        ([[1, -1, 0], [1, 0, -1]], "one turn"),             # stopped after the first turn
    ],
    "03.2": [
        (kl.rotx(g) * kl.roty(b) * kl.rotz(a), "extrinsic"),
        (kl.rotx(a) * kl.roty(b) * kl.rotz(g), "sequence"),
        (kl.rotz(g) * kl.roty(b) * kl.rotx(a), "swapped"),
        ((kl.rotz(a) * kl.roty(b) * kl.rotx(g)).T, "transposed"),
        (kl.rotz(a) * Ry_by_hand * kl.rotx(g), "R_Y sign"),
    ],
    "03.3": [
        (kl.rotx(g) * kl.roty(b) * kl.rotz(a), "extrinsic"),     # in the order performed
        (similarity_backwards(), "similarity"),
        (kl.rotz(g) * kl.roty(b) * kl.rotx(a), "swapped"),       # α about x, the first turn
        (kl.rotx(a) * kl.roty(b) * kl.rotz(g), "sequence"),      # α-β-γ about x-y-z, in turn
        (kl.rotz(a) * Ry_by_hand * kl.rotx(g), "R_Y sign"),
    ],
    "03.4": [
        (zyx_generic(R_try), "sequence"),                        # (α, β, γ) not reversed
        (kl.euler_from_matrix(R_try, "XYZ"), "extrinsic"),        # upper case: moving axes
        (np.rad2deg(zyx_generic(R_try)[::-1]), "degrees"),
    ],
    "03.5": [("b", "det"), ("c", "unreachable"), ("d", "numerical")],
    "03.6": [
        (zyx_plus_branch_everywhere, "sign"),
        (zyx_no_lock, "gimbal"),
        (zyx_generic, "gimbal"),
        (zyx_gamma_first, "sequence"),
        (zyx_degrees, "degrees"),
    ],
}
