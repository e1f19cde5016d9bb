#!/usr/bin/env bash
# Where the band study stands: one row per run of runs.txt, as a markdown
# table (the README's "Where it stands" is made from it): revolutions done
# (the last sample of drum_series.csv, in out/ or in the kept archive), of
# how many, and the state: finished, ended early on a band-count change
# (--until-band-change), running, stopped (a checkpoint to resume), kept
# (in git, not unpacked here) or not started.
set -euo pipefail
cd "$(dirname "$0")"
last_revolution() {  # the N of the last line of a drum_series.csv on stdin
  tail -n 1 | cut -d, -f1 | awk '{ printf "%.1f", $1 }'
}
echo "| run | revolutions done | of | state |"
echo "|---|---|---|---|"
awk '/^[AB]_/ { name = $1; of = "?"; for (i = 2; i < NF; ++i) if ($i == "--revolutions") of = $(i + 1); print name, of }' runs.txt |
while read -r name of; do
  dir=out/$name done="" state="not started"
  if [[ -f $dir/drum_series.csv ]]; then
    done=$(last_revolution < "$dir/drum_series.csv")
    if [[ -f $dir/summary.json ]]; then
      state=finished
      grep -q '"ended": true' "$dir/summary.json" && state="ended early: band count changed"
    elif pgrep -f "bands/$dir( |$)" >/dev/null; then state=running
    else state=stopped; fi
  elif [[ -f kept/$name.tar.gz ]]; then
    done=$(tar -xzOf "kept/$name.tar.gz" drum_series.csv | last_revolution)
    state="kept, not unpacked"
  fi
  echo "| $name | ${done:--} | $of | $state |"
done
