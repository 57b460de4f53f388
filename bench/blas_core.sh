#!/bin/sh
# The numbers behind spdfit's choice of OpenBLAS core (docs/performance.md, "The BLAS core";
# issue 19, item 1): dgemm's rate with OpenBLAS's own choice against each core forced with
# OPENBLAS_CORETYPE, on one thread and on all, and the wall time of a large fit (n = 1000,
# m = 4000, spde) with OpenBLAS's choice, with the generic Prescott kernels, with the core spdfit
# restarts with (SPDFIT_TEST_BLAS_CORE=Prescott: spdfit takes OpenBLAS for having reported
# Prescott) and with that core set by hand; then what the restart itself costs.
# Run from the source tree after a Release build:  bench/blas_core.sh [BUILD_DIR] > result.md
set -eu
build=${1:-build}
spdfit=$build/apps/spdfit
floor=$build/bench/spdfit_lapack_floor
rounds=${ROUNDS:-3}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
unset OPENBLAS_CORETYPE SPDFIT_TEST_BLAS_CORE SPDFIT_BLAS_REEXEC SPDFIT_TEST_BLAS_EXE OPENBLAS_NUM_THREADS

echo "# OpenBLAS core: dgemm and a large fit ($(date -u +%Y-%m-%dT%H:%MZ))"
echo
echo "CPU: $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) cores;" \
  "$(dpkg-query -W -f '${Package} ${Version}' libopenblas0-pthread 2>/dev/null || echo 'OpenBLAS ?')."
echo "spdfit $(git rev-parse --short HEAD 2>/dev/null || echo '?') (Release build in $build)."
echo "Load average at the start: $(cut -d' ' -f1-3 /proc/loadavg). Command: bench/blas_core.sh $build (ROUNDS=$rounds)"
echo
echo "## dgemm, C = A B (n x n), GFLOP/s by wall-clock time, median of 3"
echo
echo '```'
for threads in 1 2; do
  for core in "" Prescott Sandybridge Haswell Zen SkylakeX Cooperlake; do
    line=$(OPENBLAS_NUM_THREADS=$threads OPENBLAS_CORETYPE=$core "$floor" --benchmark_filter='BM_Dgemm' \
             --benchmark_min_time=0.5 --benchmark_repetitions=3 --benchmark_report_aggregates_only=true \
             --benchmark_format=csv 2>/dev/null |
             awk -F, '/_median/ { split($1, name, "/"); printf "n=%s %6.1f   ", name[2], $NF / 1e9 }')
    printf 'OPENBLAS_NUM_THREADS=%s OPENBLAS_CORETYPE=%-12s %s\n' "$threads" "${core:-(unset)}" "$line"
  done
done
echo '```'

/usr/bin/python3 - "$work" <<'PY'
import sys
import numpy as np
rng = np.random.default_rng(1)
n, m = 1000, 4000
A = rng.uniform(-5, 5, (m, n))
W = rng.standard_normal((n, n))
np.save(f"{sys.argv[1]}/A.npy", A)
np.save(f"{sys.argv[1]}/B.npy", A @ (W @ W.T / n + np.eye(n)) + 0.1 * rng.standard_normal((m, n)))
PY

echo
echo "## spdfit fit --method spde A.npy B.npy (n = 1000, m = 4000), wall / user seconds"
echo
echo "One OpenBLAS thread (OPENBLAS_NUM_THREADS=1: user time is the work, whatever else runs on the"
echo "machine) and OpenBLAS's default (a thread per core), the cases alternating round by round."
echo
echo '```'
for round in $(seq "$rounds"); do
  for threads in 1 all; do
    for case in default Prescott restart SkylakeX-by-hand Haswell-by-hand; do
      case $case in
        default) set -- env ;;
        Prescott) set -- env OPENBLAS_CORETYPE=Prescott ;;
        restart) set -- env SPDFIT_TEST_BLAS_CORE=Prescott ;;
        SkylakeX-by-hand) set -- env OPENBLAS_CORETYPE=SkylakeX ;;
        Haswell-by-hand) set -- env OPENBLAS_CORETYPE=Haswell ;;
      esac
      [ "$threads" = 1 ] && set -- "$@" OPENBLAS_NUM_THREADS=1
      "$@" /usr/bin/time -f "%e %U" -o "$work/time" "$spdfit" --verbose fit --method spde "$work/A.npy" \
        "$work/B.npy" > "$work/X-$threads-$case.csv" 2> "$work/verbose"
      printf 'round %s threads %-3s %-17s %s s wall %s s user   %s\n' "$round" "$threads" "$case" $(cat "$work/time") \
        "$(cat "$work/verbose")" | tee -a "$work/fits"
    done
  done
done
echo '```'
echo
echo "Per case over the $rounds rounds (the minimum is the run least disturbed by other load):"
echo
echo "| OpenBLAS threads | case | min wall (s) | median wall (s) | min user (s) | median user (s) |"
echo "|---|---|---:|---:|---:|---:|"
middle=$(( (rounds + 1) / 2 ))
for threads in 1 all; do
  for case in default Prescott restart SkylakeX-by-hand Haswell-by-hand; do
    walls=$(awk -v t="$threads" -v c="$case" '$4 == t && $5 == c { print $6 }' "$work/fits" | sort -n)
    users=$(awk -v t="$threads" -v c="$case" '$4 == t && $5 == c { print $9 }' "$work/fits" | sort -n)
    printf '| %s | %s | %s | %s | %s | %s |\n' "$threads" "$case" "$(echo "$walls" | head -1)" \
      "$(echo "$walls" | sed -n "${middle}p")" "$(echo "$users" | head -1)" "$(echo "$users" | sed -n "${middle}p")"
  done
done
echo
echo "Load average at the end: $(cut -d' ' -f1-3 /proc/loadavg)."
echo
for core in SkylakeX Haswell; do
  echo "X of the restart byte-identical to X with OPENBLAS_CORETYPE=$core by hand:" \
    "$(cmp -s "$work/X-all-restart.csv" "$work/X-all-$core-by-hand.csv" && echo yes || echo no)"
done

echo
echo "## The restart's own cost: 100 runs of spdfit --version, seconds in all, three times"
echo
echo '```'
for round in 1 2 3; do
  for case in plain restart; do
    [ $case = restart ] && export SPDFIT_TEST_BLAS_CORE=Prescott
    /usr/bin/time -f "$case %e s wall" sh -c "for i in \$(seq 100); do $spdfit --version > /dev/null; done" 2>&1
    unset SPDFIT_TEST_BLAS_CORE
  done
done
echo '```'
