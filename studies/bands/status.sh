#!/usr/bin/env bash
# Where the band study stands: one row per run of runs.txt, as a markdown
# table (the README's "Where it stands" is made from it): revolutions done
# (the last sample of drum_series.csv, in out/ or in the kept archive), of
# how many, and the state: finished, ended early on a band-count change
# (--until-band-change), running, stopped (a checkpoint to resume), kept
# (in git, not unpacked here) or not started. A run that finished (or
# ended early) before runs.txt asked for more revolutions is "lengthened":
# run.sh goes on from its end. For a run not finished, its rate: the
# revolutions between the last two progress lines of its log (out/NAME.log,
# a line a minute: run.sh's --progress-every 60) times 60, in revolutions
# per hour, and the hours left at that rate (on this machine, with as many
# runs beside it as then). The cost so far: steps (revolutions x 2 pi /
# (omega dt), from drum_run.toml) times grains, in grain updates.
set -euo pipefail
cd "$(dirname "$0")"
last_revolution() {  # the N of the last line of a drum_series.csv on stdin
  tail -n 1 | cut -d, -f1 | awk '{ printf "%.1f", $1 }'
}
# A file of the run $name: from $dir (out/NAME), or from its kept archive
# if it is not unpacked.
file_of() {
  if [[ -d $dir ]]; then cat "$dir/$1" 2>/dev/null || true
  else tar -xzOf "kept/$name.tar.gz" "$1" 2>/dev/null || true; fi
}
# Revolutions per hour in the last minute of the log on stdin; empty if unknown.
last_rate() {
  grep '^progress: rotation:' | tail -n 2 | sed -n 's/.*revolution \([0-9.]*\) of.*/\1/p' |
    awk 'NR == 1 { a = $1 } NR == 2 && $1 > a { printf "%.0f", ($1 - a) * 60 }'
}
# Grain updates of $1 revolutions of the run whose drum_run.toml is on stdin, e.g. 1.02e+11.
grain_updates() {
  awk -F' = ' -v n="$1" '$1 == "dt" { dt = $2 } $1 == "omega" { w = $2 } $1 == "grains" { g += $2 }
    END { if (dt > 0 && w > 0 && g > 0) printf "%.3g", n * 2 * 3.141592653589793 / (w * dt) * g }'
}
echo "| run | revolutions done | of | state | grain updates so far | rev/h (last minute of its log) | hours to go |"
echo "|---|---|---|---|---|---|---|"
awk '/^[AB]_/ { name = $1; of = "?"; for (i = 2; i < NF; ++i) if ($i == "--revolutions") of = $(i + 1); print name, of }' runs.txt |
while read -r name of; do
  dir=out/$name done="" state="not started"
  if [[ -f $dir/drum_series.csv || (! -d $dir && -f kept/$name.tar.gz) ]]; then
    done=$(file_of drum_series.csv | last_revolution)
    summary=$(file_of summary.json)
    if [[ -n $summary ]]; then
      state=finished
      grep -q '"ended": true' <<<"$summary" && state="ended early: band count changed"
      had=$(file_of drum_run.toml | awk -F' = ' '$1 == "revolutions" {print $2}')
      awk -v a="$of" -v h="$had" 'BEGIN {exit !(a > h)}' && state="$state; lengthened: run.sh goes on"
    elif [[ ! -d $dir ]]; then state=stopped
    elif pgrep -f "bands/$dir( |$)" >/dev/null; then state=running
    else state=stopped; fi
    [[ -d $dir ]] || state="$state (kept, not unpacked)"
  fi
  cost=""
  [[ -n $done ]] && cost=$(file_of drum_run.toml | grain_updates "$done")
  rate="" left=""
  if [[ $state != finished* && $state != ended* && -f $dir.log ]]; then
    rate=$(last_rate <"$dir.log")
    [[ -n $rate ]] && left=$(awk -v o="$of" -v d="${done:-0}" -v r="$rate" 'BEGIN { printf "%.1f", (o - d) / r }')
  fi
  echo "| $name | ${done:--} | $of | $state | ${cost:--} | ${rate:--} | ${left:--} |"
done
