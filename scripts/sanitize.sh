#!/usr/bin/env bash
# Builds everything (library, CLI, Python module, tests) with AddressSanitizer and
# UndefinedBehaviorSanitizer in build-sanitize/ (clang, -fno-sanitize-recover: the first finding
# aborts), together with the libFuzzer targets, and runs the whole test suite there, the fuzz
# targets' seed corpora and past crashes included. Used by test.sh; run setup.sh first.
set -euo pipefail
cd "$(dirname "$0")/.."

build=build-sanitize
jobs=$(nproc 2>/dev/null || echo 2)
# Debug keeps Eigen's bounds assertions on; the sanitizer option adds -O1 so the tests stay fast.
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_COMPILER=clang++-14 \
  -DSPDFIT_FUZZ=ON -DSPDFIT_BUILD_BENCHMARKS=OFF -DSPDFIT_OCTAVE=OFF >/dev/null
cmake --build "$build" --parallel "$jobs"

# Stack use after return and initialization order are off by default; leaks are on.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_stack_use_after_return=1:check_initialization_order=1:strict_init_order=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1}
# Open MPI's own allocations left at exit (tests/mpi) are not spdfit's leaks.
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$PWD/scripts/lsan-suppressions.txt:print_suppressions=0}
ctest --test-dir "$build" --output-on-failure --parallel "$jobs"
