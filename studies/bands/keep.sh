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
  # The newest moment: every file of its number (NNNNNN.tck of one process,
  # NNNNNN.rR.tck of each rank of a run that went on under mpirun).
  newest=$(ls "$dir/checkpoints/" 2>/dev/null | grep -E '^[0-9]{6}\.(r[0-9]+\.)?tck$' | sort | tail -n 1 | cut -c1-6 || true)
  if [[ -n "$newest" ]]; then
    for f in "$dir/checkpoints/$newest".*tck; do files+=("checkpoints/$(basename "$f")"); done
  fi
  tar -czf "kept/$name.tar.gz" -C "$dir" "${files[@]}"
  echo "kept/$name.tar.gz: $(du -h "kept/$name.tar.gz" | cut -f1)"
done
