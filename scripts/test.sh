#!/usr/bin/env bash
# Set up, check the formatting (scripts/format.sh), build, and run every test (ctest); then the suite again under AddressSanitizer and
# UndefinedBehaviorSanitizer with a minute of each fuzz target (scripts/sanitize.sh). VGEO_QUICK=1
# stops after the first suite.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/format.sh --check
bash scripts/build.sh
ctest --test-dir build -j "$(nproc)" --output-on-failure
[ -n "${VGEO_QUICK:-}" ] || bash scripts/sanitize.sh
