#!/bin/bash
# Start-up time of the command line: the wall time of `spdfit --version` (loading its shared
# libraries, OpenBLAS's initialization, parsing the arguments), averaged over many runs, for one
# or two builds alternating in one run. Every command pays it once; the thesis' experiments
# (issue 19: three processes, 0.1 s in all) pay it three times. It also lists the shared
# libraries each build loads at start.
# Usage: bench/startup_times.sh NEW_SPDFIT [OLD_SPDFIT] [ROUNDS]   (default 5 rounds of 100 runs)
set -euo pipefail
new=${1:?usage: bench/startup_times.sh NEW_SPDFIT [OLD_SPDFIT] [ROUNDS]}
old=${2:-}
rounds=${3:-5}
runs=100
now() { date +%s%N; }
per_run() {  # binary -> milliseconds per run of `binary --version`, over $runs runs
  local s
  s=$(now)
  for _ in $(seq "$runs"); do "$1" --version >/dev/null; done
  awk -v ns="$(($(now) - s))" -v n="$runs" 'BEGIN { printf "%.2f", ns / n / 1e6 }'
}
for label in new old; do
  binary=$([ "$label" = new ] && echo "$new" || echo "$old")
  [ -n "$binary" ] || continue
  echo "$label: $(ldd "$binary" | grep -vc linux-vdso) shared objects loaded at start (ldd)"
done
for round in $(seq "$rounds"); do
  line="round $round: new $(per_run "$new") ms"
  if [ -n "$old" ]; then line="$line, old $(per_run "$old") ms"; fi
  echo "$line"
done
