#!/usr/bin/env bash
# Installs the Debian 12 packages the build needs, only those missing.
# Usage: scripts/install-deps.sh [--peers] [--ci]
#   --peers  the python3 peer libraries the benchmark comparison runs
#   --ci     clang and its runtimes, for the fuzz and ThreadSanitizer builds of .ci/run
set -euo pipefail

packages=(
  build-essential cmake pkg-config git
  zlib1g-dev libbz2-dev libglm-dev libeigen3-dev libmeshoptimizer-dev
  libopenvdb-dev libboost-iostreams-dev
  libhidapi-dev libusb-1.0-0-dev libspnav-dev libopenxr-dev libopenxr-loader1
  libglfw3-dev libgl1-mesa-dri xvfb xauth
  libcli11-dev nlohmann-json3-dev libstb-dev libimgui-dev
  googletest libgtest-dev libgmock-dev libbenchmark-dev
  python3 python3-numpy python3-vtk9 python3-openvdb
)
for arg in "$@"; do
  case "$arg" in
    --peers) packages+=(python3-scipy python3-skimage python3-pywt) ;;
    # The fuzz build links OpenVDB (core's .vdb reader): in the list above, named again here.
    --ci) packages+=(clang libclang-rt-14-dev libopenvdb-dev libboost-iostreams-dev) ;;
    *) echo "install-deps.sh: unknown option $arg" >&2; exit 2 ;;
  esac
done

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
