#!/bin/bash
# Wall time of the experiments issue 19, item 2 sets targets for (the paper's Figure 3 sweep:
# 0.2 s; the thesis' three experiments together: 0.1 s), process start included, for one or two
# builds of the command line, alternating in one run, and whether their outputs are the same
# bytes. Usage: bench/experiment_times.sh NEW_SPDFIT [OLD_SPDFIT] [RUNS]   (default 7 runs)
set -euo pipefail
new=${1:?usage: bench/experiment_times.sh NEW_SPDFIT [OLD_SPDFIT] [RUNS]}
old=${2:-}
runs=${3:-7}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
now() { date +%s%N; }  # nanoseconds, as an integer for the shell's arithmetic
seconds() { awk -v ns="$1" 'BEGIN { printf "%.3f", ns / 1e9 }'; }
time_one() {  # label binary
  local s t1 t2
  s=$(now); "$2" experiment paper-2x2 --sweep --seed 1 >"$out/sweep-$1.json"
  t1=$(seconds $(($(now) - s)))
  s=$(now)
  for V in 0.082 0.86 1.28; do "$2" experiment thesis --noise-var "$V" --trials 2000 --seed 1 >"$out/thesis-$1-$V.txt"; done
  t2=$(seconds $(($(now) - s)))
  echo "$1 $t1 $t2" >>"$out/times"
}
for _ in $(seq "$runs"); do
  time_one new "$new"
  if [ -n "$old" ]; then time_one old "$old"; fi
done
median() { sort -n | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2}'; }
for label in new old; do
  grep -q "^$label " "$out/times" || continue
  sweep=$(awk -v l="$label" '$1==l {print $2}' "$out/times" | median)
  thesis=$(awk -v l="$label" '$1==l {print $3}' "$out/times" | median)
  echo "$label: paper-2x2 --sweep $sweep s, thesis x 3 $thesis s (median of $runs)"
done
if [ -n "$old" ]; then
  same=yes
  cmp -s "$out/sweep-new.json" "$out/sweep-old.json" || same=no
  for V in 0.082 0.86 1.28; do cmp -s "$out/thesis-new-$V.txt" "$out/thesis-old-$V.txt" || same=no; done
  echo "outputs byte for byte the same: $same"
fi
