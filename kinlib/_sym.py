"""Symbolic (sympy) versions of the elementary constructors (private).

Imported only when a constructor is given sympy expressions, so ``import kinlib`` does
not import sympy.
"""

from __future__ import annotations

import sympy as sp

__all__ = ["axis_rotation", "skew", "axis_angle", "transform", "matrix"]


def matrix(x) -> sp.Matrix:
    """``x`` as a sympy Matrix (column vector for a flat sequence)."""
    if isinstance(x, sp.MatrixBase):
        return sp.Matrix(x)
    return sp.Matrix(x)


def axis_rotation(axis: int, theta) -> sp.Matrix:
    """Rotation about coordinate axis 0, 1, 2 (x, y, z) by ``theta``."""
    theta = sp.sympify(theta)
    c, s = sp.cos(theta), sp.sin(theta)
    if axis == 0:
        return sp.Matrix([[1, 0, 0], [0, c, -s], [0, s, c]])
    if axis == 1:
        return sp.Matrix([[c, 0, s], [0, 1, 0], [-s, 0, c]])
    return sp.Matrix([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def skew(v) -> sp.Matrix:
    x, y, z = (sp.sympify(e) for e in v)
    return sp.Matrix([[0, -z, y], [z, 0, -x], [-y, x, 0]])


def axis_angle(axis, angle) -> sp.Matrix:
    """Rodrigues' matrix ``cos θ I + sin θ [u]x + (1 − cos θ) u uᵀ``.

    A numeric axis is normalised exactly; a symbolic one is taken as given (assumed unit).
    """
    u = sp.Matrix([sp.sympify(e) for e in axis])
    if all(e.is_number for e in u):
        norm = sp.sqrt(sum(e**2 for e in u))
        if norm == 0:
            from .errors import KinlibError

            raise KinlibError("axis: expected a non-zero 3-vector, got [0, 0, 0]")
        u = u / norm
    theta = sp.sympify(angle)
    c, s = sp.cos(theta), sp.sin(theta)
    return c * sp.eye(3) + s * skew(u) + (1 - c) * (u * u.T)


def transform(R=None, p=None) -> sp.Matrix:
    Rm = sp.eye(3) if R is None else sp.Matrix(R)
    pm = sp.zeros(3, 1) if p is None else sp.Matrix([sp.sympify(e) for e in p])
    T = sp.eye(4)
    T[:3, :3] = Rm
    T[:3, 3] = pm
    return T
