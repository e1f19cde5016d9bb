#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Experiment A's runs side by side, seed against seed, per block of N.

For each A run of runs.txt, its band analysis: bands.json of a finished run
(out/NAME), else that of `tumble analyze --so-far` (out/NAME/so_far; made
first with --analyze). One table per speed, one row per block of N (the
analysis' octaves, 4-8, 8-16, ..., docs/BAND-ANALYSIS.md) and run: the share of small
grains in the 2 cm next to each cap and in the bed's radial core, each as
phi - phi0 with its 95 % block interval (the revolution means as a
correlated series; "-" where the block holds fewer than 3 independent
revolutions), then the bands found. Below each table, per block that two
seeds both reach: whether their intervals overlap.

Two seeds are two samples: their spread is shown, never turned into an
interval (a Student's t with one degree of freedom is 12.7 times the
spread; docs/BAND-ANALYSIS.md says what two seeds can and cannot tell).

    python3 studies/bands/experiment_a.py --analyze   # analyze --so-far each unfinished run, then the tables
    python3 studies/bands/experiment_a.py             # from the bands.json already written
"""
import argparse
import json
import os
import re
import subprocess
from pathlib import Path

STUDY = Path(__file__).resolve().parent
REPO = STUDY.parent.parent


def a_runs():
    """{speed label: [run names]} of runs.txt's A runs, by their name's fr part (A_dry_*: without attraction)."""
    speeds = {}
    for line in (STUDY / "runs.txt").read_text().splitlines():
        words = line.split()
        if words and words[0].startswith("A_"):
            match = re.match(r"A_(dry_)?fr([0-9.]+)_seed(\d+)$", words[0])
            label = f"Froude {match.group(2)}{', no attraction (W = 0)' if match.group(1) else ''}" if match else "?"
            speeds.setdefault(label, []).append(words[0])
    return speeds


def bands_of(name, analyze):
    """(bands.json, 'finished' | 'so far') of a run in out/, or (None, why)."""
    out = STUDY / "out" / name
    if (out / "summary.json").is_file() and (out / "bands.json").is_file():
        return json.loads((out / "bands.json").read_text()), "finished"
    if not (out / "drum_series.csv").is_file():
        return None, "not in out/ (not started, or kept and not unpacked: run.sh unpacks it)"
    if analyze:
        tumble = os.environ.get("TUMBLE", str(REPO / "build" / "tumble"))
        subprocess.run([tumble, "analyze", "--so-far", str(out)], check=True, stdout=subprocess.DEVNULL)
    so_far = out / "so_far" / "bands.json"
    if not so_far.is_file():
        return None, f"no {so_far.relative_to(REPO)} (run with --analyze)"
    return json.loads(so_far.read_text()), "so far"


def value(block, key):
    """'v [lo, hi]' of a block's key, key_lo, key_hi (3 decimals, signed)."""
    v, lo, hi = block.get(key), block.get(f"{key}_lo"), block.get(f"{key}_hi")
    if v is None:
        return "-"
    return f"{v:+.3f} [{lo:+.3f}, {hi:+.3f}]" if lo is not None and hi is not None else f"{v:+.3f} [-]"


def interval(block, key):
    lo, hi = block.get(f"{key}_lo"), block.get(f"{key}_hi")
    return (lo, hi) if lo is not None and hi is not None else None


def blocks_of(bands):
    """{(from, to): {'left', 'right', 'core', 'covered'}} of a run's end layers and radial core."""
    rows = {}
    layers, core = bands["end_layers"], bands["radial_core"]["blocks"]
    for side in ("left", "right"):
        for b in layers[side]:
            rows.setdefault((b["from"], b["to"]), {})[side] = b
    for b in core:
        rows.setdefault((b["from"], b["to"]), {})["core"] = b
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--analyze", action="store_true",
                        help="run `tumble analyze --so-far` on each unfinished run first (TUMBLE=path, default "
                             "build/tumble)")
    parser.add_argument("--from-revolution", type=float, default=4.0,
                        help="leave out the blocks that end before this N (default 4: the start's first revolutions)")
    args = parser.parse_args()
    for speed, names in a_runs().items():
        runs = {}
        print(f"\n### {speed}\n")
        for name in names:
            bands, state = bands_of(name, args.analyze)
            if bands is None:
                print(f"- {name}: {state}")
                continue
            runs[name] = bands
            final = bands["final"]
            onset = bands["onset_revolution"]
            print(f"- {name} ({state}, N = {final['revolutions']:.1f}): bands at most {bands['max_bands']}"
                  f"{'' if onset is None else f', first at N = {onset:.1f}'}, {final['bands']} at the last sample;"
                  f" contrast {bands['initial']['contrast']:.3f} at N = 0, {final['contrast']:.3f} at the last")
        if not runs:
            continue
        print("\n| N | run | left cap layer | right cap layer | radial core |")
        print("|---|---|---|---|---|")
        per_run = {name: blocks_of(b) for name, b in runs.items()}
        spans = sorted({span for rows in per_run.values() for span in rows if span[1] > args.from_revolution})
        for span in spans:
            for name, rows in per_run.items():
                row = rows.get(span)
                if not row or row.get("left", {}).get("revolutions", 0) == 0:
                    continue
                reached = max(b["revolutions"] for b in row.values())  # revolutions of the block sampled
                label = f"{span[0]:g}-{span[1]:g}" + ("" if reached >= span[1] - span[0] else f" ({reached} rev)")
                print(f"| {label} | {name} | {value(row.get('left', {}), 'excess')} | "
                      f"{value(row.get('right', {}), 'excess')} | {value(row.get('core', {}), 'core_excess')} |")
        if len(per_run) < 2:
            continue
        print("\nSeeds against each other (95 % block intervals overlap: 'agree'; apart: the gap):")
        names = list(per_run)
        for span in spans:
            notes = []
            for what, key in (("left", "excess"), ("right", "excess"), ("core", "core_excess")):
                found = [interval(per_run[n].get(span, {}).get(what, {}), key) for n in names]
                if any(f is None for f in found):
                    continue
                lo, hi = max(f[0] for f in found), min(f[1] for f in found)
                notes.append(f"{what} {'agree' if lo <= hi else f'apart by {lo - hi:.3f}'}")
            if notes:
                print(f"- N = {span[0]:g}-{span[1]:g}: {', '.join(notes)}")


if __name__ == "__main__":
    main()
