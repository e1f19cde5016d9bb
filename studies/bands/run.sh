#!/usr/bin/env bash
# The band study (studies/bands/README.md): starts or continues
# the runs of runs.txt, JOBS at a time (default 2), each on THREADS threads
# (default 1), at low priority (nice 10). RUNS="NAME ..." picks runs (default:
# every run of runs.txt, experiment B first: its runs are shorter and
# answer the conjecture; finished runs are skipped). A run kept in git (kept/NAME.tar.gz: its
# newest checkpoint and written series) is unpacked and resumed; a run with
# a checkpoint in out/ is resumed; a finished run (summary.json) is
# skipped, unless runs.txt now asks for more revolutions than it has
# (`tumble resume --revolutions`: it goes on from its end). Stop the runs with stop.sh (each writes a checkpoint), then
# keep.sh packs them for a commit.
set -euo pipefail
cd "$(dirname "$0")/../.."
study=studies/bands
# TUMBLE: a tumble binary to use instead of building build/tumble (so the
# tree can be rebuilt while the study runs).
tumble=${TUMBLE:-build/tumble}
[[ -n "${TUMBLE:-}" ]] || bash scripts/build.sh >/dev/null
common=(--length 0.64 --fill 0.3 --samples 4 --snapshots 1 --checkpoint-every-revolutions 1
        --no-plot --progress-every 60)
runs=${RUNS:-$(awk '/^B_/ {print $1}' "$study/runs.txt"; awk '/^A_/ {print $1}' "$study/runs.txt")}
mkdir -p "$study/out"

one_run() {
  local name=$1 dir=$study/out/$1
  local args
  args=$(awk -v n="$name" '$1 == n {$1 = ""; print}' "$study/runs.txt")
  [[ -n "$args" ]] || { echo "bands: no run $name in $study/runs.txt" >&2; return 2; }
  if [[ ! -d "$dir/checkpoints" && -f "$study/kept/$name.tar.gz" ]]; then
    mkdir -p "$dir" && tar -xzf "$study/kept/$name.tar.gz" -C "$dir"
  fi
  # Lengthened: runs.txt asks for more revolutions than the run was started with.
  local asked had longer=()
  asked=$(sed -n 's/.*--revolutions \([0-9.]*\).*/\1/p' <<<"$args")
  had=$(awk -F' = ' '$1 == "revolutions" {print $2}' "$dir/drum_run.toml" 2>/dev/null || true)
  if [[ -n "$asked" && -n "$had" ]] && awk -v a="$asked" -v h="$had" 'BEGIN {exit !(a > h)}'; then
    longer=(--revolutions "$asked")
  fi
  if [[ -f "$dir/summary.json" && ${#longer[@]} -eq 0 ]]; then echo "bands: $name finished"; return 0; fi
  if compgen -G "$dir/checkpoints/*.tck" >/dev/null; then
    echo "bands: $name resumed ${longer[*]} (log $dir.log)"
    nice -n 10 "$tumble" resume "$dir" "${longer[@]}" --progress-every 60 >>"$dir.log" 2>&1
  else
    echo "bands: $name started (log $dir.log)"
    # shellcheck disable=SC2086
    nice -n 10 "$tumble" drum "${common[@]}" $args --threads "${THREADS:-1}" -o "$dir" --force >"$dir.log" 2>&1
  fi
}

pids=()
for name in $runs; do
  while (( $(jobs -rp | wc -l) >= ${JOBS:-2} )); do sleep 5; done
  one_run "$name" &
  pids+=($!)
done
status=0
for pid in "${pids[@]}"; do wait "$pid" || status=$?; done
exit $status
