#!/usr/bin/env bash
# Issue 13: the drum's observables at the automatic step against a quarter of
# it. The paper's default drum (two components, 1000 grains, 5 rad/s), six
# revolutions after settling, seeds 1-8 (SEEDS="..." to choose), each at the step `tumble drum`
# chooses and at a quarter of it. Resumable: run it again and every run
# continues from its newest checkpoint; finished runs are skipped. Then
# `/usr/bin/python3 studies/time_step/compare.py` writes results.md.
# Cost on the 2-vCPU Xeon of docs/BENCHMARKS.md: about 3 CPU-minutes per run
# at the step, 12 at a quarter of it (JOBS runs at a time, default 2).
set -euo pipefail
cd "$(dirname "$0")/../.."
bash scripts/build.sh >/dev/null
out=studies/time_step/out
mkdir -p "$out"
# The automatic step of the default drum, as `tumble contact --drum` reports it.
dt=$(build/tumble contact --drum --json | /usr/bin/python3 -c 'import json,sys; print(repr(json.load(sys.stdin)["dt"]))')
quarter=$(/usr/bin/python3 -c "print(repr($dt / 4))")
echo "automatic step $dt s, a quarter $quarter s" | tee "$out/steps.txt"
one() {  # one run: $1 = name, $2 = step, $3 = seed
  local dir="$out/$1_seed$3"
  if [[ -f "$dir/summary.json" ]]; then return; fi
  if [[ -d "$dir/checkpoints" ]]; then build/tumble resume -q "$dir"; return; fi
  build/tumble drum -q --no-plot --revolutions 6 --seed "$3" --dt "$2" --checkpoint-every-revolutions 1 -o "$dir" --force
}
export -f one
export out
for seed in ${SEEDS:-1 2 3 4 5 6 7 8}; do
  echo "quarter $quarter $seed"
  echo "auto $dt $seed"
done | xargs -P "${JOBS:-2}" -L 1 bash -c 'one "$0" "$1" "$2"'
