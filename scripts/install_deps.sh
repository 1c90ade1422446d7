#!/usr/bin/env bash
# Installs the Debian 12 packages pcl_ls3d builds and tests with (only the missing ones).
# Idempotent; needs root (or sudo). The README's dependency table says what each is for.
set -euo pipefail
packages=(build-essential cmake ninja-build pkg-config
          libpcl-dev libeigen3-dev libboost-dev libflann-dev libqhull-dev
          libgtest-dev nlohmann-json3-dev
          libgdal-dev libcairo2-dev fonts-dejavu-core slurm-wlm munge
          clang-format)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "[install_deps] all packages present"
  exit 0
fi
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "[install_deps] installing: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "[install_deps] done"
