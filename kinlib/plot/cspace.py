r"""Pictures of the planar 2R arm's configuration space (notebook 14; matplotlib loads on use).

- :func:`plot_obstacles`: the :class:`~kinlib.Circle` and :class:`~kinlib.Polygon` obstacles
  in the arm's plane (and the arm's reach);
- :func:`cspace_image`: the C-space grid as a picture, each obstacle's region tinted with
  that obstacle's colour, so one sees which obstacle makes which region;
- :func:`plot_cspace`: that picture with :math:`\theta_1` to the right and :math:`\theta_2`
  up over :math:`[-\pi, \pi)^2`;
- :func:`wrap_path`: an unwrapped path (:attr:`kinlib.PlanResult.q`) folded back into
  :math:`[-\pi, \pi)^2`, broken where it crosses a seam of the torus.

>>> import kinlib as kl
>>> grid = kl.planar_2r_cspace(1.0, 0.8, [kl.Circle((0.0, 1.5), 0.2)], n=16)
>>> cspace_image(grid, ["tab:red"]).shape        # rows: θ2, columns: θ1
(16, 16, 3)
>>> wrap_path([[3.0, 0.0], [3.2, 0.0], [3.4, 0.0]]).round(3)
array([[ 3.   ,  0.   ],
       [   nan,    nan],
       [-3.083,  0.   ],
       [-2.883,  0.   ]])
"""

from __future__ import annotations

import numpy as np

from .._validate import as_array, wrap_angle
from ..errors import KinlibError
from ..planning.cspace import Circle, CSpaceGrid, Polygon, planar_2r_cspace

__all__ = ["CSPACE_EXTENT", "plot_obstacles", "cspace_image", "plot_cspace", "wrap_path"]

#: ``(left, right, bottom, top)`` of the C-space picture: θ1 and θ2 from −π to π
CSPACE_EXTENT = (-np.pi, np.pi, -np.pi, np.pi)

_TINT = 0.45  # how much white is mixed into an obstacle's colour in the C-space picture


def _obstacle_list(obstacles) -> list:
    obs = [obstacles] if isinstance(obstacles, Circle | Polygon) else obstacles
    try:
        obs = list(obs)
    except TypeError:
        obs = None
    if obs is None or not all(isinstance(o, Circle | Polygon) for o in obs):
        raise KinlibError(f"obstacles: expected a list of Circle and Polygon objects, got "
                          f"{obstacles!r}")
    return obs


def _colors(colors, count: int) -> list:
    from matplotlib.colors import to_rgb

    if colors is None:
        return [f"C{k}" for k in range(count)]
    colors = [colors] if isinstance(colors, str) else list(colors)
    if len(colors) != count:
        raise KinlibError(f"colors: expected one colour per obstacle ({count}), got "
                          f"{len(colors)}")
    for c in colors:
        try:
            to_rgb(c)
        except (TypeError, ValueError):
            raise KinlibError(f"colors: expected matplotlib colours, got {c!r}") from None
    return colors


def plot_obstacles(ax, obstacles, colors=None, *, reach=None, lim=2.0, alpha=0.45):
    """Draw obstacles in the arm's plane as filled patches on the 2-D axes ``ax``.

    Parameters
    ----------
    ax : matplotlib Axes
    obstacles : sequence of Circle or Polygon
    colors : sequence of matplotlib colours, optional
        One per obstacle (default: the colour cycle ``C0``, ``C1``, …).
    reach : float, optional
        The arm's reach ``l1 + l2``: drawn as a dotted circle round the base.
    lim : float
        The axes show ``[−lim, lim]²`` (metres), with equal scaling.
    alpha : float
        Opacity of the patches.

    Returns
    -------
    list of matplotlib patches, one per obstacle, in order.

    >>> import matplotlib.pyplot as plt, kinlib as kl
    >>> fig, ax = plt.subplots()
    >>> [p.center for p in plot_obstacles(ax, [kl.Circle((0.5, 1.0), 0.2)], ["red"])]
    [(0.5, 1.0)]
    >>> plt.close(fig)
    """
    from matplotlib import patches

    obs = _obstacle_list(obstacles)
    cols = _colors(colors, len(obs))
    lim = float(as_array(lim, "lim"))
    if not lim > 0:
        raise KinlibError(f"lim: expected a half-width > 0 (metres), got {lim!r}")
    out = []
    for o, c in zip(obs, cols, strict=True):
        patch = (patches.Circle(o.center, o.radius, color=c, alpha=alpha) if isinstance(o, Circle)
                 else patches.Polygon(o.vertices, closed=True, color=c, alpha=alpha))
        out.append(ax.add_patch(patch))
    if reach is not None:
        ax.add_patch(patches.Circle((0.0, 0.0), float(as_array(reach, "reach")), fill=False,
                                    ls=":", color="grey"))
    ax.set(xlim=(-lim, lim), ylim=(-lim, lim), aspect="equal", xlabel="x (m)", ylabel="y (m)")
    return out


def cspace_image(grid, colors=None) -> np.ndarray:
    """The C-space grid as an RGB picture, each obstacle's region in a light tint of its colour.

    Each obstacle of ``grid`` gets a grid of its own (same arm, shape and margin, see
    :func:`kinlib.planar_2r_cspace`); its occupied cells are painted ``0.55·colour + 0.45``
    (later obstacles over earlier ones), free cells stay white. The union of the tinted
    cells is ``grid.occupied``.

    Parameters
    ----------
    grid : CSpaceGrid
    colors : sequence of matplotlib colours, optional
        One per obstacle of ``grid`` (default: the colour cycle).

    Returns
    -------
    ndarray, shape (n2, n1, 3)
        Row ``j``, column ``i`` is cell ``(i, j)``: ready for ``imshow(origin="lower")``.
    """
    from matplotlib.colors import to_rgb

    if not isinstance(grid, CSpaceGrid):
        raise KinlibError(f"grid: expected a CSpaceGrid from planar_2r_cspace, got "
                          f"{type(grid).__name__}")
    cols = _colors(colors, len(grid.obstacles))
    img = np.ones(grid.shape[::-1] + (3,))
    for o, c in zip(grid.obstacles, cols, strict=True):
        occ = planar_2r_cspace(grid.l1, grid.l2, [o], n=grid.shape, margin=grid.margin).occupied
        img[occ.T] = (1 - _TINT) * np.array(to_rgb(c)) + _TINT
    return img


def plot_cspace(ax, image):
    """Show a C-space picture (from :func:`cspace_image`, or any ``(n2, n1)`` or
    ``(n2, n1, 3)`` array) over ``[−π, π)²``: θ1 to the right, θ2 up. Returns the image."""
    img = np.asarray(image)
    if img.ndim not in (2, 3) or (img.ndim == 3 and img.shape[2] not in (3, 4)):
        raise KinlibError(f"image: expected an (n2, n1) or (n2, n1, 3) array, got shape "
                          f"{img.shape}")
    shown = ax.imshow(img, origin="lower", extent=CSPACE_EXTENT)
    ax.set(xlabel=r"$\theta_1$ (rad)", ylabel=r"$\theta_2$ (rad)", aspect="equal")
    return shown


def wrap_path(q) -> np.ndarray:
    """A continuous joint path ``q`` (K, 2) folded into ``(−π, π]²`` for drawing on the torus.

    Angles are wrapped to ``(−π, π]`` (kinlib's one wrap interval); where a step jumps by
    more than π (the path crossed θ = ±π), a row of NaN is inserted, so that matplotlib
    breaks the line there instead of
    drawing it across the picture.

    Returns
    -------
    ndarray, shape (K + number of crossings, 2)
    """
    a = as_array(q, "q", (2,))
    if a.ndim != 2 or len(a) == 0:
        raise KinlibError(f"q: expected a path of configurations (K, 2), got shape {a.shape}")
    w = wrap_angle(a)
    jump = np.abs(np.diff(w, axis=0)).max(axis=1) > np.pi
    return np.insert(w, np.flatnonzero(jump) + 1, np.nan, axis=0)
