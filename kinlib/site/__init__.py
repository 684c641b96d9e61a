"""The course as a static web site: ``python -m kinlib.site`` (``make site``).

Every notebook in ``notebooks/`` (of the current directory, or the folder given) is
executed in its own kernel and exported to one HTML page in ``site/``, next to an
``index.html`` holding the course outline (each notebook's title and learning goals, in the
two parts of the course) with links. The site works offline, opened
straight from the files:

- mathematics: MathJax 3's single-file TeX-to-SVG build (no web fonts, which browsers refuse
  to load from ``file://`` pages), fetched once with ``npm pack`` into ``build/`` and copied
  to ``site/_static``; a LaTeX error is reported on the browser console, and the page marks
  ``<body data-mathjax="done">`` when typesetting ends;
- matplotlib animations: ``to_jshtml`` players, inline JavaScript;
- 3-D scenes (``kinlib.viz`` widgets): drawn from the notebook's saved widget state by
  the meshcat viewer, orbitable; its bundle and kinlib's scene view are two files in
  ``site/_static`` that every page shares;
- ipywidgets: drawn from their saved state as plain HTML (:mod:`kinlib.site._widgets`).

A cell that raises stops the build with the notebook's name and the cell's number.

It needs the course's tools, ``pip install 'kinlib[course]'`` (nbformat, nbclient,
nbconvert, a Python kernel); without them its functions raise :class:`KinlibError` naming
that extra. The page template ships with the package (``kinlib/site/templates``).
"""

from __future__ import annotations

import functools
import html
import re
import shutil
import time
from concurrent.futures import ProcessPoolExecutor
from contextlib import nullcontext
from dataclasses import dataclass
from importlib import resources
from itertools import repeat
from multiprocessing import get_context
from pathlib import Path

from .._optional import course_import
from ..errors import KinlibError
from ..plot._player import offline_player
from ._widgets import freeze_widgets, with_viewer

__all__ = ["PageInfo", "outline", "build_site", "execute_notebook", "read_executed",
           "export_page", "ensure_mathjax", "index_html", "MARKER", "PARTS"]

#: the page template's folder, shipped with the package
TEMPLATES = resources.files(__package__) / "templates"
#: the default folder of the notebooks, relative to the current directory
NOTEBOOKS = Path("notebooks")
MARKER = ".kinlib-site"  # a directory holding it may be emptied by the next build
#: the two parts of the course: (title, first notebook number, last)
PARTS = (("Part 1 · Spatial descriptions and orientation", 1, 7),
         ("Part 2 · Kinematic models, inverse and differential kinematics, planning", 8, 15))

MATHJAX_VERSION = "3.2.2"
#: sha256 of MathJax 3.2.2's es5/tex-svg-full.js (TeX input, SVG output: no web fonts)
MATHJAX_SHA256 = "a4354ff94fd868aea0cc6eaaa79a57fda0588646fc46ee3700a349ee0a11cbe6"
#: where :func:`ensure_mathjax` keeps it by default, relative to the current directory
MATHJAX_FILE = Path("build") / f"mathjax-{MATHJAX_VERSION}" / "tex-svg-full.js"

MATHJAX_HEAD = r"""<script>
window.MathJax = {
  tex: {
    inlineMath: [["$", "$"], ["\\(", "\\)"]], displayMath: [["$$", "$$"], ["\\[", "\\]"]],
    processEscapes: true, processEnvironments: true, tags: "ams",
    formatError: function (jax, err) {
      console.error("LaTeX error: " + err.message);
      return jax.formatError(err);
    }
  },
  svg: {fontCache: "global"},
  options: {enableMenu: false},
  startup: {
    pageReady: function () {
      return MathJax.startup.defaultPageReady().then(function () {
        document.body.setAttribute("data-mathjax", "done");
      });
    }
  }
};
</script>
<script src="_static/tex-svg-full.js"></script>"""

CSS = """
nav.kl-nav { display: flex; justify-content: space-between; gap: 1em; max-width: 1100px;
  margin: 0.5em auto; padding: 0.5em 1em; font-family: var(--jp-ui-font-family, sans-serif);
  font-size: 14px; border-bottom: 1px solid #ddd; }
nav.kl-nav a { color: #1565c0; text-decoration: none; }
nav.kl-nav a:hover { text-decoration: underline; }
.kl-frozen { border-left: 3px solid #90caf9; padding: 0.3em 0.8em; background: #f5f9ff; }
.kl-widget-note { font-style: italic; color: #555; margin: 0.2em 0 0.5em 0; }
.kl-slider { display: flex; align-items: center; gap: 0.6em; }
.kl-slider label { min-width: 6em; text-align: right; }
.kl-slider input { width: 16em; }
"""

INDEX_CSS = """
body { font-family: system-ui, -apple-system, "Segoe UI", sans-serif; max-width: 900px;
  margin: 2em auto; padding: 0 1em; line-height: 1.5; color: #222; }
h1 { margin-bottom: 0.2em; } h2 { margin-top: 1.6em; border-bottom: 1px solid #ddd; }
.kl-lesson { margin: 1em 0 1.4em 0; } .kl-lesson h3 { margin: 0 0 0.2em 0; }
.kl-lesson a { color: #1565c0; text-decoration: none; }
.kl-lesson a:hover { text-decoration: underline; }
.kl-goals { font-size: 0.95em; color: #333; } .kl-goals ol { margin: 0.2em 0; }
footer { margin-top: 3em; font-size: 0.85em; color: #666; }
"""


@dataclass(frozen=True)
class PageInfo:
    """One notebook of the outline: ``name`` (file stem), ``number``, ``title`` and its
    learning goals as Markdown (``""`` when it states none)."""

    name: str
    number: int
    title: str
    goals: str

    @property
    def href(self) -> str:
        return f"{self.name}.html"


def _markdown_cells(nb) -> list[str]:
    return [c.source for c in nb.cells if c.cell_type == "markdown"]


def _folder(notebooks: Path | str | None) -> Path:
    folder = Path(notebooks) if notebooks is not None else NOTEBOOKS
    if notebooks is None and not folder.is_dir():
        raise KinlibError(f"no folder {folder}/ in {Path.cwd()}: expected the course's "
                          "notebooks there (run from the course repository's root), or give "
                          "their folder (notebooks=..., --notebooks FOLDER)")
    return folder


def outline(notebooks: Path | str | None = None) -> list[PageInfo]:
    """The course's notebooks (``NN_name.ipynb``) in order, with titles and goals;
    ``notebooks``: their folder (default ``notebooks/`` of the current directory)."""
    nbformat = course_import("nbformat", "kinlib.site")
    folder = _folder(notebooks)
    pages = []
    for path in sorted(folder.glob("[0-9][0-9]_*.ipynb")):
        nb = nbformat.read(path, as_version=4)
        cells = _markdown_cells(nb)
        first = cells[0] if cells else ""
        heading = re.search(r"^#\s+(.+)$", first, re.M)
        if heading is None:
            raise KinlibError(f"{path.name}: expected a '# title' line in the first markdown "
                              "cell")
        title = re.sub(r"^\d+\s*[·.:-]\s*", "", heading.group(1).strip())
        goals = re.search(r"\*\*Learning goals\.?\*\*(.*?)(?:\n\s*\n(?!\s*\d+\.)|\Z)", first,
                          re.S)
        pages.append(PageInfo(path.stem, int(path.name[:2]), title,
                              goals.group(1).strip() if goals else ""))
    if not pages:
        raise KinlibError(f"no notebooks named NN_*.ipynb in {folder}")
    return pages


def execute_notebook(path: Path | str, timeout: float = 600.0):
    """Run the notebook at ``path`` in a fresh ``python3`` kernel (working directory: its
    folder) and return the executed node, widget state included. A cell that raises becomes a
    :class:`KinlibError` naming the notebook and the cell."""
    nbformat = course_import("nbformat", "kinlib.site")
    course_import("nbclient", "kinlib.site")
    from nbclient import NotebookClient
    from nbclient.exceptions import CellExecutionError, CellTimeoutError

    path = Path(path)
    nb = nbformat.read(path, as_version=4)
    client = NotebookClient(nb, timeout=timeout, kernel_name="python3",
                            resources={"metadata": {"path": str(path.parent)}},
                            store_widget_state=True)
    try:
        client.execute()
    except CellTimeoutError as exc:
        raise KinlibError(f"{path.name}: a cell ran longer than {timeout:g} s") from exc
    except CellExecutionError as exc:
        cell = next((i for i, c in enumerate(nb.cells) if _error_output(c)), None)
        raise KinlibError(f"{path.name}: cell {cell} raised {exc.ename}: "
                          f"{exc.evalue}") from None
    return nb


def _nav(pages: list[PageInfo], here: int) -> str:
    def link(i, label):
        p = pages[i]
        return f'<a href="{p.href}">{label} {html.escape(f"{p.number:02d} · {p.title}")}</a>'

    left = link(here - 1, "←") if here > 0 else "<span></span>"
    right = link(here + 1, "→") if here + 1 < len(pages) else "<span></span>"
    return (f'<nav class="kl-nav">{left}<a href="index.html">Course outline</a>{right}</nav>')


@functools.cache
def _exporter():
    """nbconvert's HTML exporter with the page template: one per process, so its templates
    are compiled once for all the pages it writes."""
    HTMLExporter = course_import("nbconvert", "kinlib.site").HTMLExporter
    templates = Path(str(TEMPLATES))
    if not templates.is_dir():
        raise KinlibError(f"kinlib.site: its page template is not a folder on disk "
                          f"({TEMPLATES}): install kinlib from a wheel or a checkout, not a zip")
    exporter = HTMLExporter(template_name="lab", extra_template_paths=[str(templates)])
    exporter.template_file = "kinlib_page.html.j2"
    return exporter


def export_page(nb, page: PageInfo, pages: list[PageInfo]) -> str:
    """The executed notebook ``nb`` as one offline HTML page of the site."""
    exporter = _exporter()
    freeze_widgets(nb)
    here = [p.name for p in pages].index(page.name)
    resources = {"metadata": {"name": f"{page.number:02d} · {page.title} — kinlib"},
                 "kinlib": {"mathjax_head": MATHJAX_HEAD, "css": CSS,
                            "nav": _nav(pages, here)}}
    body, _ = exporter.from_notebook_node(nb, resources=resources)
    body = offline_player(body)  # (kl.plot.animate's players are so already: any other)
    body = with_viewer(body)  # the viewer, once per page, after the content
    leaks = re.findall(r'<(?:script|link)[^>]+(?:src|href)="(https?:[^"]+)"', body)
    if leaks:
        raise KinlibError(f"{page.name}: the page would load {leaks[0]} from the network")
    return body


def _error_output(cell) -> dict | None:
    """The cell's first error output (a cell that raised), or None."""
    return next((o for o in cell.get("outputs", []) if o.get("output_type") == "error"), None)


def read_executed(path: Path | str):
    """The notebook at ``path`` as it was saved after a run (by JupyterLab, say): every code
    cell must have run and none may hold an error; a :class:`KinlibError` names the first
    that did not. Its widget state is whatever the save stored (JupyterLab stores it when
    *Settings → Save Widget State Automatically* is ticked)."""
    nbformat = course_import("nbformat", "kinlib.site")
    path = Path(path)
    nb = nbformat.read(path, as_version=4)
    for i, cell in enumerate(nb.cells):
        if cell.cell_type != "code":
            continue
        if cell.get("execution_count") is None:
            raise KinlibError(f"{path.name}: cell {i} has not run; execute the notebook "
                              "first, or build without executed=True (--executed)")
        error = _error_output(cell)
        if error is not None:
            raise KinlibError(f"{path.name}: cell {i} raised {error.get('ename')}: "
                              f"{error.get('evalue')}")
    return nb


def _build_one(path: str, out: str, pages: list[PageInfo], timeout: float,
               executed: bool = False) -> tuple[str, float]:
    start = time.perf_counter()
    page = next(p for p in pages if p.name == Path(path).stem)
    nb = read_executed(path) if executed else execute_notebook(path, timeout)
    (Path(out) / page.href).write_text(export_page(nb, page, pages), encoding="utf-8")
    return page.name, time.perf_counter() - start


def ensure_mathjax(path: Path | str | None = None) -> Path:
    """MathJax's single-file TeX-to-SVG build, fetched once with ``npm pack`` from the npm
    registry into ``build/`` of the current directory (:data:`MATHJAX_FILE`; pinned version,
    checked against its sha256); ``path``: a file to use instead, as it is."""
    import hashlib
    import subprocess
    import tarfile
    import tempfile

    target = Path(path) if path is not None else MATHJAX_FILE
    if not target.exists():
        target.parent.mkdir(parents=True, exist_ok=True)
        with tempfile.TemporaryDirectory() as tmp:
            try:
                subprocess.run(["npm", "pack", "--silent", f"mathjax@{MATHJAX_VERSION}"],
                               cwd=tmp, check=True, capture_output=True, timeout=300)
            except (OSError, subprocess.SubprocessError) as exc:
                detail = getattr(exc, "stderr", b"") or b""
                raise KinlibError(f"could not fetch mathjax@{MATHJAX_VERSION} with npm "
                                  f"(needs Node.js' npm and the npm registry): {exc} "
                                  f"{detail.decode(errors='replace')[-300:]}") from None
            with tarfile.open(Path(tmp) / f"mathjax-{MATHJAX_VERSION}.tgz") as tar:
                for member, name in (("package/es5/tex-svg-full.js", target.name),
                                     ("package/LICENSE", "LICENSE")):
                    data = tar.extractfile(member).read()
                    (target.parent / (name + ".part")).write_bytes(data)
                    (target.parent / (name + ".part")).replace(target.parent / name)
    digest = hashlib.sha256(target.read_bytes()).hexdigest()
    if path is None and digest != MATHJAX_SHA256:
        raise KinlibError(f"{target}: sha256 {digest} is not MathJax {MATHJAX_VERSION}'s "
                          f"{MATHJAX_SHA256}; delete the file to fetch it again")
    return target


def _copy_mathjax(out: Path, mathjax: Path | str | None) -> None:
    source = ensure_mathjax(mathjax)
    static = out / "_static"
    static.mkdir(exist_ok=True)
    shutil.copy2(source, static / "tex-svg-full.js")
    if (source.parent / "LICENSE").exists():
        shutil.copy2(source.parent / "LICENSE", static / "MathJax-LICENSE")


def _copy_viewer(out: Path) -> None:
    """The meshcat bundle (as the meshcat package ships it, with its licence) and kinlib's
    scene view, shared by every page's scenes."""
    from ..viz._widget import BUNDLE_FILE, scene_js

    static = out / "_static"
    static.mkdir(exist_ok=True)
    shutil.copy2(BUNDLE_FILE, static / "meshcat.min.js")
    licence = BUNDLE_FILE.with_name(BUNDLE_FILE.name + ".LICENSE.txt")
    if licence.exists():
        shutil.copy2(licence, static / "meshcat.min.js.LICENSE.txt")
    (static / "kinlib-scene.js").write_text(scene_js(), encoding="utf-8")


def index_html(pages: list[PageInfo]) -> str:
    """The outline page: the two parts, each notebook's title, link and learning goals."""
    course_import("nbconvert", "kinlib.site")
    from nbconvert.filters.markdown import markdown2html_mistune

    parts = []
    for title, lo, hi in PARTS:
        lessons = [p for p in pages if lo <= p.number <= hi]
        if not lessons:
            continue
        items = "".join(
            f'<div class="kl-lesson"><h3><a href="{p.href}">{p.number:02d} · '
            f'{html.escape(p.title)}</a></h3>'
            + (f'<div class="kl-goals">{markdown2html_mistune(p.goals)}</div>' if p.goals
               else "") + "</div>" for p in lessons)
        parts.append(f"<h2>{html.escape(title)}</h2>{items}")
    rest = [p for p in pages if not any(lo <= p.number <= hi for _, lo, hi in PARTS)]
    if rest:
        parts.append("<h2>More</h2>" + "".join(
            f'<div class="kl-lesson"><h3><a href="{p.href}">{p.number:02d} · '
            f'{html.escape(p.title)}</a></h3></div>' for p in rest))
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1.0">
<title>kinlib — a course workbook for robot kinematics</title>
{MATHJAX_HEAD}
<style>{INDEX_CSS}</style></head>
<body>
<h1>kinlib — robot kinematics, a course workbook</h1>
<p>The course notebooks, executed, with their outputs: the derivations, the pictures, the
animations and the 3-D robots (as the notebook left them, and you can orbit them; driven by
sliders when you run the notebooks in JupyterLab with <code>make lab</code>).</p>
{"".join(parts)}
<footer>Built by <code>make site</code> (<code>python -m kinlib.site</code>) from the notebooks
in <code>notebooks/</code>.</footer>
</body></html>
"""


def build_site(out: Path | str = "site", notebooks: Path | str | None = None, *,
               jobs: int = 1, timeout: float = 600.0, only: list[str] | None = None,
               mathjax: Path | str | None = None, executed: bool = False,
               log=print) -> dict[str, float]:
    """Execute the notebooks and write the site to ``out``; seconds per notebook.

    ``jobs`` notebooks run at once (each in its own process and kernel). ``only`` restricts
    the build to those notebook names (the outline and navigation still list them all).
    ``notebooks``: their folder (default ``notebooks/`` of the current directory).
    ``mathjax``: a MathJax 3 ``tex-svg-full.js`` to use (default: :func:`ensure_mathjax`).
    ``out`` is emptied first if it holds a previous build (a ``.kinlib-site`` marker); an
    existing folder without one is refused rather than overwritten. ``executed=True``
    exports the notebooks as they were saved, without running them (they must have run:
    :func:`read_executed`), e.g. the ones a class ran and saved in JupyterLab.
    """
    folder = _folder(notebooks)
    out = Path(out)
    if isinstance(jobs, bool) or not isinstance(jobs, int) or jobs < 1:
        raise KinlibError(f"build_site: jobs must be a positive integer, got {jobs!r}")
    pages = outline(folder)
    names = [p.name for p in pages]
    chosen = names if only is None else list(only)
    unknown = [n for n in chosen if n not in names]
    if unknown:
        raise KinlibError(f"build_site: no notebook named {unknown[0]!r}; expected one of "
                          f"{', '.join(names)}")
    if out.exists() and any(out.iterdir()) and not (out / MARKER).exists():
        raise KinlibError(f"build_site: {out} exists and is not a kinlib site (no {MARKER}); "
                          "refusing to overwrite it")
    if out.exists():
        shutil.rmtree(out)
    out.mkdir(parents=True)
    (out / MARKER).write_text("built by python -m kinlib.site; emptied by the next build\n")
    _copy_mathjax(out, mathjax)
    _copy_viewer(out)
    (out / "index.html").write_text(index_html(pages), encoding="utf-8")
    paths = [str(folder / f"{n}.ipynb") for n in chosen]
    seconds = {}
    with (ProcessPoolExecutor(max_workers=jobs, mp_context=get_context("spawn")) if jobs > 1
          else nullcontext()) as pool:
        run = map if pool is None else pool.map  # in order; a failure is raised here
        for name, t in run(_build_one, paths, repeat(str(out)), repeat(pages),
                           repeat(timeout), repeat(bool(executed))):
            seconds[name] = t
            log(f"  {name}: {t:.1f} s")
    return seconds
