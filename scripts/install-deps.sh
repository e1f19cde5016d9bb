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
  # apt-get's messages go to a log, shown if it fails; the screen says, a
  # line per phase, what is happening and how long it took.
  log=$(mktemp /tmp/tumble-install-deps.XXXXXX.log)
  if [ "$(id -u)" -ne 0 ]; then SUDO=sudo; else SUDO=; fi
  start=$SECONDS
  fail() {
    tail -n 20 "$log" >&2
    echo "tumble: apt-get failed (above: the end of $log)" >&2
    exit 1
  }
  echo "tumble: ${#missing[@]} Debian packages are missing: ${missing[*]}" >&2
  echo "tumble: apt-get update: reading the package lists (log: $log)" >&2
  $SUDO apt-get update -q >"$log" 2>&1 || fail
  echo "tumble: apt-get install: downloading and setting up the ${#missing[@]} packages and what they need" \
       "(on a fresh Debian 12 several hundred packages: minutes, more on a slow network; log: $log)" >&2
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}" >>"$log" 2>&1 || fail
  echo "tumble: installed the packages in $(( (SECONDS - start) / 60 )) min $(( (SECONDS - start) % 60 )) s" >&2
  rm -f "$log"
fi
