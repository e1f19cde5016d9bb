#!/usr/bin/env bash
# Packs the small files of every finished point of the diffusion study
# (summary, run settings, the <z> series, the MSD and depth tables; not the
# snapshots, checkpoints or profiles) into kept/SWEEP/POINT.tar.gz, one file
# per point written once (so git keeps each only once), and frees the disk
# their snapshots take (the analysis is done: summary.json).
set -euo pipefail
cd "$(dirname "$0")"
for dir in out/*/; do
  sweep=$(basename "$dir")
  for point in "$dir"points/*/; do
    [[ -f "$point/summary.json" ]] || continue
    rm -rf "$point/snapshots" "$point/checkpoints"
    name=$(basename "$point")
    packed="kept/$sweep/$name.tar.gz"
    [[ -f "$packed" ]] && continue
    files=()
    for f in summary.json summary.txt drum_run.toml drum_series.csv axial_msd.csv depth_mobility.csv \
             depth_mobility_long.csv flow_profile.csv profile_comparison.csv; do
      [[ -f "$point/$f" ]] && files+=("points/$name/$f")
    done
    mkdir -p "kept/$sweep"
    tar -czf "$packed" -C "$dir" "${files[@]}"
  done
done
for sweep in kept/*/; do echo "$(basename "$sweep"): $(ls "$sweep" | wc -l) points kept"; done
