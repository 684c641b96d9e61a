"""The static course site (``make site``), built and then read in a real browser, offline.

The module builds the site once with ``python -m kinlib.site`` (every notebook executed in
its own kernel) into a temporary folder, then opens every page from its ``file://`` URL
in headless Chromium with all http(s) blocked and asserts:

- no request left the machine, and no console error or uncaught exception (a LaTeX error
  is a console error too: the page's MathJax reports it);
- the mathematics is typeset: MathJax finished, at least as many formulas as the
  notebook's Markdown has ``$…$``/``$$…$$`` pairs, no error node, and no raw TeX
  (``$`` or ``\\command``) left in the text;
- the meshcat snapshots (08, 09, 10) draw their robot (filled joint-axis pixels and the
  robot's names in the three.js scene); removing the robot in that same page empties the
  picture (the control);
- every matplotlib animation plays: *Next frame* shows another image and *Play* moves
  the frame counter;
- sliders appear as disabled pictures of their state, with a note, and the outline page
  links every notebook, with its learning goals.
"""

from __future__ import annotations

import json
import re
import subprocess
import sys
import time
from pathlib import Path

import pytest
from browser_helpers import EMPTY, pixels_changed, solid_axes, wait_for_mask

from kinlib.site import MARKER, outline

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOKS = ROOT / "notebooks"
PAGES = [p.name for p in outline(NOTEBOOKS)]
SCENES = {"08_urdf_and_matrix_stack": {"test_robot", "link1", "link4", "joint3"},
          "09_denavit_hartenberg": {"puma560", "link1", "link6"},
          "10_inverse_kinematics": {"puma560", "link1", "link6", "line"}}
SLIDERS = {"04_gimbal_lock": 1, "08_urdf_and_matrix_stack": 3, "09_denavit_hartenberg": 6}
AXES_SEEN = 60
ROBOT = 400
BUILD_TIMEOUT = 600

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
SCENE_NAMES = "() => { const n = []; viewer.scene.traverse(o => n.push(o.name)); return n; }"


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


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    out = tmp_path_factory.mktemp("site") / "site"
    start = time.monotonic()
    run = subprocess.run([sys.executable, "-m", "kinlib.site", "--out", str(out), "--jobs", "2"],
                         capture_output=True, text=True, timeout=BUILD_TIMEOUT, cwd=ROOT)
    assert run.returncode == 0, f"the site build failed:\n{run.stdout}\n{run.stderr[-3000:]}"
    print(f"site built in {time.monotonic() - start:.1f} s")
    return out


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
    scenes = page.locator(".kinlib-scene iframe")
    assert scenes.count() == (1 if name in SCENES else 0), f"{name}: {scenes.count()} scenes"
    if name in SCENES:
        check_snapshot(page, scenes.first, name, tmp_path)
    assert not log["errors"], f"{name}: console errors: {log['errors'][:5]}"


def check_players(page, name: str) -> None:
    source = (NOTEBOOKS / f"{name}.ipynb").read_text()
    players = page.locator("img[id^='_anim_img']")
    assert players.count() == source.count("to_jshtml("), f"{name}: {players.count()} players"
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


def check_snapshot(page, frame_el, name: str, out: Path) -> None:
    def shoot():
        frame_el.scroll_into_view_if_needed()
        return frame_el.screenshot()

    png, mask = wait_for_mask(shoot, solid_axes, lambda m: m.sum() >= AXES_SEEN, timeout=20)
    (out / "scene.png").write_bytes(png)
    assert mask.sum() >= AXES_SEEN, f"{name}: the snapshot shows {mask.sum()} joint-axis " \
                                    f"pixels; see {out}"
    frame = frame_el.element_handle().content_frame()
    names = set(frame.evaluate(SCENE_NAMES))
    assert SCENES[name] <= names, f"{name}: missing {SCENES[name] - names} in the scene"
    frame.evaluate(f"() => viewer.handle_command({{type: 'delete', "
                   f"path: '/meshcat/notebook{name[:2]}'}})")
    empty_png, empty = wait_for_mask(shoot, solid_axes, lambda m: m.sum() <= EMPTY)
    (out / "scene_emptied.png").write_bytes(empty_png)
    assert empty.sum() <= EMPTY, f"{name}: {empty.sum()} joint-axis pixels with no robot"
    assert pixels_changed(png, empty_png) >= ROBOT
