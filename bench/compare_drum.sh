#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# tumble against LAMMPS on the long flowing drum
# (docs/BENCHMARKS.md, "LAMMPS on the same drum"). Run from the repository root:
#
#   bash bench/compare_drum.sh                  # 1 and 2 cores, 3 rounds, medians
#   bash bench/compare_drum.sh --repeats 1 --steps 2000
#   TUMBLE=/path/to/tumble bash bench/compare_drum.sh
#
# Options:
#   --steps N     timed steps per run (default 10000, tumble bench's)
#   --warmup N    untimed steps turning before them (default 2000)
#   --repeats N   rounds; the table shows medians (default 3), and the ratios
#                 paired within each round with a 95 % t interval (2 or more)
#   --np N        also N threads and N MPI ranks of one thread (tumble) and N MPI
#                 ranks (LAMMPS); 1: single only (default 2)
#   --turned R    start both codes from the settled bed turned R revolutions by
#                 tumble (a bed in steady flow; tumble bench --turned), default 0
#   --law L       tumble's law in the timed steps: drum (the drum's, the paper's),
#                 peer (the deck's: no attraction, shear = spring; tumble bench
#                 --law peer) or both (default: each round runs both)
#   --out DIR     logs, the bed and results.jsonl (default build/compare_drum)
#
# Both codes start from the same settled bed: tumble bench --case long-drum
# --export writes it (making it first if the cache beside the executable
# lacks it, about 6 CPU-minutes), bench/peers/drum_peer.py turns it into a
# LAMMPS data file, and bench/peers/lammps_drum.in runs it with tumble's
# time step. Every round runs each configuration one after the other
# (never concurrently), so that background load hits both codes alike.
# LAMMPS comes from Debian (apt-get install lammps); run as root, the
# script installs it when it is missing.
set -euo pipefail

invocation_dir=$(pwd)
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)

steps=10000
warmup=2000
repeats=3
np=2
turned=0
law=both
out=""

# shellcheck source=bench/common.sh
source "$repo/bench/common.sh"  # usage, die, need_int

while [[ $# -gt 0 ]]; do
    case "$1" in
        --steps) need_int "$1" "${2:-}"; steps=$2; shift 2 ;;
        --warmup) [[ "${2:-}" =~ ^[0-9]+$ ]] || die "--warmup needs an integer"; warmup=$2; shift 2 ;;
        --repeats) need_int "$1" "${2:-}"; repeats=$2; shift 2 ;;
        --np) need_int "$1" "${2:-}"; np=$2; shift 2 ;;
        --turned) [[ "${2:-}" =~ ^[0-9]+([.][0-9]+)?$ ]] || die "--turned needs a number of revolutions >= 0, got '${2:-}'"
                  turned=$2; shift 2 ;;
        --law) [[ "${2:-}" =~ ^(drum|peer|both)$ ]] || die "--law needs drum, peer or both, got '${2:-}'"
               law=$2; shift 2 ;;
        --out) [[ -n "${2:-}" ]] || die "--out needs a directory"; out=$2; shift 2 ;;
        -h|--help) usage; exit 0 ;;
        *) die "unknown option '$1' (try --help)" ;;
    esac
done

# ------------------------------------------------------------------ tools
command -v python3 >/dev/null || die "python3 is required"
lammps_bin=${LAMMPS:-lmp}
want=()
command -v "$lammps_bin" >/dev/null || want+=(lammps)
[[ $np -gt 1 ]] && ! command -v mpirun >/dev/null && want+=(openmpi-bin)
if [[ ${#want[@]} -gt 0 && $(id -u) -eq 0 ]] && command -v apt-get >/dev/null; then
    echo "compare_drum.sh: installing ${want[*]}" >&2
    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${want[@]}" >/dev/null
fi
command -v "$lammps_bin" >/dev/null || die "LAMMPS not found ('$lammps_bin'); apt-get install lammps or set LAMMPS=/path"
deck="$repo/bench/peers/lammps_drum.in"
lib="$repo/bench/peers/peerlib.py"
drum="$repo/bench/peers/drum_peer.py"

tumble=${TUMBLE:-build/tumble}
# a relative TUMBLE is taken from where the script was started, the default
# build/tumble from the repository root
if [[ "$tumble" != /* ]]; then
    if [[ -n "${TUMBLE:-}" && -e "$invocation_dir/$tumble" ]]; then tumble="$invocation_dir/$tumble"
    else tumble="$repo/$tumble"; fi
fi
[[ -x "$tumble" ]] || die "tumble binary not found or not executable: $tumble (bash scripts/build.sh, or set TUMBLE)"

mpirun_cmd=()
if [[ $np -gt 1 ]]; then
    command -v mpirun >/dev/null || die "--np $np: mpirun not found (OpenMPI comes with the lammps package)"
    mpirun_cmd=(mpirun -np "$np")
    [[ $(id -u) -eq 0 ]] && mpirun_cmd+=(--allow-run-as-root)
fi

out=${out:-$repo/build/compare_drum}
[[ "$out" == /* ]] || out="$invocation_dir/$out"
mkdir -p "$out"
results="$out/results.jsonl"
: > "$results"

# ------------------------------------------------------------------ the bed
echo "  the bed (tumble bench --case long-drum --turned $turned --export)" >&2
"$tumble" bench --case long-drum --turned "$turned" --export "$out/bed" > "$out/export.out"
python3 "$drum" data "$out/bed/snapshots/000000.csv" "$out/bed/drum.data" >&2

# ------------------------------------------------------------------ runners
# tumble's threads bound to cores, as mpirun binds the peers' ranks (OpenMPI
# binds each of up to 2 ranks to a core by default): unbound, two threads ran
# the long drum 1 to 3.5 % slower on an Intel Xeon (studies/performance/LOG.md,
# "Threads bound to cores"). OMP_PROC_BIND=false measures them unbound.
bind=(env "OMP_PROC_BIND=${OMP_PROC_BIND:-close}" "OMP_PLACES=${OMP_PLACES:-cores}")
dt="" skin=""  # tumble's step and neighbour skin, from its first run
run_tumble() {  # round threads law [ranks]: N > 1 ranks of one thread each under mpirun
    local ranks=${4:-1} cmd=("${bind[@]}") config="$2 threads"
    local log="$out/tumble_r$1_t$2_n${ranks}_$3.out"
    # mpirun binds its ranks itself (as it does LAMMPS's)
    [[ $ranks -gt 1 ]] && cmd=("${mpirun_cmd[@]}") config="$ranks ranks"
    if ! python3 "$lib" exec "$log.time" "$log" "$log.err" -- \
            "${cmd[@]}" "$tumble" bench --case long-drum --json --steps "$steps" --warmup "$warmup" --threads "$2" \
            --turned "$turned" --law "$3"; then
        cat "$log.err" >&2
        die "tumble bench failed ($config, law $3), see $log.err"
    fi
    python3 "$drum" tumble "$log" "$config" "$log.time" "$1" >> "$results"
    [[ -n "$dt" ]] || dt=$(python3 -c 'import json, sys; print(repr(json.loads(sys.argv[1])["dt"]))' "$(tail -1 "$log")")
    [[ -n "$skin" ]] || skin=$(python3 -c 'import json, sys; print(repr(json.loads(sys.argv[1])["skin"]))' "$(tail -1 "$log")")
}

run_lammps() {  # round procs
    local log="$out/lammps_r$1_p$2.log" cmd=()
    [[ $2 -gt 1 ]] && cmd+=("${mpirun_cmd[@]}")
    cmd+=("$lammps_bin" -in "$deck" -log "$log" -screen none -nocite -var start "$out/bed/drum.data"
          -var dt "$dt" -var skin "$skin" -var steps "$steps" -var warmup "$warmup")
    if ! (cd "$out" && python3 "$lib" exec "$log.time" "$log.screen" "$log.screen" -- "${cmd[@]}"); then
        tail -5 "$log" >&2 || true
        die "LAMMPS failed ($2 procs), see $log"
    fi
    python3 "$drum" lammps "$log" "$2 procs" "$log.time" "$1" >> "$results"
}

procs=(1)
[[ $np -gt 1 ]] && procs+=("$np")
laws=(drum peer)
[[ $law != both ]] && laws=("$law")

# ------------------------------------------------------------------ machine
cpu_jiffies() { awk '/^cpu /{print $2+$3+$4+$5+$6+$7+$8+$9, $9}' /proc/stat 2>/dev/null || echo "0 0"; }
read -r jiffies0 steal0 <<< "$(cpu_jiffies)"
cpu=$(lscpu 2>/dev/null | sed -n 's/^Model name:[[:space:]]*//p' | head -1)
family=$(lscpu 2>/dev/null | sed -n 's/^CPU family:[[:space:]]*//p' | head -1)
model=$(lscpu 2>/dev/null | sed -n 's/^Model:[[:space:]]*//p' | head -1)
echo "== tumble vs LAMMPS, the long flowing drum"
echo "machine : ${cpu:-unknown CPU} (family ${family:-?} model ${model:-?}), $(nproc) logical cores, $(uname -sr)"
echo "date    : $(date -u '+%Y-%m-%d %H:%M:%S UTC')   load average at start: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "lammps  : $(dpkg-query -W -f='${Package} ${Version}' lammps 2>/dev/null || echo "$lammps_bin")  deck: bench/peers/lammps_drum.in"
echo "tumble  : $tumble  law: ${laws[*]} (drum: tumble drum's, the paper's; peer: the deck's, no attraction, shear = spring)"
echo "runs    : $steps timed steps after $warmup turning, from the bed settled and turned $turned revolutions, $repeats rounds, logs in $out"
echo

for ((r = 1; r <= repeats; r++)); do
    for l in "${laws[@]}"; do
        for p in "${procs[@]}"; do
            echo "  round $r/$repeats: tumble $p thread(s), law $l, load $(cut -d' ' -f1 /proc/loadavg)" >&2
            run_tumble "$r" "$p" "$l"
        done
        if [[ $np -gt 1 ]]; then
            echo "  round $r/$repeats: tumble $np MPI ranks of 1 thread, law $l, load $(cut -d' ' -f1 /proc/loadavg)" >&2
            run_tumble "$r" 1 "$l" "$np"
        fi
    done
    for p in "${procs[@]}"; do
        echo "  round $r/$repeats: LAMMPS $p process(es), load $(cut -d' ' -f1 /proc/loadavg)" >&2
        run_lammps "$r" "$p"
    done
done

echo "dt      : $dt s (tumble's automatic step, given to LAMMPS)"
python3 "$drum" table "$results"
read -r jiffies1 steal1 <<< "$(cpu_jiffies)"
steal_pct=$(awk -v t=$((jiffies1 - jiffies0)) -v s=$((steal1 - steal0)) 'BEGIN{ p = 0; if (t > 0) p = 100*s/t; printf "%.1f", p }')
echo "load average at end: $(cut -d' ' -f1-3 /proc/loadavg); CPU steal during the runs: ${steal_pct} %"
