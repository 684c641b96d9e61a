"""The robot really appears in a browser: headless Chromium renders the meshcat viewer.

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
