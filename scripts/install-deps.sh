#!/usr/bin/env bash
# Installs the Debian packages ParticleLab builds with, if any is missing.
# Needs root (or sudo) only when something must be installed.
set -euo pipefail
packages=(build-essential cmake pkg-config libeigen3-dev libboost-dev libboost-filesystem-dev
          nlohmann-json3-dev libspdlog-dev catch2 libcairo2-dev libmuparser-dev python3 zlib1g-dev
          python3-vtk9   # the test that VTK reads our .vtp frames
          pybind11-dev python3-dev python3-numpy python3-pytest)  # the Python module and its tests
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0
echo "installing: ${missing[*]}"
sudo_cmd=()
[ "$(id -u)" -ne 0 ] && sudo_cmd=(sudo)
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq "${missing[@]}" >/dev/null
