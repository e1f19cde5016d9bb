#!/usr/bin/env bash
# The shear-model study: the three shear models at 5 rad/s, both modes, 3 seeds
# (self-diffusion 10 revolutions, two-component 5). Resumable: run it again
# and every sweep continues from its finished points and checkpoints. Then
# `python3 studies/shear_models/table.py` prints the comparison table of
# docs/RESULTS.md ("How much the reading of the friction limit matters").
set -euo pipefail
cd "$(dirname "$0")/../.."
bash scripts/build.sh >/dev/null
for mode in self two-component; do
  for model in paper coulomb spring; do
    build/tumble sweep "studies/shear_models/sweep_${model}_${mode}.toml" -j "${JOBS:-2}"
  done
done
