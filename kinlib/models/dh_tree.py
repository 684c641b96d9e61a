"""The links and joints of a serial robot from a Denavit–Hartenberg table (what
``Robot.from_dh`` builds from).

Each row becomes one joint between links ``link{i-1}`` and ``link{i}``, so link ``i``'s
frame is exactly DH frame ``i``:

* standard, revolute:  origin ``I``,      motion ``Rz(q + offset)``, post ``Tz(d) Tx(a) Rx(α)``
* standard, prismatic: origin ``Rz(θ)``,  motion ``Tz(q + offset)``, post ``Tx(a) Rx(α)``
* modified, revolute:  origin ``Rx(α) Tx(a) Tz(d)``, motion ``Rz(q + offset)``
  (``Tz`` and ``Rz`` commute)
* modified, prismatic: origin ``Rx(α) Tx(a) Rz(θ)``, motion ``Tz(q + offset)``
* ``"fixed"`` rows: origin = the whole link transform, no motion.

A constant ``offset`` is folded into the origin (``Rz(q + o) = Rz(o) Rz(q)``), so q is the
DH joint variable and a URDF export carries the offset in its ``<origin>``.

A revolute row without limits becomes a continuous joint.
"""

from __future__ import annotations

import numpy as np

from ..errors import KinlibError
from .dh import as_dh_row, dh_transform, mdh_transform
from .tree import Joint, Link

__all__ = ["dh_tree"]


def _rz(t):
    return dh_transform(theta=t)


def _joint(i, row, modified, parent, child):
    name = row.name or f"joint{i}"
    if row.joint == "revolute" and row.theta != 0.0:
        raise KinlibError(f"DH row {i} ({name}) is revolute, so θ is the joint variable; give "
                          f"a constant angle as offset={row.theta!r}, not theta")
    if row.joint == "prismatic" and row.d != 0.0:
        raise KinlibError(f"DH row {i} ({name}) is prismatic, so d is the joint variable; give "
                          f"a constant length as offset={row.d!r}, not d")
    link_tf = mdh_transform if modified else dh_transform
    if row.joint == "fixed":
        origin = link_tf(theta=row.theta, d=row.d, a=row.a, alpha=row.alpha)
        return Joint(name, "fixed", parent, child, origin=origin, axis=(0.0, 0.0, 1.0))
    # the offset folds into the origin: Rz(q + o) = Rz(o) Rz(q), Tz(q + o) = Tz(o) Tz(q)
    shift = _rz(row.offset) if row.joint == "revolute" else dh_transform(d=row.offset)
    post = np.eye(4)
    if modified:
        pre = mdh_transform(a=row.a, alpha=row.alpha)
        origin = pre @ (dh_transform(d=row.d) if row.joint == "revolute" else _rz(row.theta))
    elif row.joint == "revolute":
        origin, post = np.eye(4), dh_transform(d=row.d, a=row.a, alpha=row.alpha)
    else:
        origin, post = _rz(row.theta), dh_transform(a=row.a, alpha=row.alpha)
    kind = "continuous" if row.joint == "revolute" and row.limits is None else row.joint
    return Joint(name, kind, parent, child, origin=origin @ shift, axis=(0.0, 0.0, 1.0),
                 limits=row.limits, post=post)


def dh_tree(rows, convention="standard"):
    """The links and joints of a serial robot from DH rows (:class:`~kinlib.DHRow` or
    dicts), and the rows as :class:`~kinlib.DHRow`: ``(links, joints, rows)``, what
    :meth:`kinlib.Robot.from_dh` builds its robot from.

    ``convention`` is ``"standard"`` (``A_i = Rz(θ) Tz(d) Tx(a) Rx(α)``) or ``"modified"``
    (Craig: row i holds ``a_{i-1}, α_{i-1}, d_i, θ_i``). Links are ``link0`` (the base) to
    ``link{n}``; joints are ``joint1`` to ``joint{n}`` unless a row names its joint.

    >>> from kinlib import DHRow
    >>> links, joints, rows = dh_tree([DHRow(a=1.0, alpha=0.0), DHRow(a=0.5, alpha=0.0)])
    >>> [lk.name for lk in links], [(jt.name, jt.type) for jt in joints]
    (['link0', 'link1', 'link2'], [('joint1', 'continuous'), ('joint2', 'continuous')])
    """
    if convention not in ("standard", "modified"):
        raise KinlibError(f"convention: expected 'standard' or 'modified', got {convention!r}")
    if isinstance(rows, str | bytes | dict):
        raise KinlibError(f"rows: expected a sequence of DH rows, got {type(rows).__name__}")
    try:
        rows = [as_dh_row(r, i + 1) for i, r in enumerate(rows)]
    except TypeError:
        raise KinlibError(f"rows: expected a sequence of DH rows, got {type(rows).__name__}") \
            from None
    if not rows:
        raise KinlibError("rows: a DH table needs at least one row")
    links = [Link(f"link{i}") for i in range(len(rows) + 1)]
    joints = [_joint(i + 1, r, convention == "modified", f"link{i}", f"link{i + 1}")
              for i, r in enumerate(rows)]
    return links, joints, tuple(rows)
