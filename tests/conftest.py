"""Shared fixtures: the visualizer tests' prefixes (the meshcat server itself: ../conftest.py)
and the browser tests' Chromium."""

import uuid

import pytest

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
    """Build visualizers on fresh prefixes; delete them from the shared scene afterwards."""
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
        v.delete()


@pytest.fixture(scope="session")
def browser():
    """One headless Chromium for the session's browser tests (each test opens its own
    context); skipped or failed without Chromium, see ``browser_helpers``."""
    from browser_helpers import launch

    with launch() as b:
        yield b


@pytest.fixture(scope="session")
def site(request, tmp_path_factory):
    """The course site, built by ``python -m kinlib.site``: the build the root conftest
    started in the background when the session was collected, or (when there is none) a
    build made now. Fails with the build's output if it failed."""
    import subprocess
    import sys
    import time
    from pathlib import Path

    build = getattr(request.config, "kinlib_site_build", None)
    if build is None:
        out = tmp_path_factory.mktemp("site") / "site"
        run = subprocess.run([sys.executable, "-m", "kinlib.site", "--out", str(out),
                              "--jobs", "2"], capture_output=True, text=True, timeout=600,
                             cwd=Path(__file__).resolve().parents[1])
        assert run.returncode == 0, f"the site build failed:\n{run.stdout}\n{run.stderr}"
        return out
    waited = time.monotonic()
    try:
        build["proc"].wait(timeout=600)
    except subprocess.TimeoutExpired:
        pytest.fail("the site build did not finish in 600 s")
    log = Path(build["folder"], "build.log").read_text(errors="replace")
    assert build["proc"].returncode == 0, f"the site build failed:\n{log[-4000:]}"
    print(f"site build: {log.strip().splitlines()[-1]} (waited {time.monotonic() - waited:.1f} s)")
    return Path(build["folder"]) / "site"
