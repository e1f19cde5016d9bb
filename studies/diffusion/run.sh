#!/usr/bin/env bash
# Issue 14, item 7: the diffusion study again (studies/diffusion/README.md).
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
  bash "$study/keep.sh"
done
