#!/usr/bin/env bash
# The test suite: builds tumble if needed, then runs every test except the
# long validations (ctest label "long"; run those with: ctest --test-dir build -L long).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
ctest --test-dir build -LE long --output-on-failure -j "$(nproc)"
