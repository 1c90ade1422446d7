#!/usr/bin/env bash
# README command 2: install dependencies, build from scratch, run every test with CTest.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/install_deps.sh"
export BUILD_DIR="${BUILD_DIR:-$root/build}"
bash "$root/scripts/build.sh"
cd "$BUILD_DIR"
ctest --output-on-failure --parallel "$(nproc)" --timeout 900
