"""The site builder's parts, without a browser: the outline read from the notebooks, frozen
widgets, offline animation players, MathJax's checksum, and its errors."""

from __future__ import annotations

import json
import re
from pathlib import Path

import nbformat
import pytest

from kinlib import KinlibError
from kinlib.plot._player import offline_player
from kinlib.site import (
    MARKER,
    build_site,
    ensure_mathjax,
    execute_notebook,
    index_html,
    outline,
    read_executed,
)
from kinlib.site._widgets import WIDGET_STATE, WIDGET_VIEW, freeze_widgets, render_widget

NOTEBOOKS = Path(__file__).resolve().parents[1] / "notebooks"


def _notebook(folder: Path, name: str, cells: list) -> Path:
    nb = nbformat.v4.new_notebook(cells=cells)
    nb.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3",
                                 "language": "python"}
    path = folder / f"{name}.ipynb"
    nbformat.write(nb, path)
    return path


def test_outline_reads_titles_and_goals_of_the_course():
    pages = outline(NOTEBOOKS)
    assert [p.number for p in pages] == list(range(1, 16))
    first = pages[0]
    assert first.title.startswith("Spatial descriptions") and first.href.endswith(".html")
    raw = json.loads((NOTEBOOKS / f"{first.name}.ipynb").read_text())
    heading = "".join(raw["cells"][0]["source"]).splitlines()[0]
    assert heading.startswith("# 01") and first.title in heading  # the number is dropped
    for page in pages:
        assert page.goals.startswith("After this notebook you can"), page.name
        last = page.goals.strip().splitlines()[-1]
        assert re.match(r"\d+\. ", last), (page.name, last)  # the list, not what follows
    assert "Conventions" not in first.goals


def test_outline_refuses_a_notebook_without_a_title(tmp_path):
    _notebook(tmp_path, "01_untitled", [nbformat.v4.new_markdown_cell("no heading here")])
    with pytest.raises(KinlibError, match=r"01_untitled\.ipynb: expected a '# title' line"):
        outline(tmp_path)
    with pytest.raises(KinlibError, match="no notebooks named NN_"):
        outline(tmp_path / "missing")


def test_index_page_lists_both_parts_and_renders_goals_as_html():
    page = index_html(outline(NOTEBOOKS))
    assert page.count('class="kl-lesson"') == 15
    assert "Part 1" in page and "Part 2" in page and "<ol>" in page
    assert "tex-svg-full.js" in page and "https://" not in page


def _slider_state():
    return {
        "s1": {"model_name": "FloatSliderModel",
               "state": {"description": "beta (°)", "value": 45.0, "min": -90.0, "max": 90.0,
                         "step": 0.5}},
        "o1": {"model_name": "OutputModel",
               "state": {"outputs": [{"output_type": "stream", "name": "stdout",
                                      "text": "det E = -0.7071 <ok>\n"}]}},
        "b1": {"model_name": "ButtonModel", "state": {"description": "forward"}},
        "v1": {"model_name": "VBoxModel",
               "state": {"children": ["IPY_MODEL_s1", "IPY_MODEL_o1", "IPY_MODEL_b1",
                                      "IPY_MODEL_zz"]}},
    }


def test_widgets_are_frozen_from_their_saved_state():
    models = _slider_state()
    html = render_widget("v1", models)
    assert 'type="range" disabled min="-90.0" max="90.0" step="0.5" value="45.0"' in html
    assert "<output>45</output>" in html and "beta (°)" in html
    assert "det E = -0.7071 &lt;ok&gt;" in html  # printed text is escaped
    assert "<button class=\"kl-widget\" disabled>forward</button>" in html
    assert "[widget]" in html  # a child whose model is missing
    nb = nbformat.v4.new_notebook()
    cell = nbformat.v4.new_code_cell("ui")
    cell.outputs = [nbformat.v4.new_output(
        "display_data", data={WIDGET_VIEW: {"model_id": "v1", "version_major": 2},
                              "text/plain": "VBox(...)"})]
    nb.cells = [cell]
    nb.metadata["widgets"] = {WIDGET_STATE: {"state": models, "version_major": 2}}
    assert freeze_widgets(nb) == 1
    assert "widgets" not in nb.metadata
    data = nb.cells[0].outputs[0]["data"]
    assert list(data) == ["text/html"] and "kl-frozen" in data["text/html"]
    assert "Interactive in JupyterLab" in data["text/html"]


def test_animation_players_lose_the_icon_font_but_keep_their_buttons():
    page = ('<link href="https://maxcdn.bootstrapcdn.com/font-awesome/4.4.0/css/'
            'font-awesome.min.css" rel="stylesheet"/>'
            '<button onclick="a.reverse_animation()"><i class="fa fa-play fa-flip-horizontal">'
            '</i></button><button onclick="a.play_animation()"><i class="fa fa-play"></i>'
            '</button><button><i class="fa fa-pause"></i></button>')
    out = offline_player(page)
    assert "font-awesome" not in out and "https://" not in out and "fa-" not in out
    assert out.count('class="kl-icon"') == 3
    assert "◀" in out and "▶" in out and "❚❚" in out


def test_mathjax_is_checked_against_its_pinned_hash(tmp_path, monkeypatch):
    import kinlib.site as site

    path = ensure_mathjax()  # fetched once into build/ (npm pack) and verified
    assert path.stat().st_size > 1_000_000
    fake = tmp_path / "tex-svg-full.js"
    fake.write_text("// not MathJax")
    assert ensure_mathjax(fake) == fake  # a file given explicitly is used as it is
    bad = tmp_path / "build" / "tex-svg-full.js"
    bad.parent.mkdir()
    bad.write_text("// tampered")
    monkeypatch.setattr(site, "MATHJAX_FILE", bad)
    with pytest.raises(KinlibError, match=r"sha256 \w+ is not MathJax 3\.2\.2's"):
        ensure_mathjax()


def test_build_refuses_bad_arguments_and_foreign_folders(tmp_path):
    foreign = tmp_path / "mine"
    foreign.mkdir()
    (foreign / "thesis.tex").write_text("precious")
    with pytest.raises(KinlibError, match=r"not a kinlib site \(no \.kinlib-site\); refusing"):
        build_site(foreign, NOTEBOOKS, only=["01_spatial_descriptions"])
    assert (foreign / "thesis.tex").read_text() == "precious"
    with pytest.raises(KinlibError, match="no notebook named '99_nothing'"):
        build_site(tmp_path / "out", NOTEBOOKS, only=["99_nothing"])
    for jobs in (0, 1.5, True):
        with pytest.raises(KinlibError, match="jobs must be a positive integer"):
            build_site(tmp_path / "out", NOTEBOOKS, jobs=jobs)


def test_a_failing_cell_names_the_notebook_and_the_cell(tmp_path):
    folder = tmp_path / "nbs"
    folder.mkdir()
    _notebook(folder, "01_broken", [nbformat.v4.new_markdown_cell("# 01 · Broken"),
                                    nbformat.v4.new_code_cell("x = 1"),
                                    nbformat.v4.new_code_cell("x / 0")])
    with pytest.raises(KinlibError, match=r"01_broken.ipynb: cell 2 raised ZeroDivisionError"):
        execute_notebook(folder / "01_broken.ipynb", timeout=60)
    out = tmp_path / "site"
    with pytest.raises(KinlibError, match=r"01_broken\.ipynb: cell 2"):
        build_site(out, folder, log=lambda _: None)
    assert (out / MARKER).exists() and not (out / "01_broken.html").exists()


def test_a_small_site_is_built_from_scratch_and_rebuilt(tmp_path):
    folder = tmp_path / "nbs"
    folder.mkdir()
    _notebook(folder, "01_small", [
        nbformat.v4.new_markdown_cell("# 01 · Small\n\n**Learning goals.** After this "
                                      "notebook you can\n\n1. add $1 + 1$."),
        nbformat.v4.new_code_cell("print(1 + 1)")])
    _notebook(folder, "02_scenes", [
        nbformat.v4.new_markdown_cell("# 02 · Scenes"),
        nbformat.v4.new_code_cell("from kinlib.robots import planar_2r\n"
                                  "from kinlib.viz import RobotVisualizer\n"
                                  "a = RobotVisualizer(planar_2r(1, 1), prefix='a')\n"
                                  "a.jupyter_cell(height=222)"),
        nbformat.v4.new_code_cell("b = RobotVisualizer(planar_2r(1, 2), prefix='b')\n"
                                  "b.jupyter_cell(height=333)")])
    out = tmp_path / "site"
    built = build_site(out, folder, log=lambda _: None)  # notebook -> its build time
    assert list(built) == ["01_small", "02_scenes"]
    page = (out / "01_small.html").read_text()
    assert "<pre>2\n</pre>" in page
    assert '<a href="index.html">Course outline</a>' in page
    assert "meshcat" not in page  # no scene, no viewer
    scenes = (out / "02_scenes.html").read_text()
    assert scenes.count('class="kl-scene-static"') == 2  # each from its saved widget state
    assert 'min-height: 222px' in scenes and 'min-height: 333px' in scenes
    assert scenes.count('<script src="_static/meshcat.min.js"></script>') == 1  # once a page
    assert (out / "_static" / "meshcat.min.js").stat().st_size > 500_000
    assert "kinlibMountScene" in (out / "_static" / "kinlib-scene.js").read_text()
    assert len(scenes) - len(page) < 50_000  # the bundle is a shared file, not inline
    (out / "stale.html").write_text("old")
    build_site(out, folder, log=lambda _: None)  # a previous build is replaced
    assert not (out / "stale.html").exists() and (out / "01_small.html").exists()


def test_executed_notebooks_are_exported_as_saved_and_unrun_ones_refused(tmp_path):
    """``executed=True`` (``--executed``): the pages are the saved outputs (nothing runs
    again: a cell whose re-run would print something else still shows what it printed),
    and a notebook with a cell that has not run, or an error, is refused by name."""
    import subprocess
    import sys

    folder = tmp_path / "nbs"
    folder.mkdir()
    path = _notebook(folder, "01_saved", [
        nbformat.v4.new_markdown_cell("# 01 · Saved"),
        nbformat.v4.new_code_cell("import random\nprint(random.random())")])
    nb = execute_notebook(path, timeout=60)
    printed = nb.cells[1].outputs[0]["text"]
    nbformat.write(nb, path)
    out = tmp_path / "site"
    build_site(out, folder, executed=True, log=lambda _: None)
    assert f"<pre>{printed}</pre>" in (out / "01_saved.html").read_text()

    nb.cells.append(nbformat.v4.new_code_cell("1 + 1"))  # added after the run
    nbformat.write(nb, path)
    with pytest.raises(KinlibError, match=r"01_saved\.ipynb: cell 2 has not run"):
        build_site(out, folder, executed=True, log=lambda _: None)
    nb.cells[2].execution_count = 2
    nb.cells[2].outputs = [nbformat.v4.new_output("error", ename="NameError",
                                                  evalue="name 'q' is not defined")]
    nbformat.write(nb, path)
    with pytest.raises(KinlibError, match=r"cell 2 raised NameError: name 'q'"):
        read_executed(path)
    # the command line's flag (run again, the notebook would pass: 1 + 1 raises nothing)
    cli = subprocess.run([sys.executable, "-m", "kinlib.site", "--out", str(tmp_path / "cli"),
                          "--notebooks", str(folder), "--executed"],
                         capture_output=True, text=True, timeout=300)
    assert cli.returncode == 1 and "cell 2 raised NameError" in cli.stderr, cli.stderr


def test_without_the_course_tools_the_builder_names_the_extra(tmp_path, monkeypatch):
    import subprocess
    import sys

    code = ("import runpy, sys\nsys.modules['nbclient'] = None\n"
            "sys.argv = ['kinlib.site', '--out', 'out']\n"
            "runpy.run_module('kinlib.site', run_name='__main__', alter_sys=True)\n")
    (tmp_path / "notebooks").mkdir()
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         cwd=tmp_path, timeout=300)
    assert out.returncode == 2, out.stdout + out.stderr
    assert "Traceback" not in out.stderr
    assert "python -m kinlib.site needs nbclient" in out.stderr
    assert "pip install 'kinlib[course]'" in out.stderr
    assert not (tmp_path / "out").exists()
    monkeypatch.setitem(sys.modules, "nbformat", None)  # and from Python
    with pytest.raises(KinlibError, match=r"kinlib\.site needs nbformat.*kinlib\[course\]"):
        outline(NOTEBOOKS)


def test_the_notebooks_default_to_the_current_directory_s(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(KinlibError, match=r"no folder notebooks/ in .*--notebooks"):
        outline()
    with pytest.raises(KinlibError, match=r"no folder notebooks/ in .*--notebooks"):
        build_site(tmp_path / "out")
    assert not (tmp_path / "out").exists()
    (tmp_path / "notebooks").mkdir()
    _notebook(tmp_path / "notebooks", "01_here",
              [nbformat.v4.new_markdown_cell("# 01 · Here\n\n**Learning goals.** 1. this")])
    assert [(p.name, p.title) for p in outline()] == [("01_here", "Here")]


def test_the_page_template_ships_with_the_package():
    from importlib import resources

    import kinlib.site as site

    template = resources.files("kinlib.site").joinpath("templates", "kinlib_page.html.j2")
    assert template.is_file() and "{%" in template.read_text(encoding="utf-8")
    assert Path(str(site.TEMPLATES)) == Path(str(template)).parent
