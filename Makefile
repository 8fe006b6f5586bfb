# Two entry points: `make demo` and `make test` (both create .venv and install the package).
PYTHON ?= python3
VENV   ?= .venv
BIN     = $(VENV)/bin
SHARED ?= ../shared

.PHONY: install install-demo demo test lint shell bench bench-hard clean fuzz

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)
	$(BIN)/pip install -q --upgrade pip

install: $(BIN)/python
	$(BIN)/pip install -q ".[test]"
	@# Graphviz draws trees, Chromium checks the HTML report; installed when root with apt-get, else tests skip
	@command -v dot >/dev/null || { [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null && apt-get update -qq && apt-get install -y -qq graphviz; } || true
	@command -v chromium >/dev/null || { [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null && { apt-get install -y -qq chromium || { apt-get update -qq && apt-get install -y -qq chromium; }; }; } || true

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
