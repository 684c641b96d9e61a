"""Reading URDF: the kinematic subset, with errors that name element and line (writing:
:mod:`kinlib.models.urdf_write`).

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
from dataclasses import dataclass
from xml.parsers import expat

import numpy as np

from ..errors import KinlibError, TreeError, URDFError
from .tree import (
    Joint,
    Link,
    Mimic,
    Visual,
    built_transform,
    origin_from_xyz_rpy,
)

__all__ = ["read_urdf", "URDFDescription", "joints_as_written", "MAX_BYTES"]

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


@dataclass(frozen=True)
class URDFDescription:
    """What a URDF file describes: the robot's name, its links and joints (in document
    order), and where each named element is, so that :meth:`located` can say which line a
    :class:`~kinlib.errors.TreeError` is about."""

    name: str
    links: tuple
    joints: tuple
    source: _Source
    #: each ``<joint>`` as the file writes it (see :func:`joints_as_written`)
    written: tuple = ()

    def located(self, error: TreeError) -> URDFError:
        """``error`` (raised for these links and joints) as a URDFError with the file and
        the line of the element at fault."""
        els = self.source.lines.get(error.element) if error.element else None
        line = f":{els[min(error.nth, len(els) - 1)].line}" if els else ""
        return URDFError(f"{self.source.label}{line}: {error}")


def read_urdf(path_or_xml) -> URDFDescription:
    """Read a URDF file path or URDF text: its name, links and joints
    (:class:`URDFDescription`); :func:`kinlib.load_urdf` makes the robot from them.

    Malformed input raises :class:`~kinlib.URDFError` naming the element and line.

    >>> d = read_urdf('<robot name="r"><link name="a"/><link name="b"/>'
    ...               '<joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint>'
    ...               '</robot>')
    >>> d.name, [lk.name for lk in d.links], [jt.type for jt in d.joints]
    ('r', ['a', 'b'], ['fixed'])
    """
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
    return URDFDescription(name, tuple(links), tuple(joints), src, tuple(values))


def joints_as_written(path_or_xml) -> list[dict]:
    """The ``<joint>`` elements of a URDF as plain data, with the numbers as the file writes
    them (document order), checked as :func:`read_urdf` checks them.

    Each joint is a dict with ``name``, ``type``, ``parent``, ``child``, ``xyz`` and ``rpy``
    (lists of 3 floats; zeros where not written), ``axis`` (3 floats, *not* normalised;
    ``None`` for a fixed joint), ``limits`` (``(lower, upper)`` or ``None``) and ``mimic``
    (a :class:`~kinlib.models.tree.Mimic` or ``None``).

    >>> (swing,) = joints_as_written('''<robot name="pendulum">
    ...   <link name="base"/> <link name="bob"/>
    ...   <joint name="swing" type="continuous"> <parent link="base"/> <child link="bob"/>
    ...     <origin xyz="0 0 1"/> <axis xyz="0 2 0"/> </joint>
    ... </robot>''')
    >>> swing["xyz"], swing["rpy"], swing["axis"]
    ([0.0, 0.0, 1.0], [0.0, 0.0, 0.0], [0.0, 2.0, 0.0])
    """
    out = []
    for v in read_urdf(path_or_xml).written:
        v = dict(v)
        for key in ("xyz", "rpy", "axis"):
            v[key] = None if v[key] is None else [float(x) for x in v[key]]
        out.append(v)
    return out
