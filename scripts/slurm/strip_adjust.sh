#!/bin/bash
# Strip block adjustment on a Slurm cluster: plan on the submit host, one job array of match
# tasks per iteration (one task per overlap), solve between the arrays, one array of apply tasks
# for the corrected strips. Gives the same numbers as the single-process run.
#   scripts/slurm/strip_adjust.sh WORK_DIR INPUT... [-split psid] [-o DIR] [-json R] [-maps DIR] ...
# Options after the inputs are those of pcl_ls3d_strip_adjust. With SLURM_SUBMIT=local the
# arrays run as local processes instead (no cluster; for a quick check).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
tool="${PCL_LS3D_STRIP_ADJUST:-pcl_ls3d_strip_adjust}"
export PCL_LS3D_STRIP_ADJUST="$tool"
work="$1"; shift
mkdir -p "$work"
"$tool" plan "$@" -work "$work"
read -r jobs units < <("$tool" counts -work "$work")

run_array() {  # stage count
  local stage="$1" count="$2"
  [ "$count" -gt 0 ] || return 0
  if [ "${SLURM_SUBMIT:-sbatch}" = local ]; then
    for ((k = 0; k < count; ++k)); do SLURM_ARRAY_TASK_ID=$k bash "$here/strip_adjust.sbatch" "$stage" "$work"; done
  else
    sbatch --wait --chdir="$work" --array=0-$((count - 1)) "$here/strip_adjust.sbatch" "$stage" "$work" >/dev/null
  fi
}

# The last solve's exit status is the run's (3: UNRELIABLE, 2: no solution), after the outputs
# are written, as in a single-process run; an error before the end stops the run.
phase=iterate
final=0
while [ "$phase" != done ]; do
  run_array match "$jobs"
  code=0
  phase="$("$tool" solve -work "$work")" || code=$?
  if [ "$code" -ne 0 ] && [ "$phase" != done ]; then exit "$code"; fi
  final=$code
  echo "solve: $phase"
done
run_array apply "$units"
exit "$final"
