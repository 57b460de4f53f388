#!/usr/bin/env bash
# fit() at large n beside the LAPACK floor (bench/lapack_floor.cpp), CPU time with one OpenBLAS
# thread, rounds interleaved so that the machine's load falls on every row alike:
#   bench/fit_against_floor.sh AFTER_BUILD [BEFORE_BUILD] [ROUNDS] [N]
# Each build directory holds bench/spdfit_bench_estimators (BEFORE: another commit's build, e.g.
# a `git worktree` configured with -DSPDFIT_BUILD_BENCHMARKS=ON); the floor is AFTER's.
set -euo pipefail
after=${1:?usage: bench/fit_against_floor.sh AFTER_BUILD [BEFORE_BUILD] [ROUNDS] [N]}
before=${2:-}
rounds=${3:-3}
n=${4:-1000}
export OPENBLAS_NUM_THREADS=1
filter="BM_(Fit|FitNoise)/(spde|procrustes)/4000/$n\$"
echo "# $(date -u +%F) $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), $(nproc) CPUs"
for ((round = 1; round <= rounds; ++round)); do
  echo "-- round $round, load $(cut -d' ' -f1 /proc/loadavg)"
  if [[ -n "$before" ]]; then
    echo "before:"
    "$before/bench/spdfit_bench_estimators" --benchmark_filter="$filter" --benchmark_min_time=0.1 2>/dev/null | grep '^BM_'
  fi
  echo "after:"
  "$after/bench/spdfit_bench_estimators" --benchmark_filter="$filter" --benchmark_min_time=0.1 2>/dev/null | grep '^BM_'
  echo "floor:"
  "$after/bench/spdfit_lapack_floor" --benchmark_filter="BM_(FloorFit|FloorFitNoise)/4000/$n\$" \
    --benchmark_min_time=0.1 2>/dev/null | grep '^BM_'
done
