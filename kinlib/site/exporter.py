"""``jupyter nbconvert --to kinlib_html``: one notebook as one HTML file whose 3-D scenes
need no kernel and no network.

nbconvert's own HTML export draws widgets with a widget manager it loads from a CDN;
this exporter (registered in pyproject.toml as the nbconvert exporter ``kinlib_html``)
instead turns every kinlib scene widget into the meshcat viewer drawing the scene the
notebook's saved widget state holds (bundle and kinlib's scene view inline, once per
file), and the other widgets into pictures of their state (:mod:`kinlib.site._widgets`).
The notebook must carry its widget state: ``--execute`` stores it, as does JupyterLab's
*Save Widget State Automatically*. The mathematics is typeset by nbconvert's MathJax
(from its CDN: offline, formulas stay as TeX; ``make site`` builds fully offline pages).
"""

from __future__ import annotations

from nbconvert.exporters import HTMLExporter

from ._widgets import freeze_widgets, with_viewer

__all__ = ["KinlibHTMLExporter"]


class KinlibHTMLExporter(HTMLExporter):
    """nbconvert's HTML exporter (lab template), with kinlib's offline 3-D scenes."""

    export_from_notebook = "HTML with kinlib scenes"

    def _preprocess(self, nb, resources):
        nb, resources = super()._preprocess(nb, resources)  # --execute runs here
        freeze_widgets(nb)  # then the widgets become scenes and pictures
        return nb, resources

    def from_notebook_node(self, nb, resources=None, **kw):
        from ..viz._widget import inline_viewer

        output, resources = super().from_notebook_node(nb, resources, **kw)
        return with_viewer(output, inline_viewer()), resources
