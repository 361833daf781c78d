# Two commands set everything up on a fresh machine:
#   make run   - create .venv, install softimpact (no extras: the report needs none), run the whole paper into results/paper
#   make test  - create .venv, install softimpact with its test extras, run the tests but the slow verification tier
#                on two processes (pytest-xdist; a test file stays on one, so its fixtures are built once), one BLAS thread each
#   make test-slow - the slow verification tier (-m slow: the whole paper report, fine meshes, the docs build);
#                files in the order tests/conftest.py sets (the shared paper first), not xdist's by-size order;
#                .ci/run runs both tiers
#   make lint  - ruff: lint and format check
#   make docs  - the documentation site (Sphinx, warnings are errors) into docs/_build/html, readable offline; it runs the
#                quick examples of the gallery and shows their figures (SOFTIMPACT_DOCS_RUN_EXAMPLES=all: every example;
#                =none: none); the slow ones show a stored thumbnail, refreshed by `.venv/bin/python docs/_ext/gallery_figures.py`
#   make fuzz  - the long property-based fuzz run (case files, CSV records, unit strings; minutes)
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
OUT ?= results/paper

.PHONY: run test test-slow lint bench clean fuzz docs

# One venv; each target installs what it needs once (a stamp per set of extras, remade when pyproject.toml changes).
$(VENV)/.installed-run: pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/pip install --quiet --upgrade pip
	$(BIN)/pip install --quiet -e .
	touch $@

$(VENV)/.installed-test: pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/pip install --quiet --upgrade pip
	$(BIN)/pip install --quiet -e '.[test]'
	touch $@

$(BIN)/softimpact: $(VENV)/.installed-test

run: $(VENV)/.installed-run
	MPLBACKEND=Agg $(BIN)/softimpact paper --out $(OUT)

test: $(VENV)/.installed-test
	MPLBACKEND=Agg OMP_NUM_THREADS=1 $(BIN)/python -m pytest -q -n 2 --dist loadfile --no-loadscope-reorder -m "not slow"

test-slow: $(VENV)/.installed-test
	MPLBACKEND=Agg OMP_NUM_THREADS=1 $(BIN)/python -m pytest -q -n 2 --dist loadfile --no-loadscope-reorder -m slow

docs: $(BIN)/softimpact
	MPLBACKEND=Agg OMP_NUM_THREADS=1 $(BIN)/python -m sphinx -W --keep-going -q -b html docs docs/_build/html

fuzz: $(BIN)/softimpact
	HYPOTHESIS_PROFILE=long MPLBACKEND=Agg $(BIN)/python -m pytest -q -m fuzz tests/test_fuzz.py

lint: $(BIN)/softimpact
	$(BIN)/ruff check .
	$(BIN)/ruff format --check .

bench: $(BIN)/softimpact
	$(BIN)/python benchmarks/bench_bar.py
	$(BIN)/python benchmarks/bench_beam.py
	$(BIN)/python benchmarks/bench_startup.py
	$(BIN)/python benchmarks/bench_plate.py
	$(BIN)/python benchmarks/bench_coupled.py

clean:
	rm -rf $(VENV) results build src/*.egg-info docs/_build docs/_generated docs/gallery docs/sg_execution_times.rst
