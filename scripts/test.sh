#!/usr/bin/env bash
# Builds streak and runs the whole test suite (GoogleTest through CTest).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh --all
ctest --test-dir build --output-on-failure --parallel "$(nproc)"
