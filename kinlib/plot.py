"""Matplotlib pictures of frames and points for the notebooks (matplotlib loads on use).

Axes are drawn x red, y green, z blue, as in every robotics text and in meshcat.
"""

from __future__ import annotations

import numpy as np

from ._validate import as_array
from .errors import KinlibError
from .transforms import check_transform

__all__ = ["axes_3d", "plot_frame", "plot_point", "AXIS_COLORS"]

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
