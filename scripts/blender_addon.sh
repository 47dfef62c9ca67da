#!/usr/bin/env bash
# Makes build/streak_blender.zip, the add-on Blender installs (Edit > Preferences > Add-ons >
# Install...): blender/streak_blender with the streak Python module and libstreak in its lib/
# folder (blender/CMakeLists.txt). It runs where the Debian packages scripts/setup.sh installs
# are (libstreak links them) with a Blender whose Python is 3.11, as Debian 12's is.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ ! -f build/build.ninja ]; then
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
fi
cmake --build build --parallel "$(nproc)" --target streak_blender_zip
echo "build/streak_blender.zip"
