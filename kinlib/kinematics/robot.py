"""``Robot``: a kinematic tree of links and joints, and its forward kinematics.

The pose of every link follows the matrix stack of seed 000: start at the root link,
and for each joint going outwards multiply the parent's pose by the joint's fixed origin
and by the motion of the joint variable,

``T_world_child = T_world_parent @ T_origin(xyz, rpy) @ motion(axis, q)``,

where ``motion`` is a rotation about the axis (revolute, continuous) or a translation
along it (prismatic). Every configuration in a batch is computed at once.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np

from .._validate import as_array, fmt_index
from ..conventions import GIMBAL_TOL, IK_POSITION_TOL, IK_ROTATION_TOL, LIMIT_TOL
from ..errors import KinlibError, TreeError
from ..models.dh_tree import dh_tree
from ..models.tree import Joint, Link, check_tree, mimic_sources
from ..models.urdf import read_urdf
from ..models.urdf_write import urdf_from_robot
from . import _fk
from .analytic import analytic_jacobian
from .ik import solve_ik

__all__ = ["Robot", "load_urdf"]


class Robot:
    """A kinematic tree: links joined by revolute, continuous, prismatic and fixed joints.

    Parameters
    ----------
    name : str
    links : sequence of :class:`kinlib.models.tree.Link`
    joints : sequence of :class:`kinlib.models.tree.Joint`
    poses : mapping of pose name to q (length ``dof``), optional
        Named configurations, e.g. ``{"zero": [0, ...], "ready": [...]}``.
    reference : str, optional
        Where the model's numbers come from.
    dh : (rows, convention), optional
        The Denavit–Hartenberg table the links and joints were built from (what
        :meth:`Robot.from_dh` passes): kept as :attr:`dh_rows` and :attr:`dh_convention`
        (both None for a robot not built from a table).

    The order of ``q`` is :attr:`joint_names`: the movable joints that do not mimic
    another, in the order given. Build robots with :func:`kinlib.load_urdf`,
    :meth:`Robot.from_dh` or the models in :mod:`kinlib.robots`.

    >>> from kinlib.robots import planar_2r
    >>> arm = planar_2r(1.0, 0.5)
    >>> arm.dof, arm.joint_names, arm.tip
    (2, ['joint1', 'joint2'], 'link2')
    >>> arm.fk([np.pi / 2, 0.0])[:3, 3].round(12)
    array([0. , 1.5, 0. ])
    """

    def __init__(self, name, links, joints, *, poses=None, reference=None, dh=None):
        if not isinstance(name, str) or not name:
            raise KinlibError(f"Robot: name must be a non-empty string, got {name!r}")
        links, joints = tuple(links), tuple(joints)
        for x, cls in [(lk, Link) for lk in links] + [(jt, Joint) for jt in joints]:
            if not isinstance(x, cls):
                raise KinlibError(f"Robot {name!r}: expected {cls.__name__} objects, got "
                                  f"{type(x).__name__}")
        self.name = name
        self.reference = reference
        self.links = links
        self.joints = joints
        self.root, self._order = check_tree(links, joints)
        sources = mimic_sources(joints)
        self.dh_rows, self.dh_convention = (None, None) if dh is None else (tuple(dh[0]), dh[1])
        self._movable = [jt for jt in joints if jt.movable and jt.mimic is None]
        q_index = {jt.name: i for i, jt in enumerate(self._movable)}
        self._frame = {self.root: 0}
        for j, jt in enumerate(self._order):
            self._frame[jt.child] = j + 1
        self._table = _fk.FKTable(self._order, self._frame, q_index, sources)
        self._parent_index = {jt.child: j for j, jt in enumerate(self._order)}
        self._all = np.arange(len(self._order), dtype=np.int64)
        self._chains = {}  # link -> _fk.ChainTable, filled on first fk(link=...)
        self._paths = {}  # link -> joint indices root → link, filled on first use
        parents = {jt.parent for jt in joints}
        leaves = [lk.name for lk in links if lk.name not in parents]
        self.tip = leaves[0] if len(leaves) == 1 else None
        self.poses = {}
        for key, q in (poses or {}).items():
            self.poses[key] = self.check_q(q, f"pose {key!r}")
            self.poses[key].setflags(write=False)

    # -- description -------------------------------------------------------------------
    @property
    def dof(self) -> int:
        """Number of joint variables (length of q)."""
        return len(self._movable)

    @property
    def joint_names(self) -> list[str]:
        """Names of the joints that q drives, in the order of q."""
        return [jt.name for jt in self._movable]

    @property
    def link_names(self) -> list[str]:
        return [lk.name for lk in self.links]

    @property
    def limits(self) -> np.ndarray:
        """(dof, 2) array of [lower, upper]; ±inf where a joint is unlimited."""
        lim = np.array([jt.limits if jt.limits is not None else (-np.inf, np.inf)
                        for jt in self._movable], dtype=float).reshape(-1, 2)
        return lim

    def joint(self, name: str) -> Joint:
        """The :class:`Joint` called ``name``."""
        for jt in self.joints:
            if jt.name == name:
                return jt
        raise KinlibError(f"robot {self.name!r} has no joint {name!r}; joints: "
                          f"{[jt.name for jt in self.joints]}")

    def link(self, name: str) -> Link:
        """The :class:`Link` called ``name``."""
        self._frame_of(name)
        return next(lk for lk in self.links if lk.name == name)

    def traversal(self) -> list[Joint]:
        """Joints in matrix-stack order: depth first from the root, children in given order."""
        return list(self._order)

    def __repr__(self) -> str:
        kinds = "".join({"revolute": "R", "continuous": "R", "prismatic": "P"}[jt.type]
                        for jt in self._movable)
        return (f"Robot({self.name!r}, dof={self.dof} ({kinds}), links={len(self.links)}, "
                f"tip={self.tip!r})")

    # -- forward kinematics --------------------------------------------------------------
    def check_q(self, q, name="q") -> np.ndarray:
        """``q`` as a float array of shape ``(..., dof)`` (a dict joint name → value: missing
        joints 0), else a :class:`KinlibError` naming the joints and the shape given."""
        if isinstance(q, Mapping):
            unknown = set(q) - set(self.joint_names)
            if unknown:
                raise KinlibError(f"{name}: unknown joints {sorted(unknown)}; robot "
                                  f"{self.name!r} has {self.joint_names}")
            q = [q.get(n, 0.0) for n in self.joint_names]
        a = as_array(q, name)
        if a.ndim == 0 or a.shape[-1] != self.dof:
            raise KinlibError(
                f"{name}: expected {self.dof} joint values (shape (..., {self.dof})) for robot "
                f"{self.name!r} with joints {self.joint_names}, got shape {a.shape}"
            )
        return a

    def check_limits(self, q, *, tol: float = LIMIT_TOL) -> np.ndarray:
        """``q`` as an array if every joint is within its limits (± ``tol``), else raise.

        The message names the joint, its limits, the value and the batch index.
        """
        a = self.check_q(q)
        lim = self.limits
        bad = (a < lim[:, 0] - tol) | (a > lim[:, 1] + tol)
        if bad.any():
            j = int(np.argwhere(bad)[0][-1])
            where = fmt_index(a.shape[:-1], bad[..., j])
            value = a[..., j][bad[..., j]].flat[0]
            raise KinlibError(
                f"q{where}: joint {self.joint_names[j]!r} = {value:.6g} is outside its limits "
                f"[{lim[j, 0]:.6g}, {lim[j, 1]:.6g}]"
            )
        return a

    def _path(self, link) -> np.ndarray:
        """Indices (traversal order) of the joints from the root to ``link`` (built once per
        link; read-only)."""
        path = self._paths.get(link)
        if path is None:
            path, at = [], link
            while at in self._parent_index:
                j = self._parent_index[at]
                path.append(j)
                at = self._order[j].parent
            path = np.array(path[::-1], dtype=np.int64)
            path.setflags(write=False)
            self._paths[link] = path
        return path

    def chain_table(self, link=None) -> _fk.ChainTable:
        """The path root → ``link`` (default: the tip) as the arrays the compiled kernels
        of :mod:`kinlib.kinematics` read (built once per link)."""
        link = self.resolve_link(link)
        chain = self._chains.get(link)
        if chain is None:
            path = self._path(link)
            chain = _fk.ChainTable(self._table, [self._order[j] for j in path], path)
            self._chains[link] = chain
        return chain

    def resolve_link(self, link=None) -> str:
        """``link`` if this robot has it, or the tip for None (a :class:`KinlibError` if the
        robot has no such link, or branches and no link is named)."""
        if link is None:
            if self.tip is None:
                raise KinlibError(f"robot {self.name!r} branches (it has several leaf links); "
                                  "pass link= to say which one")
            link = self.tip
        self._frame_of(link)
        return link

    def _frame_of(self, link) -> int:
        if link not in self._frame:
            raise KinlibError(f"robot {self.name!r} has no link {link!r}; links: "
                              f"{self.link_names}")
        return self._frame[link]

    def fk(self, q, link=None, *, check_limits: bool = False) -> np.ndarray:
        """Pose of ``link`` (default: :attr:`tip`) in the root frame, ``(..., 4, 4)``.

        ``q`` has shape ``(..., dof)`` (or is a dict joint name → value, missing joints 0).
        With ``check_limits=True`` a value outside a joint's limits raises.
        """
        link = self.resolve_link(link)
        a = self.check_limits(q) if check_limits else self.check_q(q)
        batch = a.shape[:-1]
        T = _fk.run_chain(self.chain_table(link), a.reshape(math.prod(batch), self.dof))
        return T.reshape(batch + (4, 4))

    def fk_and_jacobian(self, q, link=None) -> tuple[np.ndarray, np.ndarray]:
        """``(fk(q, link), jacobian(q, link))`` in one pass (what IK needs each step)."""
        link = self.resolve_link(link)
        a = self.check_q(q)
        batch = a.shape[:-1]
        T, J = _fk.run_chain_jacobian(self.chain_table(link),
                                      a.reshape(math.prod(batch), self.dof))
        return T.reshape(batch + (4, 4)), J.reshape(batch + (6, self.dof))

    def jacobian(self, q, link=None, *, frame=None) -> np.ndarray:
        r"""The geometric Jacobian of ``link`` (default: the tip): ``(..., 6, dof)``.

        Rows ``[v; ω]``: the linear velocity of the link's origin and the link's angular
        velocity, ``[v; ω] = J(q) q̇``. Column i, for a joint with world axis z and origin
        o on the path to the link (p: the link's origin) is ``[z × (p − o); z]``
        (revolute) or ``[z; 0]`` (prismatic); joints not on the path give zero columns.
        The vectors are expressed in the base (root) frame, or in the frame of the link
        named by ``frame`` (the reference point stays the link's origin).

        >>> from kinlib.robots import planar_2r
        >>> planar_2r(1.0, 1.0).jacobian([0.0, np.pi / 2]).round(12) + 0.0
        array([[-1., -1.],
               [ 1.,  0.],
               [ 0.,  0.],
               [ 0.,  0.],
               [ 0.,  0.],
               [ 1.,  1.]])
        """
        J = self.fk_and_jacobian(q, link)[1]
        if frame is None:
            return J
        R = self.fk(q, link=frame)[..., :3, :3]
        Rt = np.swapaxes(R, -1, -2)
        return np.concatenate([Rt @ J[..., :3, :], Rt @ J[..., 3:, :]], axis=-2)

    def analytic_jacobian(self, q, link=None, seq: str = "ZYX", *,
                          tol: float = GIMBAL_TOL) -> np.ndarray:
        """``[ṗ; φ̇] = J_a q̇`` of ``link`` for Euler/fixed angles ``seq`` (``q``, then
        ``link``, then ``seq``, as in :meth:`fk`); see
        :func:`kinlib.kinematics.analytic.analytic_jacobian` (raises at the angles' gimbal
        lock)."""
        return analytic_jacobian(self, q, link, seq, tol=tol)

    def ik(self, T_target, q0=None, *, link=None, position_only=False,
           tol_position=IK_POSITION_TOL, tol_rotation=IK_ROTATION_TOL, max_iterations=30,
           restarts=100, seed=0):
        """Joint values that put ``link`` (default: the tip) at ``T_target``.

        Damped least squares with Levenberg–Marquardt damping on the full pose (or the
        position only), within the joint limits, restarting from seeded random
        configurations when an attempt stalls; see :mod:`kinlib.kinematics.ik`. ``T_target`` is
        ``(..., 4, 4)`` (or points ``(..., 3)`` with ``position_only=True``); all targets
        are solved together. Tolerances are in metres and radians. Returns
        :class:`~kinlib.IKResult`; an unreachable target ends with ``success=False``.

        >>> from kinlib.robots import puma560
        >>> robot = puma560()
        >>> target = robot.fk([0.3, -0.6, 1.2, 0.2, 0.5, -0.4])
        >>> sol = robot.ik(target)
        >>> sol.success, sol.position_error < 1e-6, sol.rotation_error < 1e-6
        (True, True, True)
        >>> bool(np.allclose(robot.fk(sol.q), target, atol=1e-6))
        True
        """
        return solve_ik(self, T_target, q0, link=link, position_only=position_only,
                        tol_position=tol_position, tol_rotation=tol_rotation,
                        max_iterations=max_iterations, restarts=restarts, seed=seed)

    def link_poses(self, q, *, check_limits: bool = False) -> dict[str, np.ndarray]:
        """Pose of every link in the root frame: dict link name → ``(..., 4, 4)``."""
        a = self.check_limits(q) if check_limits else self.check_q(q)
        batch = a.shape[:-1]
        frames = _fk.run(self._table, a.reshape(math.prod(batch), self.dof), self._all)
        return {name: frames[:, self._frame[name]].reshape(batch + (4, 4))
                for name in self.link_names}

    # -- other constructors and export ---------------------------------------------------
    @classmethod
    def from_dh(cls, rows, convention: str = "standard", *, name: str = "dh_robot",
                poses=None, reference=None) -> Robot:
        """A serial robot from DH rows (:class:`~kinlib.DHRow` or dicts).

        ``convention`` is ``"standard"`` (``A_i = Rz(θ) Tz(d) Tx(a) Rx(α)``) or ``"modified"``
        (Craig: row i holds ``a_{i-1}, α_{i-1}, d_i, θ_i``). Links are ``link0`` (the base) to
        ``link{n}``; joints are ``joint1`` to ``joint{n}`` unless a row names its joint (see
        :mod:`kinlib.models.dh_tree`). The table is kept: :attr:`dh_rows`,
        :attr:`dh_convention`.

        >>> from kinlib import DHRow
        >>> arm = Robot.from_dh([DHRow(a=1.0, alpha=0.0), DHRow(a=0.5, alpha=0.0)], name="2R")
        >>> arm.fk([0.0, np.pi / 2])[:3, 3].round(12)
        array([1. , 0.5, 0. ])
        >>> arm.dh_convention, arm.dh_rows[1].a
        ('standard', 0.5)
        """
        links, joints, rows = dh_tree(rows, convention)
        return cls(name, links, joints, poses=poses, reference=reference, dh=(rows, convention))

    def to_urdf(self, path=None) -> str:
        """This robot as URDF text (written to ``path`` too if given)."""
        text = urdf_from_robot(self)
        if path is not None:
            with open(path, "w", encoding="utf-8") as fh:
                fh.write(text)
        return text


def load_urdf(path_or_xml, *, poses=None, reference=None) -> Robot:
    """A :class:`Robot` from a URDF file path or URDF text.

    Malformed input raises :class:`~kinlib.URDFError` naming the element and line (the
    reading is :func:`kinlib.models.urdf.read_urdf`; the tree checks are the Robot's). As
    urdfdom (ROS's reader, which pinocchio uses), a fixed joint's ``<axis>`` is not read
    and its ``<mimic>`` has no effect; a mesh's negative scale mirrors it.

    >>> robot = load_urdf('''<robot name="pendulum">
    ...   <link name="base"/> <link name="bob"/>
    ...   <joint name="swing" type="continuous">
    ...     <parent link="base"/> <child link="bob"/>
    ...     <origin xyz="0 0 1"/> <axis xyz="0 2 0"/>
    ...   </joint>
    ... </robot>''')
    >>> robot.joint("swing").axis
    array([0., 1., 0.])
    >>> robot.fk([np.pi / 2])[:3, 3]
    array([0., 0., 1.])
    """
    description = read_urdf(path_or_xml)
    try:
        return Robot(description.name, description.links, description.joints, poses=poses,
                     reference=reference)
    except TreeError as exc:
        raise description.located(exc) from None
