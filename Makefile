# Two commands: `make demo` and `make test` set everything up on a fresh machine and run.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
PIP    := $(BIN)/python -m pip install -q --disable-pip-version-check
# llama.cpp compiles for x86-64 with AVX2/FMA/F16C, not for this machine's own CPU (-march=native):
# a virtual CPU may announce AMX tiles that its host does not let a program use (tileloadd ->
# SIGILL, seen here), and a wheel pip cached on one machine is reused on the next.
export CMAKE_ARGS ?= -DGGML_NATIVE=OFF

.PHONY: demo test lint bench system-deps schema docs screenshots clean

$(BIN)/python:
	scripts/venv.sh $(PYTHON) $(VENV)

# Re-install whenever the package metadata or a compiled module changes (setup.py compiles the
# modules that stuart_bt/language/compiled.py lists with mypyc); one stamp per set of extras.
COMPILED := $(wildcard stuart_bt/language/grammar/*.py) stuart_bt/language/numbers.py \
	stuart_bt/language/wake.py stuart_bt/language/compiled.py
$(VENV)/.stamp-base: pyproject.toml setup.py $(COMPILED) | $(BIN)/python
	$(PIP) -e .
	touch $@

$(VENV)/.stamp-sim: pyproject.toml setup.py $(COMPILED) | $(BIN)/python
	$(PIP) -e ".[sim,ik]"
	touch $@

$(VENV)/.stamp-test: pyproject.toml setup.py $(COMPILED) | $(BIN)/python
	$(PIP) -e ".[test,bench,sim,ik,llm,ros,robot,web,vision,hearing]"
	touch $@

$(VENV)/.stamp-lint: pyproject.toml setup.py $(COMPILED) | $(BIN)/python
	$(PIP) -e ".[lint]"
	touch $@

$(VENV)/.stamp-bench: pyproject.toml setup.py $(COMPILED) | $(BIN)/python
	$(PIP) -e ".[test,bench,sim,ik,llm,ros,robot,web,vision,hearing]"
	touch $@

system-deps:
	scripts/system-deps.sh

## demo: the lab tour in the MuJoCo simulator, headless: report, event log, video and map in out/
demo: system-deps $(VENV)/.stamp-sim
	$(BIN)/stuart-bt run trees/lab_tour.yaml --backend sim \
		--report out/lab_tour_report.json --log out/lab_tour.jsonl \
		--record out/lab_tour.mp4 --map-out out/lab_tour_map.png

## test: the whole pytest suite, in one worker process per core (pytest-xdist; docs/testing.md)
test: system-deps $(VENV)/.stamp-test
	$(BIN)/python -m pytest -n 2

## lint: the ruff rule set and the type check (both configured in pyproject.toml); CI runs it first
lint: system-deps $(VENV)/.stamp-test $(VENV)/.stamp-lint
	$(BIN)/ruff check stuart_bt skills sim tasks tests bench examples
	$(BIN)/python scripts/typecheck.py

## bench: benchmarks -> bench/results.json and a table
bench: system-deps $(VENV)/.stamp-bench
	$(BIN)/python -m bench.run

## screenshots: the web view's browser tests again, saving a picture of each view in docs/images/web_*.png
screenshots: system-deps $(VENV)/.stamp-test
	STUART_BT_SCREENSHOTS=docs/images $(BIN)/python -m pytest -q tests/test_web_tree.py \
		tests/test_web_console.py tests/test_web_map.py tests/test_web_gestures.py

## schema: regenerate docs/tree.schema.json from the catalogue
schema: $(VENV)/.stamp-base
	$(BIN)/stuart-bt schema -o docs/tree.schema.json

clean:
	rm -rf $(VENV) out .pytest_cache
