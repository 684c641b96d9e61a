"""Static pictures of ipywidgets for the exported course site.

A page exported from an executed notebook has no kernel, so a slider cannot drive anything.
Rather than load a widget manager from a CDN (the site must work offline), each widget
output becomes plain HTML drawn from the widget state nbclient saved: sliders as disabled
range inputs at their value, buttons as disabled buttons, boxes as flex boxes, and ``Output``
widgets as the outputs they held when the notebook ran, under a note saying the controls
are live in JupyterLab.
"""

from __future__ import annotations

import html

__all__ = ["WIDGET_VIEW", "WIDGET_STATE", "render_widget", "freeze_widgets", "scene_state",
           "SCENE_SCRIPTS", "with_viewer"]

WIDGET_VIEW = "application/vnd.jupyter.widget-view+json"
WIDGET_STATE = "application/vnd.jupyter.widget-state+json"
_REF = "IPY_MODEL_"
NOTE = ("<p class=\"kl-widget-note\">Interactive in JupyterLab: these controls are a picture "
        "of their state when the notebook ran.</p>")


def _children(state: dict) -> list[str]:
    return [c[len(_REF):] for c in state.get("children", []) if str(c).startswith(_REF)]


def _output_html(output: dict) -> str:
    """One saved output (stream, display data, result or error) as HTML."""
    kind = output.get("output_type")
    if kind == "stream":
        return f"<pre>{html.escape(''.join(output.get('text', '')))}</pre>"
    if kind == "error":
        return f"<pre class=\"kl-widget-error\">{html.escape(output.get('ename', 'error'))}</pre>"
    data = output.get("data", {})
    if WIDGET_VIEW in data:
        return ""  # a widget inside an Output widget: drawn from its own model elsewhere
    for mime in ("image/png", "image/jpeg"):
        if mime in data:
            b64 = "".join(data[mime]).replace("\n", "")
            return f"<img src=\"data:{mime};base64,{b64}\" alt=\"figure\">"
    if "image/svg+xml" in data:
        return "".join(data["image/svg+xml"])
    if "text/html" in data:
        return "".join(data["text/html"])
    if "text/latex" in data:
        return "".join(data["text/latex"])
    return f"<pre>{html.escape(''.join(data.get('text/plain', '')))}</pre>"


#: what a page with 3-D scenes loads once, after its content (the files: ``_static/``)
SCENE_SCRIPTS = ('<script src="_static/meshcat.min.js"></script>\n'
                 '<script src="_static/kinlib-scene.js"></script>\n'
                 '<script>kinlibStaticScenes(MeshCat, document);</script>\n')


def with_viewer(page: str, scripts: str = SCENE_SCRIPTS) -> str:
    """``page`` with ``scripts`` (the viewer) before ``</body>`` if it holds a scene."""
    if 'class="kl-scene-static"' not in page:
        return page
    at = page.rindex("</body>")
    return page[:at] + scripts + page[at:]


def scene_state(model: dict) -> dict:
    """A saved kinlib scene widget (``model_name``, ``state``, ``buffers``) as the plain
    scene :func:`kinlib.viz.static_page` draws: binary buffers put back in their places."""
    import base64

    state = dict(model.get("state", {}))
    state["_commands"] = list(state.get("_commands", []))
    for buf in model.get("buffers", []):
        data = base64.b64decode(buf["data"]) if buf.get("encoding") == "base64" else b""
        where = buf["path"]
        if len(where) == 1:
            state[where[0]] = data
        elif len(where) == 2 and where[0] == "_commands":
            state["_commands"][where[1]] = data
    poses = state.get("_poses", b"")
    return {"commands": [c if isinstance(c, bytes) else b"" for c in state["_commands"]],
            "paths": list(state.get("_pose_paths", [])),
            "poses": poses if isinstance(poses, bytes) else b"",
            "height": int(state.get("height", 400))}


def render_widget(model_id: str, models: dict, _depth: int = 0) -> str:
    """HTML for the widget ``model_id`` and its children, from saved widget ``models``
    (``{id: {"model_name": ..., "state": {...}}}``). Unknown widgets become their name."""
    model = models.get(model_id)
    if model is None or _depth > 20:
        return "<span class=\"kl-widget\">[widget]</span>"
    name = model.get("model_name", "")
    state = model.get("state", {})
    if state.get("_kinlib") == "scene":  # a 3-D scene: drawn live by the page's viewer
        from ..viz._widget import scene_holder

        return scene_holder(scene_state(model))
    desc = html.escape(str(state.get("description", "")))
    if name.endswith("SliderModel"):
        value = state.get("value", 0)
        if isinstance(value, list):  # a range slider
            shown, value = " – ".join(f"{v:g}" for v in value), value[0]
        else:
            shown = f"{value:g}" if isinstance(value, int | float) else html.escape(str(value))
        return (f"<div class=\"kl-widget kl-slider\"><label>{desc}</label>"
                f"<input type=\"range\" disabled min=\"{state.get('min', 0)}\" "
                f"max=\"{state.get('max', 100)}\" step=\"{state.get('step', 1)}\" "
                f"value=\"{value}\"><output>{shown}</output></div>")
    if name == "ButtonModel":
        return f"<button class=\"kl-widget\" disabled>{desc}</button>"
    if name.endswith("BoxModel"):
        direction = "row" if name.startswith("HBox") else "column"
        inner = "".join(render_widget(c, models, _depth + 1) for c in _children(state))
        return (f"<div class=\"kl-widget kl-box\" style=\"display: flex; "
                f"flex-direction: {direction}; gap: 4px\">{inner}</div>")
    if name == "OutputModel":
        inner = "".join(_output_html(o) for o in state.get("outputs", []))
        return f"<div class=\"kl-widget kl-output\">{inner}</div>"
    if name in ("HTMLModel", "HTMLMathModel"):
        return f"<div class=\"kl-widget\">{state.get('value', '')}</div>"
    if name in ("LabelModel", "TextModel", "FloatTextModel", "BoundedFloatTextModel",
                "IntTextModel", "BoundedIntTextModel", "CheckboxModel", "DropdownModel"):
        value = html.escape(str(state.get("value", state.get("index", ""))))
        return f"<div class=\"kl-widget\"><label>{desc}</label> <code>{value}</code></div>"
    return f"<span class=\"kl-widget\">[{html.escape(name.removesuffix('Model'))}]</span>"


def freeze_widgets(nb) -> int:
    """Replace every widget output of ``nb`` (in place) by its static picture and drop the
    saved widget state, so the exported page loads no widget manager. Returns how many
    widget outputs were replaced."""
    saved = nb.metadata.pop("widgets", {}) or {}
    models = saved.get(WIDGET_STATE, {}).get("state", {})
    replaced = 0
    for cell in nb.cells:
        for output in cell.get("outputs", []):
            data = output.get("data", {})
            if WIDGET_VIEW not in data:
                continue
            model_id = data[WIDGET_VIEW].get("model_id", "")
            body = render_widget(model_id, models)
            if body.startswith('<div class="kl-scene-static"'):
                output["data"] = {"text/html": body}  # orbitable: no "a picture" note
            else:
                output["data"] = {"text/html": f"<div class=\"kl-frozen\">{NOTE}{body}</div>"}
            output.get("metadata", {}).pop(WIDGET_VIEW, None)
            replaced += 1
    return replaced
