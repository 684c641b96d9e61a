"""Matplotlib pictures for the notebooks (matplotlib loads on use): frames and points,
the planar 2R arm, and animations as self-contained HTML players.

Axes are drawn x red, y green, z blue, as in every robotics text and in meshcat.
"""

from __future__ import annotations

import numpy as np

from .._validate import as_array
from ..errors import KinlibError
from ..spatial.transforms import check_transform
from ._player import offline_player

__all__ = ["axes_3d", "plot_frame", "plot_point", "arm_points", "plot_arm", "animate",
           "AXIS_COLORS"]

AXIS_COLORS = ("tab:red", "tab:green", "tab:blue")


def axes_3d(limits=((-1, 1), (-1, 1), (-1, 1)), *, figsize=(5, 5), title=None):
    """A new 3-D matplotlib axes with equal scaling on the given (x, y, z) limits."""
    import matplotlib.pyplot as plt

    lim = as_array(limits, "limits", (2,))
    if lim.shape != (3, 2) or (lim[:, 0] >= lim[:, 1]).any():
        raise KinlibError(f"limits: expected three (low, high) pairs with low < high, got "
                          f"{np.asarray(limits).tolist()}")
    fig = plt.figure(figsize=figsize)
    ax = fig.add_subplot(projection="3d")
    ax.set_xlim(*lim[0])
    ax.set_ylim(*lim[1])
    ax.set_zlim(*lim[2])
    ax.set_box_aspect(lim[:, 1] - lim[:, 0])
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    ax.set_zlabel("z")
    if title:
        ax.set_title(title)
    return ax


def plot_frame(ax, T=None, label=None, length=1.0):
    """Draw the frame ``T`` (4×4 pose in the axes' frame; default identity) as three arrows.

    Returns the three quiver artists (x, y, z) so tests and students can inspect them.
    """
    T = np.eye(4) if T is None else check_transform(T)
    if T.ndim != 2:
        raise KinlibError(f"T: expected one 4×4 transform, got shape {T.shape}")
    o = T[:3, 3]
    arrows = []
    for k in range(3):
        d = T[:3, k] * length
        arrows.append(ax.quiver(*o, *d, color=AXIS_COLORS[k], arrow_length_ratio=0.15))
    if label:
        ax.text(*(o - 0.1 * length * (T[:3, 0] + T[:3, 1])), f"{{{label}}}")
    return arrows


def plot_point(ax, p, label=None, color="black"):
    """Mark the point ``p`` (3,) with a dot and an optional label."""
    p = as_array(p, "p", (3,))
    if p.ndim != 1:
        raise KinlibError(f"p: expected one point (3,), got shape {p.shape}")
    dot = ax.scatter(*p, color=color, s=25)
    if label:
        ax.text(*p, f"  {label}")
    return dot


def arm_points(q, l1, l2) -> np.ndarray:
    """Base, elbow and tip of the planar 2R arm at ``q = (θ1, θ2)``: ``(..., 3, 2)``.

    The elbow is at ``l1 (cos θ1, sin θ1)``, the tip at the forward kinematics of seed 001
    (:func:`kinlib.planar_2r_fk`); ``q`` may be a batch ``(..., 2)``.

    >>> arm_points([0.0, np.pi / 2], 1.0, 0.5).round(12) + 0.0
    array([[0. , 0. ],
           [1. , 0. ],
           [1. , 0.5]])
    """
    from ..kinematics.planar import planar_2r_fk

    q = as_array(q, "q", (2,))
    elbow = float(l1) * np.stack([np.cos(q[..., 0]), np.sin(q[..., 0])], axis=-1)
    tip = planar_2r_fk(q[..., 0], q[..., 1], l1, l2)[..., :2, 3]
    return np.stack([np.zeros_like(elbow), elbow, tip], axis=-2)


def plot_arm(ax, q, l1, l2, **style):
    """Draw the 2R arm at ``q`` (one configuration) as the polyline base → elbow → tip;
    ``style`` goes to ``ax.plot`` (default: dots at the joints). Returns the line."""
    pts = arm_points(q, l1, l2)
    if pts.ndim != 2:
        raise KinlibError(f"q: expected one configuration (θ1, θ2), got shape "
                          f"{np.shape(q)}")
    style.setdefault("marker", "o")
    return ax.plot(*pts.T, **style)[0]


def animate(fig, draw, frames, *, interval: float = 150):
    """A matplotlib animation as a self-contained HTML player (``to_jshtml``).

    ``draw(k)`` updates ``fig`` for frame ``k`` (``frames``: how many, or the frame values
    to pass). The figure is closed afterwards, so the notebook shows the player only.
    Returns an ``IPython.display.HTML`` (its ``data`` is the page fragment). The player
    needs no network: its buttons are Unicode symbols, not matplotlib's Font Awesome icons
    from a CDN (which a remote lab or an offline laptop cannot reach: blank buttons).
    """
    import matplotlib.pyplot as plt
    from IPython.display import HTML
    from matplotlib import animation

    count = frames if isinstance(frames, int | np.integer) else len(list(frames))
    if count < 1:
        raise KinlibError(f"frames: expected at least one frame, got {frames!r}")
    if not np.isfinite(interval) or interval <= 0:
        raise KinlibError(f"interval: expected milliseconds > 0, got {interval!r}")
    # FuncAnimation redraws the canvas after each frame and the player's writer draws it
    # again to save it: with the first draw skipped every frame is rendered once (half the
    # time of a player, the same pictures)
    fig.canvas.draw_idle = lambda *args, **kwargs: None
    try:
        anim = animation.FuncAnimation(fig, draw, frames=frames, interval=interval)
        html = offline_player(anim.to_jshtml())
    finally:
        del fig.canvas.draw_idle
        plt.close(fig)
    return HTML(html)
