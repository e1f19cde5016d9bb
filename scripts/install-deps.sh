#!/usr/bin/env bash
# Installs the Debian 12 packages tumble needs, if any is missing (as root).
#     bash scripts/install-deps.sh [EXTRA_PACKAGE ...]   (extras: e.g. scripts/fuzz.sh's clang)
set -euo pipefail
packages=(g++ cmake make pkg-config libtomlplusplus-dev libcli11-dev libfmt-dev libgtest-dev libgmock-dev python3 python3-vtk9 python3-matplotlib python3-numpy openmpi-bin libopenmpi-dev libpng-dev ffmpeg
          pybind11-dev python3-pybind11 python3-dev python3-pytest python3-pandas
          nlohmann-json3-dev zlib1g-dev mkdocs "$@")
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  # apt-get's messages go to a log, shown if it fails; the screen says what is happening.
  log=$(mktemp /tmp/tumble-install-deps.XXXXXX.log)
  echo "tumble: installing ${#missing[@]} Debian packages with apt-get (a few minutes; log: $log): ${missing[*]}" >&2
  if [ "$(id -u)" -ne 0 ]; then SUDO=sudo; else SUDO=; fi
  if ! { $SUDO apt-get update -q && DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q \
           --no-install-recommends "${missing[@]}"; } >"$log" 2>&1; then
    tail -n 20 "$log" >&2
    echo "tumble: apt-get failed (above: the end of $log)" >&2
    exit 1
  fi
  echo "tumble: installed the packages" >&2
  rm -f "$log"
fi
