#!/usr/bin/env bash
# The main job's build (scripts/setup.sh runtime: no tests, benchmarks or MEX, and no
# small-problem kernels) in build-main/, checked against the test build in build/: `spdfit demo`
# prints the same numbers (tests/package/compare_outputs.py), and the figures script draws every
# figure. scripts/test.sh runs it after the tests, so that the configuration new users build is
# compiled and run on every change.
set -euo pipefail
cd "$(dirname "$0")/.."
SPDFIT_BUILD_DIR=build-main SPDFIT_INSTALL=0 scripts/setup.sh runtime
build-main/apps/spdfit demo > build-main/demo.txt
build/apps/spdfit demo > build/demo.txt
/usr/bin/python3 tests/package/compare_outputs.py build/demo.txt build-main/demo.txt
PYTHONPATH="$PWD/build-main/python" MPLBACKEND=Agg /usr/bin/python3 -m spdfit.figures --quick --out build-main/figures >/dev/null
echo "check_main_build: build-main's demo agrees with build's, and its figures are drawn"
