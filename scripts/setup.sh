#!/usr/bin/env bash
# Installs spdfit's Debian packages (as root) and builds it in ./build (Release). Used by demo.sh
# and test.sh; safe to run again.
#
#   scripts/setup.sh runtime   what the main job needs: the packages of scripts/packages-runtime.txt,
#                              and the library, the spdfit command and the Python module
#   scripts/setup.sh [test]    everything: both package lists, and every target (the tests, the
#                              benchmarks, the MEX for Octave)
#
# SPDFIT_BUILD_DIR (default build) is the build tree; SPDFIT_INSTALL=0 skips the installation.
# A build tree that exists keeps its configuration, except that `test` turns the tests, the
# benchmarks, the Octave MEX and the small-problem kernels on (after `runtime`, the library is
# compiled again with them).
set -euo pipefail
cd "$(dirname "$0")/.."

mode=${1:-test}
case "$mode" in
  runtime) lists=(scripts/packages-runtime.txt) ;;
  test) lists=(scripts/packages-runtime.txt scripts/packages-test.txt) ;;
  *) echo "usage: scripts/setup.sh [runtime|test]" >&2; exit 2 ;;
esac

missing=()
for package in $(grep -hv '^#' "${lists[@]}"); do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q 'install ok installed' || missing+=("$package")
done
if [ ${#missing[@]} -gt 0 ]; then
  if [ "$(id -u)" != "0" ]; then
    echo "setup: missing Debian packages (run as root, or install them): ${missing[*]}" >&2
    exit 1
  fi
  echo "setup: installing ${#missing[@]} Debian packages: ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  start=$(date +%s)
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
  echo "setup: packages installed in $(( $(date +%s) - start )) s"
fi

jobs=$(nproc 2>/dev/null || echo 2)
build=${SPDFIT_BUILD_DIR:-build}
if [ "$mode" = runtime ]; then
  if [ ! -f "$build/CMakeCache.txt" ]; then
    # Without the small-problem kernels (CMakeLists.txt): a third less to compile; the experiments'
    # small fits take the general path. With clang (clang-14, on the runtime list): it compiles the
    # library in two thirds of GCC's time, to the same outputs at the same speed
    # (bench/results/build-times-clang-epyc-2026-12-02.md); CXX names another compiler. The test
    # build keeps its tree's compiler (GCC in a new tree, as CI builds it).
    cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DSPDFIT_BUILD_TESTS=OFF -DSPDFIT_BUILD_BENCHMARKS=OFF \
      -DSPDFIT_OCTAVE=OFF -DSPDFIT_SMALL_PROBLEM_KERNELS=OFF -DCMAKE_CXX_COMPILER="${CXX:-clang++-14}" >/dev/null
  fi
else
  # -U: Octave's MEX is built where mkoctfile is found (CMakeLists.txt), also in a tree that
  # `setup.sh runtime` configured without it.
  cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DSPDFIT_BUILD_TESTS=ON -DSPDFIT_BUILD_BENCHMARKS=ON \
    -DSPDFIT_SMALL_PROBLEM_KERNELS=ON -USPDFIT_OCTAVE >/dev/null
fi
start=$(date +%s)
cmake --build "$build" --parallel "$jobs"
echo "setup: built in $(( $(date +%s) - start )) s"

# Install (default prefix /usr/local) so that `spdfit` is on PATH and Debian's
# /usr/bin/python3 can `import spdfit` from any directory.
if [ "${SPDFIT_INSTALL:-1}" = 0 ]; then
  :
elif [ "$(id -u)" = "0" ]; then
  cmake --install "$build" >/dev/null
else
  echo "setup: not root, so not installing; use $build/apps/spdfit and PYTHONPATH=$build/python" >&2
fi
