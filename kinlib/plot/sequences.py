r"""Three-angle rotation sequences shown one elementary turn at a time.

A sequence turns the frame three times. *Intrinsic* (UPPERCASE, Euler angles): each turn is
about an axis of the **moving** frame, so after turns :math:`R_1 \cdots R_{n-1}` the next
one right-multiplies, :math:`R \leftarrow R\,R_k(t\,\theta_n)`, and its axis, written in the
fixed frame, is :math:`R\,\hat e_k`. *Extrinsic* (lowercase, fixed angles): each turn is
about a **fixed** axis :math:`\hat e_k` and left-multiplies, :math:`R \leftarrow
R_k(t\,\theta_n)\,R`. Both end at :func:`kinlib.matrix_from_euler` of the angles.

:func:`rotation_steps` gives the intermediate frames (pure numpy, for tests and for any
drawing); :func:`animate_rotation_sequences` draws several sequences side by side as one
HTML player (:func:`kinlib.plot.animate`).
"""

from __future__ import annotations

import numpy as np

from .._validate import as_array, parse_seq
from ..errors import KinlibError

__all__ = ["rotation_steps", "animate_rotation_sequences"]

_LETTERS = "xyz"


def _elementary(k: int, t: float) -> np.ndarray:
    """The rotation by ``t`` about the coordinate axis ``k`` (0, 1, 2 = x, y, z)."""
    c, s = np.cos(t), np.sin(t)
    i, j = (k + 1) % 3, (k + 2) % 3
    R = np.eye(3)
    R[i, i], R[i, j], R[j, i], R[j, j] = c, -s, s, c
    return R


def _as_steps(steps) -> int:
    if isinstance(steps, bool) or not isinstance(steps, int | np.integer) or steps < 1:
        raise KinlibError(f"steps: expected a whole number of frames per turn (>= 1), "
                          f"got {steps!r}")
    return int(steps)


def rotation_steps(angles, seq: str, steps: int = 12):
    r"""The frames of a three-angle sequence, turned one elementary rotation at a time.

    Parameters
    ----------
    angles : array_like, shape (3,)
        The three angles in radians, in the order of the letters of ``seq``.
    seq : str
        ``"ZYX"`` (intrinsic: moving axes) or ``"xyz"`` (extrinsic: fixed axes), any of
        the 24 sequences.
    steps : int
        Frames per elementary turn.

    Returns
    -------
    R : ndarray, shape (3·steps + 1, 3, 3)
        The frame's orientation in the fixed frame: the identity, then ``steps`` frames of
        the first turn, of the second, of the third; the last is
        ``matrix_from_euler(angles, seq)``.
    axes : ndarray, shape (3·steps + 1, 3)
        The unit axis, in the fixed frame, of the turn that leads to each frame (the first
        turn's axis for the identity frame).
    stage : ndarray of int, shape (3·steps + 1,)
        Which turn (0, 1, 2) leads to each frame.

    Examples
    --------
    Z-Y-X Euler angles: the second turn is about the *new* y axis, :math:`R_z(\alpha)\hat y`:

    >>> R, axes, stage = rotation_steps([np.pi / 2, 0.3, 0.2], "ZYX", steps=2)
    >>> R.shape, stage.tolist()
    ((7, 3, 3), [0, 0, 0, 1, 1, 2, 2])
    >>> axes[3].round(12) + 0.0
    array([-1.,  0.,  0.])
    >>> from kinlib import matrix_from_euler
    >>> bool(np.allclose(R[-1], matrix_from_euler([np.pi / 2, 0.3, 0.2], "ZYX")))
    True
    """
    order, intrinsic = parse_seq(seq)
    a = as_array(angles, "angles", (3,))
    if a.shape != (3,):
        raise KinlibError(f"angles: expected three angles, shape (3,), got shape {a.shape}")
    n = _as_steps(steps)
    frames, axes, stage = [np.eye(3)], [], [0]
    done = np.eye(3)
    for m, (k, theta) in enumerate(zip(order, a, strict=True)):
        axis = done[:, k].copy() if intrinsic else np.eye(3)[k]
        if m == 0:
            axes.append(axis)
        for t in np.arange(1, n + 1) / n:
            turn = _elementary(k, t * theta)
            frames.append(done @ turn if intrinsic else turn @ done)
            axes.append(axis)
            stage.append(m)
        done = frames[-1]
    return np.array(frames), np.array(axes), np.array(stage)


def _panel(spec, where: str):
    if not isinstance(spec, tuple | list) or len(spec) not in (2, 3):
        raise KinlibError(f"{where}: expected (angles, seq) or (angles, seq, names), got "
                          f"{spec!r}")
    names = tuple(spec[2]) if len(spec) == 3 else ("θ1", "θ2", "θ3")
    if len(names) != 3 or not all(isinstance(x, str) for x in names):
        raise KinlibError(f"{where}: names must be three strings, got {spec[2]!r}")
    return spec[0], spec[1], names


def animate_rotation_sequences(panels, *, steps: int = 4, hold: int = 3,
                               interval: float = 120, length: float = 1.0):
    r"""Several three-angle sequences animated side by side, one elementary turn at a time.

    Each panel shows the fixed frame (grey, labelled x, y, z), the turning frame (x red,
    y green, z blue), the frame it ends in (dotted) and the axis of the current turn (dashed
    black), with a title naming the turn: its angle and whether the axis is a moving or a
    fixed one. Each frame is rendered once, at 72 dpi, so a player of 16 frames stays small.

    Parameters
    ----------
    panels : sequence of (angles, seq) or (angles, seq, names)
        ``angles`` in letter order as for :func:`rotation_steps`; ``names`` label the three
        angles in the titles (e.g. ``("α", "β", "γ")``).
    steps : int
        Frames per turn.
    hold : int
        Extra frames that show the final orientation before the player loops.
    interval : float
        Milliseconds per frame.
    length : float
        Length of the drawn axes.

    Returns
    -------
    IPython.display.HTML
        The player (see :func:`kinlib.plot.animate`).

    Examples
    --------
    >>> a = np.deg2rad([40.0, 30.0, 60.0])
    >>> player = animate_rotation_sequences([(a, "ZYX"), (a[::-1], "xyz")], steps=1, hold=0)
    >>> "<script" in player.data
    True
    """
    import matplotlib.pyplot as plt

    from . import AXIS_COLORS, animate

    specs = list(panels) if isinstance(panels, tuple | list) else None
    if not specs:
        raise KinlibError(f"panels: expected a non-empty list of (angles, seq), got {panels!r}")
    specs = [_panel(s, f"panels[{i}]") for i, s in enumerate(specs)]
    if isinstance(hold, bool) or not isinstance(hold, int | np.integer) or hold < 0:
        raise KinlibError(f"hold: expected a whole number of frames >= 0, got {hold!r}")
    if not isinstance(length, int | float | np.number) or not np.isfinite(length) or length <= 0:
        raise KinlibError(f"length: expected a length > 0 for the drawn axes, got {length!r}")
    runs = [rotation_steps(a, s, steps) for a, s, _ in specs]
    count = len(runs[0][0])
    fig = plt.figure(figsize=(3.2 * len(specs), 3.4), dpi=72)
    axs = [fig.add_subplot(1, len(specs), i + 1, projection="3d") for i in range(len(specs))]
    fig.subplots_adjust(left=0.0, right=1.0, bottom=0.0, top=0.88, wspace=0.0)
    lim = 0.95 * length
    for ax, (R, _, _) in zip(axs, runs, strict=True):  # what stays: limits, {A}, the end
        for x in ("x", "y", "z"):
            getattr(ax, f"set_{x}lim")(-lim, lim)
        ax.set_box_aspect((1, 1, 1), zoom=1.35)
        ax.set_axis_off()  # no box: the grey fixed frame is the reference, and it draws faster
        for k in range(3):  # the fixed frame, grey; the final frame, faint and dotted
            ax.quiver(0, 0, 0, *(np.eye(3)[k] * length), color="0.7", lw=1,
                      arrow_length_ratio=0.08)
            ax.text(*(np.eye(3)[k] * 1.08 * length), _LETTERS[k], color="0.5")
            ax.plot(*np.outer([0, length], R[-1][:, k]).T, ":", color=AXIS_COLORS[k],
                    alpha=0.5)
    moving: list = []  # the artists of the current frame, replaced at each frame

    def draw(frame):
        f = min(frame, count - 1)
        while moving:
            moving.pop().remove()
        for ax, (angles, seq, names), (R, axes, stage) in zip(axs, specs, runs, strict=True):
            for k in range(3):
                moving.append(ax.quiver(0, 0, 0, *(R[f][:, k] * length), color=AXIS_COLORS[k],
                                        lw=2, arrow_length_ratio=0.12))
            moving.extend(ax.plot(*np.outer([-lim, lim], axes[f]).T, "k--", lw=1))
            m = stage[f]
            k = parse_seq(seq)[0][m]
            kind = "moving" if seq.isupper() else "fixed"
            deg = np.rad2deg(np.asarray(angles, dtype=float)[m])
            head = f"{seq}: {'intrinsic' if seq.isupper() else 'extrinsic'}"
            step = f"turn {m + 1}: {names[m]} = {deg:.0f}° about the {kind} {_LETTERS[k]}"
            step = "start" if f == 0 else step + (" (end)" if f == count - 1 else "")
            ax.set_title(f"{head}\n{step}", fontsize=10)
        return []

    return animate(fig, draw, count + int(hold), interval=interval)
