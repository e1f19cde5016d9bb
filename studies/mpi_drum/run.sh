#!/usr/bin/env bash
# The MPI drum study: does sharing the drum among MPI ranks change its observables?
# The paper's default drum (two components, 1000 grains, 5 rad/s, 6
# revolutions after settling; cut along z, its longest axis, 12 cm against
# 9 cm across, so grains cross the cut at the middle) for seeds 1-8
# (SEEDS="..."), each on
# one process (`one_seedS`) and on 2 MPI ranks (`ranks2_seedS`), one
# thread each. The runs of a seed part ways by round-off while the bed
# settles, as runs on two thread counts do, so they are compared
# statistically: `compare.py` (below) writes results.md.
# Resumable: run it again and unfinished runs continue from their
# checkpoints; finished runs are skipped. Cost on the 2-vCPU Xeon of
# docs/BENCHMARKS.md: about 3 CPU-minutes per run (JOBS processes at a time,
# default 2: one run of 2 ranks or two of one process).
set -euo pipefail
cd "$(dirname "$0")/../.."
[[ -n "${TUMBLE:-}" ]] || bash scripts/build.sh >/dev/null
tumble=${TUMBLE:-build/tumble}
out=studies/mpi_drum/out
mkdir -p "$out"
mpirun="mpirun --allow-run-as-root --oversubscribe -np 2"
one() {  # $1 = name (one, ranks2), $2 = seed
  local dir="$out/$1_seed$2" launch=""
  [[ "$1" == ranks2 ]] && launch=$mpirun
  if [[ -f "$dir/summary.json" ]]; then return; fi
  if [[ -d "$dir/checkpoints" ]]; then $launch "$tumble" resume -q "$dir"; return; fi
  $launch "$tumble" drum -q --no-plot --revolutions 6 --seed "$2" --threads 1 --checkpoint-every-revolutions 1 \
    -o "$dir" --force
}
seeds=${SEEDS:-1 2 3 4 5 6 7 8}
export -f one
export out tumble mpirun
printf '%s\n' $seeds | xargs -P "${JOBS:-2}" -I S bash -c 'one one S'  # one process each, two at a time
for seed in $seeds; do one ranks2 "$seed"; done                        # 2 ranks each, one run at a time
/usr/bin/python3 studies/time_step/compare.py --out "$out" --a ranks2 --b one \
  --title "The drum on 2 MPI ranks against one process" \
  --setup "the automatic step; 2 ranks of 1 thread against 1 process of 1 thread" \
  --results studies/mpi_drum/results.md
