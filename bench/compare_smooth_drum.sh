#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# tumble against LAMMPS on the smooth drum: the same drum, the same law as
# near as the two codes allow, from the same settled beds; the dynamic angle
# of repose and the flowing layer's depth measured by one analysis from both
# codes' snapshots, and the speeds of the same runs (docs/BENCHMARKS.md,
# "LAMMPS on the same smooth drum"). Run from the repository root:
#
#   bash bench/compare_smooth_drum.sh                       # 8 seeds, 6 revolutions: about 20 CPU-minutes
#   bash bench/compare_smooth_drum.sh --seeds "1 2 3" --revolutions 3
#   TUMBLE=/path/to/tumble bash bench/compare_smooth_drum.sh
#
# Options:
#   --seeds "S..."    tumble drum's fill seeds, one settled bed each (default "1 2 3 4 5 6 7 8")
#   --revolutions R   revolutions turned after settling (default 6)
#   --from N          measure from revolution N on (default 1.5: the start-up swing over)
#   --snapshots K     snapshots per revolution (default 16)
#   --out DIR         run directories, logs and results.jsonl (default build/compare_smooth_drum)
#
# For each seed: tumble drum (bench/peers/tumble_smooth_drum.toml, --shear
# spring) fills and settles the bed and turns it; its snapshot at the start
# of the rotation becomes a LAMMPS data file (bench/peers/smooth_drum_peer.py
# data), and LAMMPS (bench/peers/lammps_smooth_drum.in) turns that bed for
# as many steps at tumble's step, dumping as often. Then
# bench/peers/smooth_drum_peer.py measures both runs alike and prints the
# means with 95 % t intervals over the seeds and the speed ratio. One core
# each, one after the other. LAMMPS comes from Debian (apt-get install
# lammps); run as root, the script installs it when it is missing.
set -euo pipefail

invocation_dir=$(pwd)
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)

seeds="1 2 3 4 5 6 7 8"
revolutions=6
from=1.5
snapshots=16
out=""

# shellcheck source=bench/common.sh
source "$repo/bench/common.sh"  # usage, die, need_int

while [[ $# -gt 0 ]]; do
    case "$1" in
        --seeds) [[ "${2:-}" =~ ^[0-9]+([[:space:]]+[0-9]+)*$ ]] || die "--seeds needs integers, e.g. \"1 2 3\""
                 seeds=$2; shift 2 ;;
        --revolutions) [[ "${2:-}" =~ ^[0-9]+([.][0-9]+)?$ ]] || die "--revolutions needs a number"
                       revolutions=$2; shift 2 ;;
        --from) [[ "${2:-}" =~ ^[0-9]+([.][0-9]+)?$ ]] || die "--from needs a number"; from=$2; shift 2 ;;
        --snapshots) need_int "$1" "${2:-}"; snapshots=$2; shift 2 ;;
        --out) [[ -n "${2:-}" ]] || die "--out needs a directory"; out=$2; shift 2 ;;
        -h|--help) usage; exit 0 ;;
        *) die "unknown option '$1' (try --help)" ;;
    esac
done

command -v python3 >/dev/null || die "python3 is required"
lammps_bin=${LAMMPS:-lmp}
if ! command -v "$lammps_bin" >/dev/null && [[ $(id -u) -eq 0 ]] && command -v apt-get >/dev/null; then
    echo "compare_smooth_drum.sh: installing lammps" >&2
    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq lammps >/dev/null
fi
command -v "$lammps_bin" >/dev/null || die "LAMMPS not found ('$lammps_bin'); apt-get install lammps or set LAMMPS=/path"

tumble=${TUMBLE:-build/tumble}
if [[ "$tumble" != /* ]]; then
    if [[ -n "${TUMBLE:-}" && -e "$invocation_dir/$tumble" ]]; then tumble="$invocation_dir/$tumble"
    else tumble="$repo/$tumble"; fi
fi
[[ -x "$tumble" ]] || die "tumble binary not found or not executable: $tumble (bash scripts/build.sh, or set TUMBLE)"

config="$repo/bench/peers/tumble_smooth_drum.toml"
deck="$repo/bench/peers/lammps_smooth_drum.in"
lib="$repo/bench/peers/peerlib.py"
peer="$repo/bench/peers/smooth_drum_peer.py"
omega=5.0  # the config's and the deck's

out=${out:-$repo/build/compare_smooth_drum}
[[ "$out" == /* ]] || out="$invocation_dir/$out"
mkdir -p "$out"
results="$out/results.jsonl"
: > "$results"

cpu=$(sed -n 's/^model name[[:space:]]*:[[:space:]]*//p' /proc/cpuinfo | head -1)
echo "== tumble vs LAMMPS, the smooth drum"
echo "machine : ${cpu:-unknown CPU}, $(nproc) logical cores, $(uname -sr)"
echo "date    : $(date -u '+%Y-%m-%d %H:%M:%S UTC')   load average at start: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "lammps  : $(dpkg-query -W -f='${Package} ${Version}' lammps 2>/dev/null || echo "$lammps_bin")  deck: bench/peers/lammps_smooth_drum.in"
echo "tumble  : $tumble ($("$tumble" --version 2>/dev/null | head -1 || true))  config: bench/peers/tumble_smooth_drum.toml --shear spring"
echo "runs    : seeds $seeds; $revolutions revolutions each, $snapshots snapshots per revolution, measured from revolution $from; logs in $out"
echo

for seed in $seeds; do
    t="$out/tumble_s$seed" l="$out/lammps_s$seed"
    echo "  seed $seed: tumble drum ($revolutions revolutions), load $(cut -d' ' -f1 /proc/loadavg)" >&2
    if ! python3 "$lib" exec "$t.time" "$t.out" "$t.err" -- \
            "$tumble" drum --config "$config" --shear spring --seed "$seed" --revolutions "$revolutions" \
            --snapshots "$snapshots" --threads 1 --no-plot --quiet --force -o "$t"; then
        cat "$t.err" >&2
        die "tumble drum failed (seed $seed), see $t.err"
    fi
    read -r steps every dt skin <<< "$(python3 "$peer" plan "$t")"
    python3 "$peer" data "$t/snapshots/000000.csv" "$t/drum.data" >&2
    rm -rf "$l" && mkdir -p "$l"
    echo "  seed $seed: LAMMPS ($steps steps, dumps every $every), load $(cut -d' ' -f1 /proc/loadavg)" >&2
    if ! python3 "$lib" exec "$l.time" "$l.screen" "$l.screen" -- \
            "$lammps_bin" -in "$deck" -log "$l.log" -screen none -nocite -var start "$t/drum.data" \
            -var dt "$dt" -var skin "$skin" -var steps "$steps" -var every "$every" -var dumps "$l"; then
        tail -5 "$l.log" >&2 || true
        die "LAMMPS failed (seed $seed), see $l.log"
    fi
    python3 "$peer" measure tumble "$t" "$seed" "$omega" --from "$from" --timing "$t.time" >> "$results"
    python3 "$peer" measure lammps "$l" "$seed" "$omega" --from "$from" --timing "$l.time" --log "$l.log" >> "$results"
done

python3 "$peer" table "$results"
echo "load average at end: $(cut -d' ' -f1-3 /proc/loadavg); $(date -u '+%Y-%m-%d %H:%M:%S UTC')"
