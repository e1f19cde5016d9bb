#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Two builds of tumble against each other on the long flowing drum: is a
# change faster, and does it give the same numbers? (studies/performance/LOG.md,
# "Two builds in short alternated rounds"). Run from anywhere:
#
#   bash bench/compare_builds.sh OLD NEW                # 30 rounds, 1 thread
#   bash bench/compare_builds.sh OLD NEW --rounds 20 --threads 2
#   bash bench/compare_builds.sh T T --threads 1,2      # one build: 2 threads against 1
#
# OLD and NEW are tumble executables (e.g. a copy of main's build/tumble
# and the build of a branch).
#
# Options:
#   --rounds N    rounds (default 30); each runs OLD and NEW once, which one
#                 first alternating from round to round
#   --steps N     timed steps per run (default 2000, about 2 s on one core)
#   --threads N   threads per run (default 1); N,M: N for OLD, M for NEW
#   --cpu LIST    run pinned to these processors (taskset -c LIST); default:
#                 a run of 1 thread on the last processor, more unpinned
#   --cache DIR   the settled beds (default: OLD's, beside it); a bed
#                 missing there is made first, about 6 CPU-minutes
#   --out FILE    the runs' JSON lines (default: a temporary file, removed)
#
# Every run starts from the same bed turned one revolution (tumble bench
# --case long-drum --turned 1). A run is short so that a host whose speed
# drifts over minutes slows both runs of a round alike: NEW/OLD of each
# round is a paired sample. The script prints their geometric mean with a
# 95 % t interval (bench/peers/peerlib.py), the median, and whether the two
# builds ended every round with the same kinetic energies, digit for digit.
set -euo pipefail

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# shellcheck source=bench/common.sh
source "$repo/bench/common.sh"  # usage, die, need_int

rounds=30
steps=2000
threads=1,1
cpu=""
cache=""
out=""
builds=()
while [[ $# -gt 0 ]]; do
    case "$1" in
        --rounds) need_int "$1" "${2:-}"; rounds=$2; shift 2 ;;
        --steps) need_int "$1" "${2:-}"; steps=$2; shift 2 ;;
        --threads)
            [[ "${2:-}" =~ ^[1-9][0-9]*(,[1-9][0-9]*)?$ ]] || die "--threads needs N or N,M (positive integers), got '${2:-}'"
            threads=$2; [[ "$threads" == *,* ]] || threads=$threads,$threads; shift 2 ;;
        --cpu) [[ -n "${2:-}" ]] || die "--cpu needs a processor list (taskset -c)"; cpu=$2; shift 2 ;;
        --cache) [[ -n "${2:-}" ]] || die "--cache needs a directory"; cache=$2; shift 2 ;;
        --out) [[ -n "${2:-}" ]] || die "--out needs a file"; out=$2; shift 2 ;;
        -h|--help) usage; exit 0 ;;
        -*) die "unknown option '$1' (see --help)" ;;
        *) builds+=("$1"); shift ;;
    esac
done
[[ ${#builds[@]} -eq 2 ]] || die "needs two tumble executables, OLD and NEW (see --help)"
for b in "${builds[@]}"; do
    [[ -f "$b" && -x "$b" ]] || die "'$b' is not an executable file"
done
old=$(realpath "${builds[0]}")
new=$(realpath "${builds[1]}")
command -v python3 >/dev/null || die "python3 is required"
[[ -n "$cache" ]] || cache=$(dirname "$old")/bench-cache
old_threads=${threads%,*}
new_threads=${threads#*,}
if [[ -n "$cpu" ]]; then command -v taskset >/dev/null || die "--cpu needs taskset (util-linux)"; fi
if [[ -z "$out" ]]; then
    out=$(mktemp)
    trap 'rm -f "$out"' EXIT
else
    : > "$out"
fi

run() {  # run BUILD ROLE ROUND THREADS: one JSON line, with role and round added
    local line pin=() on=$cpu
    [[ -n "$on" || "$4" -gt 1 ]] || on=$(( $(nproc) - 1 ))
    [[ -z "$on" ]] || pin=(taskset -c "$on")
    line=$("${pin[@]}" "$1" bench --case long-drum --turned 1 --cache "$cache" --steps "$steps" --warmup 100 \
        --threads "$4" --json) || die "'$1 bench' failed in round $3"
    python3 -c 'import json, sys; r = json.loads(sys.argv[1]); r["role"] = sys.argv[2]; r["round"] = int(sys.argv[3]); print(json.dumps(r))' \
        "$line" "$2" "$3" >> "$out"
}

echo "compare_builds: $rounds rounds of $steps steps, threads $old_threads (old) and $new_threads (new)${cpu:+, on processor(s) $cpu}" >&2
for r in $(seq "$rounds"); do
    if (( r % 2 )); then
        run "$old" old "$r" "$old_threads"; run "$new" new "$r" "$new_threads"
    else
        run "$new" new "$r" "$new_threads"; run "$old" old "$r" "$old_threads"
    fi
    printf '\rround %d of %d' "$r" "$rounds" >&2
done
echo >&2

PYTHONPATH="$repo/bench/peers" python3 - "$out" "$old" "$new" <<'EOF'
import json, statistics, sys
from peerlib import ratio_interval

runs = [json.loads(line) for line in open(sys.argv[1])]
by_round = {}
for r in runs:
    by_round.setdefault(r["round"], {})[r["role"]] = r
pairs = [(v["old"], v["new"]) for _, v in sorted(by_round.items())]
rate = "grain_updates_per_second"
ratios = [n[rate] / o[rate] for o, n in pairs]
mean, low, high = ratio_interval(ratios)
same = all(o["kinetic_translational"] == n["kinetic_translational"] and
           o["kinetic_rotational"] == n["kinetic_rotational"] and o["contacts"] == n["contacts"] for o, n in pairs)
for role, path, k in (("old", sys.argv[2], 0), ("new", sys.argv[3], 1)):
    print(f"{role}: {path}, {pairs[0][k]['threads']} thread(s)\n"
          f"     median {statistics.median(p[k][rate] for p in pairs) / 1e6:.2f} M grain updates/s")
interval = f" [{low:.4f}, {high:.4f}] (95 % t)" if low is not None else ""
print(f"new / old, round by round: geometric mean {mean:.4f}{interval}, median {statistics.median(ratios):.4f},"
      f" {len(ratios)} rounds")
differ = pairs[0][0]["threads"] != pairs[0][1]["threads"]
print(f"the same kinetic energies and contacts at the end of every round: {'yes' if same else 'no'}"
      + (" (other thread counts add in another order: round-off)" if differ and not same else ""))
print(f"machine: {pairs[0][0]['machine']}; instructions: {pairs[0][0]['isa'].split(' (')[0]} (old),"
      f" {pairs[0][1]['isa'].split(' (')[0]} (new)")
EOF
