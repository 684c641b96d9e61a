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
