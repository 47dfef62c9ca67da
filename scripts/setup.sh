#!/usr/bin/env bash
# Installs every system dependency of streak from Debian packages.
# Idempotent and non-interactive: safe to run on a fresh Debian 12 machine or again.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libglm-dev libtbb-dev libstb-dev libopenexr-dev libcli11-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libepoxy-dev libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri
  libtinygltf-dev libtinyobjloader-dev libembree-dev nlohmann-json3-dev
  clang libclang-rt-14-dev
  python3-matplotlib python3-dev python3-pybind11 python3-numpy python3-openimageio
  parallel
  blender
)
# OpenImageIO's Python reads the deep EXRs back in the tests, as a compositor would.
# Blender (Debian's, Python 3.11 as the streak module's) runs the add-on's tests
# (tests/blender) and the Cycles ground truth of bench/cycles_reference.py.

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -gt 0 ]; then
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
