"""The robot really appears in a browser: headless Chromium renders the meshcat viewer.

The PUMA 560 is drawn in a saturated magenta no other part of the viewer uses (sky-blue
background, grey grid, orange joint axes), so its pixels can be counted in a screenshot.
The same counting function must find (almost) nothing once the robot is deleted: that is
what shows this test can fail. Needs Chromium at /usr/bin/chromium; without it the test
is skipped, or fails when ``KINLIB_REQUIRE_BROWSER=1`` (CI installs Chromium).
"""

import html
import io
import os
import re
import time
from pathlib import Path

import numpy as np
from browser_helpers import AXIS_SEEN, EMPTY, changed_fraction, joint_axis_mask

from kinlib.robots import puma560

MAGENTA = 0xFF00FF
SEEN = 300  # robot pixels needed to call the robot drawn (it covers ~2000 at 800x600)


def robot_mask(png: bytes) -> np.ndarray:
    """Pixels whose colour is (shaded) magenta: red and blue high, green well below both."""
    from PIL import Image

    rgb = np.asarray(Image.open(io.BytesIO(png)).convert("RGB"), dtype=int)
    r, g, b = rgb[..., 0], rgb[..., 1], rgb[..., 2]
    lo = np.minimum(r, b)
    return (lo > 70) & (g < 0.55 * lo) & (np.abs(r - b) < 0.4 * np.maximum(r, b))


def wait_for_picture(page, accept, timeout=15.0):
    """Screenshot until ``accept(mask)`` holds (rendering is asynchronous); the last mask."""
    deadline = time.monotonic() + timeout
    while True:
        png = page.screenshot()
        mask = robot_mask(png)
        if accept(mask) or time.monotonic() > deadline:
            return png, mask
        page.wait_for_timeout(150)


def test_mask_on_synthetic_images():
    from PIL import Image

    img = np.zeros((10, 10, 3), dtype=np.uint8)
    img[:] = (120, 190, 250)  # sky
    img[2:5, 2:5] = (200, 0, 200)  # shaded magenta
    img[6:8, 6:8] = (232, 163, 23)  # orange joint axis
    buf = io.BytesIO()
    Image.fromarray(img).save(buf, format="PNG")
    assert robot_mask(buf.getvalue()).sum() == 9


def test_puma_in_the_live_viewer_and_the_static_page(browser, tmp_path):
    from kinlib.viz import RobotVisualizer

    robot = puma560()
    viz = RobotVisualizer(robot, prefix="browser_puma", color=MAGENTA)
    viz.vis.delete()  # an empty scene: only this robot
    viz = RobotVisualizer(robot, prefix="browser_puma", color=MAGENTA)
    viz.set_camera_position([1.1, -1.0, 0.8])
    q = np.zeros(6)
    viz.set_configuration(q)
    context = browser.new_context(viewport={"width": 800, "height": 600})
    try:
        page = context.new_page()
        page.goto(viz.url())
        page.wait_for_selector("canvas", timeout=15_000)
        png, first = wait_for_picture(page, lambda m: m.sum() >= SEEN)
        (tmp_path / "puma.png").write_bytes(png)
        assert first.sum() >= SEEN, f"only {first.sum()} robot pixels; see {tmp_path}"

        q[0] += np.pi / 2
        viz.set_configuration(q)
        png, turned = wait_for_picture(page, lambda m: changed_fraction(first, m) > 0.5)
        (tmp_path / "puma_turned.png").write_bytes(png)
        assert turned.sum() >= SEEN
        assert changed_fraction(first, turned) > 0.5

        viz.save_html(tmp_path / "puma.html")
        offline = browser.new_context(viewport={"width": 800, "height": 600})
        try:  # the snapshot must render without the server: block all http(s)
            offline.route(re.compile(r"^https?://"), lambda route: route.abort())
            still = offline.new_page()
            still.goto((tmp_path / "puma.html").as_uri())
            still.wait_for_selector("canvas", timeout=15_000)
            png, snap = wait_for_picture(still, lambda m: m.sum() >= SEEN)
            (tmp_path / "static.png").write_bytes(png)
            assert snap.sum() >= SEEN, f"static page: only {snap.sum()} robot pixels"
        finally:
            offline.close()

        viz.delete()
        png, empty = wait_for_picture(page, lambda m: m.sum() <= EMPTY)
        (tmp_path / "empty.png").write_bytes(png)
        assert empty.sum() <= EMPTY, f"{empty.sum()} robot-coloured pixels on an empty scene"
    finally:
        context.close()
        viz.delete()


NOTEBOOKS = Path(__file__).resolve().parents[1] / "notebooks"
SESSION_KEYS = ("KINLIB_MESHCAT_ZMQ_URL", "KINLIB_MESHCAT_WEB_URL", "KINLIB_MESHCAT_SERVER_PID")


def meshcat_servers() -> set[int]:
    found = set()
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            try:
                with open(f"/proc/{entry}/cmdline", "rb") as fh:
                    if b"meshcat.servers.zmqserver" in fh.read():
                        found.add(int(entry))
            except OSError:
                continue
    return found


def export_html(name: str, static: bool, monkeypatch) -> str:
    """Execute notebook ``name`` in its own kernel (its own server, as in class) and export
    it to HTML with nbconvert, with or without ``KINLIB_STATIC_SCENES=1``."""
    import nbformat
    from nbclient import NotebookClient
    from nbconvert import HTMLExporter

    from kinlib.viz import STATIC_ENV

    with monkeypatch.context() as m:
        for key in SESSION_KEYS:
            m.delenv(key, raising=False)
        m.setenv(STATIC_ENV, "1" if static else "0")
        nb = nbformat.read(NOTEBOOKS / f"{name}.ipynb", as_version=4)
        NotebookClient(nb, timeout=120, kernel_name="python3",
                       resources={"metadata": {"path": str(NOTEBOOKS)}}).execute()
    body, _ = HTMLExporter().from_notebook_node(nb)
    return body


SCENE_NAMES = "() => { const n = []; viewer.scene.traverse(o => n.push(o.name)); return n; }"


def open_scene(browser, page_file: Path, shot: Path) -> tuple[int, list[str]]:
    """Open an exported page with all http(s) blocked and look at its first scene: the
    joint-axis pixels of a screenshot, and the names in its three.js scene graph."""
    context = browser.new_context(viewport={"width": 1000, "height": 800})
    try:
        context.route(re.compile(r"^https?://"), lambda route: route.abort())
        page = context.new_page()
        page.goto(page_file.as_uri())
        frame_el = page.locator("iframe").first
        frame_el.scroll_into_view_if_needed(timeout=15_000)
        frame = frame_el.element_handle().content_frame()
        deadline = time.monotonic() + 15.0
        while True:
            png = frame_el.screenshot()
            count = int(joint_axis_mask(png).sum())
            if count >= AXIS_SEEN or time.monotonic() > deadline:
                shot.write_bytes(png)
                break
            page.wait_for_timeout(200)
        try:
            names = frame.evaluate(SCENE_NAMES)
        except Exception:  # no viewer in the frame (the control case)
            names = []
        return count, names
    finally:
        context.close()


def test_exported_notebook_shows_its_scene_without_a_server(browser, tmp_path, monkeypatch):
    before = meshcat_servers()
    static = export_html("08_urdf_and_matrix_stack", True, monkeypatch)
    live = export_html("08_urdf_and_matrix_stack", False, monkeypatch)
    assert meshcat_servers() <= before, "a notebook left its meshcat server running"
    assert static.count('class="kinlib-scene"') >= 1 and 'class="kinlib-scene"' not in live
    (tmp_path / "static.html").write_text(static, encoding="utf-8")
    (tmp_path / "live.html").write_text(live, encoding="utf-8")
    seen, names = open_scene(browser, tmp_path / "static.html", tmp_path / "static.png")
    assert seen >= AXIS_SEEN, f"exported snapshot: only {seen} joint-axis pixels; see {tmp_path}"
    assert {"notebook08", "test_robot", "link1", "link4", "joint3"} <= set(names), names[:40]
    # the control: the live viewer's iframe needs the (now gone) server and shows nothing
    dead, names = open_scene(browser, tmp_path / "live.html", tmp_path / "live.png")
    assert dead <= EMPTY and "link1" not in names, f"{dead} pixels without a server?"


def test_ik_notebook_exports_its_animated_scene(browser, tmp_path, monkeypatch):
    from test_viz import page_commands

    before = meshcat_servers()
    static = export_html("10_inverse_kinematics", True, monkeypatch)
    assert meshcat_servers() <= before, "a notebook left its meshcat server running"
    (tmp_path / "static.html").write_text(static, encoding="utf-8")
    seen, names = open_scene(browser, tmp_path / "static.html", tmp_path / "static.png")
    assert seen >= AXIS_SEEN, f"only {seen} joint-axis pixels; see {tmp_path}"
    assert {"notebook10", "puma560", "link1", "link6"} <= set(names), names[:40]
    page = html.unescape(re.search(r'srcdoc="([^"]*)"', static).group(1))
    kinds = {c["type"] for c in page_commands(page)}
    assert "set_animation" in kinds, kinds  # the IK trajectory travels inside the snapshot
