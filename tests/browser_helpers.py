"""What the browser tests share: launching the system Chromium, and reading screenshots.

Chromium must be at /usr/bin/chromium (Debian/Ubuntu: ``apt-get install chromium``);
without it (or without playwright) the browser tests skip, unless
``KINLIB_REQUIRE_BROWSER=1`` (CI), when they fail.
"""

from __future__ import annotations

import io
import os
import time

import numpy as np
import pytest

CHROMIUM = "/usr/bin/chromium"
ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--enable-unsafe-swiftshader",
        "--disable-background-networking", "--disable-component-update", "--disable-sync",
        "--no-first-run"]
AXIS_SEEN = 150  # joint-axis pixels needed to call a robot drawn
EMPTY = 20  # at most this many on an empty scene
AXES_SEEN = 60  # inside pixels of joint-axis cylinders (:func:`solid_axes`) for a robot
ROBOT = 400  # pixels that must change when the robot is removed from its viewer
STILL = 5  # at most this many change between two screenshots of an untouched viewer


def drag_slider(page, slider, dx: float) -> None:
    """Drag an ipywidgets slider's handle ``dx`` pixels with the mouse, as a student would."""
    handle = slider.locator(".noUi-handle").first
    handle.scroll_into_view_if_needed()
    box = handle.bounding_box()
    x, y = box["x"] + box["width"] / 2, box["y"] + box["height"] / 2
    page.mouse.move(x, y)
    page.mouse.down()
    for k in range(1, 11):
        page.mouse.move(x + dx * k / 10, y)
    page.mouse.up()


def orbit_drag(page, element) -> None:
    """Drag the mouse from the middle of ``element`` 150 pixels right and 30 down, as a
    student orbits a 3-D view."""
    box = element.bounding_box()
    x, y = box["x"] + box["width"] / 2, box["y"] + box["height"] / 2
    page.mouse.move(x, y)
    page.mouse.down()
    for k in range(1, 11):
        page.mouse.move(x + 15 * k, y + 3 * k)
    page.mouse.up()


def unavailable(reason: str):
    if os.environ.get("KINLIB_REQUIRE_BROWSER") == "1":
        pytest.fail(f"KINLIB_REQUIRE_BROWSER=1 but {reason}")
    pytest.skip(reason)


def launch():
    """A context manager yielding a headless Chromium (fresh temporary profile)."""
    import contextlib

    if not os.path.exists(CHROMIUM):
        unavailable(f"Chromium is not installed at {CHROMIUM}")
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        unavailable("playwright is not installed")

    @contextlib.contextmanager
    def running():
        with sync_playwright() as p:
            browser = p.chromium.launch(executable_path=CHROMIUM, args=ARGS)
            try:
                yield browser
            finally:
                browser.close()

    return running()


def _rgb(png: bytes) -> np.ndarray:
    from PIL import Image

    return np.asarray(Image.open(io.BytesIO(png)).convert("RGB"), dtype=int)


def joint_axis_mask(png: bytes) -> np.ndarray:
    """Pixels of kinlib's orange joint-axis colour 0xE8A317 (shaded); meshcat's sky, floor
    grid and kinlib's grey links are blue or grey."""
    rgb = _rgb(png)
    r, g, b = rgb[..., 0], rgb[..., 1], rgb[..., 2]
    return (r > 90) & (g > 0.45 * r) & (g < 0.85 * r) & (b < 0.35 * r)


def solid(mask: np.ndarray) -> np.ndarray:
    """The pixels of ``mask`` whose four neighbours are in it too: filled shapes (joint-axis
    cylinders) keep their inside, one- or two-pixel lines (meshcat's frame triads, whose
    red axis shades into orange) vanish."""
    inner = mask.copy()
    inner[1:] &= mask[:-1]
    inner[:-1] &= mask[1:]
    inner[:, 1:] &= mask[:, :-1]
    inner[:, :-1] &= mask[:, 1:]
    inner[0] = inner[-1] = False
    inner[:, 0] = inner[:, -1] = False
    return inner


def solid_axes(png: bytes) -> np.ndarray:
    """Inside pixels of the joint-axis cylinders (:func:`joint_axis_mask`, then :func:`solid`)."""
    return solid(joint_axis_mask(png))


def changed_fraction(a: np.ndarray, b: np.ndarray) -> float:
    """How much two masks differ: |a xor b| / |a or b|."""
    return (a ^ b).sum() / max((a | b).sum(), 1)


def pixels_changed(png_a: bytes, png_b: bytes, tol: int = 40) -> int:
    """How many pixels differ by more than ``tol`` in some channel (same-size images)."""
    a, b = _rgb(png_a), _rgb(png_b)
    if a.shape != b.shape:
        raise ValueError(f"screenshots of different sizes: {a.shape} and {b.shape}")
    return int((np.abs(a - b).max(axis=-1) > tol).sum())


def wait_for_mask(shoot, mask_of, accept, timeout: float = 15.0, pause: float = 0.2):
    """Call ``shoot()`` (a PNG) until ``accept(mask_of(png))`` or the timeout; the last
    PNG and its mask (rendering is asynchronous)."""
    deadline = time.monotonic() + timeout
    while True:
        png = shoot()
        mask = mask_of(png)
        if accept(mask) or time.monotonic() > deadline:
            return png, mask
        time.sleep(pause)


def element_shooter(element):
    """A function taking a PNG screenshot of ``element`` (a playwright locator), scrolled
    into view first."""
    def shoot() -> bytes:
        element.scroll_into_view_if_needed()
        return element.screenshot()

    return shoot


def settled(shoot, tries: int = 20) -> bytes:
    """A screenshot once two in a row agree (the viewer has finished drawing)."""
    last = shoot()
    for _ in range(tries):
        time.sleep(0.15)
        png = shoot()
        if pixels_changed(last, png) <= STILL:
            return png
        last = png
    return last


#: in the page: pause the trajectory a kinlib scene element plays, if it plays one (a scene
#: made by ``viz.animate`` plays it once when it appears: its picture settles only at the end)
PAUSE_ANIMATION = ("e => { const a = e.kinlibScene && e.kinlibScene.viewer.animator;"
                   " if (a && a.playing) a.pause(); }")


def assert_robot_drawn(frame_el, what: str, shot) -> bytes:
    """The viewer ``frame_el`` (a kinlib scene element) draws a robot: at least ``AXES_SEEN``
    filled joint-axis pixels once the picture has settled (a trajectory that plays is
    paused where it is, rather than waited for). The picture is written to ``shot`` and
    returned."""
    frame_el.evaluate(PAUSE_ANIMATION)
    shoot = element_shooter(frame_el)
    wait_for_mask(shoot, solid_axes, lambda m: m.sum() >= AXES_SEEN, timeout=20)
    png = settled(shoot)
    shot.write_bytes(png)
    axes = int(solid_axes(png).sum())
    assert axes >= AXES_SEEN, f"{what} shows {axes} joint-axis pixels; see {shot}"
    return png


#: in the page: delete a path from the meshcat viewer of a kinlib scene element (the
#: ``.kinlib-scene`` div of a notebook widget or of an exported page)
DELETE_IN_VIEWER = "(e, p) => e.kinlibScene.viewer.handle_command({type: 'delete', path: p})"


def assert_removal_empties(scene_el, drawn: bytes, scene_path: str, what: str,
                           shot) -> tuple[int, int]:
    """The control for :func:`assert_robot_drawn`: delete ``scene_path`` in that same
    viewer (in the browser only); at most ``EMPTY`` joint-axis pixels may be left and at
    least ``ROBOT`` pixels must have changed from the ``drawn`` picture. Returns (pixels
    left, pixels changed)."""
    scene_el.evaluate(DELETE_IN_VIEWER, scene_path)
    png, empty = wait_for_mask(element_shooter(scene_el), solid_axes,
                               lambda m: m.sum() <= EMPTY)
    shot.write_bytes(png)
    assert empty.sum() <= EMPTY, f"{what}: {empty.sum()} joint-axis pixels with the robot " \
                                 "deleted: the pixel check cannot tell an empty scene"
    gone = pixels_changed(drawn, png)
    assert gone >= ROBOT, f"{what}: removing the robot changed only {gone} pixels"
    return int(empty.sum()), gone
