# blastscale — the two commands a new user needs are `make run` and `make test`.
PY      ?= python3
VENV    := .venv
BIN     := $(VENV)/bin
STAMP   := $(VENV)/.installed

.PHONY: install run test test-fast bench clean check-python

install: $(STAMP)

# blastscale needs Python >= 3.11 (tomllib, typing); say so instead of failing deep inside pip
check-python:
	@$(PY) -c 'import sys; sys.exit(sys.version_info < (3, 11))' 2>/dev/null || { \
	  echo "error: blastscale needs Python >= 3.11, but $(PY) is '$$($(PY) --version 2>&1 | head -n1)'; run e.g. 'make PY=python3.11 $(MAKECMDGOALS)'" >&2; \
	  exit 1; }

$(STAMP): pyproject.toml | check-python
	test -x $(BIN)/python || $(PY) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e '.[all]'
	touch $(STAMP)

# --force: a second `make run` replaces the previous results/default (only a blastscale result folder)
run: install
	mkdir -p results
	$(BIN)/blastscale run --out results/default --force

# lint and format (ruff, pyproject.toml), the architecture (import-linter contracts), then the whole suite on
# every core (pytest-xdist; a test file stays on one worker, so its module fixtures are built once). The
# suite's wall time is measured and recorded with each round in CHANGELOG.md, not here, where it would go stale.
test: install
	$(BIN)/ruff check src tests benchmarks examples
	$(BIN)/ruff format --check src tests benchmarks examples
	$(BIN)/lint-imports --no-cache
	MPLBACKEND=Agg $(BIN)/python -m pytest -q -n auto --dist loadfile --no-loadscope-reorder

# the unit tier only (tests/unit, under a minute): the quick check while editing one package
test-fast: install
	MPLBACKEND=Agg $(BIN)/python -m pytest -q tests/unit

bench: install
	$(BIN)/python benchmarks/bench_rocking.py --json
	$(BIN)/python benchmarks/bench_sim3d.py --json
	$(BIN)/python benchmarks/bench_sweeps.py --json

clean:
	rm -rf $(VENV) build *.egg-info src/*.egg-info .pytest_cache
