"""Symbolic (sympy) versions of the elementary constructors (private).

Imported only when a constructor is given sympy expressions, so ``import kinlib`` does
not import sympy.
"""

from __future__ import annotations

import sympy as sp

from ..errors import KinlibError

__all__ = [
    "axis_angle", "axis_rotation", "dh", "matrix", "scalar", "skew", "transform", "vector",
    "vee",
]


def scalar(e, name: str):
    """``e`` as one sympy expression; text, matrices and lists are errors."""
    if not isinstance(e, str | bytes):
        try:
            out = sp.sympify(e)
        except (sp.SympifyError, TypeError, ValueError):
            out = None
        if isinstance(out, sp.Expr) and not out.is_Matrix:  # MatrixExpr is an Expr
            return out
    text = repr(e).replace("\n", " ")
    raise KinlibError(
        f"{name}: expected a number or a sympy expression, got {type(e).__name__} "
        f"{text if len(text) <= 60 else text[:57] + '...'}"
    )


def vector(v, name: str, n: int = 3) -> list:
    """``v`` as a list of ``n`` sympy expressions."""
    try:
        items = [] if isinstance(v, str | bytes) else list(v)
    except TypeError:
        items = []
    if len(items) != n:
        raise KinlibError(
            f"{name}: expected {n} numbers or sympy expressions, got {type(v).__name__} "
            f"{v!r}"
        )
    return [scalar(e, name) for e in items]


def axis_rotation(axis: int, theta) -> sp.Matrix:
    """Rotation about coordinate axis 0, 1, 2 (x, y, z) by ``theta``."""
    theta = scalar(theta, "theta")
    c, s = sp.cos(theta), sp.sin(theta)
    if axis == 0:
        return sp.Matrix([[1, 0, 0], [0, c, -s], [0, s, c]])
    if axis == 1:
        return sp.Matrix([[c, 0, s], [0, 1, 0], [-s, 0, c]])
    return sp.Matrix([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def skew(v) -> sp.Matrix:
    x, y, z = vector(v, "v")
    return sp.Matrix([[0, -z, y], [z, 0, -x], [-y, x, 0]])


def vee(S) -> sp.Matrix:
    """The 3×1 vector of a symbolic skew-symmetric matrix; an error unless S = −Sᵀ provably.

    Provably by kinlib.symbolic's rule, without a ``simplify()`` search: each entry of
    S + Sᵀ expands, or reduces by :func:`kinlib.symbolic.trig_reduce`, to exactly 0. So
    Ṙ Rᵀ of a product of rotations passes (its skewness needs sin² + cos² = 1); a matrix
    that is skew only for a unit axis, or by an identity outside trig_reduce's rules, is
    refused, with the entry that did not reduce.
    """
    from . import trig_reduce

    M = matrix(S, (3, 3), "S")
    for i, j in ((0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)):
        e = M[i, j] + M[j, i]
        if sp.expand(e) != 0 and trig_reduce(e) != 0:
            text = str(e) if len(str(e)) <= 80 else str(e)[:77] + "..."
            raise KinlibError(
                f"S: expected a skew-symmetric matrix (S = -Sᵀ), but S[{i}, {j}] + S[{j}, {i}] "
                f"= {text} does not reduce to 0 (kinlib.symbolic.trig_reduce); if S is skew "
                "only for a unit axis, reduce it first: trig_reduce(S, unit=[kx, ky, kz])"
            )
    return sp.Matrix([M[2, 1], M[0, 2], M[1, 0]])


def axis_angle(axis, angle) -> sp.Matrix:
    """Rodrigues' matrix ``cos θ I + sin θ [u]x + (1 − cos θ) u uᵀ``.

    A numeric axis is normalised exactly; a symbolic one is taken as given (assumed unit).
    """
    u = sp.Matrix(vector(axis, "axis"))
    if all(e.is_number for e in u):
        norm = sp.sqrt(sum(e**2 for e in u))
        if norm == 0:
            raise KinlibError("axis: expected a non-zero 3-vector, got [0, 0, 0]")
        u = u / norm
    theta = scalar(angle, "angle")
    c, s = sp.cos(theta), sp.sin(theta)
    return c * sp.eye(3) + s * skew(u) + (1 - c) * (u * u.T)


def matrix(X, shape: tuple[int, int], name: str) -> sp.Matrix:
    """``X`` as a sympy Matrix of expressions of the given shape, else a KinlibError."""
    try:
        M = None if isinstance(X, str | bytes) else sp.Matrix(X)
    except (sp.SympifyError, TypeError, ValueError):  # ValueError includes ShapeError
        M = None
    if M is None or M.shape != shape:
        got = "" if M is None else f" of shape {M.shape}"
        raise KinlibError(f"{name}: expected a {shape[0]}×{shape[1]} matrix, got "
                          f"{type(X).__name__}{got}")
    return M


def transform(R=None, p=None) -> sp.Matrix:
    Rm = sp.eye(3) if R is None else matrix(R, (3, 3), "R")
    pm = sp.zeros(3, 1) if p is None else sp.Matrix(vector(p, "p"))
    T = sp.eye(4)
    T[:3, :3] = Rm
    T[:3, 3] = pm
    return T


def dh(theta, d, a, alpha, *, modified: bool) -> sp.Matrix:
    """Standard ``Rz(θ) Tz(d) Tx(a) Rx(α)`` or modified ``Rx(α) Tx(a) Rz(θ) Tz(d)``."""
    th, d, a, al = (scalar(x, n) for x, n in ((theta, "theta"), (d, "d"), (a, "a"),
                                               (alpha, "alpha")))

    def rot(axis, angle):
        T = sp.eye(4)
        T[:3, :3] = axis_rotation(axis, angle)
        return T

    def trans(axis, dist):
        T = sp.eye(4)
        T[axis, 3] = dist
        return T

    if modified:
        return rot(0, al) * trans(0, a) * rot(2, th) * trans(2, d)
    return rot(2, th) * trans(2, d) * trans(0, a) * rot(0, al)
