#!/usr/bin/env bash
# Installs the Debian 12 packages the build needs, only those missing.
# Usage: scripts/install-deps.sh [--peers]   (--peers adds the python3 peer libraries of the benchmarks)
set -euo pipefail

packages=(
  build-essential cmake pkg-config git
  zlib1g-dev libglm-dev libeigen3-dev
  libhidapi-dev libusb-1.0-0-dev libspnav-dev
  libglfw3-dev libgl1-mesa-dri xvfb xauth
  libcli11-dev nlohmann-json3-dev libstb-dev libimgui-dev
  googletest libgtest-dev libgmock-dev libbenchmark-dev
)
if [[ "${1:-}" == "--peers" ]]; then
  packages+=(python3 python3-numpy python3-scipy python3-skimage python3-pywt python3-vtk9 python3-openvdb)
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "installing: ${missing[*]}"
  sudo_cmd=()
  [[ $(id -u) -ne 0 ]] && sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
