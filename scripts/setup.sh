#!/usr/bin/env bash
# Installs spdfit's Debian packages (as root) and builds it in ./build (Release).
# Used by demo.sh and test.sh; safe to run again.
set -euo pipefail
cd "$(dirname "$0")/.."

missing=()
for package in $(grep -v '^#' scripts/debian-packages.txt); do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q 'install ok installed' || missing+=("$package")
done
if [ ${#missing[@]} -gt 0 ]; then
  if [ "$(id -u)" != "0" ]; then
    echo "setup: missing Debian packages (run as root, or install them): ${missing[*]}" >&2
    exit 1
  fi
  echo "setup: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build --parallel "$jobs"

# Install (default prefix /usr/local) so that `spdfit` is on PATH and Debian's
# /usr/bin/python3 can `import spdfit` from any directory.
if [ "$(id -u)" = "0" ]; then
  cmake --install build >/dev/null
else
  echo "setup: not root, so not installing; use build/apps/spdfit and PYTHONPATH=build/python" >&2
fi
