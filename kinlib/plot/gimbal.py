r"""A three-ring gimbal for an Euler-angle sequence: the picture of gimbal lock.

An intrinsic sequence ``"ABC"`` turns by :math:`\varphi_1` about axis A, then by
:math:`\varphi_2` about the once-turned B, then by :math:`\varphi_3` about the twice-turned C,
:math:`R = R_A(\varphi_1)\,R_B(\varphi_2)\,R_C(\varphi_3)`. A gimbal does the same with three
nested rings: ring 1 (outer) turns about the fixed A axis and carries ring 2, which turns
about B as ring 1 holds it and carries ring 3 (inner), which turns about C as ring 2 holds it.

Each ring is drawn as a circle whose **normal is the axis it turns about**, as that axis stands
after the rotations before it:

.. math:: n_1 = e_A, \qquad n_2 = R_A(\varphi_1)\,e_B, \qquad
          n_3 = R_A(\varphi_1)R_B(\varphi_2)\,e_C,

the three columns of the Euler-rate matrix :math:`E(\varphi)` (:func:`kinlib.euler_rate_matrix`,
:math:`\omega = E\,\dot\varphi`). A mark on each ring turns with its angle. All rings share
one centre, so rings 1 and 3 lie in one plane exactly when :math:`n_1 \parallel n_3`: gimbal
lock, at :math:`\varphi_2 = \pm 90^\circ` for three different axes (``"ZYX"``) and at
:math:`0` or :math:`180^\circ` when the first and last axes are the same (``"XYX"``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._validate import as_array, parse_seq
from ..errors import KinlibError
from ..spatial.rotations import rotx, roty, rotz
from . import AXIS_COLORS

__all__ = ["GimbalRings", "gimbal_rings", "plot_gimbal", "RING_RADII"]

#: radii of the outer, middle and inner ring
RING_RADII = (1.0, 0.8, 0.6)
_GREEK = ("α", "β", "γ")


@dataclass(frozen=True)
class GimbalRings:
    """The geometry of the three rings (index 0 = outer ring, turned first).

    ``frames`` (3, 3, 3): ring k's orientation, :math:`R_A(\\varphi_1)\\cdots` up to its own
    rotation; ``normals`` (3, 3): row k is the unit axis ring k turns about (column k of
    E); ``circles`` (3, n, 3): points of each ring; ``marks`` (3, 3): the point of each ring
    that turns with its angle; ``radii`` and ``seq`` as given."""

    frames: np.ndarray
    normals: np.ndarray
    circles: np.ndarray
    marks: np.ndarray
    radii: tuple
    seq: str


def _check(angles, seq, radii, n):
    a = as_array(angles, "angles", (3,))
    if a.ndim != 1:
        raise KinlibError(f"angles: expected one triple (φ1, φ2, φ3) in radians, got shape "
                          f"{a.shape}")
    axes, intrinsic = parse_seq(seq)
    if not intrinsic:
        raise KinlibError(f"seq: a gimbal is a chain of rings, each turning about an axis of "
                          f"the ring that carries it: expected an intrinsic (UPPERCASE) "
                          f"sequence such as 'ZYX', got {seq!r}")
    r = as_array(radii, "radii", (3,))
    if r.ndim != 1 or (r <= 0).any():
        raise KinlibError(f"radii: expected three positive radii (outer, middle, inner), got "
                          f"{np.asarray(radii).tolist()}")
    if isinstance(n, bool) or not isinstance(n, int | np.integer) or n < 8:
        raise KinlibError(f"n: expected a whole number of points per ring, at least 8, got "
                          f"{n!r}")
    return a, axes, tuple(float(x) for x in r)


def gimbal_rings(angles, seq: str = "ZYX", *, radii=RING_RADII, n: int = 73) -> GimbalRings:
    """The three rings of the gimbal at ``angles`` (radians, in the order of ``seq``).

    Ring k is the circle of radius ``radii[k]`` about the common centre, perpendicular to the
    axis it turns about; ``n`` points per ring (the first repeated at the end, so the
    polyline closes).

    >>> g = gimbal_rings([0.3, np.pi / 2, -0.4], "ZYX")
    >>> bool(abs(abs(g.normals[0] @ g.normals[2]) - 1) < 1e-12)   # rings 1 and 3: one plane
    True
    >>> g.normals[1].round(4) + 0.0                               # Rz(0.3) e_y
    array([-0.2955,  0.9553,  0.    ])
    """
    a, axes, r = _check(angles, seq, radii, n)
    turn = (rotx, roty, rotz)
    t = np.linspace(0.0, 2.0 * np.pi, n)
    frames, normals, circles, marks = [], [], [], []
    F = np.eye(3)
    for axis, angle, radius in zip(axes, a, r, strict=True):
        normals.append(F[:, axis])           # the axis as the rings before it hold it
        F = F @ turn[axis](angle)            # the ring turns with its own angle
        frames.append(F)
        u, w = F[:, (axis + 1) % 3], F[:, (axis + 2) % 3]
        circles.append(radius * (np.cos(t)[:, None] * u + np.sin(t)[:, None] * w))
        marks.append(radius * u)
    return GimbalRings(np.array(frames), np.array(normals), np.array(circles),
                       np.array(marks), r, seq)


def plot_gimbal(ax, angles, seq: str = "ZYX", *, radii=RING_RADII, body: bool = True,
                fit: bool = True, legend: bool = True, ticks: bool = False):
    """Draw the gimbal at ``angles`` on a 3-D axes: each ring in the colour of its axis
    letter (x red, y green, z blue), its axis as a thin dashed line, its mark as a dot and,
    with ``body``, the frame of the body it carries (the columns of R).

    ``fit`` sets equal limits around the rings (call ``ax.cla()`` before redrawing into the
    same axes) and, unless ``ticks``, leaves the axes without tick labels: the rings' size
    says nothing, and without ticks a picture renders faster (an animation renders every
    frame). Returns the three rings' lines, outer first.

    >>> import matplotlib.pyplot as plt
    >>> from kinlib.plot import axes_3d
    >>> rings = plot_gimbal(axes_3d(), [0.2, 0.5, -0.3])
    >>> [line.get_label() for line in rings]
    ['ring 1: α about Z', 'ring 2: β about Y', 'ring 3: γ about X']
    >>> plt.close("all")
    """
    from . import plot_frame

    g = gimbal_rings(angles, seq, radii=radii)
    axes, _ = parse_seq(seq)
    lines = []
    for k, axis in enumerate(axes):
        color, r, nk = AXIS_COLORS[axis], g.radii[k], g.normals[k]
        lines.append(ax.plot(*g.circles[k].T, color=color, lw=3.5 - k * 0.7,
                             label=f"ring {k + 1}: {_GREEK[k]} about {seq[k]}")[0])
        ax.plot(*np.c_[-1.15 * r * nk, 1.15 * r * nk], color=color, lw=0.9, ls="--")
        ax.scatter(*g.marks[k], color=color, s=28, edgecolors="black", linewidths=0.5)
    if body:
        T = np.eye(4)
        T[:3, :3] = g.frames[-1]
        plot_frame(ax, T, length=0.4 * min(g.radii))
    if fit:
        lim = 1.1 * max(g.radii)
        ax.set_xlim(-lim, lim)
        ax.set_ylim(-lim, lim)
        ax.set_zlim(-lim, lim)
        ax.set_box_aspect((1, 1, 1))
        if not ticks:
            ax.set_xticks([])
            ax.set_yticks([])
            ax.set_zticks([])
        ax.set_xlabel("x")
        ax.set_ylabel("y")
        ax.set_zlabel("z")
    if legend:
        ax.legend(handles=lines, loc="upper left", fontsize=8, frameon=False)
    return lines
