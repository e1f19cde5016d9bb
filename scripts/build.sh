#!/usr/bin/env bash
# Installs what is missing, then configures and builds tumble in build/.
#     bash scripts/build.sh            everything: tumble, the Python module, the tests
#     bash scripts/build.sh tumble     only the targets named (scripts/run.sh builds tumble alone)
# A portable binary by default; TUMBLE_ARCH=native bash scripts/build.sh
# builds for this processor only (CMakeLists.txt, TUMBLE_ARCH).
# The times below were measured from scratch on an AMD EPYC with 2 cores
# busy with other work as well (`cmake --build build --target tumble -j2`:
# 714 s, 528 s of processor time; then the rest: 880 s, 570 s), the idle
# ones from the processor time.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
if [ ! -f build/CMakeCache.txt ]; then
  echo "tumble: configuring the build in build/ (CMake, Release)" >&2
fi
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DTUMBLE_TESTS=ON -DTUMBLE_ARCH="${TUMBLE_ARCH-}" >/dev/null
if [ $# -gt 0 ]; then
  targets=("$@")
  if [ ! -x build/tumble ]; then
    echo "tumble: building $* in build/ (the first time: about 12 minutes on 2 busy cores, 5 on 2 idle ones)" >&2
  fi
  for target in "${targets[@]}"; do
    cmake --build build --target "$target" -j "$(nproc)"
  done
else
  if [ ! -x build/tumble ]; then
    echo "tumble: building tumble, its Python module and its tests in build/ (the first time: about 27 minutes on 2 busy cores, 10 on 2 idle ones)" >&2
  elif [ ! -x build/tests/unit_tests ]; then
    echo "tumble: building the Python module and the tests in build/ (the first time: about 15 minutes on 2 busy cores, 5 on 2 idle ones; tumble itself is built)" >&2
  fi
  cmake --build build -j "$(nproc)"
fi
