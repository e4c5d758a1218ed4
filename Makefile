# Convenience front door; CMake does the work (see CMakePresets.json).
#   make demo   build everything, then stream 3 s from the virtual sensor
#   make test   build everything and run the whole suite (C via ctest, Python via pytest)
#   make bench  the figures of BENCHMARKS.md (leptrino-bench, medians of 3 runs)
PYTHON ?= python3
VENV ?= build/venv
LEPTRINO := build/dev/tools/leptrino/leptrino

.PHONY: all demo test test-c test-python sanitize clang core coverage clean bench

all:
	cmake --preset dev
	cmake --build --preset dev

demo: all
	$(LEPTRINO) stream --sim --duration 3

test: test-c test-python

test-c:
	cmake --workflow --preset dev

test-python:
	$(PYTHON) -m venv $(VENV)
	$(VENV)/bin/python -m pip install -q --upgrade pip
	$(VENV)/bin/python -m pip install -q "./bindings/python[test,bridge]"
	$(VENV)/bin/python -m pytest -q -p no:cacheprovider bindings/python/tests

sanitize:
	cmake --workflow --preset sanitize

core:
	cmake --workflow --preset core

# Branch coverage of src/core under the C suite, per file (needs gcovr).
# COVERAGE_PENDING names files reported but not failed (owned elsewhere).
COVERAGE_PENDING ?=
coverage:
	find build/coverage -name '*.gcda' -delete 2>/dev/null || true
	cmake --preset coverage
	cmake --build --preset coverage
	ctest --preset coverage
	$(PYTHON) test/coverage_report.py build/coverage $(if $(COVERAGE_PENDING),--pending $(COVERAGE_PENDING))

clang:
	CC=clang cmake -S . -B build/clang -G Ninja -DLEPTRINO_BUILD_TESTS=ON
	cmake --build build/clang
	ctest --test-dir build/clang --output-on-failure

# Every figure of BENCHMARKS.md: leptrino-bench run 3 times, medians (a few minutes).
bench: all
	$(PYTHON) bench/bench_runs.py --runs 3 --out build/dev/bench.json build/dev/bench/leptrino-bench
	$(PYTHON) bench/stream_vs_cat.py --leptrino $(LEPTRINO) --sim build/dev/tools/leptrino-sim/leptrino-sim

clean:
	rm -rf build
