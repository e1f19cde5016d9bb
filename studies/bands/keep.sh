#!/usr/bin/env bash
# Packs each run of the band study for git: kept/NAME.tar.gz with its
# settings, written series and band files, and its newest checkpoint (what
# `tumble resume` needs to continue it on another machine), not the
# snapshots. Written anew each time; run it after stop.sh.
set -euo pipefail
cd "$(dirname "$0")"
mkdir -p kept
for dir in out/*/; do
  name=$(basename "$dir")
  files=()
  for f in "$dir"*; do
    [[ -f "$f" ]] && files+=("$(basename "$f")")
  done
  newest=$(ls "$dir/checkpoints/"*.tck 2>/dev/null | sort | tail -n 1 || true)
  [[ -n "$newest" ]] && files+=("checkpoints/$(basename "$newest")")
  tar -czf "kept/$name.tar.gz" -C "$dir" "${files[@]}"
  echo "kept/$name.tar.gz: $(du -h "kept/$name.tar.gz" | cut -f1)"
done
