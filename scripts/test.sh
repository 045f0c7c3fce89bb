#!/usr/bin/env bash
# Set up, build, and run every test (ctest).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
ctest --test-dir build -j "$(nproc)" --output-on-failure
