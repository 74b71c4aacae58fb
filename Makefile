# Quick start: `make demo` and `make test` (see README.md). Both create .venv on first use.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
PIP    := $(BIN)/python -m pip
export PIP_DISABLE_PIP_VERSION_CHECK := 1

.PHONY: demo test lint typecheck check system-deps clean

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)
	$(PIP) install --quiet --upgrade pip

$(VENV)/.installed: $(BIN)/python pyproject.toml
	$(PIP) install --quiet -e '.[opt,fab]'
	touch $@

$(VENV)/.installed-dev: $(VENV)/.installed pyproject.toml
	$(PIP) install --quiet -e '.[dev,opt,fab,web]'
	touch $@

# The paper's case study (Liu, Yan and Mehta, Table 1, case 1), end to end, files under out/.
demo: $(VENV)/.installed
	@mkdir -p out
	$(BIN)/corrugate materials
	$(BIN)/corrugate analyze --W 8 --n 8 --alpha 84 --material dura-lar --model paper --eta 0 --eta 90
	$(BIN)/corrugate analyze --W 8 --n 8 --alpha 84 --material dura-lar --compare-models
	$(BIN)/corrugate analyze --W 8 --n 8 --alpha 84 --material dura-lar --model paper \
		--eta 0 --eta 90 --json > out/case1_analysis.json.tmp && mv out/case1_analysis.json.tmp out/case1_analysis.json
	$(BIN)/corrugate design examples/blimp_gripper.toml --out out/blimp_gripper
	@echo "wrote out/case1_analysis.json and the blimp gripper's design and cut files under out/blimp_gripper/"

# System packages the tests need (installed when root and missing).
# chromium: the browser tests of the web app drive Debian's /usr/bin/chromium with Playwright.
system-deps:
	@command -v chromium >/dev/null || { [ "$$(id -u)" = 0 ] && apt-get update && apt-get install -y chromium; } || echo "system-deps: chromium missing (install it as root: apt-get install chromium)"

lint: $(VENV)/.installed-dev
	$(BIN)/ruff check src tests benchmarks
	$(BIN)/ruff format --check src tests benchmarks

typecheck: $(VENV)/.installed-dev
	$(BIN)/mypy

test: $(VENV)/.installed-dev system-deps lint typecheck
	$(BIN)/python -m pytest -q

clean:
	rm -rf $(VENV) out .pytest_cache .mypy_cache .ruff_cache .hypothesis
