#!/usr/bin/env bash
# Installs the Debian packages rgraph needs (only those missing), then configures and builds.
# Usage: tools/setup.sh [BUILD_DIR]   (default: build)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}

packages=(
  cmake g++ pkg-config ninja-build
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers vulkan-tools
  glslang-dev glslang-tools spirv-tools libspirv-cross-c-shared-dev
  libglm-dev libtinygltf-dev nlohmann-json3-dev libstb-dev
  libopenexr-dev liblua5.4-dev libpng-dev zlib1g-dev libgtest-dev
  libcpp-httplib-dev  # rgraph serve
  libembree-dev  # rgraph bake: the lightmap baker's ray casts
  libmeshoptimizer-dev  # levels of detail for every mesh (graph/scene/mesh_lod.cpp)
  libdraco-dev  # KHR_draco_mesh_compression (graph/scene/gltf_load_draco.cpp)
  libxxhash-dev  # the content hash of every cache key (graph/core/hash.h)
  clang-format  # tools/format.sh and the format test: the house's C++ layout (.clang-format)
  chromium  # the golden-test report is checked in a real (headless) browser
  python3-distributed  # tools/farm.py: shards on a Dask cluster (a local one in the tests)
  python3-pil python3-numpy  # tests that alter golden PNGs and measure TAA's error
)
tools/install_packages.sh "rgraph setup" "${packages[@]}"

cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRG_WERROR="${RG_WERROR:-OFF}" -DRG_SANITIZE="${RG_SANITIZE:-OFF}" >/dev/null
cmake --build "$build" --parallel "$(nproc)"
