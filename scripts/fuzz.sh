#!/usr/bin/env bash
# Runs each libFuzzer target (built by sanitize.sh in build-sanitize/) for FUZZ_SECONDS seconds
# (default 60), starting from its seed corpus in fuzz/corpus/<target>/. Fails on a crash, a
# sanitizer finding, a leak, an input that takes over 10 s, or over 2 GB of memory; the input
# that did it is then in build-sanitize/fuzz/artifacts/<target>/ (copy it to
# fuzz/regressions/<target>/ and add a unit test with it). New inputs the fuzzer finds stay in
# build-sanitize/fuzz/corpus/<target>/, out of the repository.
set -euo pipefail
cd "$(dirname "$0")/.."

build=build-sanitize
seconds=${FUZZ_SECONDS:-60}
targets=(delimited npy geometry linkage_pairs mat)
# LeakSanitizer's suppressions: libraries' own leaks (libmatio's on malformed .mat files), never
# spdfit's.
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$PWD/scripts/lsan-suppressions.txt:print_suppressions=0}
summary=""
status=0
for target in "${targets[@]}"; do
  work=$build/fuzz/corpus/$target
  artifacts=$build/fuzz/artifacts/$target
  log=$build/fuzz/$target.log
  mkdir -p "$work" "$artifacts"
  echo "fuzz: $target for ${seconds} s"
  if "$build/fuzz/fuzz_$target" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
      -print_final_stats=1 -artifact_prefix="$artifacts/" "$work" "fuzz/corpus/$target" >"$log" 2>&1; then
    result=ok
  else
    result=FAILED
    status=1
    tail -n 60 "$log" >&2
  fi
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)
  summary+=$(printf '%-14s %12s executions  %s' "$target" "${runs:-?}" "$result")$'\n'
done
echo
echo "fuzz summary (${seconds} s per target):"
printf '%s' "$summary"
exit "$status"
