#!/usr/bin/env bash
# Sets up, builds and runs every test (unit tests, the reference comparison, CLI tests, the Python
# module's, `pip install .` into a virtual environment from the same build), checks the main job's
# build configuration against that build (scripts/check_main_build.sh), runs the same tests again
# under AddressSanitizer and UndefinedBehaviorSanitizer (build-sanitize/), then each fuzz target
# for half a minute (docs/errors.md says what they check).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh test
ctest --test-dir build --output-on-failure --parallel "$(nproc 2>/dev/null || echo 2)"
scripts/check_main_build.sh
scripts/sanitize.sh
FUZZ_SECONDS=${FUZZ_SECONDS:-30} scripts/fuzz.sh
