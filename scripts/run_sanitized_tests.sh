#!/usr/bin/env bash
# The whole test suite (the consumer test included) under AddressSanitizer + UndefinedBehavior-
# Sanitizer, in its own build folder (default build-sanitize/). Not part of the default CI run:
# it takes several times longer. Any sanitizer report fails the test that triggered it.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/install_deps.sh"
export BUILD_DIR="${SANITIZE_BUILD_DIR:-$root/build-sanitize}"
bash "$root/scripts/build.sh" -DPCL_LS3D_SANITIZE=ON -DPCL_LS3D_BUILD_TESTS=ON \
  -DPCL_LS3D_BUILD_TOOLS=ON -DPCL_LS3D_BUILD_BENCHMARKS=OFF
# Leaks inside system libraries we do not build (PCL/VTK/OpenMP runtime at exit) are suppressed
# by name in scripts/lsan.supp; every other leak, and every ASan/UBSan report, fails the test.
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=0:halt_on_error=1:strict_string_checks=1:detect_stack_use_after_return=0:check_initialization_order=1"
export LSAN_OPTIONS="suppressions=$root/scripts/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
cd "$BUILD_DIR"
ctest --output-on-failure --no-tests=error --parallel "$(nproc)" --timeout 2400
