r"""Product-of-exponentials (PoE) kinematics: screw axes, forward kinematics and the space
and body Jacobians.

A serial chain with home pose :math:`M` (the pose of the link at q = 0) and the joints'
screw axes :math:`S_i` written in the base frame at q = 0 has (Brockett's formula)

.. math:: T(q) = e^{[S_1]q_1} e^{[S_2]q_2} \cdots e^{[S_n]q_n} M
               = M e^{[B_1]q_1} \cdots e^{[B_n]q_n}, \qquad B_i = \mathrm{Ad}_{M^{-1}} S_i ,

with the body screw axes :math:`B_i` written in the link's frame. A revolute joint with
unit axis ω through the point p has :math:`S = [-\omega\times p;\ \omega]`, a prismatic one
moving along v has :math:`S = [v;\ 0]` (twists are ``[v; ω]``, linear first, as the
geometric Jacobian's rows; Modern Robotics stacks ``[ω; v]``).

The space Jacobian :math:`J_s` gives the spatial twist :math:`[\dot T T^{-1}]^\vee =
J_s \dot q`, the body Jacobian the body twist :math:`[T^{-1}\dot T]^\vee = J_b \dot q`:

.. math:: J_{s,i} = \mathrm{Ad}_{e^{[S_1]q_1}\cdots e^{[S_{i-1}]q_{i-1}}} S_i ,\qquad
          J_{b,i} = \mathrm{Ad}_{(e^{[B_{i+1}]q_{i+1}}\cdots e^{[B_n]q_n})^{-1}} B_i .

Neither is the geometric Jacobian ``robot.jacobian`` (the velocity of the link's origin
and ω, both in the base frame): with p the link's origin and R its rotation,
:math:`J = \begin{bmatrix} I & -[p]_\times\\ 0 & I\end{bmatrix} J_s =
\begin{bmatrix} R & 0\\ 0 & R\end{bmatrix} J_b`.
"""

from __future__ import annotations

import numpy as np

from .._validate import as_array
from ..errors import KinlibError
from ..spatial.se3 import adjoint, exp_se3
from ..spatial.transforms import check_transform, transform_inverse

__all__ = ["screw_axes", "poe_fk", "space_jacobian", "body_jacobian"]

_FRAMES = ("space", "body")


def screw_axes(robot, link=None, *, frame: str = "space"):
    r"""The screw axes and home pose of the chain from ``robot``'s root to ``link``.

    Returns ``(S, M)``: ``S`` is ``(6, robot.dof)``, column i the screw axis of the joint
    that ``q[i]`` drives — in the base frame (``frame="space"``) or in the link's frame at
    home (``frame="body"``) — and zero for joints not on the chain (like the geometric
    Jacobian's columns); ``M = robot.fk(zeros, link)``. Works for any :class:`~kinlib.Robot`
    (URDF or DH); a mimic joint on the chain is an error (two factors would share one q).

    >>> from kinlib.robots import planar_2r
    >>> S, M = screw_axes(planar_2r(1.0, 0.5))
    >>> S.T + 0.0  # each row: [v; ω]
    array([[ 0.,  0.,  0.,  0.,  0.,  1.],
           [ 0., -1.,  0.,  0.,  0.,  1.]])
    >>> M[:3, 3]
    array([1.5, 0. , 0. ])
    """
    if frame not in _FRAMES:
        raise KinlibError(f"screw_axes: frame must be 'space' or 'body', got {frame!r}")
    link = robot.resolve_link(link)
    zeros = np.zeros(robot.dof)
    poses = robot.link_poses(zeros)
    by_child = {jt.child: jt for jt in robot.joints}
    column = {name: i for i, name in enumerate(robot.joint_names)}
    S = np.zeros((6, robot.dof))
    at = link
    while at in by_child:
        jt = by_child[at]
        at = jt.parent
        if not jt.movable:
            continue
        if jt.mimic is not None:
            raise KinlibError(
                f"screw_axes: joint {jt.name!r} on the chain to {link!r} mimics "
                f"{jt.mimic.joint!r}; a product of exponentials needs one joint per q")
        F = poses[jt.parent] @ jt.origin  # the joint frame at home, where its axis lives
        u = F[:3, :3] @ (jt.axis / np.linalg.norm(jt.axis))
        if jt.type == "prismatic":
            S[:3, column[jt.name]] = u
        else:
            S[:3, column[jt.name]] = -np.cross(u, F[:3, 3])
            S[3:, column[jt.name]] = u
    M = poses[link]
    if frame == "body":
        S = adjoint(transform_inverse(M)) @ S
    return S, M


def _screws(S, q, name):
    S = as_array(S, name)
    if S.ndim != 2 or S.shape[0] != 6:
        raise KinlibError(f"{name}: expected the screw axes as a (6, n) array, one column per "
                          f"joint, got shape {S.shape}")
    a = as_array(q, "q")
    if a.ndim == 0 or a.shape[-1] != S.shape[1]:
        raise KinlibError(f"q: expected {S.shape[1]} joint values (shape (..., {S.shape[1]})) "
                          f"for {S.shape[1]} screw axes, got shape {a.shape}")
    return S, a


def _exps(S, q):
    """``exp([S_i] q_i)`` for every joint: ``(..., n, 4, 4)``."""
    return exp_se3(np.swapaxes(S, 0, 1) * q[..., :, None])


def poe_fk(M, S, q, *, frame: str = "space"):
    r"""Forward kinematics by the product of exponentials, batched over q ``(..., n)``.

    ``frame="space"``: :math:`e^{[S_1]q_1}\cdots e^{[S_n]q_n} M`;
    ``frame="body"``: :math:`M e^{[B_1]q_1}\cdots e^{[B_n]q_n}` (``S`` holds the B's).

    >>> from kinlib.robots import puma560
    >>> robot = puma560()
    >>> S, M = screw_axes(robot)
    >>> q = [0.1, -0.5, 0.9, 0.2, 0.4, -0.3]
    >>> bool(np.allclose(poe_fk(M, S, q), robot.fk(q), atol=1e-12))
    True
    """
    if frame not in _FRAMES:
        raise KinlibError(f"poe_fk: frame must be 'space' or 'body', got {frame!r}")
    M = check_transform(M, "M")
    if M.ndim != 2:
        raise KinlibError(f"M: expected one 4×4 home pose, got shape {M.shape}")
    S, q = _screws(S, q, "S")
    E = _exps(S, q)
    T = np.broadcast_to(np.eye(4), q.shape[:-1] + (4, 4))
    for i in range(S.shape[1]):
        T = T @ E[..., i, :, :]
    return T @ M if frame == "space" else M @ T


def space_jacobian(S, q):
    r"""The space Jacobian :math:`J_s(q)` ``(..., 6, n)``: the spatial twist
    :math:`[\dot T T^{-1}]^\vee = [v_s;\ \omega] = J_s \dot q` (rows ``[v; ω]``).

    Column 1 is :math:`S_1`; column i is :math:`S_i` carried by the joints before it.
    :math:`v_s` is the velocity of the body point at the base frame's origin, not of the
    link's origin.

    >>> from kinlib.robots import planar_2r
    >>> S, M = screw_axes(planar_2r(1.0, 1.0))
    >>> space_jacobian(S, [0.0, np.pi / 2]).round(12).T + 0.0
    array([[ 0.,  0.,  0.,  0.,  0.,  1.],
           [ 0., -1.,  0.,  0.,  0.,  1.]])
    """
    S, q = _screws(S, q, "S")
    E = _exps(S, q)
    n = S.shape[1]
    J = np.empty(q.shape[:-1] + (6, n))
    T = np.broadcast_to(np.eye(4), q.shape[:-1] + (4, 4))
    for i in range(n):  # Ad_T S_i = [R v + p × (R ω); R ω]
        w = T[..., :3, :3] @ S[3:, i]
        J[..., 3:, i] = w
        J[..., :3, i] = T[..., :3, :3] @ S[:3, i] + np.cross(T[..., :3, 3], w)  # (..., 3)
        T = T @ E[..., i, :, :]
    return J


def body_jacobian(B, q):
    r"""The body Jacobian :math:`J_b(q)` ``(..., 6, n)``: the body twist
    :math:`[T^{-1}\dot T]^\vee = J_b \dot q`, written in the link's own frame.

    Column n is :math:`B_n`; column i is :math:`B_i` carried back through the joints after
    it. ``J_b = Ad_{T⁻¹} J_s``.

    >>> from kinlib.robots import planar_2r
    >>> B, M = screw_axes(planar_2r(1.0, 1.0), frame="body")
    >>> body_jacobian(B, [0.0, np.pi / 2]).round(12).T + 0.0
    array([[1., 1., 0., 0., 0., 1.],
           [0., 1., 0., 0., 0., 1.]])
    """
    B, q = _screws(B, q, "B")
    E = _exps(B, q)
    n = B.shape[1]
    J = np.empty(q.shape[:-1] + (6, n))
    T = np.broadcast_to(np.eye(4), q.shape[:-1] + (4, 4))  # e^{B_{i+1}q}…e^{B_n q}
    for i in range(n - 1, -1, -1):  # Ad_{T⁻¹} B_i = [Rᵀ (v − p × ω); Rᵀ ω]
        Rt = np.swapaxes(T[..., :3, :3], -1, -2)
        J[..., 3:, i] = Rt @ B[3:, i]
        J[..., :3, i] = np.einsum("...ij,...j->...i", Rt,
                                  B[:3, i] - np.cross(T[..., :3, 3], B[3:, i]))
        T = E[..., i, :, :] @ T
    return J
