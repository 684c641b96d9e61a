"""Notebook 12: wrong answers a student would write."""

import numpy as np
import sympy as sp

import kinlib as kl
from kinlib.symbolic import simplify_rotation

t = sp.Symbol("t", real=True)
alpha, gamma = sp.Function("alpha", real=True)(t), sp.Function("gamma", real=True)(t)
rates = {alpha.diff(t): sp.Symbol(r"\dot{\alpha}", real=True),
         gamma.diff(t): sp.Symbol(r"\dot{\gamma}", real=True),
         alpha: sp.Symbol("alpha", real=True), gamma: sp.Symbol("gamma", real=True)}
R = kl.rotx(gamma) * kl.rotz(alpha)          # the tilting turntable of exercise 12.1
R_reversed = kl.rotz(alpha) * kl.rotx(gamma)  # the product in the other order


def omega_of(W):
    return simplify_rotation(kl.vee(W.subs(rates)))


def column_reversed(z, o, o_n):                  # r × ω instead of ω × r
    return np.concatenate([np.cross(np.subtract(o_n, o), z), z])


def column_omega_first(z, o, o_n):               # Modern Robotics' order
    return np.concatenate([z, np.cross(z, np.subtract(o_n, o))])


def column_about_the_origin(z, o, o_n):          # forgot the axis passes through o
    return np.concatenate([np.cross(z, o_n), z])


def column_swapped_points(z, o, o_n):            # lever arm o − o_n: the reversed sign again
    return np.hstack([np.cross(z, np.asarray(o) - np.asarray(o_n)), z])


w_turntable, w_wheel = np.array([0.0, 0.0, 2.0]), np.array([5.0, 0.0, 0.0])

WRONG = {
    "12.1": [
        (omega_of(R.T * R.diff(t)), "frame"),          # the body angular velocity RᵀṘ
        (kl.vee((R.T * R.diff(t)).subs(rates)), "frame"),   # the same, not simplified
        (omega_of(R * R.diff(t).T), "sign"),           # R Ṙᵀ = (Ṙ Rᵀ)ᵀ
        (omega_of(R_reversed.diff(t) * R_reversed.T), "order"),   # tilt and turn swapped
        (sp.Matrix([rates[gamma.diff(t)], 0, rates[alpha.diff(t)]]), "axis"),   # γ̇ x + α̇ z
    ],
    "12.2": [
        (w_turntable + w_wheel, "frame"),                                   # frames mixed up
        (w_turntable + kl.rotz(np.pi / 2).T @ w_wheel, "transposed"),
        (w_turntable + kl.rotz(90) @ w_wheel, "degrees"),
    ],
    "12.3": [
        (column_omega_first, "rows"),
        (column_reversed, "sign"),
        (column_swapped_points, "sign"),
        (column_about_the_origin, "lever arm"),
    ],
    "12.4": [("a", "sign"), ("c", "prismatic")],
}
