#!/usr/bin/env bash
# Regenerates the figures and tables of docs/RESULTS.md: the sweep of
# examples/sweep_results.toml (4 speeds x 2 modes x 2 seeds, 12 revolutions
# each), the paper's figs. 2 and 4 from its slowest and fastest speed, the
# per-run figures of one point per mode, all copied into docs/results/full/.
# Interrupted? Run it again: finished sweep points are kept.
#     bash scripts/results.sh [SWEEP_DIR]      (default sweep-results)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
out=${1:-sweep-results}
dest=docs/results/full
start=$(date +%s)
build/tumble sweep examples/sweep_results.toml -o "$out"
points="$out/points"
build/tumble plot --compare "$points/self_omega3.000_seed1" "$points/self_omega12.000_seed1" --out "$out/fig2"
build/tumble plot --compare "$points/two-component_omega3.000_seed1" "$points/two-component_omega12.000_seed1" \
  --out "$out/fig4"
mkdir -p "$dest"
cp "$out/fig2/fig_z_compare.png" "$dest/fig2_self_z_vs_N.png"
cp "$out/fig4/fig_z_compare.png" "$dest/fig4_two_component_z_vs_N.png"
cp "$out"/figures/*.png "$out/sweep.csv" "$out/sweep_summary.csv" "$dest/"
for mode in self two-component; do
  for figure in fig1_setup fig_profiles fig_depth fig_energy; do
    [ -f "$points/${mode}_omega5.000_seed1/figures/$figure.png" ] &&
      cp "$points/${mode}_omega5.000_seed1/figures/$figure.png" "$dest/${mode}_omega5_${figure}.png"
  done
  for point in "$points/${mode}"_omega*_seed*; do
    cp "$point/depth_mobility.csv" "$dest/depth_mobility_$(basename "$point").csv"
  done
done
echo "results: figures and tables in $dest ($(( $(date +%s) - start )) s)"
