"""The 3-D viewer under a hub's base URL in Jupyter Notebook 7, with Chromium allowed to
reach that server's URLs only: the checks of tests/hub_viewer.py (the same checks run in
JupyterLab, on the course's own server: tests/test_lab.py)."""

from __future__ import annotations

import re

import pytest
from hub_viewer import (
    BASE_URL,
    NOTEBOOK,
    check_viewers,
    fenced_page,
    wait_for_kernel,
    write_viewer_notebook,
)
from lab_harness import Lab
from test_lab import run_all


@pytest.fixture(scope="module")
def hub(tmp_path_factory):
    """A Jupyter Notebook 7 server under ``/user/student/``."""
    notebooks = tmp_path_factory.mktemp("hub_notebooks")
    write_viewer_notebook(notebooks)
    server = Lab(notebooks, tmp_path_factory.mktemp("hub_notebook"), base_url=BASE_URL,
                 app="notebook")
    try:
        yield server
    finally:
        server.stop()


def test_the_viewer_works_through_the_server_alone(hub, browser, tmp_path):
    context, page, refused = fenced_page(browser, hub)
    try:
        # Notebook 7.6 throws one error of its own while it loads (a plugin's settings
        # schema; a one-cell "1 + 1" notebook gets it too): the errors before kinlib's
        # viewer runs are the baseline, and the viewer may add none
        page.goto(f"{hub.base}/notebooks/viewer.ipynb?token={hub.token}")
        page.wait_for_function(f"() => document.querySelectorAll('{NOTEBOOK} .jp-Cell')"
                               ".length === 4", timeout=90_000)
        wait_for_kernel(hub, page)
        page.wait_for_timeout(1000)  # the app settles
        at_load = list(page.errors)
        prompts = run_all(page, "viewer.ipynb")  # the same menus as JupyterLab's
        assert all(re.fullmatch(r"\[\d+\]:", p) for p in prompts), \
            f"cells that did not run: {prompts}"
        check_viewers(hub, page, refused, tmp_path, at_load)
    finally:
        page.screenshot(path=str(tmp_path / "page.png"))
        context.close()
