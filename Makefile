# Quick start: `make demo` and `make test` (see README.md). Both create .venv on first use.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
PIP    := $(BIN)/python -m pip
export PIP_DISABLE_PIP_VERSION_CHECK := 1

.PHONY: demo test test-fast lint typecheck check system-deps clean

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)
	$(PIP) install --quiet --upgrade pip

$(VENV)/.installed: $(BIN)/python pyproject.toml
	$(PIP) install --quiet -e '.[opt,fab,web]'
	touch $@

$(VENV)/.installed-dev: $(VENV)/.installed pyproject.toml
	$(PIP) install --quiet -e '.[dev,opt,fab,web,fea,dist]'
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

# System packages the tests need, installed when missing and running as root (CI runs as root):
# calculix-ccx (command ccx) for the finite-element tests, chromium for the browser tests,
# inkscape and librecad to render every cut file (SVG and DXF) in the cut-file tests.
# Otherwise it says what is missing; those tests then skip, or fail when CI=true.
system-deps:
	@missing=""; \
	command -v ccx >/dev/null || missing="$$missing calculix-ccx"; \
	command -v chromium >/dev/null || missing="$$missing chromium"; \
	command -v inkscape >/dev/null || missing="$$missing inkscape"; \
	command -v librecad >/dev/null || missing="$$missing librecad"; \
	if [ -n "$$missing" ]; then \
		if [ "$$(id -u)" = 0 ]; then apt-get update && apt-get install -y $$missing; \
		else echo "system-deps: missing$$missing (as root: apt-get install -y$$missing)"; fi; \
	fi

lint: $(VENV)/.installed-dev
	$(BIN)/ruff check src tests benchmarks docs
	$(BIN)/ruff format --check src tests benchmarks docs/*.py

typecheck: $(VENV)/.installed-dev
	$(BIN)/mypy

# Bytecode is cached here too (see test-fast): the suite's many CLI subprocesses each compile the
# package again without it.
test: $(VENV)/.installed-dev system-deps lint typecheck
	PYTHONDONTWRITEBYTECODE= $(BIN)/python -m pytest -q

# The edit-test loop: the same venv, no system packages, lint or type check, and only the tests
# marked neither fea (CalculiX), browser (Chromium) nor slow: under a minute (38-40 s wall and CPU
# on a 2-core machine at load average 0.5-0.8, `/usr/bin/time make test-fast`; docs/architecture.md, 4).
# Bytecode is cached even where PYTHONDONTWRITEBYTECODE is set: pytest rewrites and compiles every
# test module, and each test's subprocess compiles the package, again on every run without it.
test-fast: $(VENV)/.installed-dev
	PYTHONDONTWRITEBYTECODE= $(BIN)/python -m pytest -q -m "not fea and not browser and not slow"

clean:
	rm -rf $(VENV) out .pytest_cache .mypy_cache .ruff_cache .hypothesis
