# Two entry points: `make demo` and `make test` (both create .venv and install the package).
PYTHON ?= python3
VENV   ?= .venv
BIN     = $(VENV)/bin
SHARED ?= ../shared

.PHONY: install install-demo system-deps demo test lint shell bench bench-hard clean fuzz

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)
	$(BIN)/pip install -q --upgrade pip

install: $(BIN)/python system-deps
	$(BIN)/pip install -q ".[test]"

# Graphviz's `dot` (drawings) and Chromium (measures the HTML pages' drawings) for the tests that
# need them: when one is missing and make runs as root with apt-get, the Debian packages graphviz
# and chromium are installed (with their dependencies), said first; NO_SYSTEM_INSTALL=1 skips it.
# Without them those tests skip.
NO_SYSTEM_INSTALL ?=
system-deps:
	@missing=""; \
	command -v dot >/dev/null || missing=" graphviz"; \
	command -v chromium >/dev/null || command -v chromium-browser >/dev/null || missing="$$missing chromium"; \
	if [ -z "$$missing" ]; then exit 0; fi; \
	if [ -n "$(NO_SYSTEM_INSTALL)" ]; then \
		echo "make: not installing$$missing (NO_SYSTEM_INSTALL is set): the tests that need them skip"; exit 0; fi; \
	if [ "$$(id -u)" != 0 ] || ! command -v apt-get >/dev/null; then \
		echo "make: not installing$$missing (needs root and apt-get): the tests that need them skip"; exit 0; fi; \
	echo "make: installing$$missing with apt-get, with their dependencies, for the tests that draw trees"; \
	echo "make: (graphviz: 'dot' draws the trees and charts; chromium: measures the HTML pages' drawings)"; \
	echo "make: to skip this: make test NO_SYSTEM_INSTALL=1"; \
	export DEBIAN_FRONTEND=noninteractive; apt-get update -qq || true; \
	for package in $$missing; do \
		apt-get install -y -qq $$package || echo "make: apt-get could not install $$package: the tests that need it skip"; \
	done

# the demo needs only the package itself
install-demo: $(BIN)/python
	$(BIN)/pip install -q .

demo: install-demo
	$(BIN)/foon2asp solve --data demo --goals all
	$(BIN)/foon2asp solve --data demo --goals all --format json --output out/demo > /dev/null
	@echo "trees written to out/demo/; run '. $(BIN)/activate' (or 'make shell') to use foon2asp"

test: install lint
	cd tests && ../$(BIN)/python -m pytest

# lint, format check, types, the import-layer contract (pyproject.toml) and the docs site
lint: install
	$(BIN)/ruff check foon2asp tests bench
	$(BIN)/ruff format --check foon2asp tests bench
	$(BIN)/mypy
	$(BIN)/lint-imports
	@# the documentation site (mkdocs.yml, docs/): a broken link or anchor fails (not -q: it hides the warnings --strict counts)
	NO_MKDOCS_2_WARNING=1 $(BIN)/mkdocs build --strict -d build/site

# a shell with the environment active
shell: install-demo
	@echo "foon2asp is on PATH in this shell; 'exit' to leave"
	@. $(BIN)/activate && exec $${SHELL:-bash}

# P1-P3 (bench/run.py) and the hard table (bench/hard.py, about 40 minutes; BENCHMARKS.md)
bench: install
	$(BIN)/python bench/run.py --shared $(SHARED)
	$(BIN)/python bench/p2.py --shared $(SHARED)
	$(BIN)/python bench/hard.py --shared $(SHARED) $(HARD_ARGS)
	$(BIN)/python bench/schedule.py --shared $(SHARED)

# only the hard table; e.g. make bench-hard HARD_ARGS="--presets small --limit 5"
bench-hard: install
	$(BIN)/python bench/hard.py --shared $(SHARED) $(HARD_ARGS)

clean:
	rm -rf $(VENV) build *.egg-info out .pytest_cache

# property-based fuzzing of every reader of user input: FUZZ_EXAMPLES per test (7 tests)
FUZZ_EXAMPLES ?= 2000
fuzz: install
	$(BIN)/pip install -q hypothesis
	cd tests && FUZZ_EXAMPLES=$(FUZZ_EXAMPLES) ../$(BIN)/python -m pytest -q test_fuzz.py
