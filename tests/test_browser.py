"""The robot really appears in a browser: headless Chromium renders the self-contained
page of ``viz.static_html()`` (the meshcat viewer and the scene inline) from ``file://``
with all http(s) blocked. (The live widget in JupyterLab: test_lab.py, test_viewer_remote.py.)

The PUMA 560 is drawn in a saturated magenta no other part of the viewer uses (sky-blue
background, grey grid, orange joint axes), so its pixels can be counted in a screenshot.
The same counting function must find (almost) nothing once the robot is deleted: that is
what shows this test can fail. Needs Chromium at /usr/bin/chromium; without it the test
is skipped, or fails when ``KINLIB_REQUIRE_BROWSER=1`` (CI installs Chromium).
"""

import io
import re
import time

import numpy as np
from browser_helpers import EMPTY, changed_fraction

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


def test_puma_in_the_static_page(browser, tmp_path):
    from kinlib.viz import RobotVisualizer

    robot = puma560()
    viz = RobotVisualizer(robot, prefix="browser_puma", color=MAGENTA)
    viz.set_camera_position([1.1, -1.0, 0.8])
    q = np.zeros(6)
    pages = {}
    viz.set_configuration(q)
    pages["first"] = viz.static_html()
    q[0] += np.pi / 2
    viz.set_configuration(q)
    pages["turned"] = viz.static_html()
    viz.delete()
    pages["empty"] = viz.static_html()
    viz.close()
    context = browser.new_context(viewport={"width": 800, "height": 600})
    requests = []
    try:
        context.route(re.compile(r"^https?://"),
                      lambda route: (requests.append(route.request.url), route.abort()))
        masks = {}
        for name, text in pages.items():
            (tmp_path / f"{name}.html").write_text(text, encoding="utf-8")
            page = context.new_page()
            page.goto((tmp_path / f"{name}.html").as_uri())
            page.wait_for_selector("canvas", timeout=15_000)
            accept = (lambda m: m.sum() <= EMPTY) if name == "empty" else \
                (lambda m: m.sum() >= SEEN)
            png, masks[name] = wait_for_picture(page, accept)
            (tmp_path / f"{name}.png").write_bytes(png)
            page.close()
    finally:
        context.close()
    assert not requests, requests
    assert masks["first"].sum() >= SEEN, f"only {masks['first'].sum()} robot pixels"
    assert masks["turned"].sum() >= SEEN
    assert changed_fraction(masks["first"], masks["turned"]) > 0.5  # joint 1 turned 90°
    assert masks["empty"].sum() <= EMPTY, f"{masks['empty'].sum()} robot pixels, robot deleted"
