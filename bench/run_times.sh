#!/usr/bin/env bash
# CPU time (user + system) of a few workloads of the spdfit command, for two or more builds side by
# side (e.g. the same commit compiled by two compilers), rounds interleaved so that the machine's
# load falls on every build alike; prints each workload's median and range per build.
#   bench/run_times.sh BUILD_DIR BUILD_DIR... (ROUNDS=3 by default)
# The streamed fit reads a 10^7 x 6 .npy file that the script writes once into $TMPDIR (480 MB).
set -euo pipefail
cd "$(dirname "$0")/.."
rounds=${ROUNDS:-3}
npy=${TMPDIR:-/tmp}/spdfit_run_times.npy
if [ ! -f "$npy" ]; then
  /usr/bin/python3 -c "
import numpy as np
rng = np.random.default_rng(0); m = 10_000_000
A = rng.standard_normal((m, 3)); X = np.array([[4, 1, 0], [1, 3, 0.5], [0, 0.5, 2.0]])
np.save('$npy', np.hstack([A, A @ X + 0.01 * rng.standard_normal((m, 3))]))"
fi
work=(
  "demo"
  "experiment thesis --trials 100000 --noise-var 1e-4"
  "experiment paper-2x2 --std-a 0.1 --trials 1000000"
  "fit --method spd-tls --bootstrap 10000 examples/hexapod/A.csv examples/hexapod/B.csv"
  "fit --method procrustes --stream --a-cols 1:3 --b-cols 4:6 $npy"
)
times=$(mktemp)
for ((round = 1; round <= rounds; ++round)); do
  for w in "${work[@]}"; do
    for build in "$@"; do
      /usr/bin/time -o "$times.one" -f "%U %S" "$build/apps/spdfit" $w >/dev/null 2>&1
      echo "$w|$build|$(awk '{print $1 + $2}' "$times.one")" >> "$times"
    done
  done
done
/usr/bin/python3 - "$times" "$@" <<'PY'
import collections, statistics, sys
runs = collections.defaultdict(list)
for line in open(sys.argv[1]):
    work, build, seconds = line.rstrip("\n").split("|")
    runs[work, build].append(float(seconds))
builds = sys.argv[2:]
print("| workload | " + " | ".join(builds) + " |")
print("|---|" + "---|" * len(builds))
for work in dict.fromkeys(w for w, _ in runs):
    cells = [f"{statistics.median(runs[work, b]):.2f} ({min(runs[work, b]):.2f}-{max(runs[work, b]):.2f})" for b in builds]
    print(f"| {work} | " + " | ".join(cells) + " |")
PY
rm -f "$times" "$times.one"
