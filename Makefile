# Owl Kit Lab. `make demo` and `make test` bootstrap themselves; `make setup` only bootstraps.
SHELL := /bin/bash
.SHELLFLAGS := -e -o pipefail -c
ENV := source ./env.sh &&
BENCHMARKS := $(filter-out bench/measure.py,$(wildcard bench/*.py))

.PHONY: setup demo test test-fast lint bench clean

setup:
	@bash scripts/bootstrap.sh

demo: setup
	@$(ENV) owl demo

# The system tests mostly wait on processes, discovery and timers: pytest-xdist runs them in this many
# workers; `make test TEST_WORKERS=0` runs them in one. worksteal: each worker starts on a run of
# whole test files (a module's shared fixtures start once) and an idle one takes half of the busiest
# one's queue, so the suite does not end on one worker's long tail (loadfile, whole files per worker
# with the longest first, took 661 s against 629 s: the heaviest files ran side by side at the
# start). One worker per test slot (a core and one more, and three spares for an idle machine:
# tests/conftest.py) and one that may wait outside them for the class server's lab.
TEST_WORKERS ?= $(shell echo $$(( $$(nproc) + 5 )))
PYTEST := python -m pytest -n $(TEST_WORKERS) --dist worksteal
# pytest rewrites each test module's asserts as it imports it (5 s of CPU for the suite), and where
# PYTHONDONTWRITEBYTECODE is set (CI machines, ours too) every worker did it again: two collections
# side by side write the rewritten modules once, and the workers read them.
REWRITE_TESTS := for tests in src tests; do PYTHONDONTWRITEBYTECODE= python -m pytest --collect-only \
  $$tests >/dev/null 2>&1 & done; wait

test: setup
	@bash scripts/test_prereqs.sh
	@$(ENV) $(REWRITE_TESTS); $(PYTEST)

# The inner loop while working: the unit tests, the style checks and the layout, no process of ROS.
test-fast: setup
	@$(ENV) $(REWRITE_TESTS); $(PYTEST) src tests/test_code_style.py tests/test_layout.py

lint: setup
	@$(ENV) ruff check . && python -m mypy && \
	  python -m mypy --allow-untyped-defs --allow-incomplete-defs --follow-untyped-imports \
	    --cache-dir build/mypy_cache_outside_src tests scripts bench docs

bench: setup  # every benchmark in turn; each prints its numbers and ratio to its baseline
	@$(ENV) for script in $(BENCHMARKS); do echo "== $$script"; python "$$script"; done

clean:
	rm -rf build install log .venv .pytest_cache web/node_modules
