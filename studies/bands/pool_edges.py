#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The boundaries' blur pooled over the finished runs of the band study.

For experiment B's question (docs/BAND-ANALYSIS.md, "How fast the start's boundaries
blur"): do small grains enter a band of large grains faster than large
grains enter a band of small ones, D(0.25) > D(0.75)? Each finished run's
bands.json (in out/NAME, else in kept/NAME.tar.gz) gives D per boundary at
u = 0.25, 0.5, 0.75. The two or more boundaries of one run share its
history, so the run, not the boundary, is the independent unit: the mean of
log(D(0.25) / D(0.75)) over a run's boundaries, then over the runs, with a
95 % Student's t interval (a percentile bootstrap over a handful of units is
too narrow). Prints a markdown table, then the pooled ratio for all runs and
for each species at the ends.

    python3 studies/bands/pool_edges.py            # the runs of runs.txt
    python3 studies/bands/pool_edges.py --runs B_k2_small_seed1 B_k2_large_seed1
"""
import argparse
import json
import math
import statistics
import tarfile
from pathlib import Path

STUDY = Path(__file__).resolve().parent

# Student's t, two-sided 95 %, by degrees of freedom (Abramowitz & Stegun
# table 26.10); beyond 30 the normal quantile with its first correction.
T95 = [12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228, 2.201, 2.179, 2.160, 2.145, 2.131,
       2.120, 2.110, 2.101, 2.093, 2.086, 2.080, 2.074, 2.069, 2.064, 2.060, 2.056, 2.052, 2.048, 2.045, 2.042]


def t95(dof):
    return T95[dof - 1] if dof <= len(T95) else 1.960 + 2.4 / dof


def run_file(name, member, finished=True):
    """The bytes of a run's file (member of out/NAME, else of kept/NAME.tar.gz), or None.

    finished: only from a finished run (summary.json beside the file)."""
    out = STUDY / "out" / name
    if (out / member).is_file() and (not finished or (out / "summary.json").is_file()):
        return (out / member).read_bytes()
    kept = STUDY / "kept" / f"{name}.tar.gz"
    if kept.is_file():
        with tarfile.open(kept) as tar:
            names = tar.getnames()
            if member in names and (not finished or "summary.json" in names):
                return tar.extractfile(member).read()
    return None


def finished_bands(name):
    """bands.json of a finished run, or None."""
    text = run_file(name, "bands.json")
    return None if text is None else json.loads(text)


def study_runs():
    lines = (STUDY / "runs.txt").read_text().splitlines()
    return [line.split()[0] for line in lines if line.startswith("B_")]


def pooled(log_ratios):
    """Geometric mean of the ratios and its 95 % interval (t on the logs)."""
    n = len(log_ratios)
    mean = statistics.fmean(log_ratios)
    if n < 3:
        return math.exp(mean), math.nan, math.nan
    half = t95(n - 1) * statistics.stdev(log_ratios) / math.sqrt(n)
    return math.exp(mean), math.exp(mean - half), math.exp(mean + half)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", nargs="+", help="run names (default: every B run of runs.txt, and the kept "
                                                   "equal-width ones)")
    args = parser.parse_args()
    names = args.runs or study_runs() + [p.name[:-7] for p in sorted((STUDY / "kept").glob("B_*_equal_widths.tar.gz"))]

    print("| run | boundary z (m) | D(0.25) | D(0.5) | D(0.75) | D(0.25) / D(0.75) |")
    print("|---|---|---|---|---|---|")
    per_run = {}
    for name in dict.fromkeys(names):
        bands = finished_bands(name)
        if bands is None:
            continue
        logs = []
        for b in bands.get("edges", {}).get("boundaries", []):
            d25, d50, d75 = b["D"]
            if d25 is None or d75 is None or not (d25 > 0 and d75 > 0):
                continue
            logs.append(math.log(d25 / d75))
            print(f"| {name} | {b['z']:+.3f} | {d25:.2e} | {d50:.2e} | {d75:.2e} | {d25 / d75:.2f} |")
        if logs:
            per_run[name] = statistics.fmean(logs)
    print()
    groups = {"all runs": per_run,
              "small grains at the ends": {k: v for k, v in per_run.items() if "_small_" in k},
              "large grains at the ends": {k: v for k, v in per_run.items() if "_large_" in k}}
    for label, runs in groups.items():
        if not runs:
            continue
        ratio, lo, hi = pooled(list(runs.values()))
        interval = f"[{lo:.2f}, {hi:.2f}]" if math.isfinite(lo) else "(no interval: fewer than 3 runs)"
        print(f"{label}: D(0.25) / D(0.75) = {ratio:.2f} {interval}, {len(runs)} runs as units")


if __name__ == "__main__":
    main()
