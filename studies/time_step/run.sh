#!/usr/bin/env bash
# The drum's observables at several time steps. The paper's default drum
# (two components, 1000 grains), REVOLUTIONS revolutions after settling
# (default 6), for each speed of OMEGAS (rad/s, default 5), each step of
# STEPS (default "auto quarter": the step `tumble drum` chooses and a quarter
# of it; a number is a step in s) and each seed of SEEDS (default 1 to 8).
# Runs are named STEP_seedS at 5 rad/s and omegaW_STEP_seedS at other
# speeds (a number's step named dtNUMBER). Resumable: run it again and every
# run continues from its newest checkpoint; finished runs are skipped. Then
# `/usr/bin/python3 studies/time_step/compare.py` compares two sets.
# TUMBLE: the program (default build/tumble, built first); JOBS runs at a
# time (default 2).
# Cost on the 2-vCPU Xeon of docs/BENCHMARKS.md: about 3 CPU-minutes per run
# at 5 rad/s and the automatic step, 12 at a quarter of it; a run's cost
# grows as 1/omega and 1/dt. The study of the two speeds
#   OMEGAS="3 12" STEPS="auto 2.614e-5 quarter" SEEDS="1 2 3 4 5 6" bash studies/time_step/run.sh
# takes about 65 CPU-minutes on the AMD Zen 5 (36 runs).
set -euo pipefail
cd "$(dirname "$0")/../.."
if [[ -z "${TUMBLE:-}" ]]; then
  bash scripts/build.sh >/dev/null
  TUMBLE=build/tumble
fi
out=studies/time_step/out
mkdir -p "$out"
# The automatic step of the default drum, as `tumble contact --drum` reports it.
dt=$("$TUMBLE" contact --drum --json | /usr/bin/python3 -c 'import json,sys; print(repr(json.load(sys.stdin)["dt"]))')
quarter=$(/usr/bin/python3 -c "print(repr($dt / 4))")
echo "automatic step $dt s, a quarter $quarter s" | tee "$out/steps.txt"
one() {  # one run: $1 = name, $2 = step, $3 = seed, $4 = omega
  local dir="$out/$1_seed$3"
  if [[ -f "$dir/summary.json" ]]; then return; fi
  if [[ -d "$dir/checkpoints" ]]; then "$TUMBLE" resume -q "$dir"; return; fi
  "$TUMBLE" drum -q --no-plot --omega "$4" --revolutions "${REVOLUTIONS:-6}" --seed "$3" --dt "$2" \
    --checkpoint-every-revolutions 1 -o "$dir" --force
}
export -f one
export out TUMBLE REVOLUTIONS
for seed in ${SEEDS:-1 2 3 4 5 6 7 8}; do
  for omega in ${OMEGAS:-5}; do
    prefix=$([[ "$omega" == 5 ]] && echo "" || echo "omega${omega}_")
    for step in ${STEPS:-quarter auto}; do
      case "$step" in
        auto) echo "${prefix}auto $dt $seed $omega" ;;
        quarter) echo "${prefix}quarter $quarter $seed $omega" ;;
        *) echo "${prefix}dt$step $step $seed $omega" ;;
      esac
    done
  done
done | xargs -P "${JOBS:-2}" -L 1 bash -c 'one "$0" "$1" "$2" "$3"'
