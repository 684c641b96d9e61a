"""The student edition in JupyterLab, second part: notebooks 08–15, with the checks of
``test_lab.py`` (its docstring says what they are), on a JupyterLab server and page of this
module's own, so that pytest-xdist runs the two parts side by side."""

from __future__ import annotations

import pytest

# lab and lab_page are module fixtures: imported, they give this module its own server and page
from test_lab import PART2, check_notebook, lab, lab_page  # noqa: F401


@pytest.mark.parametrize("name", PART2)
def test_notebook_runs_in_jupyterlab(lab, lab_page, name, tmp_path, site_feed):  # noqa: F811
    check_notebook(lab, lab_page, name, tmp_path, site_feed)
