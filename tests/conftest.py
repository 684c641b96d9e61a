"""Shared fixtures: the visualizer tests' visualizers and the browser tests' Chromium (the
course site: ../conftest.py); the compiled kernels, ready before the first test."""

import uuid

import pytest


@pytest.fixture(scope="session", autouse=True)
def compiled_kernels():
    """Every test in this process meets kinlib's compiled kernels ready (numba installed),
    as every call after a student's first few seconds does: a test that compares the
    compiled path with the numpy one (``compiled=False``) then really compares the two,
    instead of racing the background preparation (tests/test_background.py tests that)."""
    import kinlib

    return kinlib.prepare_kernels()

STL = """solid t
facet normal 0 0 1
 outer loop
  vertex 0 0 0
  vertex 0.1 0 0
  vertex 0 0.1 0
 endloop
endfacet
endsolid t
"""


@pytest.fixture
def make_viz(tmp_path):
    """Build visualizers on fresh prefixes; close their scene widgets afterwards."""
    (tmp_path / "tri.stl").write_text(STL)
    made = []

    def make(robot, **kw):
        kw.setdefault("prefix", f"test_{uuid.uuid4().hex[:8]}")
        kw.setdefault("mesh_dir", tmp_path)
        from kinlib.viz import RobotVisualizer

        v = RobotVisualizer(robot, **kw)
        made.append(v)
        return v

    yield make
    for v in made:
        v.vis.close()


@pytest.fixture(scope="session")
def browser():
    """One headless Chromium for the session's browser tests (each test opens its own
    context); skipped or failed without Chromium, see ``browser_helpers``."""
    from browser_helpers import launch

    with launch() as b:
        yield b
