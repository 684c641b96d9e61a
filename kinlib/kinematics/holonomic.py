r"""The holonomic mobile base of seed 000 ("Global controls for base").

The robot's root link sits on a base that moves in the ground plane. *Holonomic* means it
can move in any direction of that plane without turning first: forward along its heading,
sideways along its lateral axis, and it can turn on the spot. Its pose is the transform

.. math:: {}^W T_B = \begin{bmatrix} R_z(\psi) & (x, y, 0)^T \\ 0 & 1 \end{bmatrix}

in kinlib's **z-up** world (ground plane ``z = 0``, yaw ``ψ`` about ``z``).

To move the base, the lecture transforms the base's local axes into world coordinates:
*heading* (where "forward" points) and *lateral* (where "left" points). They are free
vectors, so only the rotation applies (homogeneous coordinate 0,
:func:`kinlib.transform_vectors`). KinEval (three.js, **y-up**) calls them the base's
local **z** axis (heading, stored in ``robot_heading``) and local **x** axis (lateral,
``robot_lateral``); in kinlib's z-up frames the same two directions are the base's local
**x** axis (heading) and local **y** axis (lateral).

>>> T = base_pose(1.0, 2.0, np.pi / 2)
>>> heading, lateral = base_heading_lateral(T)
>>> heading.round(12) + 0.0, lateral.round(12) + 0.0
(array([0., 1., 0.]), array([-1.,  0.,  0.]))
>>> base_step(T, forward=0.5)[:3, 3].round(12)
array([1. , 2.5, 0. ])
"""

from __future__ import annotations

import numpy as np

from .._validate import as_array, broadcast
from ..errors import KinlibError
from ..spatial.transforms import check_transform, transform_vectors

__all__ = ["base_pose", "base_heading_lateral", "base_step"]


def _scalars(value, name):
    """``value`` as a finite float array (any shape), else a clear :class:`KinlibError`."""
    if isinstance(value, bool | np.bool_):
        raise KinlibError(f"{name}: expected a number, got the boolean {value!r}")
    return as_array(value, name)


def _yaw_matrices(yaw: np.ndarray) -> np.ndarray:
    c, s = np.cos(yaw), np.sin(yaw)
    R = np.zeros(yaw.shape + (3, 3))
    R[..., 0, 0], R[..., 0, 1] = c, 0.0 - s  # 0.0 - s: no "-0." at yaw 0
    R[..., 1, 0], R[..., 1, 1] = s, c
    R[..., 2, 2] = 1.0
    return R


def base_pose(x, y, yaw) -> np.ndarray:
    r"""Pose ``T_world_base`` of a base at ``(x, y)`` on the ground, turned by ``yaw``.

    Parameters
    ----------
    x, y : float or array_like
        Position on the ground plane ``z = 0`` (metres).
    yaw : float or array_like
        Rotation about the world ``z`` axis (radians); ``yaw = 0`` heads along world ``x``.
        The three inputs broadcast; the result has shape ``(..., 4, 4)``.

    Returns
    -------
    ndarray
        :math:`\begin{bmatrix} R_z(\text{yaw}) & (x, y, 0)^T \\ 0 & 1 \end{bmatrix}`.

    Examples
    --------
    >>> base_pose(5.0, 3.0, 0.0)
    array([[1., 0., 0., 5.],
           [0., 1., 0., 3.],
           [0., 0., 1., 0.],
           [0., 0., 0., 1.]])
    >>> base_pose([0.0, 1.0], 0.0, [0.0, np.pi]).shape
    (2, 4, 4)
    """
    xs, ys, yaws = _scalars(x, "x"), _scalars(y, "y"), _scalars(yaw, "yaw")
    batch = broadcast((xs, 0, "x"), (ys, 0, "y"), (yaws, 0, "yaw"))
    T = np.zeros(batch + (4, 4))
    T[..., :3, :3] = _yaw_matrices(np.broadcast_to(yaws, batch))
    T[..., 0, 3] = xs
    T[..., 1, 3] = ys
    T[..., 3, 3] = 1.0
    return T


def base_heading_lateral(T_world_base) -> tuple[np.ndarray, np.ndarray]:
    """The base's heading and lateral directions in world coordinates.

    ``heading`` is the base's local ``x`` axis and ``lateral`` its local ``y`` axis, each
    mapped into the world as a free vector (rotation only, no translation). In KinEval
    (three.js, y-up) the same vectors are the local ``z`` (``robot_heading``) and local
    ``x`` (``robot_lateral``) axes; kinlib's world is z-up.

    Parameters
    ----------
    T_world_base : array_like, shape (..., 4, 4)
        Pose of the base in the world (a rigid transform).

    Returns
    -------
    heading, lateral : ndarray, shape (..., 3)
        Unit vectors in world coordinates.

    Examples
    --------
    >>> h, l = base_heading_lateral(base_pose(0.0, 0.0, np.pi / 6))
    >>> h.round(4), l.round(4)
    (array([0.866, 0.5  , 0.   ]), array([-0.5  ,  0.866,  0.   ]))
    """
    T = check_transform(T_world_base, "T_world_base")
    heading = transform_vectors(T, [1.0, 0.0, 0.0])
    lateral = transform_vectors(T, [0.0, 1.0, 0.0])
    return heading, lateral


def base_step(T_world_base, forward=0.0, lateral=0.0, turn=0.0) -> np.ndarray:
    r"""Move a holonomic base: translate in its own axes, then turn about its own ``z``.

    The new pose is

    .. math:: T' = \text{Trans}(f\,h + l\,s)\; T \; R_z(\text{turn}),

    with ``h, s`` the heading and lateral vectors of :func:`base_heading_lateral`: the base
    first slides ``forward`` metres along its heading and ``lateral`` metres along its
    lateral axis (positive = to its left), then yaws by ``turn`` radians about its own
    ``z`` axis (positive = counter-clockwise seen from above), staying where it is.

    Parameters
    ----------
    T_world_base : array_like, shape (..., 4, 4)
    forward, lateral, turn : float or array_like
        Broadcast against the batch of ``T_world_base``.

    Returns
    -------
    ndarray, shape (..., 4, 4)

    Examples
    --------
    >>> T = base_step(base_pose(0.0, 0.0, 0.0), forward=1.0, lateral=2.0, turn=np.pi / 2)
    >>> T.round(12) + 0.0
    array([[ 0., -1.,  0.,  1.],
           [ 1.,  0.,  0.,  2.],
           [ 0.,  0.,  1.,  0.],
           [ 0.,  0.,  0.,  1.]])
    """
    T = check_transform(T_world_base, "T_world_base")
    f, s, t = _scalars(forward, "forward"), _scalars(lateral, "lateral"), _scalars(turn, "turn")
    batch = broadcast((T, 2, "T_world_base"), (f, 0, "forward"), (s, 0, "lateral"),
                      (t, 0, "turn"))
    heading, side = base_heading_lateral(T)
    out = np.array(np.broadcast_to(T, batch + (4, 4)))
    out[..., :3, 3] += f[..., None] * heading + s[..., None] * side
    out[..., :3, :3] = out[..., :3, :3] @ _yaw_matrices(np.broadcast_to(t, batch))
    return out
