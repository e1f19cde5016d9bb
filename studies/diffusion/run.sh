#!/usr/bin/env bash
# The diffusion study: the paper's results regenerated (studies/diffusion/README.md).
# Resumable across machines: the finished points kept in git
# (kept/SWEEP/POINT.tar.gz) are unpacked where the sweeps look for them, then the
# sweeps run their remaining points (JOBS at a time, default 2; an
# interrupted point starts again, each is a few minutes). Run ./keep.sh
# before committing: it packs the small files of every finished point.
set -euo pipefail
cd "$(dirname "$0")/../.."
# TUMBLE: a tumble binary to use instead of building build/tumble (so the
# tree can be rebuilt while the study runs).
tumble=${TUMBLE:-build/tumble}
[[ -n "${TUMBLE:-}" ]] || bash scripts/build.sh >/dev/null
study=studies/diffusion
for packed in "$study"/kept/*/*.tar.gz; do
  [[ -f "$packed" ]] || continue
  sweep=$(basename "$(dirname "$packed")")
  mkdir -p "$study/out/$sweep"
  tar -xzf "$packed" -C "$study/out/$sweep" --skip-old-files
done
for sweep in caps_two-component caps_self periodic_two-component periodic_self long_two-component long_self; do
  "$tumble" sweep "$study/sweep_$sweep.toml" -j "${JOBS:-2}"
  # The lag analysis needs the long run's snapshots, which keep.sh deletes.
  [[ $sweep != long_self ]] || /usr/bin/python3 "$study/msd_lags.py"
  # The periodic runs' first Fourier mode needs their profiles.csv (not kept in git).
  [[ $sweep != periodic_self ]] || /usr/bin/python3 "$study/periodic_modes.py"
  bash "$study/keep.sh"
done
# The tables (results.md, comparisons.md) and the figures and sweep tables docs/RESULTS.md shows.
/usr/bin/python3 "$study/verdicts.py" >/dev/null
/usr/bin/python3 "$study/comparisons.py" >/dev/null
out=$study/out dest=docs/results/study
mkdir -p "$dest"
cp "$out/caps_self/figures/fig3_self_D_vs_omega.png" "$out/caps_two-component/figures/fig5_two_component_D_vs_omega.png" \
   "$out/caps_two-component/figures/fig6_ke_ratio_vs_omega.png" "$dest/"
cp "$out/caps_self/figures/fig_surface_share_vs_omega.png" "$dest/fig_surface_share_self.png"
cp "$out/caps_two-component/figures/fig_surface_share_vs_omega.png" "$dest/fig_surface_share_two_component.png"
# The long runs' own figures exist only where the runs were made (kept/ holds
# no profiles); elsewhere the committed copies stay.
for mode in self two-component; do
  for figure in fig_z fig_profiles; do
    made="$out/long_$mode/points/${mode}_omega5.000_seed101/figures/$figure.png"
    [[ ! -f "$made" ]] || cp "$made" "$dest/long_${mode/-/_}_$figure.png"
  done
done
for sweep in caps_self caps_two-component periodic_self periodic_two-component long_self long_two-component; do
  cp "$out/$sweep/sweep.csv" "$dest/sweep_$sweep.csv"
done
