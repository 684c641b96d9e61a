"""The 3-D scene as a Jupyter widget: meshcat's viewer over the notebook's own connection.

A :class:`Scene` is an anywidget whose view runs the meshcat viewer (the three.js bundle
that ships inside the meshcat package) in the notebook page. Scene commands are meshcat's
own command objects (``meshcat.commands``), packed with msgpack exactly as meshcat packs
them for its server, and they travel as widget state over the kernel's comm channel: no
server process, no ZeroMQ, no port of its own, so the viewer works wherever Jupyter does
(a laptop, JupyterHub, Binder, a remote kernel).

The widget state holds the whole scene, so a reloaded browser tab and an exported
notebook (saved widget state) show it again:

==================  ===================================================================
``_commands``       the scene's ``set_object`` / ``set_property`` / ``delete`` /
                    ``set_animation`` messages, compacted: a path's latest object, each
                    property's latest value; deleting a path drops what lay under it
``_pose_paths``     the paths that have a pose ...
``_poses``          ... and their 4x4 matrices, float32 column-major, in one buffer
``_seq``            how many pose updates were sent (the view counts what it drew)
==================  ===================================================================

Poses change every frame, so they are one binary buffer, sent alone; objects change
rarely. The meshcat bundle (~850 kB) is the state of one :class:`MeshcatBundle` widget
per kernel, which every scene refers to: it reaches the page once, however many viewers.
"""

from __future__ import annotations

import base64
import contextlib
import functools
import html
import json
import warnings
from pathlib import Path

import numpy as np

from ..errors import KinlibError

with warnings.catch_warnings():
    warnings.simplefilter("ignore", DeprecationWarning)
    warnings.simplefilter("ignore", ResourceWarning)
    import anywidget
    import ipywidgets
    import meshcat
    import traitlets as t
    import umsgpack
    from meshcat.commands import Delete, SetAnimation, SetObject, SetProperty
    from meshcat.path import Path as ScenePath

__all__ = ["Scene", "SceneNode", "MeshcatBundle", "bundle", "bundle_source", "scene_js",
           "scene_holder", "static_page", "inline_viewer", "close_tree", "check_height"]

BUNDLE_FILE = Path(meshcat.__file__).resolve().parent / "viewer" / "dist" / "main.min.js"


@functools.cache
def bundle_source() -> str:
    """The meshcat viewer's JavaScript bundle (three.js and meshcat), as shipped."""
    return BUNDLE_FILE.read_text(encoding="utf-8")


@functools.cache
def scene_js() -> str:
    """kinlib's scene view (``scene.js``): shared by the widget and exported pages."""
    from importlib import resources

    return resources.files(__package__).joinpath("scene.js").read_text(encoding="utf-8")


_ENTRY = """
async function kinlibMeshCat(model) {
  // the bundle, evaluated once per page (every scene shares it)
  if (!globalThis.__kinlibMeshCat) {
    globalThis.__kinlibMeshCat = (async () => {
      const ref = model.get("_bundle");
      const lib = await model.widget_manager.get_model(ref.slice("IPY_MODEL_".length));
      const module = { exports: {} };
      new Function("module", "exports", lib.get("source"))(module, module.exports);
      return module.exports;
    })();
    globalThis.__kinlibMeshCat.catch(() => { globalThis.__kinlibMeshCat = undefined; });
  }
  return globalThis.__kinlibMeshCat;
}

async function render({ model, el }) {
  const MeshCat = await kinlibMeshCat(model);
  const ctl = kinlibMountScene(MeshCat, el, model.get("height"));
  let applied = [];
  const commands = () => {
    const list = (model.get("_commands") || []).map(kinlibBytes);
    const grows = applied.length <= list.length &&
      applied.every((a, i) => kinlibSameBytes(a, list[i]));
    ctl.commands(grows ? list.slice(applied.length) : list);
    applied = list;
  };
  const poses = () => ctl.poses(model.get("_pose_paths") || [], model.get("_poses") || [],
                                model.get("_seq"));
  const everything = () => { commands(); poses(); };
  const height = () => ctl.height(model.get("height"));
  everything();
  model.on("change:_commands", everything);
  model.on("change:_poses", poses);
  model.on("change:height", height);
  return () => {
    model.off("change:_commands", everything);
    model.off("change:_poses", poses);
    model.off("change:height", height);
    ctl.dispose();
  };
}

export default { render };
"""


class MeshcatBundle(ipywidgets.Widget):
    """The meshcat viewer bundle as widget state (never displayed): one per kernel,
    shared by every :class:`Scene`, so the ~850 kB reach the page once."""

    source = t.Unicode().tag(sync=True)


_BUNDLE: list[MeshcatBundle] = []  # this kernel's one bundle widget


def bundle() -> MeshcatBundle:
    """This kernel's :class:`MeshcatBundle`, made on first use (again if it was closed)."""
    holder = _BUNDLE
    if not holder or holder[0].comm is None:
        holder[:] = [MeshcatBundle(source=bundle_source())]
    return holder[0]


def close_tree(widget) -> None:
    """Close ``widget`` and the widgets it holds (children, layout, style), so nothing of
    it stays in the kernel's widget registry (ipywidgets' ``close`` closes one widget)."""
    seen = set()

    def walk(w):
        if id(w) in seen or not isinstance(w, ipywidgets.Widget):
            return
        seen.add(id(w))
        for name in w.keys:
            if name == "_bundle":
                continue  # shared by every scene of the kernel
            value = getattr(w, name, None)
            for item in value if isinstance(value, list | tuple) else (value,):
                if isinstance(item, ipywidgets.Widget):
                    walk(item)
        w.close()

    walk(widget)


def check_height(height) -> int:
    """A viewer height in pixels: a positive whole number, else a :class:`KinlibError`."""
    if isinstance(height, bool) or not isinstance(height, int | np.integer) or height <= 0:
        raise KinlibError(f"height: expected a positive whole number of pixels, got {height!r}")
    return int(height)


def _key_path(path: str) -> str:
    return "/" + "/".join(p for p in path.split("/") if p)


def _under(path: str, root: str) -> bool:
    return path == root or path.startswith(root.rstrip("/") + "/")


class Scene(anywidget.AnyWidget):
    """A meshcat scene drawn in the notebook (display it: make it a cell's last value).

    Use it like ``meshcat.Visualizer``: ``scene["a/b"].set_object(geometry, material)``,
    ``.set_transform(T)``, ``.set_property(key, value)``, ``.delete()``,
    ``scene.set_animation(animation)``. ``frozen=True`` makes a picture that refuses
    changes (see :meth:`copy`).
    """

    _esm = scene_js() + _ENTRY
    _bundle = t.Instance(MeshcatBundle).tag(sync=True, **ipywidgets.widget_serialization)
    _kinlib = t.Unicode("scene").tag(sync=True)  # how exported pages find kinlib's scenes
    _commands = t.List(t.Bytes()).tag(sync=True)
    _pose_paths = t.List(t.Unicode()).tag(sync=True)
    _poses = t.Bytes(b"").tag(sync=True)
    _seq = t.Int(0).tag(sync=True)
    height = t.Int(400).tag(sync=True)

    def __init__(self, height: int = 400, frozen: bool = False):
        super().__init__(_bundle=bundle(), height=check_height(height))
        self._store: dict[tuple, bytes] = {}
        self._pose_of: dict[str, np.ndarray] = {}
        self._batches = 0  # open batch() blocks: the synced traits are set when they close
        self._pending: set[str] = set()
        self.frozen = bool(frozen)

    # -- the meshcat-like API ------------------------------------------------------------
    def __getitem__(self, path: str) -> SceneNode:
        return SceneNode(self, ScenePath(("meshcat",)).append(path))

    def set_animation(self, animation, play: bool = True, repetitions: int = 1) -> None:
        """Send a ``meshcat.animation.Animation`` (the viewer shows its play controls)."""
        self.send_command(SetAnimation(animation, play=play, repetitions=repetitions))

    def _check_open(self) -> None:
        if self.frozen:
            raise KinlibError("this scene is a frozen picture (a snapshot): change the "
                              "visualizer's live scene instead")

    def send_command(self, command) -> None:
        """Record a ``meshcat.commands`` object and send the changed scene to the view."""
        self._check_open()
        data = command.lower()
        kind = data["type"]
        path = _key_path(data.get("path", ""))
        if kind == "set_transform":
            self.set_poses({path: np.reshape(data["matrix"], (4, 4)).T})
            return
        if kind == "delete":
            for key in [k for k in self._store if k[0] != "animation" and _under(k[1], path)]:
                del self._store[key]
            for p in [p for p in self._pose_of if _under(p, path)]:
                del self._pose_of[p]
            key = ("delete", path)
        elif kind == "set_object":
            for key in [k for k in self._store if k[0] == "property" and k[1] == path]:
                del self._store[key]
            key = ("object", path)
        elif kind == "set_property":
            key = ("property", path, data["property"])
        elif kind == "set_animation":
            key = ("animation",)
        else:
            raise KinlibError(f"scene command: expected set_object, set_transform, "
                              f"set_property, set_animation or delete, got {kind!r}")
        self._store.pop(key, None)  # a changed entry moves to the end: the view replays
        self._store[key] = umsgpack.packb(data)
        if kind == "delete":
            self._changed("commands", "poses")
        else:
            self._changed("commands")

    def set_poses(self, poses: dict[str, np.ndarray]) -> None:
        """Set many paths' transforms (``path -> 4x4``) in one message."""
        self._check_open()
        for path, T in poses.items():
            self._pose_of[_key_path(path)] = np.asarray(T, dtype=np.float32)
        self._changed("poses")

    def _changed(self, *parts: str) -> None:
        """Set the synced traits of ``parts`` ("commands", "poses") from the store now, or
        when the outermost :meth:`batch` closes (each list is built and sent once)."""
        self._pending.update(parts)
        if self._batches:
            return
        parts, self._pending = self._pending, set()
        with self.hold_sync():
            if "commands" in parts:
                self._commands = list(self._store.values())
            if "poses" in parts:
                paths = list(self._pose_of)
                if paths:
                    stack = np.stack([self._pose_of[p] for p in paths])  # (n, 4, 4)
                    data = np.ascontiguousarray(stack.transpose(0, 2, 1),
                                                dtype=np.float32).tobytes()
                else:
                    data = b""
                self._pose_paths = paths
                self._poses = data
                self._seq = self._seq + 1

    def close(self) -> None:
        """Close the widget (its views leave the page) and its layout widget."""
        layout = getattr(self, "layout", None)
        super().close()
        if isinstance(layout, ipywidgets.Widget):
            layout.close()

    @contextlib.contextmanager
    def batch(self):
        """Send everything done inside as one message."""
        self._batches += 1
        try:
            yield self
        finally:
            self._batches -= 1
            if self._pending and not self._batches:
                self._changed()

    # -- copies and pages ------------------------------------------------------------------
    def copy(self, frozen: bool = True) -> Scene:
        """A new scene holding this scene as it is now; frozen (a picture) by default."""
        other = Scene(height=self.height)
        other._store = dict(self._store)
        other._pose_of = dict(self._pose_of)
        other._changed("commands", "poses")
        other.frozen = frozen
        return other

    def state(self) -> dict:
        """The scene as plain data: ``commands`` (bytes), ``paths``, ``poses`` (bytes),
        ``height`` -- what an exported page needs to draw it."""
        return {"commands": list(self._store.values()), "paths": list(self._pose_paths),
                "poses": bytes(self._poses), "height": int(self.height)}


class SceneNode:
    """A path in a :class:`Scene`, with meshcat's ``Visualizer`` methods."""

    __slots__ = ("path", "scene")

    def __init__(self, scene: Scene, path: ScenePath):
        self.scene = scene
        self.path = path

    def __getitem__(self, path: str) -> SceneNode:
        return SceneNode(self.scene, self.path.append(path))

    def set_object(self, geometry, material=None) -> None:
        self.scene.send_command(SetObject(geometry, material, self.path))

    def set_transform(self, matrix=None) -> None:
        T = np.eye(4) if matrix is None else np.asarray(matrix, dtype=float)
        if T.shape != (4, 4):
            raise KinlibError(f"set_transform: expected a 4x4 matrix, got shape {T.shape}")
        self.scene.set_poses({self.path.lower(): T})

    def set_property(self, key: str, value) -> None:
        self.scene.send_command(SetProperty(key, value, self.path))

    def delete(self) -> None:
        self.scene.send_command(Delete(self.path))

    def __repr__(self) -> str:
        return f"SceneNode({self.path.lower()!r})"


def scene_holder(state: dict) -> str:
    """The HTML element an exported page turns into a viewer: ``state`` as
    :meth:`Scene.state` gives it, inside ``<div class="kl-scene-static">``."""
    b64 = lambda data: base64.b64encode(bytes(data)).decode("ascii")  # noqa: E731
    data = {"commands": [b64(c) for c in state["commands"]], "paths": list(state["paths"]),
            "poses": b64(state["poses"]), "height": int(state["height"])}
    text = json.dumps(data).replace("</", "<\\/")  # never ends the script element early
    return (f'<div class="kl-scene-static" style="min-height: {data["height"]}px">'
            f'<script type="application/json">{text}</script></div>')


def static_page(states: list[dict], title: str = "kinlib scene") -> str:
    """A self-contained HTML page drawing ``states`` (see :meth:`Scene.state`): the
    meshcat bundle and kinlib's scene view inline, no kernel and no network needed."""
    holders = "\n".join(scene_holder(s) for s in states)
    return (f"<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>{html.escape(title)}"
            f"</title><style>body {{ margin: 0; }}</style></head><body>\n{holders}\n"
            f"{inline_viewer()}</body></html>\n")


def inline_viewer() -> str:
    """The scripts that turn a page's scene holders into viewers, inline (the meshcat
    bundle and kinlib's scene view): once per page, after its content."""
    return (f"<script>{bundle_source()}</script>\n<script>{scene_js()}\n"
            "kinlibStaticScenes(MeshCat, document);</script>\n")
