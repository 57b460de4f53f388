#!/usr/bin/env bash
# The compile time of each translation unit of the main job's build (scripts/setup.sh runtime: the
# library, the spdfit command, the Python module), from a new build tree, and the build's wall time.
#
#   bench/build_unit_times.sh [BUILD_DIR] [extra cmake arguments...]
#
# A compiler launcher records each unit's wall time (milliseconds, in bash's arithmetic); ccache is
# off so that every unit compiles.
# Prints the units sorted by time and their sum (one core's seconds), then the wall time of
# `cmake --build` with every core (nproc). bench/results/build-times-*.md has measurements.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build-unit-times}
shift || true
log=$(mktemp)
launcher=$(mktemp)
cat > "$launcher" <<LAUNCHER
#!/usr/bin/env bash
start=\$(date +%s%N)
"\$@"; status=\$?
out=""; previous=""
for argument in "\$@"; do [ "\$previous" = "-o" ] && out=\$argument; previous=\$argument; done
echo "\$(( (\$(date +%s%N) - start) / 1000000 )) \$out" >> "$log"
exit \$status
LAUNCHER
chmod +x "$launcher"
rm -rf "$build"
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DSPDFIT_BUILD_TESTS=OFF -DSPDFIT_BUILD_BENCHMARKS=OFF \
  -DSPDFIT_OCTAVE=OFF -DCMAKE_CXX_COMPILER_LAUNCHER="$launcher" "$@" >/dev/null
start=$(date +%s)
CCACHE_DISABLE=1 cmake --build "$build" --parallel "$(nproc)" >/dev/null
wall=$(( $(date +%s) - start ))
sort -rn "$log" | awk '{printf "%8.1f s  %s\n", $1 / 1000, $2; total += $1 / 1000} END {printf "%8.1f s  in all (%d units)\n", total, NR}'
echo "cmake --build with $(nproc) jobs: $wall s of wall time"
rm -f "$log" "$launcher"
