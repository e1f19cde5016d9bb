#!/usr/bin/env bash
# The main job on its built-in default: builds tumble if needed, then runs the
# demonstration scenario (examples/demo.toml) into demo-out/.
# Extra arguments go to `tumble run` (e.g. --out DIR).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
exec build/tumble run examples/demo.toml --out demo-out --force "$@"
