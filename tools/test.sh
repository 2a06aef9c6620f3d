#!/usr/bin/env bash
# Installs what is missing, builds, and runs the whole test suite (unit, lua, gpu, golden).
# Extra arguments go to ctest, e.g. tools/test.sh -L unit
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh build
ctest --test-dir build --output-on-failure -j "$(nproc)" "$@"
