"""The parts a robot model is made of: links, joints, visual shapes, mimic rules.

These are plain, immutable data. :class:`kinlib.Robot` checks that they form a tree;
:func:`kinlib.load_urdf` builds them from a URDF file.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .._validate import as_array, as_limits, as_unit_vectors
from ..errors import KinlibError, TreeError
from ..spatial.euler import euler_from_matrix
from ..spatial.transforms import check_transform

__all__ = ["Joint", "Link", "Visual", "Mimic", "JOINT_TYPES", "origin_from_xyz_rpy",
           "xyz_rpy_from_origin", "check_tree", "mimic_sources"]

JOINT_TYPES = ("revolute", "continuous", "prismatic", "fixed")


def _frozen(a: np.ndarray) -> np.ndarray:
    a = np.array(a, dtype=float)  # a plain ndarray, also for a _Built view
    a.setflags(write=False)
    return a


class _Built(np.ndarray):
    """A 4×4 transform kinlib made itself from numbers it has already checked (a URDF
    ``<origin>``, a DH row). :class:`Joint` and :class:`Visual` store it without checking
    it again: input is validated once, where it enters (parsing 12,000 joints spent 83 % of
    its time re-checking origins built from checked ``xyz``/``rpy``). It never leaves this
    module's objects, which keep plain read-only arrays."""


def built_transform(T) -> np.ndarray:
    """Mark a transform kinlib built from checked numbers (see :class:`_Built`)."""
    return np.asarray(T, dtype=float).view(_Built)


def _identity() -> np.ndarray:
    return built_transform(np.eye(4))


def _pose(T, what: str) -> np.ndarray:
    """``T`` frozen, checked unless kinlib built it (:func:`built_transform`)."""
    if type(T) is _Built and T.shape == (4, 4):
        return _frozen(T)
    return _frozen(check_transform(T, what))


def origin_from_xyz_rpy(xyz=(0.0, 0.0, 0.0), rpy=(0.0, 0.0, 0.0)) -> np.ndarray:
    """The 4×4 transform of a URDF ``<origin xyz rpy>``: ``R = Rz(yaw) Ry(pitch) Rx(roll)``.

    >>> origin_from_xyz_rpy([5, 3, 0], [0, 0, np.pi / 2]).round(12) + 0.0
    array([[ 0., -1.,  0.,  5.],
           [ 1.,  0.,  0.,  3.],
           [ 0.,  0.,  1.,  0.],
           [ 0.,  0.,  0.,  1.]])
    """
    xyz, rpy = as_array(xyz, "xyz", (3,)), as_array(rpy, "rpy", (3,))
    if xyz.ndim != 1 or rpy.ndim != 1:
        raise KinlibError(f"xyz, rpy: expected three numbers each, got shapes {xyz.shape} "
                          f"and {rpy.shape}")
    roll, pitch, yaw = rpy.tolist()
    cr, sr, cp, sp = math.cos(roll), math.sin(roll), math.cos(pitch), math.sin(pitch)
    cy, sy = math.cos(yaw), math.sin(yaw)
    x, y, z = xyz.tolist()
    return np.array([  # Rz(yaw) Ry(pitch) Rx(roll), multiplied out (a robot file has
        # thousands of these: no array arithmetic per joint)
        [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr, x],
        [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr, y],
        [-sp, cp * sr, cp * cr, z],
        [0.0, 0.0, 0.0, 1.0]])


def xyz_rpy_from_origin(T) -> tuple[np.ndarray, np.ndarray]:
    """``(xyz, rpy)`` of a transform, the inverse of :func:`origin_from_xyz_rpy`."""
    T = check_transform(T, "origin")
    return T[:3, 3].copy(), euler_from_matrix(T[:3, :3], "xyz")


@dataclass(frozen=True)
class Mimic:
    """A joint that follows another: ``q = multiplier * q[joint] + offset``."""

    joint: str
    multiplier: float = 1.0
    offset: float = 0.0


@dataclass(frozen=True)
class Visual:
    """A shape drawn with a link, in the link's frame moved by ``origin``.

    ``kind`` is ``"box"`` (size = x, y, z lengths), ``"cylinder"`` (size = radius, length;
    its axis is the local z axis, as in URDF), ``"sphere"`` (size = radius,) or ``"mesh"``
    (``filename``, size = scale x, y, z). Sizes are positive; a mesh's scale factors may
    be negative, which mirrors the mesh (real robots draw their left arm as the right
    one mirrored, ``scale="1 -1 1"``), but not zero. ``rgba`` is a colour with components
    in [0, 1].

    >>> Visual("mesh", (1, -1, 1), filename="arm.stl").size
    (1.0, -1.0, 1.0)
    >>> Visual("mesh", (1, 0, 1), filename="arm.stl")
    Traceback (most recent call last):
    ...
    kinlib.errors.KinlibError: mesh scale: expected non-zero numbers (...), got [1.0, 0.0, 1.0]
    """

    kind: str
    size: tuple[float, ...]
    origin: np.ndarray = field(default_factory=_identity)
    rgba: tuple[float, float, float, float] | None = None
    filename: str | None = None

    def __post_init__(self):
        n = {"box": 3, "cylinder": 2, "sphere": 1, "mesh": 3}.get(self.kind)
        if n is None:
            raise KinlibError(
                f"Visual: kind must be box, cylinder, sphere or mesh, got {self.kind!r}"
            )
        what = "mesh scale" if self.kind == "mesh" else f"{self.kind} size"
        size = as_array(self.size, what, (n,))
        if size.ndim != 1:
            raise KinlibError(f"{what}: expected {n} numbers, got shape {size.shape}")
        if self.kind == "mesh" and (size == 0).any():
            raise KinlibError(f"{what}: expected non-zero numbers (a negative one mirrors the "
                              f"mesh), got {size.tolist()}")
        if self.kind != "mesh" and (size <= 0).any():
            raise KinlibError(f"{what}: expected positive numbers, got {size.tolist()}")
        object.__setattr__(self, "size", tuple(float(s) for s in size))
        object.__setattr__(self, "origin", _pose(self.origin, "visual origin"))
        if self.kind == "mesh" and not self.filename:
            raise KinlibError("Visual: a mesh needs a filename")
        if self.rgba is not None:
            c = as_array(self.rgba, "rgba", (4,))
            if ((c < 0) | (c > 1)).any():
                raise KinlibError(f"rgba: expected 4 numbers in [0, 1], got {c.tolist()}")
            object.__setattr__(self, "rgba", tuple(float(x) for x in c))


@dataclass(frozen=True)
class Link:
    """A rigid body of the robot: a name and the shapes drawn with it."""

    name: str
    visuals: tuple[Visual, ...] = ()

    def __post_init__(self):
        if not isinstance(self.name, str) or not self.name:
            raise KinlibError(f"Link: name must be a non-empty string, got {self.name!r}")
        object.__setattr__(self, "visuals", tuple(self.visuals))


@dataclass(frozen=True, eq=False)
class Joint:
    """A joint between a ``parent`` and a ``child`` link.

    Its frame is the child link's frame: ``T_parent_child = origin @ motion(q) @ post``
    (``post`` is identity for URDF joints; standard-DH rows need it, see
    :meth:`kinlib.Robot.from_dh`). ``axis`` is a unit vector in the joint frame
    (normalised here). ``limits`` is ``(lower, upper)``; continuous and fixed joints have
    none. ``mimic`` makes the joint follow another one.
    """

    name: str
    type: str
    parent: str
    child: str
    origin: np.ndarray = field(default_factory=_identity)
    axis: np.ndarray = field(default_factory=lambda: np.array([1.0, 0.0, 0.0]))
    limits: tuple[float, float] | None = None
    mimic: Mimic | None = None
    post: np.ndarray = field(default_factory=_identity)

    def __post_init__(self):
        where = f"joint {self.name!r}"
        if not isinstance(self.name, str) or not self.name:
            raise KinlibError(f"Joint: name must be a non-empty string, got {self.name!r}")
        if self.type not in JOINT_TYPES:
            raise KinlibError(
                f"{where}: unsupported joint type {self.type!r}; kinlib supports "
                f"{', '.join(JOINT_TYPES)}"
            )
        for role in ("parent", "child"):
            v = getattr(self, role)
            if not isinstance(v, str) or not v:
                raise KinlibError(f"{where}: {role} must be a link name, got {v!r}")
        object.__setattr__(self, "origin", _pose(self.origin, f"{where} origin"))
        object.__setattr__(self, "post", _pose(self.post, f"{where} post"))
        object.__setattr__(self, "axis", _frozen(as_unit_vectors(self.axis, f"{where} axis")))
        if self.type in ("continuous", "fixed"):
            if self.limits is not None and self.type == "fixed":
                raise KinlibError(f"{where}: a fixed joint has no limits")
            object.__setattr__(self, "limits", None)
        elif self.limits is not None:
            object.__setattr__(self, "limits", as_limits(self.limits, where))
        if self.mimic is not None:
            m = self.mimic
            if not isinstance(m, Mimic):
                raise KinlibError(f"{where}: mimic must be a Mimic, got {type(m).__name__}")
            if self.type == "fixed":
                raise KinlibError(f"{where}: a fixed joint cannot mimic another joint")
            if not all(math.isfinite(v) for v in (m.multiplier, m.offset)):
                raise KinlibError(f"{where}: mimic multiplier and offset must be finite")

    @property
    def movable(self) -> bool:
        """True for revolute, continuous and prismatic joints."""
        return self.type != "fixed"


def check_tree(links, joints):
    """Check that ``links`` and ``joints`` form one tree; return (root, joints in depth-first
    order). Raises :class:`~kinlib.errors.TreeError` naming the element at fault."""
    link_names = [lk.name for lk in links]
    seen = set()
    for lk in links:
        if lk.name in seen:
            raise TreeError(f"duplicate link name {lk.name!r}", ("link", lk.name), nth=1)
        seen.add(lk.name)
    jseen, parent_joint, children = set(), {}, {n: [] for n in link_names}
    for jt in joints:
        if jt.name in jseen:
            raise TreeError(f"duplicate joint name {jt.name!r}", ("joint", jt.name), nth=1)
        jseen.add(jt.name)
        for role in ("parent", "child"):
            if getattr(jt, role) not in seen:
                raise TreeError(f"joint {jt.name!r}: {role} link {getattr(jt, role)!r} does "
                                "not exist", ("joint", jt.name))
        if jt.parent == jt.child:
            raise TreeError(f"joint {jt.name!r}: link {jt.parent!r} is its own parent",
                            ("joint", jt.name))
        if jt.child in parent_joint:
            raise TreeError(f"link {jt.child!r} has two parent joints: "
                            f"{parent_joint[jt.child].name!r} and {jt.name!r}", ("joint", jt.name))
        parent_joint[jt.child] = jt
        children[jt.parent].append(jt)
    if not links:
        raise TreeError("the robot has no links", None)
    roots = [n for n in link_names if n not in parent_joint]
    if len(roots) > 1:
        raise TreeError(f"several root links (links with no parent joint): {roots}; a robot is one "
                        "tree with a single root", ("link", roots[1]))
    if not roots:  # every link has a parent: follow parents until one repeats
        seen_at, walk, name = {}, [], link_names[0]
        while name not in seen_at:
            seen_at[name] = len(walk)
            walk.append(parent_joint[name])
            name = parent_joint[name].parent
        loop = walk[seen_at[name]:][::-1]
        raise TreeError("no root link: joints " + " -> ".join(repr(j.name) for j in loop)
                        + " form a cycle", ("joint", loop[0].name))
    # depth first, children in document order: the matrix-stack traversal (an explicit
    # stack of iterators, so a long chain does not hit the recursion limit)
    order = []
    stack = [iter(children[roots[0]])]
    while stack:
        jt = next(stack[-1], None)
        if jt is None:
            stack.pop()
            continue
        order.append(jt)
        stack.append(iter(children[jt.child]))
    if len(order) != len(joints):
        reached = {roots[0]} | {jt.child for jt in order}
        lost = [n for n in link_names if n not in reached]
        raise TreeError(f"links {lost} are not connected to the root {roots[0]!r}: their joints "
                        "form a cycle", ("link", lost[0]))
    return roots[0], order


def mimic_sources(joints):
    """For each movable joint: (name of the joint whose q drives it, multiplier, offset).

    Each mimic chain is walked once (results are memoised), so this is linear in the
    number of joints.
    """
    by_name = {jt.name: jt for jt in joints}
    out = {}
    for jt in joints:
        if not jt.movable or jt.name in out:
            continue
        chain, on_chain, cur = [], set(), jt
        while cur.mimic is not None and cur.name not in out:
            chain.append(cur)
            on_chain.add(cur.name)
            m = cur.mimic
            src = by_name.get(m.joint)
            if src is None or not src.movable:
                what = "does not exist" if src is None else "is fixed"
                raise TreeError(f"joint {cur.name!r} mimics {m.joint!r}, which {what}",
                                ("joint", cur.name))
            if src.name in on_chain:
                names = [c.name for c in chain]
                loop = names[names.index(src.name):] + [src.name]
                raise TreeError(f"mimic joints form a cycle: {' -> '.join(loop)}",
                                ("joint", src.name))
            cur = src
        root, mult, off = out.get(cur.name, (cur.name, 1.0, 0.0))
        for c in reversed(chain):  # q_c = m * q_src + o, q_src = mult * q_root + off
            m = c.mimic
            mult, off = m.multiplier * mult, m.multiplier * off + m.offset
            out[c.name] = (root, mult, off)
        out.setdefault(cur.name, (cur.name, 1.0, 0.0))  # cur drives itself (no mimic)
    return out
