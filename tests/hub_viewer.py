"""The 3-D viewer the way students meet Jupyter: on a hub, a remote machine, Binder.

What tests/test_lab.py's JupyterLab and Notebook 7 checks share: a
Jupyter server under a base URL, as a JupyterHub serves ``/user/NAME/``, and a browser
page that may reach that server's URLs only: every other request (another port, another
path, the internet) is aborted and recorded, and so is any websocket to anywhere else; any
recorded request fails the test. In that page a notebook (``viewer.ipynb``) draws the PUMA
560 in a viewer (pixels of its orange joint axes), a joint slider moves it, and removing the
robot from the kernel's side empties the view (the control: the pixel check can tell an
empty scene), while a second viewer in the same notebook is untouched by both (two viewers
are independent). In JupyterLab also:

- reloading the browser tab (the notebook saved) shows the scene again, from the widget
  state the kernel holds;
- running the viewer's cell again and again replaces its scene: the viewers and WebGL
  canvases in the page stay two, the kernel holds no more widgets than after the first
  run, and the meshcat bundle was evaluated once in the page (its one style sheet).
"""

from __future__ import annotations

import json
import re
import time
from pathlib import Path

import nbformat
from browser_helpers import (
    AXES_SEEN,
    EMPTY,
    ROBOT,
    STILL,
    assert_robot_drawn,
    drag_slider,
    element_shooter,
    pixels_changed,
    settled,
    solid_axes,
    wait_for_mask,
)

BASE_URL = "/user/student/"
NAME = "viewer"  # the notebook: viewer.ipynb
VIEWER_CELL = """from kinlib.robots import puma560
from kinlib.viz import RobotVisualizer, joint_panel

robot = puma560()
viz = RobotVisualizer(robot, prefix="hub/puma560")
viz.set_configuration(robot.poses["ready"])
viz.jupyter_cell(height=360)"""
PANEL_CELL = "joint_panel(viz)"
SECOND_CELL = """from kinlib.robots import planar_2r

viz2 = RobotVisualizer(planar_2r(0.4, 0.3), prefix="hub/arm2")
viz2.jupyter_cell(height=240)"""
WIDGETS_CELL = ("from ipywidgets.widgets.widget import _instances  # the kernel's live widgets\n"
                "print('WIDGETS', len(_instances))")
NOTEBOOK = ".jp-NotebookPanel:not(.lm-mod-hidden)"
MOVED = 200  # pixels of a viewer that must change when a joint slider turns the robot


def write_viewer_notebook(folder: Path) -> Path:
    """``viewer.ipynb`` in ``folder``: the two viewers, a joint panel and a widget count."""
    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(VIEWER_CELL),
                                         nbformat.v4.new_code_cell(PANEL_CELL),
                                         nbformat.v4.new_code_cell(WIDGETS_CELL),
                                         nbformat.v4.new_code_cell(SECOND_CELL)])
    nb.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3",
                                 "language": "python"}
    path = Path(folder) / f"{NAME}.ipynb"
    nbformat.write(nb, path)
    return path


def fenced_page(browser, server):
    """A new context and page that may reach ``server``'s URLs only, and the list of
    everything else the page tried. ``page.errors``: its uncaught exceptions;
    ``page.console``: its console messages."""
    allowed = server.base + "/"
    ws_allowed = allowed.replace("http://", "ws://", 1)
    refused: list[str] = []
    context = browser.new_context(viewport={"width": 1280, "height": 900})

    def gate(route):
        if route.request.url.startswith(allowed):
            route.continue_()
        else:
            refused.append(route.request.url)
            route.abort()

    context.route("**/*", gate)
    page = context.new_page()
    page.on("websocket", lambda ws: None if ws.url.startswith(ws_allowed)
            else refused.append(ws.url))
    page.errors = []
    page.on("pageerror", lambda e: page.errors.append(str(e)))
    page.console = []
    page.on("console", lambda m: page.console.append(f"{m.type}: {m.text}"))
    return context, page, refused


def kernel_idle(server, name: str = NAME) -> dict | None:
    """The notebook's session once its kernel is idle, else None."""
    sessions = [s for s in server.api("GET", "api/sessions")
                if s["path"].endswith(f"{name}.ipynb")]
    if sessions and sessions[0]["kernel"]["execution_state"] == "idle":
        return sessions[0]
    return None


def printed_widgets(page) -> int:
    text = page.locator(f"{NOTEBOOK} .jp-OutputArea-output", has_text="WIDGETS").last
    return int(re.search(r"WIDGETS (\d+)", text.inner_text()).group(1))


def run_cell(page, index: int) -> None:
    """Run code cell ``index`` again from the page (click it and press Ctrl+Enter, as a
    student presses) and wait until its prompt shows the new count."""
    cell = page.locator(f"{NOTEBOOK} .jp-CodeCell").nth(index)
    before = cell.locator(".jp-InputPrompt").inner_text().strip()
    cell.locator(".jp-InputArea-editor").click()
    page.keyboard.press("Control+Enter")
    page.wait_for_function(
        f"""() => {{ const p = document.querySelectorAll('{NOTEBOOK} .jp-CodeCell')[{index}]
          .querySelector('.jp-InputPrompt').innerText.trim();
          return /^\\[\\d+\\]:$/.test(p) && p !== {json.dumps(before)}; }}""", timeout=60_000)


def run_in_kernel(server, code: str) -> None:
    """Run ``code`` in the notebook's kernel through a second client (as another cell
    would): what it changes reaches the page over the widget's comm."""
    from jupyter_client import BlockingKernelClient

    session = kernel_idle(server)
    assert session is not None
    client = BlockingKernelClient(connection_file=str(
        Path(server.work) / "runtime" / f"kernel-{session['kernel']['id']}.json"))
    client.load_connection_file()
    client.start_channels()
    try:
        reply = client.execute_interactive(code, timeout=30)
        assert reply["content"]["status"] == "ok", reply["content"]
    finally:
        client.stop_channels()


def wait_for_kernel(server, page, timeout: float = 90.0) -> None:
    deadline = time.monotonic() + timeout
    while kernel_idle(server) is None:
        assert time.monotonic() < deadline, "the kernel did not become idle"
        page.wait_for_timeout(250)


def check_viewers(server, page, refused: list, tmp_path: Path, at_load: list[str],
                  reopen=None) -> None:
    """The checks of this module's docstring, on ``viewer.ipynb`` open in ``page`` with
    every cell run; ``at_load``: the page's errors before its cells ran (the app's own, if
    it has any), to which the viewers may add none. ``reopen()`` (JupyterLab) loads the app
    on the notebook again, as reloading the tab does: then the reload and re-run checks
    run too."""
    lab = reopen is not None
    app = "JupyterLab" if lab else "Notebook 7"
    scenes = page.locator(f"{NOTEBOOK} .jp-OutputArea-output .kinlib-scene")
    assert scenes.count() == 2, f"{scenes.count()} viewers"
    scene, other = scenes.first, scenes.nth(1)
    other_png = assert_robot_drawn(other, f"{app}: the second viewer",
                                   tmp_path / "other.png")
    png = assert_robot_drawn(scene, f"{app}: the viewer", tmp_path / "drawn.png")

    # a joint slider turns the robot; the control: untouched, the picture stays
    shoot = element_shooter(scene)
    before = settled(shoot)
    assert pixels_changed(before, shoot()) <= STILL, "the viewer changes by itself"
    slider = page.locator(f"{NOTEBOOK} .widget-slider",
                          has=page.locator(".widget-label", has_text="joint2"))
    value0 = slider.locator(".widget-readout").inner_text()
    drag_slider(page, slider, 70)
    png_moved, _ = wait_for_mask(
        shoot, lambda p: pixels_changed(before, p), lambda n: n >= MOVED, timeout=15)
    (tmp_path / "moved.png").write_bytes(png_moved)
    assert slider.locator(".widget-readout").inner_text() != value0
    assert pixels_changed(before, png_moved) >= MOVED, "the slider did not move the robot"
    assert pixels_changed(other_png, settled(element_shooter(other))) <= STILL, \
        "the slider of the first viewer changed the second"

    if lab:
        # save (as autosave would) and reload the tab: the saved output names the widget,
        # and the scene comes back from its state in the running kernel
        page.locator(f"{NOTEBOOK} .jp-Notebook").click(position={"x": 5, "y": 5})
        page.keyboard.press("Control+s")
        page.wait_for_function("() => !document.querySelector("
                               "'#jp-main-dock-panel .lm-TabBar-tab.jp-mod-dirty')",
                               timeout=30_000)
        reopen()
        page.wait_for_selector(f"{NOTEBOOK} .kinlib-scene", timeout=90_000)
        scene = page.locator(f"{NOTEBOOK} .jp-OutputArea-output .kinlib-scene").first
        assert_robot_drawn(scene, "after a reload", tmp_path / "reloaded.png")
        # run the viewer cell again and again: one scene, no widgets piling up
        run_cell(page, 2)
        widgets_before = printed_widgets(page)
        for _ in range(3):  # (a widget left behind per run would show as 3 or more)
            run_cell(page, 0)
        run_cell(page, 1)
        run_cell(page, 2)
        scene = page.locator(f"{NOTEBOOK} .jp-OutputArea-output .kinlib-scene")
        assert scene.count() == 2, f"{scene.count()} viewers after re-running the cell"
        assert page.locator(f"{NOTEBOOK} canvas").count() == 2
        assert printed_widgets(page) <= widgets_before, "widgets pile up in the kernel"
        sheets = page.evaluate("() => [...document.styleSheets].filter(s => [...s.cssRules]"
                               ".some(r => r.cssText.includes('meshcat-visibility-checkbox')"
                               ")).length")
        assert sheets == 1, f"the meshcat bundle was evaluated {sheets} times"
        scene, other = scene.first, scene.nth(1)
        png = assert_robot_drawn(scene, "after re-running", tmp_path / "rerun.png")

    # the control: remove the robot in the kernel; the view must empty
    run_in_kernel(server, "viz.delete()")
    empty_png, empty = wait_for_mask(element_shooter(scene), solid_axes,
                                     lambda m: m.sum() <= EMPTY, timeout=20)
    (tmp_path / "emptied.png").write_bytes(empty_png)
    assert empty.sum() <= EMPTY, f"{empty.sum()} joint-axis pixels with the robot deleted"
    assert int(solid_axes(png).sum()) >= AXES_SEEN
    assert pixels_changed(png, empty_png) >= ROBOT
    left = int(solid_axes(settled(element_shooter(other))).sum())
    assert left >= AXES_SEEN, f"the second viewer lost its robot too ({left} pixels)"

    assert not refused, f"requests outside {server.base}/: {refused[:5]}"
    assert page.errors == at_load, page.errors[len(at_load):][:3]
    assert not lab or not at_load, at_load  # JupyterLab loads cleanly
    lost = [m for m in page.console if "WebGL" in m and "context" in m.lower()]
    assert not lost, lost[:3]
