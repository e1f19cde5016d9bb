#!/usr/bin/env bash
# Stops the band study's runs: SIGTERM, so each writes a checkpoint and
# exits (code 4); `bash studies/bands/run.sh` continues them.
set -u
# run.sh first: else it starts the next runs of its list when these stop.
pkill -TERM -f "studies/bands/run.sh" || true
pkill -TERM -f "studies/bands/out/" && echo "bands: asked the runs to stop" || echo "bands: no run was running"
for _ in $(seq 60); do pgrep -f "studies/bands/out/" >/dev/null || exit 0; sleep 1; done
echo "bands: runs still running after 60 s" >&2
exit 1
