#!/usr/bin/env bash
# README command 1: install dependencies, build, generate two overlapping terrain clouds with a
# known 7-parameter transform, register them with LS3D (-params 7: the pair has a scale; the
# default is rigid) and print the report.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/install_deps.sh"
export BUILD_DIR="${BUILD_DIR:-$root/build}"
bash "$root/scripts/build.sh" -DPCL_LS3D_BUILD_TESTS=OFF >/dev/null
out="${EXAMPLE_DIR:-$root/build/example}"
mkdir -p "$out"
"$BUILD_DIR/pcl_ls3d_synth" pair -seed 7 -o "$out" -overwrite
if [ -x "$BUILD_DIR/pcl_ls3d_register" ]; then
  "$BUILD_DIR/pcl_ls3d_register" "$out/source.pcd" "$out/target.pcd" \
    -params 7 -o "$out/aligned.pcd" -json "$out/report.json" -truth "$out/truth.json" -overwrite
fi
