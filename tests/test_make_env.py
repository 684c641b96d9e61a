"""The environment ``make venv`` builds (the one ``make lab`` and ``make test`` use) leaves
out rfc3987-syntax, as the Makefile says why: jsonschema then imports without compiling
lark grammars, in every Jupyter server, nbconvert and pytest process."""

from __future__ import annotations

import importlib.util
import subprocess
import sys
from pathlib import Path

import pytest

OVERRIDES = Path(sys.prefix) / "uv-overrides.txt"  # written by the Makefile's install


@pytest.fixture
def made_by_make():
    if not OVERRIDES.exists():
        pytest.skip(f"not an environment made by `make venv` ({OVERRIDES} is missing)")


def test_the_override_names_the_package_left_out(made_by_make):
    lines = [ln for ln in OVERRIDES.read_text().splitlines() if ln.strip()]
    assert lines == ['rfc3987-syntax ; sys_platform == "never"'], lines


def test_jsonschema_imports_without_lark(made_by_make):
    assert importlib.util.find_spec("rfc3987_syntax") is None, \
        "rfc3987-syntax is installed: the Makefile's override was not applied"
    code = ("import sys, jsonschema\n"
            "from jsonschema import Draft7Validator, FormatChecker\n"
            "Draft7Validator({'format': 'uri'}, format_checker=FormatChecker()).validate('x:y')\n"
            "print(sorted(m for m in ('lark', 'rfc3987_syntax') if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout
    assert out.strip() == "[]", out
