#!/usr/bin/env bash
# The radial core's baseline (docs/BANDS.md, "The radial core's baseline"):
# the core_* runs of runs.txt, one after the other on one thread at low
# priority, through run.sh (finished runs skipped, stopped ones resumed).
# In the order of runs.txt: the null and A seed by seed, then A_dry.
#     nohup studies/bands/core_null.sh > studies/bands/out/core_null.log 2>&1 &
# TUMBLE: the binary (default build/tumble, built by run.sh).
set -euo pipefail
cd "$(dirname "$0")"
RUNS=$(awk '/^core_/ {print $1}' runs.txt) JOBS=1 THREADS=1 exec ./run.sh
