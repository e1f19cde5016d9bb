#!/usr/bin/env python3
"""The time-step study: the drum's observables at the automatic step
against a quarter of it (studies/time_step/run.sh). Per run: the dynamic angle of repose, the
kinetic energy per grain of each material (mean over N >= 1) and each
material's axial self-diffusion D from the grains' mean-squared displacement
(summary.json). Seeds are the independent samples: mean, standard error
s/sqrt(n) and a 95 % Student interval per step; the two steps are compared
by Welch's test. Writes results.md beside this file; run with /usr/bin/python3
(numpy, scipy).

Any two sets of drum runs NAME_seedS in one folder compare the same way:
compare.py --out DIR --a NAME --b NAME --title TEXT --setup TEXT (the MPI drum
study, studies/mpi_drum: one process against 2 MPI ranks)."""
import argparse
import csv
import json
import pathlib
import re
import sys

import numpy as np
from scipy import stats

HERE = pathlib.Path(__file__).resolve().parent


def column_name(name):
    """A name as tumble writes it into CSV column names (older runs kept the '-')."""
    return re.sub(r"[^0-9A-Za-z_]", "_", name)


def observables(run):
    summary = json.loads((run / "summary.json").read_text())
    rows = [{column_name(k): v for k, v in r.items()} for r in csv.DictReader(open(run / "drum_series.csv"))]
    late = [r for r in rows if float(r["revolutions"]) >= 1.0]
    values = {"angle of repose (degrees)": summary["angle_of_repose"]}
    if "kinetic_energy_ratio_total" in summary:  # the paper's kinetic-energy ratio, material 2 over material 1
        values["kinetic-energy ratio"] = summary["kinetic_energy_ratio_total"]
    for c in summary["components"]:
        name = c["name"]
        column = "kinetic_per_grain_" + column_name(name)
        values[f"kinetic energy per grain, {name} (J)"] = np.mean([float(r[column]) for r in late])
        values[f"MSD D, {name} (m^2/rev)"] = c["msd"]["D"]
    return values


def runs(out, name):
    found = sorted((d for d in out.glob(f"{name}_seed*") if (d / "summary.json").exists()),
                   key=lambda d: int(d.name.split("seed")[1]))
    return found, [observables(d) for d in found]


def interval(x):
    x = np.asarray(x, float)
    n = len(x)
    se = x.std(ddof=1) / np.sqrt(n)
    return x.mean(), se, stats.t.ppf(0.975, n - 1) * se


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", default=str(HERE / "out"), help="folder of the runs NAME_seedS")
    parser.add_argument("--a", default="auto", help="name of the first set (default: auto)")
    parser.add_argument("--b", default="quarter", help="name of the second set, the reference (default: quarter)")
    parser.add_argument("--title", default="The drum's observables at the automatic step and at a quarter of it")
    parser.add_argument("--setup", default="", help="what the runs are (default: the time-step study's)")
    parser.add_argument("--results", default=str(HERE / "results.md"), help="file to write")
    args = parser.parse_args()
    out = pathlib.Path(args.out)
    (auto_dirs, auto), (quarter_dirs, quarter) = runs(out, args.a), runs(out, args.b)
    if len(auto) < 2 or len(quarter) < 2:
        sys.exit(f"need at least 2 finished runs of each set; have {len(auto)} and {len(quarter)}")
    setup = args.setup or (out / "steps.txt").read_text().strip()
    omega = json.loads((auto_dirs[0] / "summary.json").read_text())["omega"]
    lines = [
        f"# {args.title}",
        "",
        f"Made by `studies/time_step/compare.py` from {len(auto)} runs `{args.a}` and {len(quarter)} `{args.b}`"
        f" ({setup}; seeds {', '.join(d.name.split('seed')[1] for d in auto_dirs)} and"
        f" {', '.join(d.name.split('seed')[1] for d in quarter_dirs)}). Each run: the default drum (two components,"
        f" 1000 grains, {omega:g} rad/s), 6 revolutions after settling; means over N >= 1. +- is the 95 % Student"
        " interval over seeds; the difference's interval and p are Welch's (p: two-sided test of equal means).",
        "",
        f"| observable | {args.a} | {args.b} | difference [95 % interval], of {args.b}'s mean | p |",
        "|---|---|---|---|---|",
    ]
    verdicts = []
    for key in auto[0]:
        a = [v[key] for v in auto]
        q = [v[key] for v in quarter]
        (ma, sa, ha), (mq, sq, hq) = interval(a), interval(q)
        p = stats.ttest_ind(a, q, equal_var=False).pvalue
        # Welch's 95 % interval of the difference, relative to the quarter step's mean.
        df = (sa**2 + sq**2) ** 2 / (sa**4 / (len(a) - 1) + sq**4 / (len(q) - 1))
        half = stats.t.ppf(0.975, df) * np.hypot(sa, sq)
        lines.append(f"| {key} | {ma:.4g} +- {ha:.2g} | {mq:.4g} +- {hq:.2g} | {100 * (ma / mq - 1):+.1f} % "
                     f"[{100 * (ma - mq - half) / mq:+.1f}, {100 * (ma - mq + half) / mq:+.1f}] | {p:.2f} |")
        verdicts.append((key, p))
    lines += ["", "Per run:", "", "| run | " + " | ".join(auto[0]) + " |", "|---" * (len(auto[0]) + 1) + "|"]
    for d, v in zip(auto_dirs + quarter_dirs, auto + quarter):
        lines.append(f"| {d.name} | " + " | ".join(f"{x:.4g}" for x in v.values()) + " |")
    significant = [k for k, p in verdicts if p < 0.05]
    lines += ["", "Differences significant at 5 %: " + (", ".join(significant) if significant else "none") + "."]
    pathlib.Path(args.results).write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
