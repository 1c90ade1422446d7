#!/usr/bin/env bash
# README command 2: install dependencies, build, run every test with CTest.
# Whatever configured the build folder before (README command 1 turns the tests off), the test
# suite and the tools it runs are switched on here, warnings are errors, the C++ layout is
# checked (scripts/check_format.sh), and CTest fails when it finds no test.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/install_deps.sh"
bash "$root/scripts/check_format.sh"
export BUILD_DIR="${BUILD_DIR:-$root/build}"
bash "$root/scripts/build.sh" -DPCL_LS3D_BUILD_TESTS=ON -DPCL_LS3D_BUILD_TOOLS=ON -DPCL_LS3D_WERROR=ON
cd "$BUILD_DIR"
ctest --output-on-failure --no-tests=error --parallel "$(nproc)" --timeout 900
