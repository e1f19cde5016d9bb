#!/usr/bin/env bash
# Packs the small files of every finished point of the diffusion study
# (summary, run settings, the <z> series, the MSD and depth tables; not the
# snapshots, checkpoints or profiles) into kept/SWEEP.tar.gz, for git, and
# frees the disk their snapshots take (the analysis is done: summary.json).
set -euo pipefail
cd "$(dirname "$0")"
mkdir -p kept
for dir in out/*/; do
  sweep=$(basename "$dir")
  files=()
  for point in "$dir"points/*/; do
    [[ -f "$point/summary.json" ]] || continue
    rm -rf "$point/snapshots" "$point/checkpoints"
    name=points/$(basename "$point")
    for f in summary.json summary.txt drum_run.toml drum_series.csv axial_msd.csv depth_mobility.csv \
             depth_mobility_long.csv flow_profile.csv profile_comparison.csv; do
      [[ -f "$point/$f" ]] && files+=("$name/$f")
    done
  done
  if [[ ${#files[@]} -gt 0 ]]; then
    tar -czf "kept/$sweep.tar.gz" -C "$dir" "${files[@]}"
  fi
done
ls -la kept
