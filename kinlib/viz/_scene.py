"""Small helpers of :class:`kinlib.viz.RobotVisualizer`: colours, materials, mesh files.

meshcat is imported here (and only in :mod:`kinlib.viz`), with the warnings its import
raises under current pyzmq (``zmq.eventloop.ioloop`` is deprecated: meshcat's package
imports its server module, which kinlib never starts) filtered locally.
"""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np

from ..errors import KinlibError

with warnings.catch_warnings():
    warnings.simplefilter("ignore", DeprecationWarning)
    warnings.simplefilter("ignore", ResourceWarning)
    import meshcat.geometry as mg

__all__ = ["color_int", "material", "mesh_geometry", "resolve_mesh", "sphere", "cylinder",
           "SPHERE_SEGMENTS", "CYLINDER_SEGMENTS"]

#: triangles per primitive: meshcat draws spheres 20 x 20 and cylinders with 50 sides;
#: kinlib's links are thin, and a software renderer (a headless browser, a remote desktop)
#: draws a 50-link robot about 5 times faster with these (bench/bench_viewer.py)
SPHERE_SEGMENTS = (16, 10)
CYLINDER_SEGMENTS = 16


class _Sphere(mg.Sphere):
    """meshcat's sphere, with :data:`SPHERE_SEGMENTS` (meshcat fixes 20 x 20)."""

    def lower(self, object_data):
        data = super().lower(object_data)
        data["widthSegments"], data["heightSegments"] = SPHERE_SEGMENTS
        return data


def sphere(radius: float):
    """A meshcat sphere geometry of ``radius`` with kinlib's segment counts."""
    return _Sphere(float(radius))


def cylinder(height: float, radius: float):
    """A meshcat cylinder geometry (along its local y) with kinlib's segment count."""
    geom = mg.Cylinder(float(height), float(radius))
    geom.radialSegments = CYLINDER_SEGMENTS
    return geom


def color_int(color, name: str = "color") -> int:
    """A colour as three.js's integer ``0xRRGGBB``.

    Accepts an int ``0xRRGGBB``, a string ``"#rrggbb"`` or ``(r, g, b[, a])`` in [0, 1].

    >>> hex(color_int("#ff00ff")), hex(color_int((1.0, 0.5, 0.0))), color_int(0x00FF00)
    ('0xff00ff', '0xff8000', 65280)
    """
    if isinstance(color, bool):
        raise KinlibError(f"{name}: expected a colour, got {color!r}")
    if isinstance(color, int | np.integer):
        if not 0 <= int(color) <= 0xFFFFFF:
            raise KinlibError(f"{name}: expected an integer 0xRRGGBB in [0, 0xFFFFFF], "
                              f"got {color!r}")
        return int(color)
    if isinstance(color, str):
        text = color.strip().lstrip("#")
        if len(text) != 6 or any(ch not in "0123456789abcdefABCDEF" for ch in text):
            raise KinlibError(f"{name}: expected a colour string '#rrggbb', got {color!r}")
        return int(text, 16)
    try:
        c = np.asarray(color, dtype=float)
    except (TypeError, ValueError):
        c = None
    if c is None or c.shape not in ((3,), (4,)) or not np.isfinite(c).all() \
            or (c < 0).any() or (c > 1).any():
        raise KinlibError(f"{name}: expected 0xRRGGBB, '#rrggbb' or (r, g, b[, a]) in [0, 1], "
                          f"got {color!r}")
    r, g, b = (int(x) for x in np.rint(255 * c[:3]))
    return (r << 16) | (g << 8) | b


def material(color, opacity: float = 1.0):
    """A meshcat Phong material of ``color`` (see :func:`color_int`)."""
    return mg.MeshPhongMaterial(color=color_int(color), opacity=float(opacity))


_SCHEMES = ("package://", "file://", "model://")


def resolve_mesh(filename: str, mesh_dir=None) -> Path | None:
    """The existing file a URDF mesh ``filename`` refers to, or None.

    ``package://pkg/meshes/a.stl`` is looked up as ``mesh_dir/pkg/meshes/a.stl`` and
    ``mesh_dir/meshes/a.stl``; ``file://`` and absolute paths are used as they are; other
    relative paths are taken relative to ``mesh_dir`` (or the working directory).
    """
    candidates = []
    rel = filename
    for scheme in _SCHEMES:
        if filename.startswith(scheme):
            rel = filename[len(scheme):]
            if scheme == "file://":
                candidates.append(Path(rel))
            break
    path = Path(rel)
    if path.is_absolute():
        candidates.append(path)
    else:
        base = Path(mesh_dir) if mesh_dir is not None else Path.cwd()
        candidates.append(base / path)
        if filename.startswith(("package://", "model://")) and len(path.parts) > 1:
            candidates.append(base.joinpath(*path.parts[1:]))
    for c in candidates:
        if c.is_file():
            return c
    return None


_MESH_LOADERS = {".stl": mg.StlMeshGeometry, ".obj": mg.ObjMeshGeometry,
                 ".dae": mg.DaeMeshGeometry}


def mesh_geometry(path: Path):
    """A meshcat mesh geometry for an ``.stl``, ``.obj`` or ``.dae`` file, else None."""
    loader = _MESH_LOADERS.get(path.suffix.lower())
    return None if loader is None else loader.from_file(str(path))
