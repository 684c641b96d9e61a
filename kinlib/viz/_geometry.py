"""Pure-numpy geometry for drawing a robot with three.js primitives (no meshcat here).

three.js (and so meshcat) builds a cylinder along its local **y** axis, centred on its
origin. To draw a link from point ``p0`` to point ``p1`` we take a cylinder of height 1,
stretch it along y to the length ``|p1 - p0|``, turn its y axis onto the direction
``p1 - p0`` and put its centre at the midpoint. The rotation that turns ``e_y`` onto a unit
vector ``u`` is the rotation about ``e_y × u`` by the angle between them (Rodrigues); when
``u = -e_y`` the cross product vanishes and any half turn about an axis ⟂ y will do (we use
the x axis).

Everything here is batched over leading dimensions.
"""

from __future__ import annotations

import numpy as np

__all__ = ["rotation_y_to", "segment_transforms", "axis_transforms", "decompose",
           "HIDDEN_SCALE"]

#: scale given to a zero-length segment: invisible, but still a valid (invertible) matrix
HIDDEN_SCALE = 1e-9
_EPS = 1e-12


def rotation_y_to(u) -> np.ndarray:
    """Rotation matrices ``R`` (..., 3, 3) with ``R @ [0, 1, 0] = u / |u|``.

    The rotation is the shortest one (about ``e_y × u``); antiparallel ``u`` gives a half
    turn about x; a zero vector gives the identity.

    >>> rotation_y_to([1.0, 0.0, 0.0]).round(12) + 0.0
    array([[ 0.,  1.,  0.],
           [-1.,  0.,  0.],
           [ 0.,  0.,  1.]])
    >>> (rotation_y_to([0.0, -2.0, 0.0]) @ [0.0, 1.0, 0.0]).round(12) + 0.0
    array([ 0., -1.,  0.])
    """
    u = np.asarray(u, dtype=float)
    norm = np.linalg.norm(u, axis=-1)
    safe = np.where(norm > _EPS, norm, 1.0)
    u = u / safe[..., None]
    # v = e_y × u = (u_z, 0, -u_x); |v| = sin(angle), u_y = cos(angle)
    v = np.stack([u[..., 2], np.zeros_like(u[..., 0]), -u[..., 0]], axis=-1)
    s = np.linalg.norm(v, axis=-1)
    c = u[..., 1]
    k = v / np.where(s > _EPS, s, 1.0)[..., None]
    K = np.zeros(u.shape[:-1] + (3, 3))
    K[..., 0, 1], K[..., 0, 2] = -k[..., 2], k[..., 1]
    K[..., 1, 0], K[..., 1, 2] = k[..., 2], -k[..., 0]
    K[..., 2, 0], K[..., 2, 1] = -k[..., 1], k[..., 0]
    R = np.eye(3) + s[..., None, None] * K + (1.0 - c)[..., None, None] * (K @ K)
    flip = (s <= _EPS) & (c < 0.0)  # antiparallel: half turn about x
    R[flip] = np.diag([1.0, -1.0, -1.0])
    R[norm <= _EPS] = np.eye(3)
    return R


def segment_transforms(p0, p1) -> np.ndarray:
    """Transforms (..., 4, 4) that map a unit-height y cylinder onto segments ``p0 → p1``.

    The result is ``[R diag(1, L, 1), (p0 + p1) / 2; 0, 1]``: the points ``(0, ±0.5, 0)`` of
    the unit cylinder land on ``p1`` and ``p0``. A zero-length segment is scaled to
    :data:`HIDDEN_SCALE` in every direction (hidden, no NaN).

    >>> T = segment_transforms([0.0, 0.0, 0.0], [0.0, 0.0, 2.0])
    >>> (T @ [0.0, 0.5, 0.0, 1.0]).round(12) + 0.0, (T @ [0.0, -0.5, 0.0, 1.0]).round(12) + 0.0
    (array([0., 0., 2., 1.]), array([0., 0., 0., 1.]))
    """
    p0, p1 = np.broadcast_arrays(np.asarray(p0, dtype=float), np.asarray(p1, dtype=float))
    d = p1 - p0
    length = np.linalg.norm(d, axis=-1)
    T = np.zeros(d.shape[:-1] + (4, 4))
    zero = length <= _EPS
    scale = np.ones(d.shape[:-1] + (3,))
    scale[..., 1] = length
    scale[zero] = HIDDEN_SCALE
    T[..., :3, :3] = rotation_y_to(d) * scale[..., None, :]
    T[..., :3, 3] = 0.5 * (p0 + p1)
    T[..., 3, 3] = 1.0
    return T


def axis_transforms(T_joint, axis) -> np.ndarray:
    """Transforms (..., 4, 4) placing a y cylinder on a joint axis.

    ``T_joint`` (..., 4, 4) is the joint frame in the world and ``axis`` (3,) the joint's
    unit axis in that frame; the cylinder's centre goes to the joint frame's origin and its
    y axis onto the axis direction in world coordinates.

    >>> T = axis_transforms(np.eye(4), [0.0, 0.0, 1.0])
    >>> (T[:3, :3] @ [0.0, 1.0, 0.0]).round(12) + 0.0
    array([0., 0., 1.])
    """
    T_joint = np.asarray(T_joint, dtype=float)
    world_axis = T_joint[..., :3, :3] @ np.asarray(axis, dtype=float)
    T = np.array(T_joint, dtype=float)
    T[..., :3, :3] = rotation_y_to(world_axis)
    return T


def decompose(M) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Split ``M = [R diag(s), p]`` into position (..., 3), rotation (..., 3, 3), scale (..., 3).

    A mirroring ``M`` (negative determinant: a mesh scaled ``1 -1 1``) gets a negative x
    scale and a proper rotation, as three.js's ``Matrix4.decompose`` splits it.

    >>> p, R, s = decompose(np.diag([2.0, 3.0, 4.0, 1.0]))
    >>> s, bool(np.allclose(R, np.eye(3)))
    (array([2., 3., 4.]), True)
    >>> p, R, s = decompose(np.diag([1.0, -1.0, 1.0, 1.0]))
    >>> s, R.round(12) + 0.0
    (array([-1.,  1.,  1.]), array([[-1.,  0.,  0.],
           [ 0., -1.,  0.],
           [ 0.,  0.,  1.]]))
    """
    M = np.asarray(M, dtype=float)
    scale = np.linalg.norm(M[..., :3, :3], axis=-2)
    scale[..., 0] *= np.where(np.linalg.det(M[..., :3, :3]) < 0, -1.0, 1.0)
    R = M[..., :3, :3] / np.where(scale != 0, scale, 1.0)[..., None, :]
    return M[..., :3, 3].copy(), R, scale
