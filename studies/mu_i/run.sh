#!/bin/bash
# mu(I) in the flowing layer: for each bead friction and seed, the drum of
# drum.toml turned 2 revolutions (the start-up), then its fields in the
# drum's frame over the next 1.5 s (30 states 0.05 s apart, 0.7 revolutions).
# A finished run is skipped, so the script resumes where it stopped.
#     bash studies/mu_i/run.sh [TUMBLE] [OUT]     (default build/tumble, studies/mu_i/out)
# Cost on one core (AMD Zen 5): README.md.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
tumble=${1:-$here/../../build/tumble}
out=${2:-$here/out}
mkdir -p "$out"
for mu in 0.5 0.1; do
    sed "s/^mu = 0.5 .*/mu = $mu/" "$here/drum.toml" > "$out/drum_mu$mu.toml"
    for seed in 1 2 3; do
        run="$out/mu${mu}_seed$seed"
        [ -f "$run/flowing_layer/drum_frame.json" ] && continue
        rm -rf "$run"
        "$tumble" drum -q --no-plot --config "$out/drum_mu$mu.toml" --seed "$seed" --revolutions 2 --threads 1 -o "$run"
        "$tumble" fields "$run" --frame drum --samples 30 --every 0.05 -q
    done
done
# What the analysis reads, kept in the repository (studies/mu_i/kept, 75 kB
# a run): python3 studies/mu_i/analyse.py then writes the table and figure.
python3 "$here/analyse.py" --keep "$out"
