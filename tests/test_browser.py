"""The robot really appears in a browser: headless Chromium renders the self-contained
page of ``viz.static_html()`` (the meshcat viewer and the scene inline) from ``file://``
with all http(s) blocked. (The live widget in JupyterLab and Notebook 7: test_lab.py.)

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
from browser_helpers import EMPTY, changed_fraction, orbit_drag

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


#: the first scene of a page: how many display frames its loop has used, and renders
LOOP = "() => { const s = document.querySelector('.kinlib-scene').kinlibScene.stats; " \
       "return [s.ticks, s.renders]; }"
PLAYING = "() => document.querySelector('.kinlib-scene').kinlibScene.viewer.animator.playing"
PLAY = "() => document.querySelector('.kinlib-scene').kinlibScene.viewer.animator.play()"
FRAMES = """ms => new Promise(done => { let n = 0; const t0 = performance.now();
  const f = () => { n += 1; if (performance.now() - t0 < ms) requestAnimationFrame(f);
                    else done(n); };
  requestAnimationFrame(f); })"""


def test_an_idle_viewer_uses_no_frames_until_something_changes(browser, tmp_path):
    """A viewer draws on demand: once the picture is drawn its loop stops (no display frame
    used while the page offers dozens), and a mouse drag (the camera orbits) or playing
    its animation starts it again, until there is nothing left to draw. The control for
    "stopped": the page's own frame counter, in the same second, counts the display
    frames the browser offers."""
    from kinlib.viz import RobotVisualizer

    robot = puma560()
    viz = RobotVisualizer(robot, prefix="idle_puma", color=MAGENTA)
    viz.set_camera_position([1.1, -1.0, 0.8])
    viz.set_configuration(np.zeros(6))
    qs = np.linspace(0, 1, 15)[:, None] * np.array([1.5, -0.5, 0.8, 0, 0.5, 0])
    viz.animate(qs, fps=30)  # half a second, played once when the page loads
    (tmp_path / "idle.html").write_text(viz.static_html(), encoding="utf-8")
    viz.close()
    context = browser.new_context(viewport={"width": 800, "height": 600})
    try:
        context.route(re.compile(r"^https?://"), lambda route: route.abort())
        page = context.new_page()
        page.goto((tmp_path / "idle.html").as_uri())
        page.wait_for_selector(".kinlib-scene canvas", timeout=15_000)
        wait_for_picture(page, lambda m: m.sum() >= SEEN)
        page.wait_for_function(f"() => !({PLAYING})()", timeout=15_000)

        def idle_second() -> tuple[int, int]:
            """(frames the viewer used, frames the page was offered) in one second."""
            ticks0, _ = page.evaluate(LOOP)
            offered = page.evaluate(FRAMES, 1000)
            return page.evaluate(LOOP)[0] - ticks0, offered

        used, offered = idle_second()
        assert offered >= 10, f"the browser offered only {offered} frames in a second"
        assert used <= 1, f"an idle viewer used {used} of {offered} display frames"

        before = page.screenshot()
        _, renders0 = page.evaluate(LOOP)
        orbit_drag(page, page.locator(".kinlib-scene canvas").first)
        page.wait_for_timeout(300)
        _, renders1 = page.evaluate(LOOP)
        orbited = robot_mask(page.screenshot())
        assert renders1 > renders0, "the drag drew nothing"
        assert changed_fraction(robot_mask(before), orbited) > 0.2, "the camera did not orbit"
        assert idle_second()[0] <= 1, "the loop kept running after the drag"

        page.evaluate(PLAY)  # meshcat's Play button
        assert page.evaluate(PLAYING)
        page.wait_for_function(f"() => !({PLAYING})()", timeout=15_000)
        _, renders2 = page.evaluate(LOOP)
        assert renders2 - renders1 >= 5, f"{renders2 - renders1} renders while it played"
        assert idle_second()[0] <= 1, "the loop kept running after the animation ended"
    finally:
        context.close()
