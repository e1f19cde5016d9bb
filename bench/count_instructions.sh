#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Instructions per particle update of `tumble bench`, counted by valgrind's
# callgrind: reproducible to a few parts in 10^4 on a loaded machine, where
# wall-clock times are not (docs/BENCHMARKS.md, "Instruction counts").
# Only the time steps are counted (Simulation::advance), not the set-up.
#
#   bash bench/count_instructions.sh                 # 21^3 cube, 20 steps, 1 thread
#   bash bench/count_instructions.sh --size 46 --steps 5
#   TUMBLE=/path/to/tumble bash bench/count_instructions.sh
#
# Prints the total, the count per update and the functions above 1 %.
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
tumble=${TUMBLE:-$repo/build/tumble}
size=21
steps=20
while [[ $# -gt 0 ]]; do
    case "$1" in
        --size) size=$2; shift 2 ;;
        --steps) steps=$2; shift 2 ;;
        *) echo "count_instructions.sh: unknown option '$1'" >&2; exit 1 ;;
    esac
done
command -v valgrind >/dev/null || { echo "count_instructions.sh: valgrind is required (apt-get install valgrind)" >&2; exit 1; }
[[ -x "$tumble" ]] || { echo "count_instructions.sh: no tumble binary at $tumble (build first)" >&2; exit 1; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
valgrind --tool=callgrind --callgrind-out-file="$out/cg" --toggle-collect='tumble::Simulation::advance*' \
    "$tumble" bench --size "$size" --steps "$steps" --warmup 0 --threads 1 >"$out/log" 2>&1
total=$(callgrind_annotate "$out/cg" | awk '/PROGRAM TOTALS/ { gsub(",", "", $1); print $1 }')
particles=$((size * size * size))
echo "tumble bench --size $size: $particles spheres, $steps steps, $total instructions"
awk -v t="$total" -v n="$particles" -v s="$steps" 'BEGIN { printf "instructions per particle update: %.1f\n", t / (n * s) }'
callgrind_annotate "$out/cg" | awk '/file:function/ { on = 1; next } on && /%\)/ { gsub(/\[.*\]/, ""); print "  " $0 }' |
    awk '{ if (match($0, /\( *[0-9.]+%\)/)) { p = substr($0, RSTART + 1, RLENGTH - 3) + 0; if (p >= 1.0) print } }'
