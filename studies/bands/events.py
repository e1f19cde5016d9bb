#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The band-count changes of the band study's finished B runs, one row each.

For each finished run (bands.json in out/NAME, else in kept/NAME.tar.gz):
the start's bands (S: rich in small grains, L: in large ones; from the
run's --bands and --ends), the revolutions turned, every event of its band
analysis (N, kind, and the start band it took away: its species and width,
from the band edges of drum_run.toml), and the bands at the end. Where a
band vanished, its fading time over the square of its width, in
revolutions per cm^2: a diffusive fading time grows as the width squared
(studies/bands/LOG.md, "Five bands with large ends").

    python3 studies/bands/events.py
    python3 studies/bands/events.py --runs B_k5_small_seed1 B_k5_large_seed1
"""
import argparse
import tomllib
from pathlib import Path

from pool_edges import STUDY, finished_bands, run_file, study_runs


def run_info(name):
    """drum_run.toml of a run, from out/ or its kept archive, or None."""
    text = run_file(name, "drum_run.toml", finished=False)
    return None if text is None else tomllib.loads(text.decode())


def start_pattern(name, bands):
    """S L S ... of a run's start, from its --ends in runs.txt."""
    for line in (STUDY / "runs.txt").read_text().splitlines():
        words = line.split()
        if words and words[0] == name and "--ends" in words:
            first = "S" if words[words.index("--ends") + 1] == "small" else "L"
            other = "L" if first == "S" else "S"
            return [first if k % 2 == 0 else other for k in range(bands)]
    return None


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--runs", nargs="+", help="runs (default: every B run of runs.txt)")
    names = parser.parse_args().runs or study_runs()
    print("| run | start | revolutions turned | events | end | band gone: species, width | N / width^2 (rev/cm^2) |")
    print("|---|---|---|---|---|---|---|")
    for name in names:
        bands = finished_bands(name)
        info = run_info(name)
        if bands is None or info is None:
            continue
        edges = info.get("band_edges", [])
        pattern = start_pattern(name, len(edges) - 1) if len(edges) > 1 else None
        final = bands["final"]
        end = " ".join("S" if b["rich"] else "L" for b in final.get("list", [])) or "none"
        events, gone, scaled = [], [], []
        for e in bands["events"]:
            events.append(f"N = {e['revolutions']:.1f}: {e['kind']} ({e['before']} -> {e['after']})")
            k = next((k for k in range(len(edges) - 1) if edges[k] <= e["z"] < edges[k + 1]), None)
            if k is None or pattern is None:
                continue
            width_cm = 100.0 * (edges[k + 1] - edges[k])
            gone.append(f"{pattern[k]} at z = {e['z']:+.3f} m, {width_cm:.1f} cm")
            scaled.append(f"{e['revolutions'] / width_cm ** 2:.2f}")
        print(f"| {name} | {' '.join(pattern) if pattern else '?'} | {final['revolutions']:.1f} | "
              f"{'; '.join(events) or 'none'} | {end} | {'; '.join(gone) or '-'} | {'; '.join(scaled) or '-'} |")


if __name__ == "__main__":
    main()
