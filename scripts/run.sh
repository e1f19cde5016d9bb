#!/usr/bin/env bash
# The main job on its built-in default: builds the tumble program if needed
# (only it: scripts/test.sh builds the tests), then runs the paper's drum
# experiment (tumble drum, docs/DRUM.md) into drum-out/.
# Extra arguments go to `tumble drum` (e.g. --revolutions 20 --out DIR).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh tumble
exec build/tumble drum --force "$@"  # into drum-out/, tumble drum's default, unless --out says otherwise
