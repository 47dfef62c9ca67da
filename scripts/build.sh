#!/usr/bin/env bash
# Configures (once) and builds streak in build/ (Release, Ninja): the library, the `streak`
# command line, the tests and the benchmarks.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ ! -f build/build.ninja ]; then
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
fi
cmake --build build --parallel "$(nproc)"
