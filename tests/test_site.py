"""The static course site (``make site``), built and then read in a real browser, offline.

The session builds the site once with ``python -m kinlib.site`` (every notebook executed
in its own kernel; in the background, see ../conftest.py) into a temporary folder; this
module opens every page from its ``file://`` URL
in headless Chromium with all http(s) blocked and asserts:

- no request left the machine, and no console error or uncaught exception (a LaTeX error
  is a console error too: the page's MathJax reports it);
- the mathematics is typeset: MathJax finished, at least as many formulas as the
  notebook's Markdown has ``$…$``/``$$…$$`` pairs, no error node, and no raw TeX
  (``$`` or ``\\command``) left in the text;
- the 3-D scenes (04, 08–11, 13–15), drawn from the notebooks' saved widget state, show their
  robot (filled joint-axis pixels and the robot's names in the three.js scene; 11's
  carries its IK animation, which plays); removing the robot in that same page empties the
  picture (the control);
- every matplotlib animation plays: *Next frame* shows another image and *Play* moves
  the frame counter;
- a scene can be orbited with the mouse, and it is the saved state that draws it: the
  same page with the scene's saved commands removed shows no robot (the control);
- sliders appear as disabled pictures of their state, with a note, and the outline page
  links every notebook, with its learning goals.
"""

from __future__ import annotations

import json
import re
import shutil
from pathlib import Path

import pytest
from browser_helpers import (
    AXIS_SEEN,
    EMPTY,
    STILL,
    assert_removal_empties,
    assert_robot_drawn,
    element_shooter,
    joint_axis_mask,
    orbit_drag,
    pixels_changed,
    settled,
    wait_for_mask,
)

from kinlib.site import MARKER, outline

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOKS = ROOT / "notebooks"
PAGES = [p.name for p in outline(NOTEBOOKS)]
SCENES = {"04_gimbal_lock": {"gimbal", "body", "alpha_z", "gamma_x"},
          "08_urdf_and_matrix_stack": {"test_robot", "link1", "link4", "joint3"},
          "09_denavit_hartenberg": {"puma560", "link1", "link6"},
          "10_inverse_kinematics_2r": {"up", "down", "link2"},
          "11_numerical_inverse_kinematics": {"puma560", "link1", "link6", "line"},
          "13_singularities_and_manipulability": {"puma560", "link6", "joint5"},
          "14_configuration_space_planning": {"arm", "obstacles", "link2"},
          "15_se3_twists_and_poe": {"ur5", "link6", "joint5", "screws"}}
#: pages whose scene carries a viz.animate trajectory (the IK solve, the planned path)
ANIMATED = {"11_numerical_inverse_kinematics", "14_configuration_space_planning"}
SLIDERS = {"04_gimbal_lock": 4, "08_urdf_and_matrix_stack": 3, "09_denavit_hartenberg": 6}

MATH_STATE = """() => {
const SKIP = 'pre, code, script, style, textarea, mjx-container, .jp-InputArea, .kl-frozen';
return {
  done: document.body.getAttribute('data-mathjax'),
  formulas: document.querySelectorAll('mjx-container').length,
  errors: document.querySelectorAll('mjx-container [data-mml-node="merror"]').length,
  raw: (() => {
    const out = [];
    const walk = document.createTreeWalker(document.body, NodeFilter.SHOW_TEXT, {
      acceptNode: n => n.parentElement.closest(SKIP) ? NodeFilter.FILTER_REJECT
                                                     : NodeFilter.FILTER_ACCEPT});
    while (walk.nextNode()) {
      const t = walk.currentNode.nodeValue;
      if (/\\$|\\\\[a-zA-Z]+/.test(t)) out.push(t.trim().slice(0, 120));
    }
    return out;
  })()
}; }"""
SCENE_NAMES = ("e => { const n = []; e.kinlibScene.viewer.scene.traverse(o => n.push(o.name));"
               " return n; }")


def math_pairs(name: str) -> int:
    """How many formulas the notebook's Markdown cells hold (``$$…$$`` and ``$…$`` pairs,
    code spans and escaped dollars left out)."""
    nb = json.loads((NOTEBOOKS / f"{name}.ipynb").read_text())
    count = 0
    for cell in nb["cells"]:
        if cell["cell_type"] != "markdown":
            continue
        text = "".join(cell["source"])
        text = re.sub(r"```.*?```|`[^`]*`|\\\$", "", text, flags=re.S)
        display = re.findall(r"\$\$.+?\$\$", text, flags=re.S)
        text = re.sub(r"\$\$.+?\$\$", "", text, flags=re.S)
        count += len(display) + len(re.findall(r"\$[^$]+\$", text))
    return count


@pytest.fixture
def offline_page(browser):
    """A page that may read files but reaches no network: every http(s) request is
    aborted and recorded, as are console errors and uncaught exceptions."""
    context = browser.new_context(viewport={"width": 1200, "height": 900})
    log = {"requests": [], "errors": []}

    def block(route):
        log["requests"].append(route.request.url)
        route.abort()

    context.route(re.compile(r"^https?://"), block)
    page = context.new_page()
    page.on("console", lambda m: m.type == "error" and log["errors"].append(m.text))
    page.on("pageerror", lambda e: log["errors"].append(f"uncaught: {e}"))
    try:
        yield page, log
    finally:
        context.close()


def open_page(page, path: Path) -> dict:
    page.goto(path.as_uri())
    page.wait_for_function("() => document.body.getAttribute('data-mathjax') === 'done'",
                           timeout=60_000)
    return page.evaluate(MATH_STATE)


def problems(page, log, path: Path) -> tuple[list[str], dict]:
    """Open ``path`` offline and list what is wrong with it (and the MathJax state)."""
    state = open_page(page, path)
    found = [f"network request: {u}" for u in log["requests"]]
    found += [f"console: {e}" for e in log["errors"]]
    if state["errors"]:
        found.append(f"{state['errors']} formulas with LaTeX errors")
    found += [f"untypeset TeX: {t}" for t in state["raw"]]
    return found, state


def test_the_page_checks_catch_a_broken_page(site, offline_page, tmp_path):
    """The control: a page with a LaTeX error, TeX that MathJax skipped, an image from the
    network and a script that throws; each of the four must be reported."""
    from kinlib.site import MATHJAX_HEAD

    (tmp_path / "_static").mkdir()
    (tmp_path / "_static" / "tex-svg-full.js").write_bytes(
        (site / "_static" / "tex-svg-full.js").read_bytes())
    (tmp_path / "broken.html").write_text(
        f"<!DOCTYPE html><html><head><meta charset='utf-8'>{MATHJAX_HEAD}</head><body>"
        "<p>fine: $x^2$; broken: $\\frac{1}$</p><img src='https://example.invalid/x.png'>"
        "<script>MathJax.startup.promise.then(() => document.body.insertAdjacentHTML("
        "'beforeend', '<p>raw $\\\\alpha$</p>'));</script>"  # TeX that MathJax never saw
        "<script>throw new Error('boom')</script>"
        "</body></html>")
    page, log = offline_page
    found, state = problems(page, log, tmp_path / "broken.html")
    text = "\n".join(found)
    assert "network request: https://example.invalid/x.png" in text, text
    assert "LaTeX error" in text and "formulas with LaTeX errors" in text, text
    assert "untypeset TeX: raw $\\alpha$" in text, text
    assert "boom" in text, text
    assert state["formulas"] == 2, state  # the fine formula was typeset, as was the broken one


def test_the_site_has_an_outline_and_a_page_per_notebook(site):
    assert (site / MARKER).exists() and (site / "_static" / "tex-svg-full.js").exists()
    index = (site / "index.html").read_text()
    for page in outline(NOTEBOOKS):
        assert f'href="{page.href}"' in index and (site / page.href).exists(), page.name
        assert page.goals, f"{page.name} states no learning goals"
    # the two parts of the course, in order
    assert index.index("Part 1") < index.index("01_spatial") < index.index("Part 2") \
        < index.index("08_urdf")


def test_outline_page_renders_offline(site, offline_page):
    page, log = offline_page
    found, state = problems(page, log, site / "index.html")
    assert not found, found
    goals = sum(math_pairs(n) > 0 for n in PAGES)
    assert state["formulas"] >= goals and not state["errors"] and not state["raw"], state
    links = page.evaluate("() => [...document.querySelectorAll('a')].map(a => a.href)")
    for name in PAGES:
        assert (site / f"{name}.html").as_uri() in links, name


@pytest.mark.parametrize("name", PAGES)
def test_page_renders_offline(site, offline_page, name, tmp_path):
    page, log = offline_page
    found, state = problems(page, log, site / f"{name}.html")
    page.screenshot(path=str(tmp_path / "top.png"))
    assert not found, f"{name}: {found[:5]}"
    expected = math_pairs(name)
    assert expected > 10 and state["formulas"] >= expected, \
        f"{name}: {state['formulas']} formulas typeset, the Markdown has {expected}"

    nav = page.evaluate("() => [...document.querySelectorAll('nav.kl-nav a')].map(a => a.href)")
    assert (site / "index.html").as_uri() in nav
    assert all(Path(u.removeprefix("file://")).exists() for u in nav), nav

    frozen = page.locator(".kl-frozen input[type=range][disabled]")
    assert frozen.count() == SLIDERS.get(name, 0), f"{name}: {frozen.count()} frozen sliders"
    if frozen.count():
        assert page.locator(".kl-widget-note").count() >= 1

    check_players(page, name)
    scenes = page.locator(".kinlib-scene")
    assert scenes.count() == (1 if name in SCENES else 0), f"{name}: {scenes.count()} scenes"
    if name in SCENES:
        check_snapshot(scenes.first, name, tmp_path)
    assert not log["errors"], f"{name}: console errors: {log['errors'][:5]}"


def check_players(page, name: str) -> None:
    source = (NOTEBOOKS / f"{name}.ipynb").read_text()
    players = page.locator("img[id^='_anim_img']")
    made = len(re.findall(r"(?<![.\w])(animate|animate_rotation_sequences)\(", source))
    assert players.count() == made, f"{name}: {players.count()} players, {made} made"
    for k in range(players.count()):
        img = players.nth(k)
        anim = img.get_attribute("id").removeprefix("_anim_img")
        img.scroll_into_view_if_needed()
        first = img.get_attribute("src")
        assert first and first.startswith("data:image/"), f"{name}: player {k} shows no frame"
        page.locator(f"button[onclick='anim{anim}.next_frame()']").click()
        assert img.get_attribute("src") != first, f"{name}: Next frame changed nothing"
        slider = page.locator(f"#_anim_slider{anim}")
        at = int(slider.input_value())
        page.locator(f"button[onclick='anim{anim}.play_animation()']").click()
        page.wait_for_function(f"() => +document.getElementById('_anim_slider{anim}').value "
                               f"!== {at}", timeout=10_000)
        page.locator(f"button[onclick='anim{anim}.pause_animation()']").click()


def check_snapshot(scene_el, name: str, out: Path) -> None:
    png = assert_robot_drawn(scene_el, f"{name}: the scene", out / "scene.png")
    names = set(scene_el.evaluate(SCENE_NAMES))
    assert SCENES[name] <= names, f"{name}: missing {SCENES[name] - names} in the scene"
    if name in ANIMATED:  # the trajectory is in the page and moves the robot
        from test_viz import page_commands

        kinds = {c["type"] for c in page_commands(scene_el.page.content())}
        assert "set_animation" in kinds, kinds
        animator = "e => e.kinlibScene.viewer.animator"
        duration = scene_el.evaluate(f"e => ({animator})(e).duration")
        assert duration > 0, "no animation in the scene"
        shots = []
        for t in (0, duration):  # the trajectory's first and last frame differ
            scene_el.evaluate(f"(e, t) => {{ const a = ({animator})(e); a.pause(); a.seek(t); }}",
                              t)
            shots.append(settled(element_shooter(scene_el)))
        assert pixels_changed(*shots) >= 200, "the IK animation moves nothing"
    assert_removal_empties(scene_el, png, f"/meshcat/notebook{name[:2]}", name,
                           out / "scene_emptied.png")


# --- an exported scene, orbited; and the control without its saved state ---

def open_scene(browser, page_file: Path, shot: Path, timeout: float = 15.0,
               orbit: bool = False) -> dict:
    """Open an exported page with all http(s) blocked and look at its first scene: the
    joint-axis pixels of a screenshot, the names in its three.js scene graph, and (with
    ``orbit``) how many pixels a mouse drag across it changes, beside how many change
    between two screenshots of the untouched scene."""
    context = browser.new_context(viewport={"width": 1000, "height": 800})
    requests = []
    try:
        context.route(re.compile(r"^https?://"),
                      lambda route: (requests.append(route.request.url), route.abort()))
        page = context.new_page()
        page.goto(page_file.as_uri())
        scene_el = page.locator(".kinlib-scene").first
        scene_el.scroll_into_view_if_needed(timeout=15_000)
        shoot = element_shooter(scene_el)
        png, mask = wait_for_mask(shoot, joint_axis_mask, lambda m: m.sum() >= AXIS_SEEN,
                                  timeout=timeout)
        shot.write_bytes(png)
        seen = {"axis": int(mask.sum()), "names": scene_el.evaluate(SCENE_NAMES),
                "requests": requests}
        if orbit:
            still = settled(shoot)
            seen["still"] = pixels_changed(still, shoot())
            orbit_drag(page, scene_el)
            moved = settled(shoot)
            shot.with_name(shot.stem + "_orbited.png").write_bytes(moved)
            seen["orbited"] = pixels_changed(still, moved)
        return seen
    finally:
        context.close()


def test_exported_scene_draws_from_saved_state_and_orbits(browser, site, tmp_path):
    """The site's page of notebook 08, from file:// with the network blocked: the robot is
    drawn and a mouse drag orbits the camera. The control: the same page with the scene's
    saved commands taken out shows no robot, so the saved widget state is what draws it."""
    page_file = site / "08_urdf_and_matrix_stack.html"
    seen = open_scene(browser, page_file, tmp_path / "static.png", orbit=True)
    assert not seen["requests"], seen["requests"]
    assert seen["axis"] >= AXIS_SEEN, f"{seen['axis']} joint-axis pixels; see {tmp_path}"
    assert {"notebook08", "test_robot", "link1", "link4", "joint3"} <= set(seen["names"])
    assert seen["still"] <= STILL and seen["orbited"] >= 2000, seen
    text = page_file.read_text(encoding="utf-8")
    emptied = re.sub(r'("commands": )\[[^\]]*\]', r"\1[]", text)
    assert emptied != text
    (tmp_path / "emptied.html").write_text(emptied, encoding="utf-8")
    shutil.copytree(site / "_static", tmp_path / "_static")
    dead = open_scene(browser, tmp_path / "emptied.html", tmp_path / "emptied.png", timeout=4)
    assert dead["axis"] <= EMPTY, f"{dead['axis']} joint-axis pixels without the scene's objects"


def test_nbconvert_kinlib_html_shows_scenes_offline(browser, tmp_path):
    """``jupyter nbconvert --to kinlib_html --execute``: one file whose scene draws from
    file:// with the network blocked. The control: nbconvert's own ``--to html`` of the
    same notebook draws its widgets with a manager from a CDN, so offline it shows none."""
    import subprocess
    import sys

    import nbformat

    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(
        "from kinlib.robots import puma560\nfrom kinlib.viz import RobotVisualizer\n"
        "viz = RobotVisualizer(puma560(), prefix='export/puma560')\n"
        "viz.set_configuration(puma560().poses['ready'])\nviz.jupyter_cell(height=300)")])
    nb.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3",
                                 "language": "python"}
    nbformat.write(nb, tmp_path / "one.ipynb")
    run = [sys.executable, "-m", "jupyter", "nbconvert"]
    # one command executes and exports (the exporter found by its entry point) ...
    done = subprocess.Popen(run + ["--to", "kinlib_html", "--execute", "--output",
                                   "one_kinlib_html", "one.ipynb"], cwd=tmp_path,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        # ... and the control, meanwhile: nbconvert's own HTML of the same notebook, run
        from nbclient import NotebookClient
        from nbconvert import HTMLExporter

        ran = nbformat.read(tmp_path / "one.ipynb", as_version=4)
        NotebookClient(ran, timeout=300, kernel_name="python3",
                       store_widget_state=True).execute()
        html, _ = HTMLExporter().from_notebook_node(ran)
        (tmp_path / "one_html.html").write_text(html, encoding="utf-8")
        _, stderr = done.communicate(timeout=300)
    finally:
        if done.poll() is None:
            done.kill()
            done.wait()
    assert done.returncode == 0, stderr[-3000:]
    page = tmp_path / "one_kinlib_html.html"
    seen = open_scene(browser, page, tmp_path / "kinlib_html.png", orbit=True)
    assert seen["axis"] >= AXIS_SEEN, f"{seen['axis']} joint-axis pixels; see {tmp_path}"
    assert {"export", "puma560", "link6"} <= set(seen["names"])
    assert seen["orbited"] >= 2000 and seen["still"] <= STILL, seen
    plain = tmp_path / "one_html.html"
    assert "application/vnd.jupyter.widget-state+json" in plain.read_text(encoding="utf-8")
    context = browser.new_context()
    try:  # the state is in the file, but offline nothing draws it
        context.route(re.compile(r"^https?://"), lambda route: route.abort())
        offline = context.new_page()
        offline.goto(plain.as_uri())
        offline.wait_for_timeout(3000)
        assert offline.locator(".kinlib-scene").count() == 0
        assert offline.locator("canvas").count() == 0
    finally:
        context.close()
