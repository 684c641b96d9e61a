"""The student's view: every notebook of the student edition (``notebooks/``, every
exercise blank) run in JupyterLab in a real (headless) browser.

One JupyterLab server for the module (``lab_harness.Lab``: free port, temporary config,
a copy of the notebooks) and one browser page on it, in a fresh workspace. Each notebook is
opened through JupyterLab (no reload, as a student opens the next one), the test waits for
its kernel, clicks *Run → Run All Cells* and waits until every code cell has an execution
count; afterwards the notebook is closed and its kernel shut down. Then:

- no error output: neither in the page (a traceback) nor in the notebook as JupyterLab
  saves it;
- every exercise's check ran, in order, and says "not answered yet" (the blank student
  edition runs top to bottom: nothing depends on an answer);
- the notebooks that show 3-D viewers (04, 08–11, 13–15) show them, and each viewer draws a
  robot: at least ``AXIS_SEEN`` pixels of kinlib's orange joint axes; the control removes
  the robot from that same viewer and the count must fall to ``EMPTY`` or below;
- sliders are rendered where the notebook makes them (04: the Euler-rate determinant;
  08 and 09: ``joint_panel``), and dragging one with the mouse changes what it drives:
  the printed ``det E`` equals ``-cos β`` at the new ``β``, and the robot in the viewer
  moves.

The server runs under a hub's base URL (``/user/student/``, as JupyterHub serves a
student) and the page may reach that server's URLs only: any other request or websocket
fails the test (``hub_viewer.fenced_page``). On the same server, the last two tests
run the viewer checks of tests/hub_viewer.py (two viewers, a slider, a reload, re-running
the cell, removing the robot from the kernel's side): in JupyterLab, on the same page, and
in Jupyter Notebook 7, which the same server serves (its ``/notebooks/`` pages, as a hub
running JupyterLab with Notebook 7 installed does), in a page of its own.

Screenshots of every notebook go to pytest's ``tmp_path``; with
``KINLIB_SCREENSHOTS=DIR`` (``make screenshots``), the two the README shows go to ``DIR``.
The kernels run on kinlib's numpy path (``KINLIB_NUMBA=0``, as for a student without
numba: nbval runs the instructor edition compiled), and JupyterLab saves the widget state:
the notebooks it saves are the ones the course site is exported from (``site_feed``,
../conftest.py), so the student edition runs once for both. The module fixture stops the
server and its kernels even when a test fails, and checks that no process it started is
left.
"""

from __future__ import annotations

import json
import math
import os
import re
import time
from pathlib import Path

import pytest
from browser_helpers import (
    STILL,
    assert_removal_empties,
    assert_robot_drawn,
    drag_slider,
    element_shooter,
    pixels_changed,
    settled,
    solid_axes,
)
from hub_viewer import (
    BASE_URL,
    MOVED,
    NOTEBOOK,
    check_viewers,
    fenced_page,
    wait_for_kernel,
    write_viewer_notebook,
)
from lab_harness import Lab, marked_processes

from kinlib.check import exercises, results

NOTEBOOKS = Path(__file__).resolve().parents[1] / "notebooks"
NAMES = sorted(p.stem for p in NOTEBOOKS.glob("[0-9][0-9]_*.ipynb"))
VIEWERS = {"04_gimbal_lock", "08_urdf_and_matrix_stack", "09_denavit_hartenberg",
           "10_inverse_kinematics_2r", "11_numerical_inverse_kinematics",
           "13_singularities_and_manipulability", "14_configuration_space_planning",
           "15_se3_twists_and_poe"}
#: notebook → how many sliders it renders (04: β, then the gimbal robot's three joints)
SLIDERS = {"04_gimbal_lock": 4, "08_urdf_and_matrix_stack": 3, "09_denavit_hartenberg": 6}
#: the README's pictures: notebook → file name
README_SHOTS = {"09_denavit_hartenberg": "lab_denavit_hartenberg.png",
                "04_gimbal_lock": "lab_gimbal_lock.png"}
RUN_TIMEOUT = 240.0

PROMPTS = f"""() => [...document.querySelectorAll('{NOTEBOOK} .jp-CodeCell .jp-InputPrompt')]
  .map(p => p.innerText.trim())"""
STDERR = '.jp-OutputArea-output[data-mime-type="application/vnd.jupyter.stderr"]'
TRACEBACKS = f"""() => [...document.querySelectorAll('{NOTEBOOK} {STDERR}')]
  .map(o => o.innerText).filter(t => /Traceback|Error/.test(t)).map(t => t.slice(0, 400))"""
STATUS = """() => document.querySelector('.jp-Notebook-ExecutionIndicator')
  ?.getAttribute('data-status')"""


@pytest.fixture(scope="module")
def lab(tmp_path_factory, site_feed):
    """The module's JupyterLab, its kernels on kinlib's numpy path; what it saves feeds the
    course site's build (``site_feed``), which starts when the module is done."""
    try:
        server = Lab(NOTEBOOKS, tmp_path_factory.mktemp("lab"), env={"KINLIB_NUMBA": "0"},
                     save_widget_state=True, base_url=BASE_URL)
    except BaseException:
        site_feed.done()
        raise
    try:
        yield server
    finally:
        site_feed.done()
        closed = server.closed_sessions()  # (each shut its kernel down, or failed to)
        killed = server.stop()
        left = marked_processes(server.marker)
        assert not left, f"processes left running after the lab stopped: {left}"
        assert not killed, f"these needed SIGKILL to stop: {killed}; see {server.log}"
        assert all(status == 204 for status in closed), f"closing sessions: {closed}"


def _session(lab: Lab, name: str) -> dict | None:
    return next((s for s in lab.api("GET", "api/sessions")
                 if s.get("path", "").endswith(f"{name}.ipynb")), None)


#: in a page where JupyterLab runs: open a notebook (as a double click in the file browser
#: would), and close every document without asking to save (the file is saved already).
#: OPEN answers null, not the command's result: that is the notebook's widget, and handing
#: it back would have Playwright walk JupyterLab's objects to serialise it (2–3 s a
#: notebook)
OPEN = ("path => window.jupyterapp.commands.execute('docmanager:open', {path})"
        ".then(() => null)")
CLOSE_ALL = """() => { for (const w of Array.from(window.jupyterapp.shell.widgets('main')))
  w.dispose(); }"""


def open_notebook(lab: Lab, page, name: str, cells: int) -> None:
    """Open ``name`` and wait until its kernel is idle: in a page where JupyterLab already
    runs, through JupyterLab itself (no reload); else by loading JupyterLab on it, in a
    fresh workspace."""
    if page.url.startswith(lab.base) and page.evaluate("() => !!window.jupyterapp"):
        page.evaluate(CLOSE_ALL)
        page.evaluate(OPEN, f"{name}.ipynb")
    else:
        page.goto(f"{lab.base}/lab/workspaces/test-{name}/tree/{name}.ipynb"
                  f"?reset&token={lab.token}")
    page.wait_for_function(
        f"() => document.querySelectorAll('.jp-NotebookPanel:not(.lm-mod-hidden) "
        f".jp-Cell').length === {cells}", timeout=60_000)
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline:
        session = _session(lab, name)
        if (session and session["kernel"]["execution_state"] == "idle"
                and page.evaluate(STATUS) == "idle"):
            return
        page.wait_for_timeout(250)
    raise AssertionError(f"{name}: the kernel did not become idle in 60 s")


def run_all(page, name: str, timeout: float = RUN_TIMEOUT) -> list[str]:
    """Run → Run All Cells, then wait until every code cell has run (or one failed)."""
    for _attempt in range(3):
        page.locator(".lm-MenuBar-itemLabel", has_text="Run").first.click()
        page.locator(".lm-Menu-item:not(.lm-mod-disabled) .lm-Menu-itemLabel",
                     has_text="Run All Cells").first.click()
        try:  # the first cell is queued or has run: Run All was taken
            page.wait_for_function(f"() => ({PROMPTS})()[0] !== '[ ]:'", timeout=10_000)
            break
        except Exception:  # the menu was not ready yet: try again
            page.keyboard.press("Escape")
    deadline = time.monotonic() + timeout
    while True:
        prompts = page.evaluate(PROMPTS)
        if all(re.fullmatch(r"\[\d+\]:", p) for p in prompts):
            return prompts
        if page.evaluate(TRACEBACKS) and page.evaluate(STATUS) == "idle":
            return prompts  # Run All stops at an error; the caller reports it
        if time.monotonic() > deadline:
            raise AssertionError(f"{name}: not finished after {timeout:g} s: {prompts}")
        page.wait_for_timeout(300)


#: the notebook's tab while it has unsaved changes
DIRTY_TAB = "#jp-main-dock-panel .lm-TabBar-tab.jp-mod-dirty"


def saved_notebook(lab: Lab, page, name: str, timeout: float = 60.0) -> dict:
    """Save the notebook from JupyterLab (Ctrl+S) and read the file it wrote.

    The Jupyter server writes the file in place (it truncates it, then writes), so the file
    is read only once JupyterLab says the save is done (the tab's unsaved-changes mark has
    gone), and read again if it is still not complete JSON."""
    page.locator(".jp-NotebookPanel:not(.lm-mod-hidden) .jp-Notebook").click(
        position={"x": 5, "y": 5})
    page.keyboard.press("Control+s")
    path = lab.root / f"{name}.ipynb"
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if page.locator(DIRTY_TAB).count() == 0:
            try:
                nb = json.loads(path.read_text())
            except json.JSONDecodeError:  # caught between the truncation and the write
                nb = None
            code = [c for c in nb["cells"] if c["cell_type"] == "code"] if nb else []
            if code and all(c.get("execution_count") for c in code):
                return nb
        page.wait_for_timeout(250)
    raise AssertionError(f"{name}: JupyterLab did not save the notebook in {timeout:g} s")


def error_outputs(nb: dict) -> list[str]:
    return [f"cell {i}: {o.get('ename')}: {o.get('evalue')}"
            for i, c in enumerate(nb["cells"]) for o in c.get("outputs", [])
            if o.get("output_type") == "error"]


def viewer_frames(page):
    """The 3-D viewers (kinlib scene widgets) of the open notebook."""
    return page.locator(".jp-NotebookPanel:not(.lm-mod-hidden) .jp-OutputArea-output "
                        ".kinlib-scene")


def readout(slider) -> str:
    return slider.locator(".widget-readout").first.inner_text().strip()


def check_gimbal_slider(page, out: Path) -> None:
    """Drag the β slider: the printed det E must become −cos β at the new β (the picture
    the same slider redraws may make the text lag behind the readout: wait for it)."""
    slider = page.locator(".widget-slider").first
    text = slider.locator("xpath=ancestor::div[contains(@class,'jp-OutputArea-output')]")
    beta0 = float(readout(slider))
    drag_slider(page, slider, 60)
    deadline = time.monotonic() + 10
    while float(readout(slider)) == beta0 and time.monotonic() < deadline:
        page.wait_for_timeout(100)
    beta = float(readout(slider))
    assert beta > beta0 + 1, f"the slider did not move: β {beta0} → {beta}"

    def printed() -> float | None:
        m = re.search(r"det E = ([-+0-9.]+)", text.inner_text())
        return float(m.group(1)) if m else None

    deadline = time.monotonic() + 30
    while (det := printed()) is None or abs(det + math.cos(math.radians(beta))) > 2e-4:
        if time.monotonic() > deadline:
            break
        page.wait_for_timeout(200)
    assert det is not None and abs(det - (-math.cos(math.radians(beta)))) < 2e-4, \
        (beta, det, text.inner_text())
    slider.screenshot(path=str(out / "slider_moved.png"))


#: the joint whose slider is dragged: one that carries most of the robot (in 08, joint1
#: turns only link2's frame, a few hundred pixels at most)
DRAGGED = {"08_urdf_and_matrix_stack": "joint2", "09_denavit_hartenberg": "joint1"}


def check_panel_slider(page, name: str, out: Path) -> None:
    """Drag a joint's slider of the joint panel: the robot in the viewer must move. The
    control: two screenshots of the untouched viewer agree."""
    shoot = element_shooter(viewer_frames(page).first)
    before = settled(shoot)
    assert pixels_changed(before, shoot()) <= STILL, "the viewer changes by itself"
    joint = DRAGGED[name]
    slider = page.locator(".widget-slider", has=page.locator(".widget-label", has_text=joint))
    assert slider.count() == 1, f"{name}: no slider for {joint}"
    value0 = readout(slider)
    drag_slider(page, slider, 70)
    deadline = time.monotonic() + 10
    while readout(slider) == value0 and time.monotonic() < deadline:
        page.wait_for_timeout(100)
    assert readout(slider) != value0, "the joint slider did not move"
    deadline = time.monotonic() + 10
    while (changed := pixels_changed(before, after := shoot())) < MOVED \
            and time.monotonic() < deadline:
        page.wait_for_timeout(150)
    (out / "viewer_before.png").write_bytes(before)
    (out / "viewer_moved.png").write_bytes(after)
    assert changed >= MOVED, f"{joint} moved {value0} → {readout(slider)} but only " \
                             f"{changed} pixels of the viewer changed; see {out}"


def check_viewer(frame_el, name: str, k: int, out: Path) -> None:
    """The viewer draws a robot: filled orange joint-axis cylinders, and many pixels that
    go when the robot is removed from this viewer (the control, which must leave none)."""
    what = f"{name}: viewer {k}"
    png = assert_robot_drawn(frame_el, what, out / f"viewer{k}.png")
    left, gone = assert_removal_empties(frame_el, png, f"/meshcat/notebook{name[:2]}", what,
                                        out / f"viewer{k}_emptied.png")
    print(f"{what}: {int(solid_axes(png).sum())} joint-axis pixels ({left} when emptied), "
          f"{gone} robot pixels")


@pytest.fixture(scope="module")
def lab_page(lab, browser):
    """One page of JupyterLab for the module: each notebook is opened in it through
    JupyterLab (as a student opens the next one) and closed after; ``page.errors`` collects
    the page's JavaScript errors, ``page.refused`` every request it made outside the
    server (aborted)."""
    context, page, page.refused = fenced_page(browser, lab)
    try:
        yield page
    finally:
        context.close()


@pytest.mark.parametrize("name", NAMES)
def test_notebook_runs_in_jupyterlab(lab, lab_page, name, tmp_path, site_feed):
    nb = json.loads((NOTEBOOKS / f"{name}.ipynb").read_text())
    n_code = sum(c["cell_type"] == "code" for c in nb["cells"])
    page, errors_so_far = lab_page, len(lab_page.errors)
    try:
        open_notebook(lab, page, name, len(nb["cells"]))
        start = time.monotonic()
        prompts = run_all(page, name)
        seconds = time.monotonic() - start
        page.screenshot(path=str(tmp_path / "end.png"))
        tracebacks = page.evaluate(TRACEBACKS)
        assert not tracebacks, f"{name}: error output in the page:\n{tracebacks[0]}"
        assert len(prompts) == n_code and all(re.fullmatch(r"\[\d+\]:", p) for p in prompts), \
            f"{name}: cells that did not run: {prompts}"
        saved = saved_notebook(lab, page, name)
        errors = error_outputs(saved)
        assert not errors, f"{name}: error outputs in the saved notebook: {errors}"
        checked = results(saved)
        assert [c["exercise"] for c in checked] == [e.id for e in exercises(name[:2])], checked
        answered = [c for c in checked if c["status"] != "unanswered"]
        assert not answered, f"{name}: a blank exercise is judged: {answered[0]}"
        site_feed.save(name, saved)  # the course site's page of it is exported from this

        frames = viewer_frames(page)
        expected = "some" if name in VIEWERS else "none"
        assert (frames.count() > 0) == (name in VIEWERS), \
            f"{name}: {frames.count()} 3-D viewers, expected {expected}"
        sliders = page.locator(".jp-NotebookPanel:not(.lm-mod-hidden) .widget-slider")
        assert sliders.count() == SLIDERS.get(name, 0), \
            f"{name}: {sliders.count()} sliders rendered, expected {SLIDERS.get(name, 0)}"
        if name == "04_gimbal_lock":
            check_gimbal_slider(page, tmp_path)
        elif name in SLIDERS:
            check_panel_slider(page, name, tmp_path)
        if name in README_SHOTS:
            take_readme_shot(page, name, tmp_path)
        for k in range(frames.count()):
            check_viewer(frames.nth(k), name, k, tmp_path)
        messages = page.errors[errors_so_far:]
        assert not messages, f"{name}: JavaScript errors in JupyterLab: {messages[:3]}"
        assert not page.refused, f"{name}: requests outside {lab.base}/: {page.refused[:5]}"
        print(f"{name}: {n_code} cells in {seconds:.1f} s")
    finally:
        page.evaluate(CLOSE_ALL)
        session = _session(lab, name)
        if session is not None:  # close the kernel, as a student closing the tab would
            lab.close_session(session["id"])


def take_readme_shot(page, name: str, tmp_path: Path) -> None:
    """The README's picture of ``name``, sidebar hidden: 09's viewer, 04's β slider (with
    the det E it drives and the gimbal it redraws)."""
    target = Path(os.environ.get("KINLIB_SCREENSHOTS") or tmp_path) / README_SHOTS[name]
    target.parent.mkdir(parents=True, exist_ok=True)
    page.keyboard.press("Control+b")  # hide the file browser
    anchor = page.locator(".widget-slider") if name == "04_gimbal_lock" else viewer_frames(page)
    anchor.first.scroll_into_view_if_needed()
    page.wait_for_timeout(1500)
    page.screenshot(path=str(target))
    page.keyboard.press("Control+b")  # the file browser back, for the next notebook


def test_readme_shows_the_screenshots_this_suite_takes():
    from PIL import Image

    readme = (NOTEBOOKS.parent / "README.md").read_text()
    shots = re.findall(r"\]\((notebooks/screenshots/[^)]+\.png)\)", readme)
    assert sorted(Path(s).name for s in shots) == sorted(README_SHOTS.values()), shots
    for shot in shots:
        with Image.open(NOTEBOOKS.parent / shot) as im:  # the suite's viewport
            assert im.size == (1280, 900), (shot, im.size)


def test_the_viewer_works_through_the_server_alone(lab, lab_page, tmp_path):
    """tests/hub_viewer.py's checks in JupyterLab under the hub's base URL, the page fenced
    to the server: two viewers, a slider, a reload, re-running the cell, and removing the
    robot from the kernel's side."""
    page = lab_page
    write_viewer_notebook(lab.root)
    try:
        open_notebook(lab, page, "viewer", 4)
        at_load = list(page.errors)
        run_all(page, "viewer")
        check_viewers(lab, page, page.refused, tmp_path, at_load, reopen=lambda: page.goto(
            f"{lab.base}/lab/tree/viewer.ipynb?token={lab.token}"))
    finally:
        page.screenshot(path=str(tmp_path / "page.png"))
        page.evaluate(CLOSE_ALL)
        session = _session(lab, "viewer")
        if session is not None:
            lab.close_session(session["id"])


def test_the_viewer_works_in_notebook_7(lab, browser, tmp_path):
    """tests/hub_viewer.py's checks in Jupyter Notebook 7 (the ``/notebooks/`` page the same
    server serves under the hub's base URL), in a page fenced to the server."""
    write_viewer_notebook(lab.root)
    context, page, refused = fenced_page(browser, lab)
    try:
        # Notebook 7.6 throws one error of its own while it loads (a plugin's settings
        # schema; a one-cell "1 + 1" notebook gets it too): the errors before kinlib's
        # viewer runs are the baseline, and the viewer may add none
        page.goto(f"{lab.base}/notebooks/viewer.ipynb?token={lab.token}")
        page.wait_for_function(f"() => document.querySelectorAll('{NOTEBOOK} .jp-Cell')"
                               ".length === 4", timeout=90_000)
        shell = page.evaluate("() => [document.body.dataset.notebook, "
                              "!!document.getElementById('jp-NotebookLogo')]")
        assert shell == ["notebooks", True], f"not Notebook 7's notebook page: {shell}"
        wait_for_kernel(lab, page)
        page.wait_for_timeout(1000)  # the app settles
        at_load = list(page.errors)
        prompts = run_all(page, "viewer")  # the same menus as JupyterLab's
        assert all(re.fullmatch(r"\[\d+\]:", p) for p in prompts), \
            f"cells that did not run: {prompts}"
        check_viewers(lab, page, refused, tmp_path, at_load)
    finally:
        page.screenshot(path=str(tmp_path / "page.png"))
        context.close()
        session = _session(lab, "viewer")
        if session is not None:
            lab.close_session(session["id"])
