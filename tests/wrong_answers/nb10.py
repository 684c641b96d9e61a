"""Notebook 10: wrong answers a student would write."""

import numpy as np
import sympy as sp

x, y, c2 = sp.symbols("x y c_2", real=True)
l1, l2 = sp.symbols("l_1 l_2", positive=True)


def ik_up(x, y, l1, l2):                  # the minus sign of the other root
    c2 = (x**2 + y**2 - l1**2 - l2**2) / (2 * l1 * l2)
    s2 = -np.sqrt(1 - c2**2)
    return np.arctan2(y, x) - np.arctan2(l2 * s2, l1 + l2 * c2), np.arctan2(s2, c2)


def ik_acos(x, y, l1, l2):                # the polar angle by arccos
    c2 = (x**2 + y**2 - l1**2 - l2**2) / (2 * l1 * l2)
    theta2 = np.arccos(c2)
    phi = np.arccos(x / np.sqrt(x**2 + y**2))
    return phi - np.arctan2(l2 * np.sin(theta2), l1 + l2 * c2), theta2


def ik_atan(x, y, l1, l2):                # arctan of the ratio
    c2 = (x**2 + y**2 - l1**2 - l2**2) / (2 * l1 * l2)
    s2 = np.sqrt(1 - c2**2)
    return np.arctan(y / x) - np.arctan2(l2 * s2, l1 + l2 * c2), np.arctan2(s2, c2)


def ik_plus(x, y, l1, l2):                # θ1 = φ + β
    c2 = (x**2 + y**2 - l1**2 - l2**2) / (2 * l1 * l2)
    s2 = np.sqrt(1 - c2**2)
    return np.arctan2(y, x) + np.arctan2(l2 * s2, l1 + l2 * c2), np.arctan2(s2, c2)


def ik_swapped(x, y, l1, l2):
    c2 = (x**2 + y**2 - l1**2 - l2**2) / (2 * l1 * l2)
    s2 = np.sqrt(1 - c2**2)
    theta1 = np.arctan2(y, x) - np.arctan2(l2 * s2, l1 + l2 * c2)
    return np.arctan2(s2, c2), theta1


def ik_degrees(x, y, l1, l2):
    c2 = (x**2 + y**2 - l1**2 - l2**2) / (2 * l1 * l2)
    s2 = np.sqrt(1 - c2**2)
    theta1 = np.arctan2(y, x) - np.arctan2(l2 * s2, l1 + l2 * c2)
    return np.degrees(theta1), np.degrees(np.arctan2(s2, c2))


WRONG = {
    "10.1": [
        # the law of cosines with the triangle's angle at the elbow, r² = l1² + l2² − 2 l1 l2 cos γ
        ((l1**2 + l2**2 - x**2 - y**2) / (2 * l1 * l2), "sign"),
        ((x**2 + y**2 - l1**2 - l2**2) / (l1 * l2), "factor 2"),
        ((x**2 + y**2 - l1**2 - l2**2) / 2 * l1 * l2, "precedence"),   # typed by hand
        (sp.solve(sp.Eq(x**2 + y**2, l1**2 + l2**2 + 2 * l1 * l2 * c2), c2), "type"),
    ],
    "10.2": [(ik_up, "other elbow"), (ik_acos, "acos"), (ik_atan, "atan"),
             (ik_plus, "beta sign"), (ik_swapped, "swapped"), (ik_degrees, "degrees")],
    "10.3": [([2, 2, 0], "boundary"), ([0, 2, 0], "boundary reachable"),
             ([1, 1, 0], "one inside"), ([1, 2, 1], "closest")],
    "10.4": [("a", "excluded"), ("b", "theta1 free"), ("c", "theta1 free")],
}
