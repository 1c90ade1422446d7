#!/bin/bash
# CTest: the staged strip adjustment (scripts/slurm/strip_adjust.sh with SLURM_SUBMIT=local: the
# job arrays as local processes) gives the single-process verdict on IGN's decimated 1 km
# test_semis_2023 block: UNRELIABLE (corrections the discrepancies do not confirm), exit 3, the
# report written. Skipped (77) without ../shared/data.
#   staged_unreliable.sh TOOL_DIR SOURCE_DIR DATA_DIR
set -uo pipefail
tools="$1"; src="$2"; data="$3"
las="$data/registration/ign_lidarhd/test_semis_2023_0292_6833_LA93_IGN69.las"
[ -f "$las" ] || { echo "shared data not found under $data; skipped"; exit 77; }
tmp="$(mktemp -d /tmp/pcl_ls3d_staged.XXXXXX)"
trap 'rm -rf "$tmp"' EXIT
PCL_LS3D_STRIP_ADJUST="$tools/pcl_ls3d_strip_adjust" SLURM_SUBMIT=local \
  bash "$src/scripts/slurm/strip_adjust.sh" "$tmp/work" "$las" -split psid -json "$tmp/r.json" -q >"$tmp/log" 2>&1
code=$?
[ "$code" -eq 3 ] || { echo "expected exit 3 (UNRELIABLE), got $code"; cat "$tmp/log"; exit 1; }
grep -q '"termination": "UNRELIABLE"' "$tmp/r.json" || { echo "the report does not say UNRELIABLE"; exit 1; }
echo "staged run: exit 3 and an UNRELIABLE report, as the single-process run"
