#!/usr/bin/env bash
# The main job: set up, build, and run `spdfit demo`: the thesis' and the paper's experiments on
# built-in data, and what they show (a few seconds).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
echo
build/apps/spdfit demo
