#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The cohesion control of the band study (studies/bands/LOG.md, "Cohesion"):
# the paper's grains with the paper's surface energy W = 0.2 J/m^2 and
# without attraction (W = 0), the rest of the law the same, in a short
# drum with a periodic axis (the paper's 8 cm cross-section, 16 cm long,
# fill 0.3: 1,620 grains), mixed at the start, Froude 0.3, 40 revolutions,
# 2 seeds each. What it measures: the radial core (the small grains'
# share near the bed's centre against its periphery) and the grains'
# axial MSD, per run.
#
#   bash studies/cohesion/run.sh            # the runs not finished, one after the other, into studies/cohesion/out/
#   TUMBLE=/path/to/tumble bash studies/cohesion/run.sh
#   python3 studies/cohesion/compare.py     # the table (studies/bands/LOG.md, "Cohesion")
#
# Each finished run's settings, series and analysis (not its snapshots or
# checkpoints) are copied to results/NAME, which git keeps.
#
# Cost (AMD Zen 4, one thread beside the band study's two runs, 2026-12-02):
# 4 to 7 minutes a run (367 to 610 revolutions per hour; 7.3e5 steps of
# 1,620 grains and 1,260 wall spheres), 20 minutes for the four.
set -euo pipefail
cd "$(dirname "$0")"
tumble=${TUMBLE:-../../build/tumble}
[[ -x $tumble ]] || { echo "cohesion: no tumble at $tumble (bash scripts/build.sh, or set TUMBLE)" >&2; exit 1; }
mkdir -p out
for W in 0.2 0; do
  for seed in 1 2; do
    name=W${W}_seed${seed} dir=out/W${W}_seed${seed}
    [[ -f $dir/summary.json ]] && { echo "cohesion: $name finished"; continue; }
    echo "cohesion: $name (log $dir.log)"
    nice -n 10 "$tumble" drum --length 0.16 --periodic-axis --fill 0.3 --arrangement mixed --froude 0.3 \
      --revolutions 40 --samples 4 --snapshots 1 --seed "$seed" --surface-energy "$W" --threads 1 \
      --no-plot -o "$dir" --force > "$dir.log" 2>&1
  done
done
for dir in out/W*/; do
  name=$(basename "$dir")
  [[ -f $dir/summary.json ]] || continue
  mkdir -p "results/$name"
  cp "$dir"/{drum_run.toml,summary.txt,summary.json,bands.json,bands.csv,drum_series.csv,axial_msd.csv} "results/$name/"
done
