r"""A picture of one standard Denavit–Hartenberg row: the four parameters drawn on the two
joint axes they relate (matplotlib loads on use).

Row :math:`i` of a standard table places frame :math:`i` in frame :math:`i-1` by
:math:`A_i = R_z(\theta_i)\,T_z(d_i)\,T_x(a_i)\,R_x(\alpha_i)` (:func:`kinlib.dh_transform`).
Read on the axes (seed 001):

* :math:`\theta_i`: the angle from :math:`x_{i-1}` to :math:`x_i`, about :math:`z_{i-1}`;
* :math:`d_i`: the distance from :math:`o_{i-1}` to where :math:`x_i` meets :math:`z_{i-1}`
  (the *foot* of the common normal), along :math:`z_{i-1}`;
* :math:`a_i`: the distance from :math:`z_{i-1}` to :math:`z_i` along the common normal
  :math:`x_i`;
* :math:`\alpha_i`: the angle from :math:`z_{i-1}` to :math:`z_i`, about :math:`x_i`.

:func:`dh_geometry` computes what is drawn (the two frames, the foot, the segments of
:math:`d_i` and :math:`a_i`, the arcs of :math:`\theta_i` and :math:`\alpha_i`, and the two
consecutive links with their joints: link :math:`i-1`, which carries frame :math:`i-1` and
ends at joint :math:`i`, and link :math:`i`, which carries frame :math:`i` from joint
:math:`i` to joint :math:`i+1`); :func:`plot_dh_row` draws it on a 3-D axes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import KinlibError
from ..models.dh import dh_transform
from ..spatial.transforms import check_transform
from . import AXIS_COLORS, plot_frame

__all__ = ["DHGeometry", "dh_geometry", "plot_dh_row"]


@dataclass(frozen=True)
class DHGeometry:
    """What the picture of one DH row shows, in the coordinates of the axes.

    ``T_prev`` and ``T`` are the poses of frames :math:`i-1` and :math:`i`
    (``T = T_prev @ dh_transform(theta, d, a, alpha)``); ``foot`` is the point of
    :math:`z_{i-1}` where the common normal :math:`x_i` starts; ``d_segment`` runs from
    :math:`o_{i-1}` to the foot, ``a_segment`` from the foot to :math:`o_i` (each 2×3);
    ``theta_arc`` (n×3, centred at the foot) turns from :math:`x_{i-1}` to :math:`x_i`
    about :math:`z_{i-1}`; ``alpha_arc`` (n×3, centred at :math:`o_i`) turns from
    :math:`z_{i-1}` to :math:`z_i` about :math:`x_i`.

    The two links, each a 2×3 segment: ``link_prev`` (link :math:`i-1`) arrives along
    :math:`x_{i-1}` at :math:`o_{i-1}` on joint :math:`i`'s axis (in DH, :math:`x_{i-1}` is
    the common normal from joint :math:`i-1`'s axis, which lies beyond the picture);
    ``link`` (link :math:`i`) runs along the common normal :math:`x_i` from the foot on
    joint :math:`i`'s axis to :math:`o_i` on joint :math:`i+1`'s. The joints, each a 2×3
    segment of its axis: ``joint`` (joint :math:`i`, on :math:`z_{i-1}`) spans
    :math:`o_{i-1}` and the foot, where the two links meet it, and ``joint_next``
    (joint :math:`i+1`, on :math:`z_i`) is centred at :math:`o_i`; both reach ``radius``/2
    beyond those points.
    """

    theta: float
    d: float
    a: float
    alpha: float
    T_prev: np.ndarray
    T: np.ndarray
    foot: np.ndarray
    d_segment: np.ndarray
    a_segment: np.ndarray
    theta_arc: np.ndarray
    alpha_arc: np.ndarray
    radius: float
    link_prev: np.ndarray
    link: np.ndarray
    joint: np.ndarray
    joint_next: np.ndarray


def _scalar(x, name: str) -> float:
    if isinstance(x, bool) or not isinstance(x, int | float | np.integer | np.floating):
        if isinstance(x, np.ndarray) and x.shape == () and np.isrealobj(x):
            x = x.item()
        else:
            raise KinlibError(f"{name}: expected one real number, got {x!r}")
    if not math.isfinite(x):
        raise KinlibError(f"{name}: expected a finite number, got {x!r}")
    return float(x)


def _arc(center, axis, start, angle, radius, n):
    """``n`` points at ``radius`` from ``center``, turning the unit vector ``start`` (⟂ the
    unit ``axis``) by 0 … ``angle`` about ``axis`` (Rodrigues for a perpendicular vector)."""
    t = np.linspace(0.0, angle, n)[:, None]
    return center + radius * (np.cos(t) * start + np.sin(t) * np.cross(axis, start))


def dh_geometry(theta, d, a, alpha, *, T_prev=None, radius=None, n=48) -> DHGeometry:
    r"""The points and arcs that show the standard DH row ``(theta, d, a, alpha)``.

    ``T_prev`` is the pose of frame :math:`i-1` (default: the identity); ``radius`` the
    radius of the two arcs (default: a third of the larger of :math:`|a|`, :math:`|d|`,
    or 0.3); ``n`` the number of points per arc.

    >>> g = dh_geometry(np.pi / 2, 0.5, 1.0, np.pi / 2, radius=0.25)
    >>> g.foot, g.T[:3, 3].round(12) + 0.0      # up d along z0, then a along x1 = y0
    (array([0. , 0. , 0.5]), array([0. , 1. , 0.5]))
    >>> g.theta_arc[-1].round(12) + 0.0         # the θ arc ends on x1, at the foot
    array([0.  , 0.25, 0.5 ])
    """
    theta, d, a, alpha = (_scalar(v, k) for v, k in ((theta, "theta"), (d, "d"), (a, "a"),
                                                     (alpha, "alpha")))
    T_prev = np.eye(4) if T_prev is None else check_transform(T_prev, "T_prev")
    if T_prev.shape != (4, 4):
        raise KinlibError(f"T_prev: expected one 4×4 transform, got shape {T_prev.shape}")
    if radius is None:
        radius = max(abs(a), abs(d), 0.3) / 3.0
    radius = _scalar(radius, "radius")
    if radius <= 0.0:
        raise KinlibError(f"radius: expected a length > 0, got {radius!r}")
    if isinstance(n, bool) or not isinstance(n, int | np.integer) or n < 2:
        raise KinlibError(f"n: expected a whole number of points ≥ 2, got {n!r}")
    T = T_prev @ dh_transform(theta=theta, d=d, a=a, alpha=alpha)
    o_prev, x_prev, z_prev = T_prev[:3, 3], T_prev[:3, 0], T_prev[:3, 2]
    foot = o_prev + d * z_prev
    x_i, o_i, z_i = T[:3, 0], T[:3, 3], T[:3, 2]
    reach = 0.5 * radius
    low, high = min(0.0, d) - reach, max(0.0, d) + reach      # along z_{i-1}, from o_{i-1}
    return DHGeometry(
        theta, d, a, alpha, T_prev, T, foot,
        d_segment=np.stack([o_prev, foot]),
        a_segment=np.stack([foot, T[:3, 3]]),
        theta_arc=_arc(foot, z_prev, x_prev, theta, radius, int(n)),
        alpha_arc=_arc(T[:3, 3], x_i, z_prev, alpha, radius, int(n)),
        radius=radius,
        link_prev=np.stack([o_prev - 1.5 * radius * x_prev, o_prev]),
        link=np.stack([foot, o_i]),
        joint=np.stack([o_prev + low * z_prev, o_prev + high * z_prev]),
        joint_next=np.stack([o_i - 2 * reach * z_i, o_i + 2 * reach * z_i]),
    )


def _line(ax, points, **style):
    points = np.asarray(points)
    return ax.plot(points[:, 0], points[:, 1], points[:, 2], **style)[0]


def _cylinder(ax, segment, radius, n=20, **style):
    """An open cylinder of ``radius`` about the 2×3 ``segment``, as a surface."""
    p, q = segment
    u = (q - p) / np.linalg.norm(q - p)
    e = np.cross(u, [1.0, 0.0, 0.0] if abs(u[0]) < 0.9 else [0.0, 1.0, 0.0])
    e /= np.linalg.norm(e)
    f = np.cross(u, e)
    t = np.linspace(0.0, 2.0 * np.pi, n)
    ring = radius * (np.cos(t)[:, None] * e + np.sin(t)[:, None] * f)      # n×3
    X = np.stack([p + ring, q + ring])                                      # 2×n×3
    return ax.plot_surface(X[..., 0], X[..., 1], X[..., 2], **style)


def plot_dh_row(ax, theta, d, a, alpha, *, T_prev=None, radius=None, frame_length=None,
                index="i", links=True):
    r"""Draw the standard DH row ``(theta, d, a, alpha)`` on the 3-D axes ``ax``.

    Shows the joint axes :math:`z_{i-1}` (joint :math:`i`) and :math:`z_i` (joint
    :math:`i+1`) as long dash-dotted lines, frames :math:`i-1` and :math:`i`, the
    segments of :math:`d_i` (along :math:`z_{i-1}`) and :math:`a_i` (along the common
    normal :math:`x_i`), and the arcs of :math:`\theta_i` (about :math:`z_{i-1}`, from a
    dashed copy of :math:`x_{i-1}` at the foot of the normal) and :math:`\alpha_i` (about
    :math:`x_i`, from a dashed copy of :math:`z_{i-1}` at :math:`o_i`). With ``links``
    (the default) it draws the two consecutive links too, as grey bars — link
    :math:`i-1` arriving at joint :math:`i`, link :math:`i` from joint :math:`i` to joint
    :math:`i+1` — and the two joints as translucent cylinders on their axes. ``index``
    names the row in the labels. Returns ``(geometry, artists)``: the :class:`DHGeometry`
    and a dict of what was drawn (the lines ``"d"``, ``"a"``, ``"theta"``, ``"alpha"``,
    ``"z_prev"``, ``"z_next"``, ``"x_prev_copy"``, ``"z_prev_copy"``, and with ``links``
    the lines ``"link_prev"``, ``"link"`` and the surfaces ``"joint"``, ``"joint_next"``).
    """
    g = dh_geometry(theta, d, a, alpha, T_prev=T_prev, radius=radius)
    if not isinstance(index, str) or not index:
        raise KinlibError(f"index: expected a non-empty label such as 'i' or '2', got {index!r}")
    if not isinstance(links, bool):
        raise KinlibError(f"links: expected True or False, got {links!r}")
    if index.isdigit():
        now, before, after = index, str(int(index) - 1), str(int(index) + 1)
    else:
        now, before, after = index, f"{index}-1", f"{index}+1"
    L = _scalar(frame_length, "frame_length") if frame_length is not None else 1.6 * g.radius
    if L <= 0.0:
        raise KinlibError(f"frame_length: expected a length > 0, got {L!r}")
    o_prev, x_prev, z_prev = g.T_prev[:3, 3], g.T_prev[:3, 0], g.T_prev[:3, 2]
    o_i, x_i, z_i = g.T[:3, 3], g.T[:3, 0], g.T[:3, 2]
    span = abs(g.d) + 1.5 * L
    axis_style = dict(color="0.35", lw=1.0, ls="-.")
    art = {
        "z_prev": _line(ax, [o_prev - 0.8 * L * z_prev, o_prev + span * z_prev], **axis_style),
        "z_next": _line(ax, [o_i - 1.6 * L * z_i, o_i + 1.6 * L * z_i], **axis_style),
    }
    ax.text(*(o_prev + span * z_prev), f"  joint {now}: $z_{{{before}}}$", color="0.25")
    ax.text(*(o_i + 1.6 * L * z_i), f"  joint {after}: $z_{{{now}}}$", color="0.25")
    plot_frame(ax, g.T_prev, label=before, length=L)
    plot_frame(ax, g.T, label=now, length=L)
    ax.text(*(o_prev + 1.1 * L * x_prev), f"$x_{{{before}}}$", color=AXIS_COLORS[0])
    ax.text(*(o_i + 1.1 * L * x_i), f"$x_{{{now}}}$", color=AXIS_COLORS[0])
    helper = dict(color="0.5", lw=1.0, ls="--")
    art["x_prev_copy"] = _line(ax, [g.foot, g.foot + 1.3 * g.radius * x_prev],
                               **helper)
    art["z_prev_copy"] = _line(ax, [o_i, o_i + 1.3 * g.radius * z_prev], **helper)
    art["foot"] = ax.scatter(*g.foot, color="black", s=12)
    if links:
        bar = dict(color="0.55", lw=9.0, alpha=0.4, solid_capstyle="round")
        art["link_prev"] = _line(ax, g.link_prev, **bar)
        art["link"] = _line(ax, g.link, **bar)
        ax.text(*g.link_prev[0], f"link {before}  ", color="0.3", ha="right")
        ax.text(*(g.link.mean(axis=0) - 0.6 * g.radius * z_prev), f"link {now}",
                color="0.3", ha="center", va="top")
        body = dict(color="tab:cyan", alpha=0.25, linewidth=0.0, shade=False)
        art["joint"] = _cylinder(ax, g.joint, 0.22 * g.radius, **body)
        art["joint_next"] = _cylinder(ax, g.joint_next, 0.22 * g.radius, **body)
    art["d"] = _line(ax, g.d_segment, color="tab:orange", lw=3.0)
    art["a"] = _line(ax, g.a_segment, color="tab:purple", lw=3.0)
    art["theta"] = _line(ax, g.theta_arc, color=AXIS_COLORS[2], lw=2.0)
    art["alpha"] = _line(ax, g.alpha_arc, color=AXIS_COLORS[0], lw=2.0)
    side = np.cross(z_prev, x_i)          # away from the two segments, for the labels
    at_d = g.d_segment.mean(axis=0) - g.radius * (0.5 * side + 0.2 * x_prev)
    ax.text(*at_d, f"$d_{{{now}}}$", color="tab:orange", ha="right", fontsize=13)
    ax.text(*(g.a_segment.mean(axis=0) + 0.25 * g.radius * z_prev), f"$a_{{{now}}}$",
            color="tab:purple", fontsize=13)
    mid = len(g.theta_arc) // 2
    ax.text(*(g.foot + 1.35 * (g.theta_arc[mid] - g.foot)), f"$\\theta_{{{now}}}$",
            color=AXIS_COLORS[2], fontsize=13)
    ax.text(*(o_i + 1.35 * (g.alpha_arc[mid] - o_i)), f"$\\alpha_{{{now}}}$",
            color=AXIS_COLORS[0], fontsize=13)
    return g, art
