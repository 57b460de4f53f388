#!/usr/bin/env bash
# The main job: set up, build, run `spdfit demo` (the thesis' and the paper's experiments on
# built-in data, and what they show), then draw the source documents' figures into ./figures.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh runtime
echo
build/apps/spdfit demo
echo
echo "== Figures (matplotlib; about 20 s):"
PYTHONPATH="$PWD/build/python" /usr/bin/python3 -m spdfit.figures --out figures
echo "The figures are in $PWD/figures/."
