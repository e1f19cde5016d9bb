#!/usr/bin/env bash
# Installs the Debian 12 packages tumble needs, if any is missing (as root).
#     bash scripts/install-deps.sh [EXTRA_PACKAGE ...]   (extras: e.g. scripts/fuzz.sh's clang)
set -euo pipefail
packages=(g++ cmake make pkg-config libtomlplusplus-dev libcli11-dev libfmt-dev libgtest-dev libgmock-dev python3 python3-vtk9 python3-matplotlib python3-numpy openmpi-bin libpng-dev ffmpeg
          pybind11-dev python3-pybind11 python3-dev python3-pytest python3-pandas "$@")
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "tumble: installing ${missing[*]}" >&2
  if [ "$(id -u)" -ne 0 ]; then SUDO=sudo; else SUDO=; fi
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
