# The README's commands. `make run` and `make test` set everything up first.
PYTHON ?= python3
VENV   := .venv
VPY    := $(VENV)/bin/python
# Everything the installed package is built from: a change re-installs it (incrementally).
SOURCES := CMakeLists.txt pyproject.toml $(shell find cpp python sim -type f \( -name '*.cpp' -o -name '*.hpp' -o -name '*.py' -o -name '*.pyi' -o -name 'py.typed' \) 2>/dev/null)

.PHONY: setup run test bench clean
setup: $(VENV)/.installed

$(VENV)/.base:
	scripts/install-system-deps.sh
	$(PYTHON) -m venv $(VENV)
	$(VPY) -m pip install -q --upgrade pip
	$(VPY) -m pip install -q "scikit-build-core>=0.10" "pybind11>=2.12" cmake ninja
	touch $@

$(VENV)/.installed: $(VENV)/.base $(SOURCES)
	$(VPY) -m pip install -q --no-build-isolation ".[sim,plot,test]"
	touch $@

run: setup
	$(VPY) -m robokin.demo

test: setup
	$(VPY) -m pytest -q

bench: setup
	scripts/install-system-deps.sh python3-pykdl
	$(VPY) -m pip install -q pin
	$(VPY) benchmarks/run_all.py

clean:
	rm -rf build $(VENV)
