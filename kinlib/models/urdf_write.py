"""URDF text for a robot (:meth:`kinlib.Robot.to_urdf`): links, joints, visuals, limits
and mimic rules, with every number written exactly (``repr`` of the float), so reading the
text back gives the same robot.
"""

from __future__ import annotations

import numpy as np

from ..errors import KinlibError
from .tree import Visual, xyz_rpy_from_origin

__all__ = ["urdf_from_robot"]


def _num(x) -> str:
    return " ".join(repr(float(v)) for v in np.atleast_1d(x))


def _origin_xml(T, indent):
    if np.array_equal(T, np.eye(4)):
        return ""
    xyz, rpy = xyz_rpy_from_origin(T)
    return f'{indent}<origin xyz="{_num(xyz)}" rpy="{_num(rpy)}"/>\n'


def _visual_xml(v: Visual) -> str:
    shape = {
        "box": lambda: f'<box size="{_num(v.size)}"/>',
        "cylinder": lambda: f'<cylinder radius="{_num(v.size[0])}" length="{_num(v.size[1])}"/>',
        "sphere": lambda: f'<sphere radius="{_num(v.size[0])}"/>',
        "mesh": lambda: f'<mesh filename="{v.filename}" scale="{_num(v.size)}"/>',
    }[v.kind]()
    out = "    <visual>\n" + _origin_xml(v.origin, "      ")
    out += f"      <geometry>{shape}</geometry>\n"
    if v.rgba is not None:
        out += f'      <material name=""><color rgba="{_num(v.rgba)}"/></material>\n'
    return out + "    </visual>\n"


UNLIMITED_PRISMATIC = 1e6  # URDF cannot say "unlimited" for a prismatic joint


def urdf_from_robot(robot) -> str:
    """URDF text for ``robot``; a joint with a ``post`` transform (standard DH) is written
    as the moving joint into ``<child>_motion`` followed by a fixed joint ``<name>_post``,
    so every link of the robot keeps its frame.
    """
    from xml.sax.saxutils import quoteattr

    names = set(robot.link_names)
    body, extra_links = [], []
    for jt in robot.joints:
        child = jt.child
        has_post = not np.array_equal(jt.post, np.eye(4))
        if has_post:
            child = f"{jt.child}_motion"
            if child in names:
                raise KinlibError(f"cannot export: link name {child!r} is already taken")
            extra_links.append(child)
        kind = jt.type
        if kind == "revolute" and jt.limits is not None and not np.isfinite(jt.limits).all():
            kind = "continuous"
        s = f"  <joint name={quoteattr(jt.name)} type={quoteattr(kind)}>\n"
        s += f"    <parent link={quoteattr(jt.parent)}/>\n    <child link={quoteattr(child)}/>\n"
        s += _origin_xml(jt.origin, "    ")
        if jt.movable:
            s += f'    <axis xyz="{_num(jt.axis)}"/>\n'
        if kind in ("revolute", "prismatic"):
            lo, hi = jt.limits if jt.limits is not None else (-np.inf, np.inf)
            lo, hi = max(lo, -UNLIMITED_PRISMATIC), min(hi, UNLIMITED_PRISMATIC)
            s += f'    <limit lower="{_num(lo)}" upper="{_num(hi)}" effort="0" velocity="0"/>\n'
        if jt.mimic is not None:
            m = jt.mimic
            s += (f"    <mimic joint={quoteattr(m.joint)} multiplier=\"{_num(m.multiplier)}\" "
                  f"offset=\"{_num(m.offset)}\"/>\n")
        s += "  </joint>\n"
        if has_post:
            s += f"  <joint name={quoteattr(jt.name + '_post')} type=\"fixed\">\n"
            s += (f"    <parent link={quoteattr(child)}/>\n"
                  f"    <child link={quoteattr(jt.child)}/>\n")
            s += _origin_xml(jt.post, "    ") + "  </joint>\n"
        body.append(s)
    links = []
    for lk in robot.links:
        if lk.visuals:
            inner = "".join(_visual_xml(v) for v in lk.visuals)
            links.append(f"  <link name={quoteattr(lk.name)}>\n{inner}  </link>\n")
        else:
            links.append(f"  <link name={quoteattr(lk.name)}/>\n")
    links += [f"  <link name={quoteattr(n)}/>\n" for n in extra_links]
    return (f'<?xml version="1.0"?>\n<robot name={quoteattr(robot.name)}>\n'
            + "".join(links) + "".join(body) + "</robot>\n")
