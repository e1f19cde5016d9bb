#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# tumble against LIGGGHTS and LAMMPS on the paper's dense periodic cube
# (the seed paper's table 1; docs/BENCHMARKS.md). Run from the repository root:
#
#   bash bench/compare_peers.sh                      # 21^3 = 9261 spheres, 1 and 2 cores, 3 rounds, medians
#   bash bench/compare_peers.sh --size 21 --size 46  # also 46^3 = 97336
#   bash bench/compare_peers.sh --np 1               # one thread / one process only
#   bash bench/compare_peers.sh --peers-only         # the peers alone (no tumble needed)
#   TUMBLE=/path/to/tumble bash bench/compare_peers.sh
#
# Options:
#   --size N        lattice edge (repeatable; default 21)
#   --steps N       timed steps per run (default 2000)
#   --warmup N      untimed steps before them (default 200)
#   --repeats N     rounds; the table shows medians (default 3), and the ratios
#                   paired within each round with a 95 % t interval (2 or more)
#   --np N          also N threads (tumble) and N MPI ranks (peers); 1: single only (default 2)
#   --peers-only    skip tumble
#   --no-liggghts   skip LIGGGHTS
#   --no-lammps     skip LAMMPS
#   --lean          also LIGGGHTS without rolling friction (the only model
#                   combination near ours that this LIGGGHTS build compiles
#                   into an optimised template)
#   --mpi           (kept for old command lines; 2 ranks are the default now)
#   --out DIR       keep logs and results.jsonl there (default build/compare_peers)
#
# Every round runs tumble, then each peer configuration, one after the
# other (never concurrently), so that background load hits all codes alike.
# The peers come from Debian (apt-get install liggghts lammps); run as root,
# the script installs them when they are missing.
set -euo pipefail

invocation_dir=$(pwd)
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)

sizes=()
steps=2000
warmup=200
repeats=3
peers_only=0
np=2
liggghts=1
lammps=1
lean=0
out=""

# shellcheck source=bench/common.sh
source "$repo/bench/common.sh"  # usage, die, need_int

while [[ $# -gt 0 ]]; do
    case "$1" in
        --size) need_int "$1" "${2:-}"; sizes+=("$2"); shift 2 ;;
        --steps) need_int "$1" "${2:-}"; steps=$2; shift 2 ;;
        --warmup) [[ "${2:-}" =~ ^[0-9]+$ ]] || die "--warmup needs an integer"; warmup=$2; shift 2 ;;
        --repeats) need_int "$1" "${2:-}"; repeats=$2; shift 2 ;;
        --np) need_int "$1" "${2:-}"; np=$2; shift 2 ;;
        --peers-only) peers_only=1; shift ;;
        --no-liggghts) liggghts=0; shift ;;
        --no-lammps) lammps=0; shift ;;
        --mpi) shift ;;
        --lean) lean=1; shift ;;
        --out) [[ -n "${2:-}" ]] || die "--out needs a directory"; out=$2; shift 2 ;;
        -h|--help) usage; exit 0 ;;
        *) die "unknown option '$1' (try --help)" ;;
    esac
done
[[ ${#sizes[@]} -gt 0 ]] || sizes=(21)
for n in "${sizes[@]}"; do [[ $n -ge 4 ]] || die "--size must be at least 4"; done

# ------------------------------------------------------------------ tools
command -v python3 >/dev/null || die "python3 is required (JSON parsing and medians)"
liggghts_bin=${LIGGGHTS:-liggghts}
lammps_bin=${LAMMPS:-lmp}
# the peers' own install step (Debian 12 packages; OpenMPI comes with them)
want=()
[[ $liggghts -eq 1 ]] && ! command -v "$liggghts_bin" >/dev/null && want+=(liggghts)
[[ $lammps -eq 1 ]] && ! command -v "$lammps_bin" >/dev/null && want+=(lammps)
[[ $np -gt 1 ]] && ! command -v mpirun >/dev/null && want+=(openmpi-bin)
if [[ ${#want[@]} -gt 0 && $(id -u) -eq 0 ]] && command -v apt-get >/dev/null; then
    echo "compare_peers.sh: installing ${want[*]}" >&2
    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${want[@]}" >/dev/null
fi
[[ $liggghts -eq 0 ]] || command -v "$liggghts_bin" >/dev/null ||
    die "LIGGGHTS not found ('$liggghts_bin'); apt-get install liggghts, set LIGGGHTS=/path, or --no-liggghts"
[[ $lammps -eq 0 ]] || command -v "$lammps_bin" >/dev/null ||
    die "LAMMPS not found ('$lammps_bin'); apt-get install lammps, set LAMMPS=/path, or --no-lammps"
deck="$repo/bench/peers/liggghts_cube.in"
lammps_deck="$repo/bench/peers/lammps_cube.in"
lib="$repo/bench/peers/peerlib.py"
[[ -f "$deck" && -f "$lammps_deck" && -f "$lib" ]] || die "missing $deck, $lammps_deck or $lib"

tumble=""
if [[ $peers_only -eq 0 ]]; then
    tumble=${TUMBLE:-build/tumble}
    # a relative TUMBLE is taken from where the script was started, the
    # default build/tumble from the repository root
    if [[ "$tumble" != /* ]]; then
        if [[ -n "${TUMBLE:-}" && -e "$invocation_dir/$tumble" ]]; then tumble="$invocation_dir/$tumble"
        else tumble="$repo/$tumble"; fi
    fi
    [[ -x "$tumble" ]] || die "tumble binary not found or not executable: $tumble
  build it first (bash scripts/build.sh, or cmake --build build), set TUMBLE=/path/to/tumble,
  or run the LIGGGHTS side alone with --peers-only"
fi

mpirun_cmd=()
if [[ $np -gt 1 && $liggghts$lammps != 00 ]]; then
    command -v mpirun >/dev/null || die "--np $np: mpirun not found (OpenMPI comes with the peers' packages)"
    mpirun_cmd=(mpirun -np "$np")
    [[ $(id -u) -eq 0 ]] && mpirun_cmd+=(--allow-run-as-root)
fi

out=${out:-$repo/build/compare_peers}
[[ "$out" == /* ]] || out="$invocation_dir/$out"
mkdir -p "$out"
results="$out/results.jsonl"
: > "$results"

# ------------------------------------------------------------------ runners
# tumble's threads bound to cores, as mpirun binds the peers' ranks (OpenMPI
# binds each of up to 2 ranks to a core by default): unbound, two threads ran
# the long drum 1 to 3.5 % slower on an Intel Xeon (studies/performance/LOG.md,
# "Threads bound to cores"). OMP_PROC_BIND=false measures them unbound.
bind=(env "OMP_PROC_BIND=${OMP_PROC_BIND:-close}" "OMP_PLACES=${OMP_PLACES:-cores}")
run_tumble() {  # size round threads
    local log="$out/tumble_N$1_r$2_t$3.out" label="$3 threads"
    [[ $3 -eq 1 ]] && label="1 thread"
    if ! python3 "$lib" exec "$log.time" "$log" "$log.err" -- \
            "${bind[@]}" "$tumble" bench --json --size "$1" --steps "$steps" --warmup "$warmup" --threads "$3"; then
        cat "$log.err" >&2
        die "tumble bench failed (size $1, $3 threads), see $log.err"
    fi
    python3 "$lib" tumble "$log" tumble "$label" "$log.time" "$2" >> "$results"
}

run_peer() {  # size round config-name rolling np label code
    local log="$out/$7_N$1_r$2_$3.log" cmd=()
    [[ $5 -gt 1 ]] && cmd+=("${mpirun_cmd[@]}")
    if [[ $7 == lammps ]]; then
        cmd+=("$lammps_bin" -in "$lammps_deck" -log "$log" -screen none -nocite
              -var N "$1" -var steps "$steps" -var warmup "$warmup")
    else
        cmd+=("$liggghts_bin" -in "$deck" -log "$log" -screen none -nocite
              -var N "$1" -var steps "$steps" -var warmup "$warmup" -var rolling "$4")
    fi
    # run inside $out so that nothing LIGGGHTS writes lands in the repository
    if ! (cd "$out" && python3 "$lib" exec "$log.time" "$log.screen" "$log.screen" -- "${cmd[@]}"); then
        tail -5 "$log" >&2 || true
        die "$7 failed (size $1, $3), see $log"
    fi
    python3 "$lib" liggghts "$log" "$7" "$6" "$log.time" "$2" >> "$results"
}

# code|name|rolling|procs|label
configs=()
if [[ $liggghts -eq 1 ]]; then
    configs+=("liggghts|full 1p|cdt|1|hertz+history+sjkr+cdt, 1 proc")
    [[ $lean -eq 1 ]] && configs+=("liggghts|lean 1p|off|1|hertz+history+sjkr, no rolling, 1 proc")
    [[ $np -gt 1 ]] && configs+=("liggghts|full ${np}p|cdt|$np|hertz+history+sjkr+cdt, mpirun -np $np")
fi
if [[ $lammps -eq 1 ]]; then
    configs+=("lammps|granular 1p|-|1|granular hertz/material+viscoelastic+mindlin+marshall, 1 proc")
    [[ $np -gt 1 ]] && configs+=("lammps|granular ${np}p|-|$np|granular hertz/material+viscoelastic+mindlin+marshall, mpirun -np $np")
fi
tumble_threads=(1)
[[ $np -gt 1 ]] && tumble_threads+=("$np")

# ------------------------------------------------------------------ machine
# total and steal jiffies of all CPUs (steal: time the hypervisor gave our
# virtual CPUs to someone else; 0 on bare metal)
cpu_jiffies() { awk '/^cpu /{print $2+$3+$4+$5+$6+$7+$8+$9, $9}' /proc/stat 2>/dev/null || echo "0 0"; }
read -r jiffies0 steal0 <<< "$(cpu_jiffies)"
cpu=$(lscpu 2>/dev/null | sed -n 's/^Model name:[[:space:]]*//p' | head -1)
echo "== tumble vs LIGGGHTS and LAMMPS, dense periodic cube (docs/BENCHMARKS.md)"
echo "machine : ${cpu:-unknown CPU}, $(nproc) logical cores, $(free -g 2>/dev/null | awk '/^Mem:/{print $2" GiB"}') memory, $(uname -sr)"
echo "date    : $(date -u '+%Y-%m-%d %H:%M:%S UTC')   load average at start: $(cut -d' ' -f1-3 /proc/loadavg)"
[[ $liggghts -eq 1 ]] && echo "liggghts: $(dpkg-query -W -f='${Package} ${Version}' liggghts 2>/dev/null || echo "$liggghts_bin")  deck: bench/peers/liggghts_cube.in"
[[ $lammps -eq 1 ]] && echo "lammps  : $(dpkg-query -W -f='${Package} ${Version}' lammps 2>/dev/null || echo "$lammps_bin")  deck: bench/peers/lammps_cube.in"
[[ -n "$tumble" ]] && echo "tumble  : $tumble"
echo "runs    : sizes ${sizes[*]}, $steps timed steps after $warmup warm-up steps, $repeats rounds, logs in $out"
echo

for n in "${sizes[@]}"; do
    for ((r = 1; r <= repeats; r++)); do
        if [[ -n "$tumble" ]]; then
            for t in "${tumble_threads[@]}"; do
                echo "  N=$n^3 round $r/$repeats: tumble $t thread(s)" >&2
                run_tumble "$n" "$r" "$t"
            done
        fi
        for c in "${configs[@]}"; do
            IFS='|' read -r code name rolling procs label <<< "$c"
            echo "  N=$n^3 round $r/$repeats: $code $name" >&2
            run_peer "$n" "$r" "${name// /_}" "$rolling" "$procs" "$label" "$code"
        done
    done
done

echo
python3 "$lib" table "$results"
read -r jiffies1 steal1 <<< "$(cpu_jiffies)"
steal_pct=$(awk -v t=$((jiffies1 - jiffies0)) -v s=$((steal1 - steal0)) 'BEGIN{ p = 0; if (t > 0) p = 100*s/t; printf "%.1f", p }')
echo "load average at end: $(cut -d' ' -f1-3 /proc/loadavg); CPU steal during the runs: ${steal_pct} %"
echo "paper (Kohring 1995, table 1): 24.1-45.2 thousand updates/s (Sparc-10 .. IBM Power2), 9261 spheres"
