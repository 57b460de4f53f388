#!/bin/bash
# Start-up time of the command line: the wall time of `spdfit --version` (loading its shared
# libraries, OpenBLAS's initialization, parsing the arguments), averaged over 100 runs, for one
# or more builds alternating in each round. Every command pays it once; the thesis' experiments
# (issue 19: three processes, 0.1 s in all) pay it three times. Also lists how many shared
# objects each build loads at start.
# Usage: [ROUNDS=5] bench/startup_times.sh SPDFIT [SPDFIT ...]
set -euo pipefail
[ $# -ge 1 ] || { echo "usage: [ROUNDS=5] bench/startup_times.sh SPDFIT [SPDFIT ...]" >&2; exit 2; }
rounds=${ROUNDS:-5}
runs=100
now() { date +%s%N; }
per_run() {  # binary -> milliseconds per run of `binary --version`, over $runs runs
  local s
  s=$(now)
  for _ in $(seq "$runs"); do "$1" --version >/dev/null; done
  awk -v ns="$(($(now) - s))" -v n="$runs" 'BEGIN { printf "%.2f", ns / n / 1e6 }'
}
for binary in "$@"; do
  echo "$binary: $(ldd "$binary" | grep -vc linux-vdso) shared objects loaded at start (ldd)"
done
for round in $(seq "$rounds"); do
  line="round $round:"
  for binary in "$@"; do line="$line $(per_run "$binary") ms"; done
  echo "$line"
done
