# kinlib: two commands on a fresh machine.
#   make lab   creates .venv if missing, installs kinlib with its notebook dependencies,
#              starts JupyterLab on notebooks/, the student edition (it prints the URL)
#   make test  same environment, runs the whole test suite (lint + pytest)
#   make site  same environment, executes every notebook into a static site in site/
#              (offline: open site/index.html; MathJax is fetched once with npm into build/)
#   make lab-instructor   JupyterLab on instructor/, the notebooks with the solutions
#   make release          regenerate the student editions (notebooks/, assignments/release/)
#                         from instructor/ and assignments/source/
#   make student-repo     what students receive, as a repository of its own, in
#                         $(STUDENT_REPO) (default build/student-repo, which make clean
#                         removes; a clone of the published student repository, kept beside
#                         this one, is updated in place): the student editions, a README,
#                         kinlib's wheel and the Binder environment. Set STUDENT_REPO_URL to
#                         its https address for the README's Binder link.
#                         This repository (instructor/, assignments/source/) stays with
#                         instructors: point students at the student repository only.
PYTHON ?= python3
VENV   ?= .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.kinlib-installed

.PHONY: lab lab-instructor release student-repo test venv bench lint clean site screenshots

# The install goes through uv (from PyPI, into the venv: about 25 s where pip takes about
# 60 s; --compile-bytecode as pip does, else every first import compiles its module); pip
# does it if uv cannot (say, on a machine whose only package index is pip's own
# configuration, which uv does not read).
#
# One transitive package is left out, through uv's override with a marker no machine has:
# rfc3987-syntax, which jsonschema imports when it is installed (jupyter-events asks for
# jsonschema[format-nongpl]) to check the "iri" string format, and which compiles 38 lark
# grammars as it is imported: 1.2 s in every process that imports jsonschema (each Jupyter
# server, nbconvert, every pytest process through nbval's nbformat), for a format nothing
# here uses. Without it jsonschema imports in 0.2 s and simply does not check "iri".
EXTRAS := .[lab,course,dev,fast]
OVERRIDES := $(VENV)/uv-overrides.txt
$(STAMP): pyproject.toml
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	printf 'rfc3987-syntax ; sys_platform == "never"\n' > $(OVERRIDES)
	( $(BIN)/python -m pip install --quiet uv \
	  && $(BIN)/uv pip install --quiet --compile-bytecode --python $(BIN)/python \
	       --override $(OVERRIDES) -e '$(EXTRAS)' ) \
	|| { $(BIN)/python -m pip install --quiet --upgrade pip \
	     && $(BIN)/python -m pip install --quiet -e '$(EXTRAS)' \
	     && $(BIN)/python -m pip uninstall --quiet -y rfc3987-syntax; }
	touch $(STAMP)

venv: $(STAMP)

# Jupyter refuses to run as root unless told (containers, CI machines).
ROOT_FLAG := $(if $(filter 0,$(shell id -u)),--allow-root)

lab: $(STAMP)
	$(BIN)/jupyter lab --notebook-dir=notebooks $(ROOT_FLAG)

lab-instructor: $(STAMP)
	$(BIN)/jupyter lab --notebook-dir=instructor $(ROOT_FLAG)

release: $(STAMP)
	$(BIN)/python -m kinlib.assign

# The student editions are regenerated first: the release refuses stale ones.
STUDENT_REPO     ?= build/student-repo
STUDENT_REPO_URL ?=
student-repo: release
	$(BIN)/python -m kinlib.assign --student-repo '$(STUDENT_REPO)' \
	    $(if $(STUDENT_REPO_URL),--repo-url '$(STUDENT_REPO_URL)')

lint: $(STAMP)
	$(BIN)/ruff check .
	$(BIN)/lint-imports

# Two workers (pytest-xdist); a file's tests stay together in one worker (a notebook's cells
# share its kernel, the JupyterLab suite its server); the longest files first (conftest.py).
WORKERS ?= 2

# Bytecode is written (and kinlib's compiled first) even where the environment says
# PYTHONDONTWRITEBYTECODE, as on some CI machines: else each of the suite's hundreds of
# Python processes (workers, kernels, sandboxed submissions) compiles the modules it imports
# again, and each worker rewrites every test module's asserts again (collecting takes
# 18 s instead of 8 s).
test: lint
	$(BIN)/python -m compileall -q kinlib
	env -u PYTHONDONTWRITEBYTECODE $(BIN)/python -m pytest -n $(WORKERS) --dist loadfile \
	    --no-loadscope-reorder

site: $(STAMP)
	$(BIN)/python -m kinlib.site --out site --jobs 2

# The README's two JupyterLab screenshots, retaken by the browser suite (needs Chromium).
screenshots: $(STAMP)
	KINLIB_SCREENSHOTS=notebooks/screenshots KINLIB_REQUIRE_BROWSER=1 $(BIN)/python -m pytest \
	    -q tests/test_lab.py -k "04_gimbal_lock or 09_denavit_hartenberg"

bench: $(STAMP)
	$(BIN)/python -m pip install --quiet -e '.[bench]'
	$(BIN)/python bench/bench_conversions.py
	$(BIN)/python bench/bench_fk.py
	$(BIN)/python bench/bench_diffkin.py
	$(BIN)/python bench/bench_poe.py
	$(BIN)/python bench/bench_numpy.py
	$(BIN)/python bench/bench_first_call.py
	$(BIN)/python bench/bench_grader.py

clean:
	rm -rf $(VENV) build site *.egg-info
