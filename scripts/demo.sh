#!/usr/bin/env bash
# The main job: set up, build, and show spdfit at work on the shipped example data.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
spdfit=build/apps/spdfit

echo
echo "== A simulated hexapod identification (thesis experiment 2 set-up, m = 12, n = 6):"
echo "   every estimator on the same accelerations A and forces B, against the true M_p"
echo
"$spdfit" compare --truth examples/hexapod/truth.csv examples/hexapod/A.csv examples/hexapod/B.csv
echo
echo "== The paper's 2x2 example with noise in A and B (std 1.5 and 1)"
echo
"$spdfit" compare --truth examples/paper_2x2/truth.csv examples/paper_2x2/A.csv examples/paper_2x2/B.csv
echo
echo "== Covariance repair: an indefinite correlation matrix made positive definite"
echo
"$spdfit" nearest --min-eig 1e-6 examples/covariance/C.csv
