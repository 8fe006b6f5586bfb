# Two entry points: `make demo` and `make test` (both create .venv and install the package).
PYTHON ?= python3
VENV   ?= .venv
BIN     = $(VENV)/bin
SHARED ?= ../shared

.PHONY: install demo test bench clean fuzz

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)
	$(BIN)/pip install -q --upgrade pip

install: $(BIN)/python
	$(BIN)/pip install -q ".[test]"

demo: install
	$(BIN)/foon2asp solve --goals all
	$(BIN)/foon2asp solve --goals all --format json --output out/demo > /dev/null
	@echo "trees written to out/demo/"

test: install
	cd tests && ../$(BIN)/python -m pytest

bench: install
	$(BIN)/python bench/run.py --shared $(SHARED)

clean:
	rm -rf $(VENV) build *.egg-info out .pytest_cache

# property-based fuzzing of every reader of user input: FUZZ_EXAMPLES per test (7 tests)
FUZZ_EXAMPLES ?= 2000
fuzz: install
	$(BIN)/pip install -q hypothesis
	cd tests && FUZZ_EXAMPLES=$(FUZZ_EXAMPLES) ../$(BIN)/python -m pytest -q test_fuzz.py
