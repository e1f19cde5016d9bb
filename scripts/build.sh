#!/usr/bin/env bash
# Installs what is missing, then configures and builds tumble in build/.
# A portable binary by default; TUMBLE_ARCH=native bash scripts/build.sh
# builds for this processor only (CMakeLists.txt, TUMBLE_ARCH).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
if [ ! -x build/tumble ]; then
  echo "tumble: building tumble and its tests in build/ (CMake, Release; a few minutes: about 5 on 2 cores)" >&2
fi
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DTUMBLE_TESTS=ON -DTUMBLE_ARCH="${TUMBLE_ARCH-}" >/dev/null
cmake --build build -j "$(nproc)"
