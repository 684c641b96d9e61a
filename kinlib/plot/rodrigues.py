r"""The picture of Rodrigues' formula: a vector split along an axis, and its turn.

A unit axis :math:`k` splits a vector :math:`b` into the part along it and the part across it
(seed 000),

.. math:: b_\parallel = (k\cdot b)\,k, \qquad b_\perp = b - b_\parallel = -k\times(k\times b).

A rotation by :math:`\theta` about :math:`k` leaves :math:`b_\parallel` alone and turns
:math:`b_\perp` in the plane perpendicular to :math:`k`, which :math:`b_\perp` and
:math:`k\times b` span (perpendicular, of equal length):

.. math:: b_\perp' = b_\perp\cos\theta + (k\times b)\sin\theta, \qquad b' = b_\parallel + b_\perp'.

The tip of :math:`b` travels on the circle of radius :math:`|b_\perp|` about the point
:math:`b_\parallel` of the axis.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._validate import as_array, as_unit_vectors, is_symbolic
from ..errors import KinlibError

__all__ = ["RodriguesParts", "split_along_axis", "rodrigues_parts", "plot_rodrigues"]


@dataclass(frozen=True)
class RodriguesParts:
    """The pieces of one rotation of ``b`` by ``angle`` about the unit ``axis``: each a
    3-vector, ``circle`` (n, 3) the tip's full circle, ``arc`` (m, 3) the part from
    ``b`` to ``rotated``."""

    axis: np.ndarray
    angle: float
    b: np.ndarray
    parallel: np.ndarray
    perpendicular: np.ndarray
    k_cross_b: np.ndarray
    perpendicular_rotated: np.ndarray
    rotated: np.ndarray
    circle: np.ndarray
    arc: np.ndarray


def _one(x, name):
    a = as_array(x, name, (3,))
    if a.ndim != 1:
        raise KinlibError(f"{name}: expected one 3-vector, got shape {a.shape}")
    return a


def split_along_axis(b, axis):
    r"""The parts of ``b`` along and across ``axis``: ``(b_par, b_perp)``, with
    :math:`b_\parallel = (k\cdot b)\,k` and :math:`b_\perp = b - b_\parallel`.

    Numbers: ``b`` and ``axis`` are 3-vectors, the axis is normalised (a zero axis raises
    :class:`KinlibError`) and the parts are numpy arrays. Sympy: ``b`` and ``axis`` are 3×1
    matrices (or sequences of three expressions), the axis is taken as given, i.e. unit (as
    in :func:`kinlib.matrix_from_axis_angle`), and the parts are 3×1 ``sympy.Matrix``.

    >>> split_along_axis([1.0, 2.0, 3.0], [0.0, 0.0, 2.0])
    (array([0., 0., 3.]), array([1., 2., 0.]))
    >>> import sympy as sp
    >>> b_par, b_perp = split_along_axis(sp.symbols("x y z"), [0, 0, 1])
    >>> b_par.T, b_perp.T
    (Matrix([[0, 0, z]]), Matrix([[x, y, 0]]))
    """
    if is_symbolic(b, axis):
        import sympy as sp

        v, k = (sp.Matrix(list(x)) if not isinstance(x, sp.MatrixBase) else x.reshape(
            len(x), 1) for x in (b, axis))
        if v.shape != (3, 1) or k.shape != (3, 1):
            raise KinlibError(f"b, axis: expected two 3-vectors, got shapes {v.shape} and "
                              f"{k.shape}")
        par = k * (k.T * v)[0, 0]
        return par, v - par
    v = _one(b, "b")
    k = as_unit_vectors(_one(axis, "axis"), "axis")
    par = (k @ v) * k
    return par, v - par


def rodrigues_parts(b, axis, angle, *, n: int = 73) -> RodriguesParts:
    """Split ``b`` along ``axis`` (normalised; a zero axis raises) and turn it by ``angle``
    (radians), the way seed 000 derives Rodrigues' formula.

    >>> p = rodrigues_parts([1.0, 0.0, 1.0], [0.0, 0.0, 2.0], np.pi / 2)
    >>> p.parallel, p.perpendicular, p.k_cross_b
    (array([0., 0., 1.]), array([1., 0., 0.]), array([0., 1., 0.]))
    >>> p.rotated.round(12) + 0.0
    array([0., 1., 1.])
    """
    v = _one(b, "b")
    k = as_unit_vectors(_one(axis, "axis"), "axis")
    t = as_array(angle, "angle")
    if t.ndim != 0:
        raise KinlibError(f"angle: expected one angle in radians, got shape {t.shape}")
    if isinstance(n, bool) or not isinstance(n, int | np.integer) or n < 8:
        raise KinlibError(f"n: expected a whole number of points on the circle, at least 8, "
                          f"got {n!r}")
    t = float(t)
    par, perp = split_along_axis(v, k)
    kxb = np.cross(k, v)

    def turned(s):
        s = np.asarray(s, dtype=float)[..., None]
        return par + np.cos(s) * perp + np.sin(s) * kxb

    m = max(2, int(np.ceil(abs(t) / (2 * np.pi) * (n - 1))) + 1)
    return RodriguesParts(k, t, v, par, perp, kxb, turned(t) - par, turned(t),
                          turned(np.linspace(0.0, 2 * np.pi, n)), turned(np.linspace(0.0, t, m)))


def plot_rodrigues(ax, b, axis, angle, *, fit: bool = True):
    """Draw the pieces of :func:`rodrigues_parts` on a 3-D axes: the axis ``k`` (dashed),
    ``b`` and ``b′`` from the origin, ``b∥`` along the axis, ``b⊥``, ``k × b`` and ``b⊥′``
    from the centre of the circle the tip of ``b`` travels on, that circle and the arc from
    ``b`` to ``b′``, on a light disc: the plane perpendicular to ``k`` in which ``b⊥`` turns.
    Returns ``{name: artist}`` (the arrows are quivers).

    >>> import matplotlib.pyplot as plt
    >>> from kinlib.plot import axes_3d
    >>> sorted(plot_rodrigues(axes_3d(), [1.0, 0.0, 1.0], [0.0, 0.0, 1.0], 1.0))
    ['arc', 'b', 'b_par', 'b_perp', 'b_perp_rot', 'b_rot', 'circle', 'k', 'k_cross_b']
    >>> plt.close("all")
    """
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    p = rodrigues_parts(b, axis, angle)
    radius = np.linalg.norm(p.perpendicular)
    top = max(abs(p.axis @ p.b) + 0.6 * radius, 0.5 * np.linalg.norm(p.b), 1e-9)
    o, c = np.zeros(3), p.parallel

    def arrow(start, vec, color, label, lw=2.0, at=1.05):
        q = ax.quiver(*start, *vec, color=color, lw=lw, arrow_length_ratio=0.12)
        ax.text(*(start + at * vec), f" {label}", color=color, fontsize=10)
        return q

    out = {"k": arrow(o, top * p.axis, "black", "k", lw=1.2)}
    ax.plot(*np.c_[-0.25 * top * p.axis, o], color="black", lw=0.8, ls="--")
    out["circle"] = ax.plot(*p.circle.T, color="0.55", lw=1.0)[0]
    ax.add_collection3d(Poly3DCollection([p.circle], facecolor="0.5", alpha=0.12))
    out["arc"] = ax.plot(*p.arc.T, color="tab:purple", lw=2.5)[0]
    out["b"] = arrow(o, p.b, "tab:blue", "b")
    out["b_par"] = arrow(o, p.parallel, "tab:gray", "b∥", at=0.5)
    out["b_perp"] = arrow(c, p.perpendicular, "tab:orange", "b⊥", at=0.55)
    out["k_cross_b"] = arrow(c, p.k_cross_b, "tab:green", "k × b")
    out["b_perp_rot"] = arrow(c, p.perpendicular_rotated, "tab:brown", "b⊥′", at=0.55)
    out["b_rot"] = arrow(o, p.rotated, "tab:red", "b′")
    if fit:
        pts = np.vstack([p.circle, o, top * p.axis, -0.25 * top * p.axis])
        mid, half = pts.mean(axis=0), 0.55 * np.ptp(pts, axis=0).max()
        ax.set_xlim(mid[0] - half, mid[0] + half)
        ax.set_ylim(mid[1] - half, mid[1] + half)
        ax.set_zlim(mid[2] - half, mid[2] + half)
        ax.set_box_aspect((1, 1, 1))
        ax.locator_params(nbins=4)
    return out
