"""Reading and writing URDF: the kinematic subset, with errors that name element and line.

Read: ``<robot>``, ``<link>`` (with ``<visual>`` boxes, cylinders, spheres and meshes, and
materials), ``<joint>`` of type revolute, continuous, prismatic or fixed with ``<origin>``,
``<axis>`` (normalised), ``<limit>`` and ``<mimic>``. Other elements (``<inertial>``,
``<collision>``, ``<dynamics>``, ``<transmission>``, ``<gazebo>``, ...) are skipped. Where
real files rely on how urdfdom (ROS's reader, pinocchio's) reads them, kinlib reads them
the same way: a fixed joint's ``<axis>`` and ``<mimic>`` move nothing, and a negative mesh
scale mirrors the mesh.

Write: :func:`urdf_from_robot` (``Robot.to_urdf``) builds the document with ElementTree,
so every name is escaped, and writes numbers exactly.

The file is parsed with expat directly, so every element knows its line. Document type
declarations are refused (they are how entity-expansion attacks work and URDF never needs
them), and files larger than :data:`MAX_BYTES` or deeper/bigger than any robot are refused
before they can use much memory or time.
"""

from __future__ import annotations

import math
import os
import re
import xml.etree.ElementTree as ET
from xml.parsers import expat

import numpy as np

from .errors import KinlibError, URDFError
from .model import (
    Joint,
    Link,
    Mimic,
    Visual,
    built_transform,
    origin_from_xyz_rpy,
    xyz_rpy_from_origin,
)

__all__ = ["load_urdf", "joints_as_written", "urdf_from_robot", "MAX_BYTES"]

MAX_BYTES = 16 * 2**20   # 16 MiB: the largest real URDFs are a few MB
MAX_ELEMENTS = 200_000
MAX_DEPTH = 64


class _El:
    __slots__ = ("attrib", "children", "line", "parent", "tag")

    def __init__(self, tag, attrib, line, parent):
        self.tag, self.attrib, self.children, self.line = tag, attrib, [], line
        self.parent = parent

    def all(self, tag):
        return [c for c in self.children if c.tag == tag]

    def describe(self):
        """``<joint name='j1'> <origin>``: the element, after its nearest named ancestor."""
        name = self.attrib.get("name")
        me = f"<{self.tag}{'' if name is None else f' name={name!r}'}>"
        up = self.parent
        while name is None and up is not None and up.tag != "robot":
            if "name" in up.attrib:
                return f"<{up.tag} name={up.attrib['name']!r}> {me}"
            up = up.parent
        return me


class _Source:
    """Builds URDFErrors that say where: ``file:line: <element name=...>: message``."""

    def __init__(self, label):
        self.label = label
        self.lines = {}

    def error(self, msg, el=None):
        if el is None:
            return URDFError(f"{self.label}: {msg}")
        return URDFError(f"{self.label}:{el.line}: {el.describe()}: {msg}")

    def tree_error(self, msg, where, occurrence=0):
        els = self.lines.get(where) if where else None
        line = f":{els[occurrence].line}" if els else ""
        return URDFError(f"{self.label}{line}: {msg}")


def _parse_xml(data: bytes, src: _Source) -> _El:
    parser = expat.ParserCreate()
    parser.SetParamEntityParsing(expat.XML_PARAM_ENTITY_PARSING_NEVER)
    stack: list[_El] = []
    top: list[_El] = []
    count = [0]

    def start(tag, attrib):
        count[0] += 1
        if count[0] > MAX_ELEMENTS:
            raise src.error(f"more than {MAX_ELEMENTS} elements; this is not a robot")
        if len(stack) >= MAX_DEPTH:
            raise src.error(f"line {parser.CurrentLineNumber}: elements nested more than "
                            f"{MAX_DEPTH} deep")
        el = _El(tag, attrib, parser.CurrentLineNumber, stack[-1] if stack else None)
        (stack[-1].children if stack else top).append(el)
        stack.append(el)

    def end(tag):
        stack.pop()

    def doctype(*args):
        raise src.error(f"line {parser.CurrentLineNumber}: a <!DOCTYPE> declaration is not "
                        "allowed in URDF (entity definitions can expand without bound)")

    def entity(*args):
        raise src.error(f"line {parser.CurrentLineNumber}: <!ENTITY> declarations are not "
                        "allowed in URDF")

    parser.StartElementHandler = start
    parser.EndElementHandler = end
    parser.StartDoctypeDeclHandler = doctype
    parser.EntityDeclHandler = entity
    try:
        parser.Parse(data, True)
    except expat.ExpatError as exc:
        raise src.error(f"line {exc.lineno}: XML syntax error: {expat.errors.messages[exc.code]}"
                        f" (column {exc.offset + 1})") from None
    except LookupError as exc:  # <?xml encoding="..."?> that Python does not know
        raise src.error(f"line {parser.CurrentLineNumber}: {exc}") from None
    return top[0]


def _count(n: int) -> str:
    return "a number" if n == 1 else f"{n} numbers"


def _floats(el: _El, attr: str, n: int, src: _Source, default=None):
    text = el.attrib.get(attr)
    if text is None:
        if default is None:
            raise src.error(f"missing attribute {attr}", el)
        return np.array(default, dtype=float)
    parts = text.split()
    try:
        vals = [float(p) for p in parts]
    except ValueError:
        raise src.error(f"{attr}={text!r}: expected {_count(n)}", el) from None
    if len(vals) != n:
        raise src.error(f"{attr}={text!r}: expected {_count(n)}, got {len(vals)}", el)
    if not all(math.isfinite(v) for v in vals):
        raise src.error(f"{attr}={text!r}: NaN or infinity is not allowed", el)
    return np.array(vals)


def _one(el: _El, tag: str, src: _Source, required: bool):
    found = el.all(tag)
    if len(found) > 1:
        raise src.error(f"more than one <{tag}> (lines {[f.line for f in found]})", el)
    if required and not found:
        raise src.error(f"missing <{tag}>", el)
    return found[0] if found else None


def _name(el: _El, src: _Source, attr="name"):
    name = el.attrib.get(attr)
    if name is None or not name.strip():
        raise src.error(f"missing or empty attribute {attr}", el)
    return name


def _xyz_rpy(el: _El, src: _Source):
    """The ``xyz`` and ``rpy`` of the ``<origin>`` of ``el`` (zeros where not written)."""
    o = _one(el, "origin", src, required=False)
    if o is None:
        return np.zeros(3), np.zeros(3)
    return _floats(o, "xyz", 3, src, (0, 0, 0)), _floats(o, "rpy", 3, src, (0, 0, 0))


def _origin(el: _El, src: _Source):
    """The ``<origin>`` of ``el``, built from numbers ``_floats`` has checked (finite), so
    the model takes it without checking it again (``built_transform``)."""
    return built_transform(origin_from_xyz_rpy(*_xyz_rpy(el, src)))


def _visual(vis: _El, materials: dict, src: _Source):
    geom = _one(vis, "geometry", src, required=True)
    if len(geom.children) != 1:
        raise src.error("expected exactly one shape in <geometry>", geom)
    g = geom.children[0]
    if g.tag == "box":
        kind, size, fname = "box", _floats(g, "size", 3, src), None
    elif g.tag == "cylinder":
        kind, fname = "cylinder", None
        size = np.concatenate([_floats(g, "radius", 1, src), _floats(g, "length", 1, src)])
    elif g.tag == "sphere":
        kind, size, fname = "sphere", _floats(g, "radius", 1, src), None
    elif g.tag == "mesh":
        kind, size, fname = "mesh", _floats(g, "scale", 3, src, (1, 1, 1)), _name(g, src,
                                                                                 "filename")
    else:
        raise src.error(f"unknown geometry <{g.tag}>: expected box, cylinder, sphere or mesh", g)
    rgba = None
    mat = _one(vis, "material", src, required=False)
    if mat is not None:
        color = _one(mat, "color", src, required=False)
        if color is not None:
            rgba = _floats(color, "rgba", 4, src)
        elif mat.attrib.get("name") in materials:
            rgba = materials[mat.attrib["name"]]
    try:
        return Visual(kind, tuple(size), _origin(vis, src), None if rgba is None
                      else tuple(np.clip(rgba, 0, 1)), fname)
    except URDFError:
        raise
    except KinlibError as exc:
        raise src.error(str(exc), g) from None


def _joint(el: _El, src: _Source) -> tuple[Joint, dict]:
    """A ``<joint>`` as a :class:`Joint` and as the values the file writes (see
    :func:`joints_as_written`)."""
    name = _name(el, src)
    kind = el.attrib.get("type")
    if kind is None:
        raise src.error("missing attribute type", el)
    if kind not in ("revolute", "continuous", "prismatic", "fixed"):
        what = "kinlib does not support" if kind in ("floating", "planar") else "unknown"
        raise src.error(f"{what} joint type {kind!r}; expected revolute, continuous, "
                        "prismatic or fixed", el)
    parent = _name(_one(el, "parent", src, required=True), src, "link")
    child = _name(_one(el, "child", src, required=True), src, "link")
    xyz, rpy = _xyz_rpy(el, src)
    axis = None  # as urdfdom: a fixed joint's axis is never read (real files say 0 0 0)
    if kind != "fixed":
        axis_el = _one(el, "axis", src, required=False)
        axis = np.array([1.0, 0.0, 0.0]) if axis_el is None else _floats(axis_el, "xyz", 3,
                                                                          src, (1, 0, 0))
        if not np.any(axis):
            raise src.error("axis xyz is the zero vector; a joint axis needs a direction",
                            axis_el)
    limits = None
    lim = _one(el, "limit", src, required=False)
    if kind in ("revolute", "prismatic"):
        if lim is None:
            raise src.error(f"a {kind} joint needs <limit lower=... upper=...>", el)
        lo = float(_floats(lim, "lower", 1, src, (0.0,))[0])
        hi = float(_floats(lim, "upper", 1, src, (0.0,))[0])
        if lo > hi:
            raise src.error(f"lower={lo:g} is greater than upper={hi:g}", lim)
        limits = (lo, hi)
    mimic = None
    m = _one(el, "mimic", src, required=False)
    if m is not None:
        mimic = Mimic(_name(m, src, "joint"),
                      float(_floats(m, "multiplier", 1, src, (1.0,))[0]),
                      float(_floats(m, "offset", 1, src, (0.0,))[0]))
        if kind == "fixed":  # checked, then ignored as urdfdom does: nothing moves
            mimic = None
    try:
        jt = Joint(name, kind, parent, child,
                   origin=built_transform(origin_from_xyz_rpy(xyz, rpy)),
                   axis=(1.0, 0.0, 0.0) if axis is None else axis, limits=limits, mimic=mimic)
    except URDFError:
        raise
    except KinlibError as exc:
        raise src.error(str(exc), el) from None
    return jt, {"name": name, "type": kind, "parent": parent, "child": child, "xyz": xyz,
                "rpy": rpy, "axis": axis, "limits": limits, "mimic": mimic}


def _read(path_or_xml) -> tuple[bytes, str]:
    if isinstance(path_or_xml, bytes):
        data, label = path_or_xml, "<urdf bytes>"
    elif isinstance(path_or_xml, str) and path_or_xml.lstrip("\ufeff \t\r\n").startswith("<"):
        label = "<urdf string>"
        try:
            data = path_or_xml.encode("utf-8")
        except UnicodeEncodeError as exc:
            raise URDFError(f"{label}: not valid Unicode text ({exc.reason} at character "
                            f"{exc.start})") from None
    elif isinstance(path_or_xml, str) and not path_or_xml.strip():
        raise URDFError("load_urdf: got an empty string; expected a file path or URDF text")
    elif isinstance(path_or_xml, str | os.PathLike):
        label = os.fspath(path_or_xml)
        try:
            size = os.path.getsize(label)
            if size <= MAX_BYTES:
                with open(label, "rb") as fh:
                    data = fh.read(MAX_BYTES + 1)
        except OSError as exc:
            raise URDFError(f"{label}: cannot read the file: {exc.strerror}") from None
        except ValueError as exc:  # e.g. a NUL byte in the path
            raise URDFError(f"{label!r}: cannot read the file: {exc}") from None
        if size > MAX_BYTES:
            raise URDFError(f"{label}: {size} bytes is larger than any robot description "
                            f"(limit {MAX_BYTES} bytes)")
    else:
        raise URDFError(f"load_urdf: expected a file path or URDF text, got "
                        f"{type(path_or_xml).__name__}")
    if len(data) > MAX_BYTES:
        raise URDFError(f"{label}: {len(data)} bytes is larger than any robot description "
                        f"(limit {MAX_BYTES} bytes)")
    return data, label


def _load(path_or_xml, poses=None, reference=None):
    """The robot of a URDF and the values its joints are written with (:func:`_joint`)."""
    from .robot import Robot

    data, label = _read(path_or_xml)
    src = _Source(label)
    root = _parse_xml(data, src)
    if root.tag != "robot":
        raise src.error(f"the top element is <{root.tag}>, expected <robot>", root)
    name = _name(root, src)
    materials = {}
    for mat in root.all("material"):
        color = _one(mat, "color", src, required=False)
        if color is not None:
            materials[_name(mat, src)] = _floats(color, "rgba", 4, src)
    links = []
    for el in root.all("link"):
        lname = _name(el, src)
        src.lines.setdefault(("link", lname), []).append(el)
        links.append(Link(lname, tuple(_visual(v, materials, src) for v in el.all("visual"))))
    joints, values = [], []
    for el in root.all("joint"):
        jt, v = _joint(el, src)
        src.lines.setdefault(("joint", jt.name), []).append(el)
        joints.append(jt)
        values.append(v)
    robot = Robot(name, links, joints, poses=poses, reference=reference,
                  _error=src.tree_error)
    return robot, values


def load_urdf(path_or_xml, *, poses=None, reference=None):
    """A :class:`~kinlib.Robot` from a URDF file path or URDF text.

    Malformed input raises :class:`~kinlib.URDFError` naming the element and line. As
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
    return _load(path_or_xml, poses, reference)[0]


def joints_as_written(path_or_xml):
    """``(robot, joints)``: :func:`load_urdf`'s robot and its ``<joint>`` elements as plain
    data with the numbers as the file writes them (document order).

    Each joint is a dict with ``name``, ``type``, ``parent``, ``child``, ``xyz`` and ``rpy``
    (lists of 3 floats; zeros where not written), ``axis`` (3 floats, *not* normalised;
    ``None`` for a fixed joint), ``limits`` (``(lower, upper)`` or ``None``) and ``mimic``
    (a :class:`~kinlib.model.Mimic` or ``None``), checked as :func:`load_urdf` checks them.

    >>> robot, (swing,) = joints_as_written('''<robot name="pendulum">
    ...   <link name="base"/> <link name="bob"/>
    ...   <joint name="swing" type="continuous"> <parent link="base"/> <child link="bob"/>
    ...     <origin xyz="0 0 1"/> <axis xyz="0 2 0"/> </joint>
    ... </robot>''')
    >>> robot.root, swing["xyz"], swing["rpy"], swing["axis"]
    ('base', [0.0, 0.0, 1.0], [0.0, 0.0, 0.0], [0.0, 2.0, 0.0])
    """
    robot, values = _load(path_or_xml)
    out = []
    for v in values:
        v = dict(v)
        for key in ("xyz", "rpy", "axis"):
            v[key] = None if v[key] is None else [float(x) for x in v[key]]
        out.append(v)
    return robot, out


# -- writing ---------------------------------------------------------------------------
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
    written exactly (``repr``), so :func:`load_urdf` gives back the same robot.

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
