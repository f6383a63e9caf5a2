# Set-up, main job, tests and benchmarks. Every target installs what it
# needs first (pinned in requirements.lock) into .venv.
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed

.PHONY: test-loaded setup run test bench fmu clean browser windows

setup: $(STAMP)

$(STAMP): requirements.lock pyproject.toml
	@$(PYTHON) -c 'import sys; sys.exit(sys.version_info < (3, 11) and "Python >= 3.11 is needed, found " + sys.version.split()[0])'
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --disable-pip-version-check -r requirements.lock
	$(BIN)/python -m pip install --quiet --disable-pip-version-check --no-deps --no-build-isolation -e .
	@touch $@

# Main job: the 4-DOF stability map with the paper's parameters (Fig. 14).
run: setup
	$(BIN)/judder map --preset paper-4dof --driveline chain --out out/map-4dof.npz --plot out/map-4dof.png

# The suite on two processes (pytest-xdist), each test file whole on one
# of them (its module fixtures, and the README's commands in their
# order); the signal and Dask tests wait for ready markers, so they hold
# beside the other process too.
test: setup browser windows
	$(BIN)/python -m pytest -q -n 2 --dist loadfile

# The tests that signal a child or start Dask workers, ten times in a row
# with two busy processes beside them (a loaded machine: they wait for
# ready markers, never a fixed delay); says how many runs failed.
LOADED_TESTS := tests/test_reliability.py::test_signal_while_starting \
  tests/test_reliability.py::test_ctrl_c_during_a_map \
  tests/test_reliability.py::test_ctrl_c_of_the_process_group_with_workers \
  tests/test_reliability.py::test_a_second_signal_does_not_wait_for_the_clean_up \
  tests/test_cli.py::test_ctrl_c_leaves_no_partial_file \
  tests/test_faults.py::test_sigterm_like_ctrl_c \
  tests/test_faults.py::test_campaign_workers_die_with_their_parent \
  tests/test_parallel.py tests/test_leftovers.py

test-loaded: setup
	@yes >/dev/null & a=$$!; yes >/dev/null & b=$$!; \
	trap 'kill $$a $$b' EXIT; failed=0; \
	for run in 1 2 3 4 5 6 7 8 9 10; do \
	  echo "run $$run of 10"; \
	  $(BIN)/python -m pytest -q -p no:cacheprovider $(LOADED_TESTS) \
	    || failed=$$((failed + 1)); \
	done; \
	echo "$$failed of 10 runs failed"; test $$failed = 0

# Debian's Chromium, in which tests/test_report.py opens the HTML report
# (about 1 min to install); without it that test skips and says why.
browser:
	@command -v chromium >/dev/null 2>&1 || apt-get install -y chromium >/dev/null 2>&1 \
	  || (apt-get update >/dev/null 2>&1 && apt-get install -y chromium >/dev/null 2>&1) \
	  || echo "chromium could not be installed: the report's browser test will skip"

# Debian's mingw-w64 and wine (about 20 s to install), with which
# tests/test_fmu_corpus.py cross-compiles the Windows binary of an FMU
# (python -m fmu --windows) and runs it; without them those tests skip and
# say why.
windows:
	@(command -v x86_64-w64-mingw32-gcc >/dev/null 2>&1 && test -x /usr/lib/wine/wine64) \
	  || apt-get install -y --no-install-recommends gcc-mingw-w64-x86-64 wine64 >/dev/null 2>&1 \
	  || (apt-get update >/dev/null 2>&1 && apt-get install -y --no-install-recommends gcc-mingw-w64-x86-64 wine64 >/dev/null 2>&1) \
	  || echo "mingw-w64 or wine could not be installed: the Windows FMU tests will skip"

bench: setup
	$(BIN)/python benchmarks/bench.py

# FMUs of the Modelica examples (FMI 2.0 and FMI 3.0, ME+CS each) under
# build/fmu; rebuilt only when the library or the compiler changed.
MO_SOURCES := $(shell find modelica -name '*.mo' -o -name package.order)
FMU_COMPILER := $(wildcard fmu/*.py fmu/c/*.c fmu/c/*.h)
FMU_STAMP := build/fmu/.built

fmu: $(FMU_STAMP)

$(FMU_STAMP): $(STAMP) $(MO_SOURCES) $(FMU_COMPILER)
	$(BIN)/python -m fmu --out build/fmu
	@touch $@

clean:
	rm -rf $(VENV) out build
