"""URDF text for a robot (:meth:`kinlib.Robot.to_urdf`): links, joints, visuals, limits
and mimic rules, built with :mod:`xml.etree.ElementTree` (so every name is escaped) and with
every number written exactly (``repr`` of the float), so reading the text back gives the
same robot.
"""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET

import numpy as np

from ..errors import KinlibError
from .tree import Visual, xyz_rpy_from_origin

__all__ = ["urdf_from_robot"]

UNLIMITED_PRISMATIC = 1e6  # URDF cannot say "unlimited" for a prismatic joint

# what XML 1.0 can hold (its production Char): no other control characters, no surrogates
_NOT_XML = re.compile("[^\t\n\r\x20-\ud7ff\ue000-\ufffd\U00010000-\U0010ffff]")


def _num(x) -> str:
    """Numbers as ``repr`` writes them: the shortest text that reads back to the same float."""
    return " ".join(repr(float(v)) for v in np.atleast_1d(x))


def _text(value: str, what: str) -> str:
    bad = _NOT_XML.search(value)
    if bad is not None:
        raise KinlibError(f"cannot export: {what} {value!r} holds the character "
                          f"{bad.group()!r}, which XML cannot hold")
    if not value.strip():
        raise KinlibError(f"cannot export: {what} {value!r} is blank; URDF needs a name")
    return value


def _origin_el(parent, T) -> None:
    if not np.array_equal(T, np.eye(4)):
        xyz, rpy = xyz_rpy_from_origin(T)
        ET.SubElement(parent, "origin", xyz=_num(xyz), rpy=_num(rpy))


def _visual_el(parent, v: Visual, where: str) -> None:
    el = ET.SubElement(parent, "visual")
    _origin_el(el, v.origin)
    geom = ET.SubElement(el, "geometry")
    if v.kind == "box":
        ET.SubElement(geom, "box", size=_num(v.size))
    elif v.kind == "cylinder":
        ET.SubElement(geom, "cylinder", radius=_num(v.size[0]), length=_num(v.size[1]))
    elif v.kind == "sphere":
        ET.SubElement(geom, "sphere", radius=_num(v.size[0]))
    else:
        ET.SubElement(geom, "mesh", filename=_text(v.filename, f"{where}: mesh filename"),
                      scale=_num(v.size))
    if v.rgba is not None:
        ET.SubElement(ET.SubElement(el, "material", name=""), "color", rgba=_num(v.rgba))


def _joint_el(parent, name, kind, parent_link, child_link, T):
    el = ET.SubElement(parent, "joint", name=_text(name, "joint name"), type=kind)
    ET.SubElement(el, "parent", link=parent_link)
    ET.SubElement(el, "child", link=child_link)
    _origin_el(el, T)
    return el


def urdf_from_robot(robot) -> str:
    """URDF text for ``robot``; a joint with a ``post`` transform (standard DH) is written
    as the moving joint into ``<child>_motion`` followed by a fixed joint ``<name>_post``,
    so every link of the robot keeps its frame.

    The text is built with :mod:`xml.etree.ElementTree`, so any name or mesh file name
    (``&``, ``<``, quotes, non-ASCII) is escaped and reads back as it was; numbers are
    written exactly (``repr``), so :func:`kinlib.load_urdf` gives back the same robot.

    >>> from kinlib import load_urdf
    >>> robot = load_urdf('''<robot name="R&amp;D"> <link name="a"/> <link name="b"/>
    ...   <joint name="j" type="continuous"> <parent link="a"/> <child link="b"/>
    ...     <origin xyz="0.1 0 0"/> <axis xyz="0 0 1"/> </joint> </robot>''')
    >>> print(urdf_from_robot(robot))
    <?xml version="1.0" encoding="utf-8"?>
    <robot name="R&amp;D">
      <link name="a" />
      <link name="b" />
      <joint name="j" type="continuous">
        <parent link="a" />
        <child link="b" />
        <origin xyz="0.1 0.0 0.0" rpy="0.0 0.0 0.0" />
        <axis xyz="0.0 0.0 1.0" />
      </joint>
    </robot>
    """
    names = set(robot.link_names)
    top = ET.Element("robot", name=_text(robot.name, "robot name"))
    for lk in robot.links:
        el = ET.SubElement(top, "link", name=_text(lk.name, "link name"))
        for v in lk.visuals:
            _visual_el(el, v, f"link {lk.name!r}")
    joints = ET.Element("joints")  # after every link, as the files ROS writes
    for jt in robot.joints:
        child = jt.child
        has_post = not np.array_equal(jt.post, np.eye(4))
        if has_post:
            child = f"{jt.child}_motion"
            if child in names:
                raise KinlibError(f"cannot export: link name {child!r} is already taken")
            ET.SubElement(top, "link", name=child)
        kind = jt.type
        if kind == "revolute" and jt.limits is not None and not np.isfinite(jt.limits).all():
            kind = "continuous"
        el = _joint_el(joints, jt.name, kind, jt.parent, child, jt.origin)
        if jt.movable:
            ET.SubElement(el, "axis", xyz=_num(jt.axis))
        if kind in ("revolute", "prismatic"):
            lo, hi = jt.limits if jt.limits is not None else (-np.inf, np.inf)
            lo, hi = max(lo, -UNLIMITED_PRISMATIC), min(hi, UNLIMITED_PRISMATIC)
            ET.SubElement(el, "limit", lower=_num(lo), upper=_num(hi), effort="0",
                          velocity="0")
        if jt.mimic is not None:
            m = jt.mimic
            ET.SubElement(el, "mimic", joint=m.joint, multiplier=_num(m.multiplier),
                          offset=_num(m.offset))
        if has_post:
            _joint_el(joints, jt.name + "_post", "fixed", child, jt.child, jt.post)
    top.extend(list(joints))
    ET.indent(top, space="  ")
    return '<?xml version="1.0" encoding="utf-8"?>\n' + ET.tostring(top, encoding="unicode") + "\n"
