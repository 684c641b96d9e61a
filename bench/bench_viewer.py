"""The 3-D viewer widget under load: frames sent from a Python loop against frames drawn.

In a real JupyterLab and a real (headless) Chromium, a notebook draws a 50-link robot
(``Robot.from_dh``, 50 revolute rows) and a cell moves it from a Python loop at ``--fps``
frames per second for ``--seconds`` (each frame one ``viz.set_configuration``: one widget
message carrying every pose). The view logs each pose update it draws (its sequence number
and the time), so the script reports:

- frames sent, frames received by the page, frames drawn (an update that reached the
  screen; updates that arrive within one display frame are drawn together);
- the lag from ``set_configuration`` to the drawn frame: median over the first and the last
  second of the run (lag building up shows as a last-second lag far above the first);
- for an exported page (``kinlib.viz.static_page``, from ``file://``): a ``viz.animate`` of
  ``--anim-frames`` frames at 30 fps, how many renders the page makes per second while it
  plays, beside how many display frames (``requestAnimationFrame``) it gets.

Run: ``.venv/bin/python bench/bench_viewer.py`` (about a minute). Times here are the
kernel's and the browser's clocks on one machine; the figures are ratios and lags of one
run, never compared across runs.
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))

SETUP = """import json, time
import numpy as np
from kinlib import DHRow, Robot
from kinlib.viz import RobotVisualizer

robot = Robot.from_dh([DHRow(a=0.04, alpha=0.3) for _ in range(50)], name="snake50")
viz = RobotVisualizer(robot, prefix="bench/snake50")
viz.jupyter_cell(height=400)"""

LOOP = """sent = {{}}
start = time.perf_counter()
for k in range({frames}):
    q = 0.4 * np.sin(0.15 * k + 0.2 * np.arange(robot.dof))
    viz.set_configuration(q)
    sent[viz.vis._seq] = time.time() * 1000.0
    time.sleep(max(0.0, start + (k + 1) / {fps} - time.perf_counter()))
print("SENT", json.dumps(sent))"""

STATS = ("e => { const s = e.kinlibScene.stats; "
         "return {log: s.log, poses: s.poses}; }")
#: the display frames the page is offered (the viewer's own loop runs only while it has
#: something to draw, so its count is not the display's rate)
COUNT_FRAMES = ("() => { window.klFrames = 0; const f = () => { window.klFrames += 1; "
                "requestAnimationFrame(f); }; requestAnimationFrame(f); }")
FRAMES = "() => window.klFrames"


def run_live(fps: float, seconds: float) -> dict:
    import nbformat
    from browser_helpers import launch
    from lab_harness import Lab

    frames = round(fps * seconds)
    work = Path(tempfile.mkdtemp(prefix="kinlib-bench-viewer-"))
    (work / "nbs").mkdir()
    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(SETUP),
                                         nbformat.v4.new_code_cell(LOOP.format(
                                             frames=frames, fps=fps))])
    nb.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3",
                                 "language": "python"}
    nbformat.write(nb, work / "nbs" / "bench.ipynb")
    lab = Lab(work / "nbs", work / "lab")
    try:
        with launch() as browser:
            page = browser.new_page(viewport={"width": 1280, "height": 900})
            page.goto(f"{lab.base}/lab/tree/bench.ipynb?reset&token={lab.token}")
            page.wait_for_selector(".jp-NotebookPanel .jp-Cell", timeout=90_000)
            deadline = time.monotonic() + 90
            while not any(s["kernel"]["execution_state"] == "idle"
                          for s in lab.api("GET", "api/sessions")):
                if time.monotonic() > deadline:
                    raise RuntimeError("the kernel did not start")
                time.sleep(0.25)
            page.wait_for_timeout(1000)
            page.evaluate("() => window.jupyterapp.commands.execute("
                          "'notebook:run-all-cells')")
            scene = page.locator(".kinlib-scene").first
            scene.wait_for(timeout=60_000)
            page.evaluate(COUNT_FRAMES)
            t_frames0 = time.monotonic()
            out = page.locator(".jp-OutputArea-output", has_text="SENT")
            out.wait_for(timeout=(seconds + 120) * 1000)
            sent = {int(k): v for k, v in
                    json.loads(out.inner_text().split("SENT", 1)[1]).items()}
            page.wait_for_timeout(500)  # the last frames reach the screen
            stats = scene.evaluate(STATS)
            display = page.evaluate(FRAMES) / (time.monotonic() - t_frames0)
    finally:
        lab.stop()
    drawn = [(seq, t) for seq, t in stats["log"] if seq in sent]
    lag = [(sent[seq], t - sent[seq]) for seq, t in drawn]
    t0, t1 = min(sent.values()), max(sent.values())
    first = [d for s, d in lag if s <= t0 + 1000.0]
    last = [d for s, d in lag if s >= t1 - 1000.0]
    return {"sent": len(sent), "received": stats["poses"], "drawn": len(drawn),
            "display_fps": display,
            "lag_first_ms": statistics.median(first) if first else float("nan"),
            "lag_last_ms": statistics.median(last) if last else float("nan"),
            "lag_max_ms": max(d for _, d in lag) if lag else float("nan")}


PLAYBACK = """() => new Promise(done => {
  const ctl = document.querySelector('.kinlib-scene').kinlibScene;
  const a = ctl.viewer.animator;
  a.reset(); a.play();
  const r0 = ctl.stats.renders; let frames = 0; const t0 = performance.now();
  function count() {
    frames += 1;
    if (performance.now() - t0 < %d) requestAnimationFrame(count);
    else done({renders: ctl.stats.renders - r0, frames, ms: performance.now() - t0,
               playing: a.playing, duration: a.duration});
  }
  requestAnimationFrame(count);
})"""


def run_exported(anim_frames: int) -> dict:
    import numpy as np
    from browser_helpers import launch

    from kinlib import DHRow, Robot
    from kinlib.viz import RobotVisualizer

    robot = Robot.from_dh([DHRow(a=0.04, alpha=0.3) for _ in range(50)], name="snake50")
    viz = RobotVisualizer(robot, prefix="bench/snake50")
    k = np.arange(anim_frames)[:, None]
    viz.animate(0.4 * np.sin(0.15 * k + 0.2 * np.arange(robot.dof)), fps=30)
    page_file = Path(tempfile.mkdtemp(prefix="kinlib-bench-anim-")) / "anim.html"
    page_file.write_text(viz.static_html(), encoding="utf-8")
    size = page_file.stat().st_size
    window_ms = min(anim_frames / 30.0, 6.0) * 1000.0 - 500.0
    with launch() as browser:
        page = browser.new_page(viewport={"width": 1000, "height": 700})
        page.route("**/*", lambda r: r.continue_() if r.request.url.startswith("file:")
                   else r.abort())
        page.goto(page_file.as_uri())
        page.wait_for_selector(".kinlib-scene")
        page.wait_for_timeout(1000)
        got = page.evaluate(PLAYBACK % window_ms)
    viz.vis.close()
    got["page_bytes"] = size
    return got


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fps", type=float, default=30.0)
    parser.add_argument("--seconds", type=float, default=10.0)
    parser.add_argument("--anim-frames", type=int, default=200)
    args = parser.parse_args(argv)
    live = run_live(args.fps, args.seconds)
    print(f"live, 50-link robot, {args.fps:g} fps for {args.seconds:g} s from a Python loop:")
    print(f"  frames sent {live['sent']}, received by the page {live['received']}, "
          f"drawn {live['drawn']} ({live['drawn'] / live['sent']:.0%} of sent); the page's "
          f"display frames: {live['display_fps']:.1f}/s")
    print(f"  lag set_configuration -> drawn: median {live['lag_first_ms']:.0f} ms in the "
          f"first second, {live['lag_last_ms']:.0f} ms in the last (max "
          f"{live['lag_max_ms']:.0f} ms)")
    anim = run_exported(args.anim_frames)
    rate = anim["renders"] / anim["ms"] * 1000.0
    display = anim["frames"] / anim["ms"] * 1000.0
    print(f"exported page ({anim['page_bytes'] / 1e6:.2f} MB, file://), viz.animate of "
          f"{args.anim_frames} frames at 30 fps:")
    print(f"  {rate:.1f} renders/s while playing, display {display:.1f} frames/s "
          f"(ratio {rate / display:.2f}); still playing: {anim['playing']}")


if __name__ == "__main__":
    main()
