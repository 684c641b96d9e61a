"""Small helpers of :class:`kinlib.viz.RobotVisualizer`: colours, server probe, mesh files.

meshcat is imported here (and only in :mod:`kinlib.viz`), with the warnings its import
raises under current pyzmq (``zmq.eventloop.ioloop`` is deprecated) filtered locally.
"""

from __future__ import annotations

import os
import warnings
from pathlib import Path

import numpy as np

from .._viewer_server import own_server
from ..errors import KinlibError

with warnings.catch_warnings():
    warnings.simplefilter("ignore", DeprecationWarning)
    warnings.simplefilter("ignore", ResourceWarning)
    import meshcat
    import meshcat.geometry as mg
    import zmq

__all__ = ["color_int", "material", "connect", "mesh_geometry",
           "resolve_mesh", "ZMQ_ENV", "WEB_ENV"]

#: environment variable naming the meshcat server to use (set by the test session)
ZMQ_ENV = "KINLIB_MESHCAT_ZMQ_URL"
#: its web address, for browsers
WEB_ENV = "KINLIB_MESHCAT_WEB_URL"


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


def _probe(zmq_url: str, timeout: float) -> str:
    """Ask the server at ``zmq_url`` for its web URL; a clear error if nobody answers."""
    ctx = zmq.Context.instance()
    sock = ctx.socket(zmq.REQ)
    sock.setsockopt(zmq.LINGER, 0)
    try:
        sock.connect(zmq_url)
        sock.send(b"url")
        if not sock.poll(int(timeout * 1000)):
            raise KinlibError(f"no meshcat server answers at {zmq_url!r} (waited {timeout} s); "
                              "start one with `python -m meshcat.servers.zmqserver` or pass "
                              "zmq_url=None to start one")
        return sock.recv().decode("utf-8")
    except zmq.ZMQError as exc:
        raise KinlibError(f"cannot connect to a meshcat server at {zmq_url!r}: {exc}") from None
    finally:
        sock.close()


def connect(zmq_url=None, timeout: float = 10.0):
    """A ``meshcat.Visualizer``: at ``zmq_url``, else ``$KINLIB_MESHCAT_ZMQ_URL``, else
    this process's own server (:func:`kinlib._viewer_server.own_server`: started on first
    use, shared by all visualizers of the process, ended with the process even if it is
    killed).
    """
    if zmq_url is None:
        zmq_url = os.environ.get(ZMQ_ENV) or None
    if zmq_url is None:
        zmq_url = own_server().zmq_url
    if not isinstance(zmq_url, str):
        raise KinlibError(f"zmq_url: expected a string such as 'tcp://127.0.0.1:6000', "
                          f"got {zmq_url!r}")
    _probe(zmq_url, timeout)
    return meshcat.Visualizer(zmq_url=zmq_url)


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
