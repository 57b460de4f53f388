#!/bin/sh
# Runtime dispatch of spdfit's own kernels (src/numerics/block_qr.cpp), checked in the machine code
# of each binary given: only the block QR's AVX2 and AVX-512 variants use the wider registers
# (ymm, zmm), the AVX2 one no zmm, and the baseline variant none, so no Eigen code or other kernel
# was compiled for more than SSE2 and the binary runs on any x86-64. Skipped off x86-64. For the
# plain build only: the sanitizers' instrumentation keeps the compiler from vectorizing the variants.
set -eu
case "$(uname -m)" in x86_64) ;; *) echo "not x86-64: skipped"; exit 0 ;; esac
status=0
for binary in "$@"; do
  listing=$(objdump -d --no-show-raw-insn -C "$binary" |
    awk '/^[0-9a-f]+ <.*>:$/ { name = $0; sub(/^[0-9a-f]+ </, "", name); sub(/>:$/, "", name) }
         /%zmm/ { print "zmm\t" name } /%ymm/ { print "ymm\t" name }' | sort -u)
  wide_functions=$(printf '%s\n' "$listing" | cut -f2 | sort -u | grep -v '^$' || true)
  others=$(printf '%s\n' "$wide_functions" | grep -v -e '::absorb_avx2(' -e '::absorb_avx512(' || true)
  if [ -n "$others" ]; then
    echo "$binary: functions outside the dispatched kernels use ymm/zmm registers:"; echo "$others"; status=1
  fi
  if printf '%s\n' "$listing" | grep -q "^zmm	.*::absorb_avx2("; then
    echo "$binary: the AVX2 variant uses zmm registers"; status=1
  fi
  for expected in absorb_avx2 absorb_avx512; do
    if ! printf '%s\n' "$wide_functions" | grep -q "::${expected}("; then
      echo "$binary: the block QR's $expected variant is missing or uses no ymm/zmm register"; status=1
    fi
  done
  if ! printf '%s\n' "$listing" | grep -q "^zmm	.*::absorb_avx512("; then
    echo "$binary: the AVX-512 variant uses no zmm register"; status=1
  fi
  if ! objdump -d -C "$binary" | grep -q "::absorb_baseline("; then
    echo "$binary: the baseline variant is missing"; status=1
  fi
  [ "$status" = 0 ] && echo "$binary: ymm/zmm only in the block QR's AVX2 and AVX-512 variants"
done
exit "$status"
