"""Assignment 06's derivation: the space Jacobian of a planar 3R arm by the product of
exponentials, with sympy.

The student's ``space_jacobian_3r(theta1, theta2, theta3, l1, l2, l3)`` gets sympy symbols
(other names, exact lengths, one length for all links too) and returns J_s as a 6×3 sympy
Matrix, rows [v; ω]. The arm: three joints about the base z axis, through (0, 0, 0),
(l1, 0, 0) and (l1 + l2, 0, 0) at home, the end effector at (l1 + l2 + l3, 0, 0). The
reference is built with kinlib's :func:`~kinlib.exp_se3` of a symbolic angle and
:func:`~kinlib.adjoint`; the mistakes are the same construction carried wrongly
(:func:`planar_3r_jacobian`'s keywords), the body Jacobian and the geometric one (closed
forms of the planar arm). Each case's reference and models are made once per grading
process.

Why three joints: the product before joint 2 is a turn about the base origin (p = 0), so
with two joints the adjoint's [p]R block would never matter; joint 3's axis is carried by
a product that also moves the origin.

>>> import sympy as sp
>>> t = sp.symbols("theta1:4", real=True)
>>> l = sp.symbols("l1:4", positive=True)
>>> J = planar_3r_jacobian(*t, *l)
>>> J.shape, J.free_symbols <= {*t[:2], *l[:2]}  # no θ3, no l3
((6, 3), True)
>>> sp.simplify(J[0, 2])
l1*sin(theta1) + l2*sin(theta1 + theta2)
"""

from __future__ import annotations

from functools import lru_cache, partial

import numpy as np

import kinlib as kl
from kinlib.check.mistakes import ROWS

from .._checks import Check, Mistake, Verdict
from .._symbolic import symbolic_error_hint, symbolic_judge

__all__ = ["planar_3r_jacobian", "planar_3r_body_jacobian", "planar_3r_geometric_jacobian",
           "sj_symbols", "space_jacobian_3r_check"]


def _axes(l1, l2, moment=-1):
    """The screw axes [moment · ω × q; ω] of the three joints (ω = e_z, q on the x axis)."""
    import sympy as sp

    z = sp.Matrix([0, 0, 1])
    return [sp.Matrix.vstack(moment * z.cross(sp.Matrix([x, 0, 0])), z) for x in
            (0, l1, l1 + l2)]


def _mr_adjoint(T):
    """Modern Robotics' [[R, 0], [[p]R, R]] (for [ω; v] twists)."""
    import sympy as sp

    R, p = T[:3, :3], T[:3, 3]
    return sp.Matrix.vstack(sp.Matrix.hstack(R, sp.zeros(3)), sp.Matrix.hstack(kl.skew(p) * R, R))


def _swapped_adjoint(T):
    """[[R, R[p]], [0, R]]: the product [p]R written the other way round."""
    import sympy as sp

    R, p = T[:3, :3], T[:3, 3]
    return sp.Matrix.vstack(sp.Matrix.hstack(R, R * kl.skew(p)), sp.Matrix.hstack(sp.zeros(3), R))


def planar_3r_jacobian(t1, t2, t3, l1, l2, l3, *, carry=kl.adjoint, moment=-1):
    """J_s: column i = carry(T) S_i, T = e^{[S_1]θ_1} ⋯ e^{[S_{i−1}]θ_{i−1}}; the keywords
    make the mistakes (``carry``: another adjoint; ``moment=1``: the axes [ω × q; ω])."""
    import sympy as sp

    T, cols = sp.eye(4), []
    for S, theta in zip(_axes(l1, l2, moment), (t1, t2, t3), strict=True):
        cols.append(carry(T) * S)
        T = T * kl.exp_se3(S, theta)
    return sp.Matrix.hstack(*cols)


def _tip_columns(t1, t2, t3, l1, l2, l3, *, body: bool):
    """Columns [z × (p − q_i); z], q_i where joint i's axis is at θ and p the end effector's
    origin: the geometric Jacobian; ``body``: the linear parts turned into the end
    effector's frame, Rᵀ (z × (p − q_i)), which is J_b = Ad(T⁻¹) J_s of a planar arm."""
    import sympy as sp

    def along(a):
        return sp.Matrix([sp.cos(a), sp.sin(a), 0])

    z = sp.Matrix([0, 0, 1])
    points = [sp.zeros(3, 1), l1 * along(t1)]
    points.append(points[1] + l2 * along(t1 + t2))
    tip = points[2] + l3 * along(t1 + t2 + t3)
    turn = kl.rotz(-(t1 + t2 + t3)) if body else sp.eye(3)
    return sp.Matrix.hstack(*[sp.Matrix.vstack(turn * z.cross(tip - q), z) for q in points])


def planar_3r_body_jacobian(*args):
    """J_b = Ad(T⁻¹) J_s, T the end effector's pose (tested against kinlib's body_jacobian)."""
    return _tip_columns(*args, body=True)


def planar_3r_geometric_jacobian(*args):
    """[I, −[p]; 0, I] J_s: the velocity of the end effector's origin p (assignment 03)."""
    return _tip_columns(*args, body=False)


def _cached(f):
    """``f`` of the same arguments built once (every submission meets the same cases);
    not simplified, which would cost more than it saves the judge."""
    @lru_cache(maxsize=64)
    def once(*args):
        import sympy as sp

        return sp.ImmutableMatrix(f(*args))
    return once


# built once per grading process: load_assignment makes the checks anew for each submission
_REFERENCE = _cached(planar_3r_jacobian)
_MOMENT = _cached(partial(planar_3r_jacobian, moment=1))
_MR_ADJOINT = _cached(partial(planar_3r_jacobian, carry=_mr_adjoint))
_SWAPPED_ADJOINT = _cached(partial(planar_3r_jacobian, carry=_swapped_adjoint))
_BODY = _cached(planar_3r_body_jacobian)
_GEOMETRIC = _cached(planar_3r_geometric_jacobian)


def sj_symbols(rng: np.random.Generator) -> list[tuple]:
    """(θ1, θ2, θ3, l1, l2, l3): the angles real Symbols; the lengths positive symbols,
    other names, exact numbers, or one symbol for all three links."""
    import sympy as sp

    k = int(rng.integers(1, 10))
    t = sp.symbols("theta1:4", real=True)
    q = sp.symbols(f"q{k}:{k + 3}", real=True)
    length = sp.Symbol(f"L{k}", positive=True)
    exact = [sp.Rational(int(n), 10) for n in rng.choice(np.arange(3, 16), 3, replace=False)]
    return [(*t, *sp.symbols("l1:4", positive=True)),
            (*q, *sp.symbols(f"a{k} b{k} c{k}", positive=True)), (*t, *exact),
            (*q, length, length, length)]


def space_jacobian_3r_check(points: float) -> Check:
    """``space_jacobian_3r(theta1, theta2, theta3, l1, l2, l3)``: J_s, a 6×3 sympy Matrix."""
    import sympy as sp

    from kinlib.symbolic import simplify_rotation

    def untransformed(t1, t2, t3, l1, l2, l3):
        return sp.Matrix.hstack(*_axes(l1, l2))

    home = Mistake("untransformed", "you returned the screw axes at home: column i is joint "
                                    "i's axis where the joints before it have carried it, "
                                    "Ad(e^[S1]θ1 ⋯ e^[S(i−1)]θ(i−1)) S_i", untransformed)
    reference = _REFERENCE
    symbolic = symbolic_judge(
        reference, names=("theta1", "theta2", "theta3", "l1", "l2", "l3"),
        show=simplify_rotation, swaps=[(0, 1), (3, 4)],
        mistakes=[
            home,
            Mistake("moment", "the linear parts have the wrong sign: a revolute joint about ω "
                              "through q has S = [−ω × q; ω] = [q × ω; ω] (the velocity of "
                              "the body point at the origin), not [ω × q; ω]",
                    _MOMENT),
            ROWS.of(lambda *a: sp.Matrix.vstack(reference(*a)[3:, :], reference(*a)[:3, :]),
                    "your rows are in the order [ω; v] (Modern Robotics'): the course's J_s "
                    "has the linear part first, rows [v; ω], like its screw axes"),
            Mistake("mr adjoint", "you used Modern Robotics' adjoint [[R, 0], [[p]R, R]], "
                                  "which is for twists [ω; v]; for [v; ω] it is Ad_T = "
                                  "[[R, [p]R], [0, R]]",
                    _MR_ADJOINT),
            Mistake("adjoint", "the upper-right block of Ad_T is [p]R, not R[p]: Ad_T = "
                               "[[R, [p]R], [0, R]] (only column 3 shows it: before joint 2 "
                               "the product is a turn about the origin, p = 0)",
                    _SWAPPED_ADJOINT),
            Mistake("body", "this is the body Jacobian J_b = Ad(T⁻¹) J_s, in the end "
                            "effector's frame: the space Jacobian's columns are in the base "
                            "frame and do not depend on θ3 or l3", _BODY),
            Mistake("geometric", "this is the geometric Jacobian of assignment 03, the "
                                 "velocity of the end effector's origin: J_s's v is that of "
                                 "the body point passing through the base origin, so l3 and "
                                 "θ3 do not appear in it", _GEOMETRIC)])

    def judge(args, got):  # numbers: the home axes with exact lengths are numbers
        axes = untransformed(*args)
        if isinstance(got, np.ndarray) and got.shape == (6, 3) and got.dtype.kind in "iuf" \
                and not axes.free_symbols \
                and np.allclose(got, np.array(axes, dtype=float), atol=1e-12):
            return Verdict(False, home.key, home.message, reference(*args))
        return symbolic(args, got)
    return Check("space_jacobian_3r", points, "J_s of a planar 3R arm derived with sympy",
                 sj_symbols, judge=judge, on_error=symbolic_error_hint, time_limit=10.0)
