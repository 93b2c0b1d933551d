# blastscale — the two commands a new user needs are `make run` and `make test`.
PY      ?= python3
VENV    := .venv
BIN     := $(VENV)/bin
STAMP   := $(VENV)/.installed

.PHONY: install run test bench clean

install: $(STAMP)

$(STAMP): pyproject.toml
	test -x $(BIN)/python || $(PY) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e '.[all]'
	touch $(STAMP)

run: install
	$(BIN)/blastscale run --out results/default

test: install
	MPLBACKEND=Agg $(BIN)/python -m pytest -q

bench: install
	$(BIN)/python benchmarks/bench_rocking.py --json
	$(BIN)/python benchmarks/bench_sim3d.py --json
	$(BIN)/python benchmarks/bench_sweeps.py --json

clean:
	rm -rf $(VENV) build *.egg-info src/*.egg-info .pytest_cache
