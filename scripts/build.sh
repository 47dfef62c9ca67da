#!/usr/bin/env bash
# Configures (once) and builds streak in build/ (Release, Ninja). By default only what rendering
# needs, the library and the `streak` command line, so that the README's first command reaches
# its image soon. `--all` builds everything else too: the tests, the sanitized suite, the
# fuzzers, the benchmarks, the examples and the Python module (scripts/test.sh does).
set -euo pipefail
cd "$(dirname "$0")/.."
targets=(--target streak)
case "${1:-}" in
  "") ;;
  --all) targets=() ;;
  *) echo "usage: scripts/build.sh [--all]" >&2; exit 2 ;;
esac
if [ ! -f build/build.ninja ]; then
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
fi
cmake --build build --parallel "$(nproc)" "${targets[@]}"
