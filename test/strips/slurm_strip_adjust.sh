#!/bin/bash
# CTest: the strip adjustment's job arrays on a single-node Slurm cluster on localhost give the
# single-process result to 1e-9 relative. Starts munged, slurmctld and slurmd (proctrack/linuxproc,
# task/none, a slurm.conf written into a temporary directory) and stops exactly those processes
# by their ids. Needs root (the daemons run as root) and Debian's slurm-wlm + munge.
#   slurm_strip_adjust.sh TOOL_DIR SOURCE_DIR
set -euo pipefail
tools="$1"; src="$2"
for exe in munged slurmctld slurmd sbatch sinfo; do
  command -v "$exe" >/dev/null || { echo "slurm test: $exe not found (scripts/install_deps.sh installs slurm-wlm and munge)" >&2; exit 1; }
done
tmp="$(mktemp -d /tmp/pcl_ls3d_slurm.XXXXXX)"
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done
  for p in "${pids[@]}"; do for _ in $(seq 50); do kill -0 "$p" 2>/dev/null || break; sleep 0.1; done; kill -9 "$p" 2>/dev/null || true; done
  rm -rf "$tmp"
}
trap cleanup EXIT
chmod 700 "$tmp"
mkdir -p "$tmp/munge" "$tmp/state" "$tmp/spool" "$tmp/work"
chmod 700 "$tmp/munge"
# A fresh munge key, readable by root only.
head -c 1024 /dev/urandom > "$tmp/munge/munge.key"
chmod 400 "$tmp/munge/munge.key"
munged -f -F --key-file="$tmp/munge/munge.key" --socket="$tmp/munge/munge.socket" \
  --pid-file="$tmp/munge/munged.pid" --log-file="$tmp/munge/munged.log" --seed-file="$tmp/munge/seed" >"$tmp/munged.out" 2>&1 &
pids+=($!)
free_port() { python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'; }
host="$(hostname -s)"
cat > "$tmp/slurm.conf" <<CONF
ClusterName=ls3dtest
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$(free_port)
SlurmdPort=$(free_port)
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$tmp/munge/munge.socket
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool
SlurmctldPidFile=$tmp/slurmctld.pid
SlurmdPidFile=$tmp/slurmd.pid
SlurmctldLogFile=$tmp/slurmctld.log
SlurmdLogFile=$tmp/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
ReturnToService=2
SlurmctldTimeout=30
SlurmdTimeout=30
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) RealMemory=$(awk '/MemTotal/ {print int($2 / 1024) - 512}' /proc/meminfo) State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$tmp/slurm.conf"
for _ in $(seq 50); do [ -S "$tmp/munge/munge.socket" ] && break; sleep 0.1; done
slurmctld -D -f "$SLURM_CONF" -i >"$tmp/slurmctld.out" 2>&1 &
pids+=($!)
slurmd -D -f "$SLURM_CONF" >"$tmp/slurmd.out" 2>&1 &
pids+=($!)
up=0
for _ in $(seq 120); do
  if sinfo -h -o '%T' 2>/dev/null | grep -Eq 'idle|mixed'; then up=1; break; fi
  sleep 0.5
done
[ "$up" = 1 ] || { echo "slurm test: the node did not come up"; tail -5 "$tmp/slurmctld.log" "$tmp/slurmd.log"; exit 1; }

# A generated 3-strip block (LAS), adjusted in one process and on the cluster.
"$tools/pcl_ls3d_synth" strips -o "$tmp/in" -format las -strips 3 -length 240 -swath 120 -density 2 -seed 3 \
  -shift_sigma 0.3 -angle_sigma 5e-4 -scale_sigma 0 >/dev/null
"$tools/pcl_ls3d_strip_adjust" "$tmp/in/strips.las" -split psid -o "$tmp/single" -json "$tmp/single.json" -q
PCL_LS3D_STRIP_ADJUST="$tools/pcl_ls3d_strip_adjust" bash "$src/scripts/slurm/strip_adjust.sh" "$tmp/work" \
  "$tmp/in/strips.las" -split psid -o "$tmp/cluster" -json "$tmp/cluster.json" -q
python3 - "$tmp/single.json" "$tmp/cluster.json" <<'PY'
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
assert a["converged"] and b["converged"], "not converged"
worst = 0.0
for sa, sb in zip(a["strips"], b["strips"]):
    for x, y in zip(sa["parameters"], sb["parameters"]):
        worst = max(worst, abs(x - y) / max(abs(x), 1e-3))
for k in ("sigma0", "iterations", "observations"):
    assert abs(a[k] - b[k]) <= 1e-9 * max(1.0, abs(a[k])), (k, a[k], b[k])
print(f"slurm run vs single process: worst relative parameter difference {worst:.3g}, sigma0 {b['sigma0']:.6f}, {b['iterations']} iterations")
assert worst <= 1e-9, worst
PY
for f in "$tmp"/single/*.las; do cmp "$f" "$tmp/cluster/$(basename "$f")"; done
echo "slurm test: PASS"
