#!/usr/bin/env bash
# The positive control for axial banding (PLAN.md): starts or continues
# each seed's run of drum.toml, JOBS at a time (default 2), each on THREADS
# threads (default 1), at low priority (nice 10).
#
#   bash studies/band_control/run.sh                 # the three seeds of the control
#   CASES="control nocap" bash studies/band_control/run.sh   # also frictionless caps
#   nohup bash studies/band_control/run.sh > studies/band_control/out/run.log 2>&1 &
#
# A run with a checkpoint is resumed (tumble resume); a finished run
# (summary.json) is skipped unless REVOLUTIONS now asks for more, when it
# goes on from its end (tumble resume --revolutions). Stop a run with
# kill -INT PID (it writes a checkpoint first); run.sh again resumes it.
#
# Settings (environment):
#   TUMBLE       the tumble binary (default build/tumble; built if absent)
#   SEEDS        seeds (default "1 2 3")
#   CASES        control: the drum as in drum.toml (caps of the wall's friction);
#                nocap: the same with frictionless end caps (cap_friction 0),
#                the negative control; cohesive: the paper's attraction,
#                W = 0.2 J/m^2 on every pair (--surface-energy 0.2), the
#                fair test of Kohring's question (default "control")
#   REVOLUTIONS  revolutions in all (default 100)
#   OUT          where the run directories go (default studies/band_control/out)
set -euo pipefail
cd "$(dirname "$0")/../.."
study=studies/band_control
tumble=${TUMBLE:-build/tumble}
if [[ -z "${TUMBLE:-}" && ! -x "$tumble" ]]; then bash scripts/build.sh >/dev/null; fi
out=${OUT:-$study/out}
revs=${REVOLUTIONS:-100}
common=(--config "$study/drum.toml" --revolutions "$revs" --snapshots 1
        --checkpoint-every-revolutions 1 --no-plot --progress-every 300)
mkdir -p "$out"

one_run() {
  local case=$1 seed=$2 name dir extra=()
  name=${case}_seed$seed
  dir=$out/$name
  case $case in
    control) ;;
    nocap) extra=(--cap-friction 0) ;;
    cohesive) extra=(--surface-energy 0.2) ;;
    *) echo "band_control: unknown case $case (control, nocap, cohesive)" >&2; return 2 ;;
  esac
  local had longer=()
  had=$(awk -F' = ' '$1 == "revolutions" {print $2}' "$dir/drum_run.toml" 2>/dev/null || true)
  if [[ -n "$had" ]] && awk -v a="$revs" -v h="$had" 'BEGIN {exit !(a > h)}'; then
    longer=(--revolutions "$revs")
  fi
  if [[ -f "$dir/summary.json" && ${#longer[@]} -eq 0 ]]; then
    echo "band_control: $name finished"; return 0
  fi
  if compgen -G "$dir/checkpoints/*.tck" >/dev/null; then
    echo "band_control: $name resumed ${longer[*]} (log $dir.log)"
    nice -n 10 "$tumble" resume "$dir" "${longer[@]}" --progress-every 300 >>"$dir.log" 2>&1
  else
    echo "band_control: $name started (log $dir.log)"
    nice -n 10 "$tumble" drum "${common[@]}" "${extra[@]}" --seed "$seed" \
      --threads "${THREADS:-1}" -o "$dir" --force >"$dir.log" 2>&1
  fi
}

pids=()
for seed in ${SEEDS:-1 2 3}; do
  for case in ${CASES:-control}; do
    while (( $(jobs -rp | wc -l) >= ${JOBS:-2} )); do sleep 5; done
    one_run "$case" "$seed" &
    pids+=($!)
  done
done
status=0
for pid in "${pids[@]}"; do wait "$pid" || status=$?; done
exit $status
