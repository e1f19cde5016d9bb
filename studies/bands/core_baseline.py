#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The radial core's baseline (docs/BANDS.md, "The radial core's baseline").

The radial core index is phi_core - phi_periphery (docs/BAND-ANALYSIS.md):
phi, the small grains' volume fraction, in the inner third of each axial
bin's grain volume about the bed's centre less that in the outer third,
pooled over the bins. This sets it against its null: the same drum with two
species of one size and material, told apart by their tag only
(core_null.toml), in which any core is the geometry's or the start's.

Two steps:

    python3 studies/bands/core_baseline.py collect   # the core_* runs of out/ -> core_baseline.csv
    python3 studies/bands/core_baseline.py           # core_baseline.csv -> core_baseline.md (the table)
    python3 studies/bands/core_baseline.py --check   # core_baseline.md is core_baseline.csv's table (a test)
    python3 studies/bands/core_baseline.py --figure  # docs/results/bands/core_baseline.png

`collect` reads each run of runs.txt named core_* from out/NAME (a finished
run's bands.csv and radial_shells.csv; `tumble analyze` is run first on a
run without the latter, TUMBLE the binary, default build/tumble) and
writes one row per run (core_baseline.csv, kept in git):

- index_N0: the index at N = 0, the settled bed before turning;
- index_B_<from>_<to>: the mean of the revolution means in the blocks of N
  that bands.json uses ([0, 1), [1, 2), [2, 4), [4, 8), [8, 16));
- index_late: the same over N = 4 to 16 (revolutions 4 to 15);
- shells_N0, shells_late: the second measure, phi in the inner two of six
  shells of equal grain volume about the bed's centre (the whole drum ranked
  at once, from the particle snapshots) less phi in the outer two, at
  N = 0 and averaged over the snapshots of N = 4 to 15;
- phi_shell_<k>_late: phi per shell over N = 4 to 15 (k = 0 innermost).

The table gives, per kind of run (null, A, A_dry; settle_*: settling only,
N = 0), the mean over seeds with its 95 % Student's t interval
(n - 1 degrees of freedom: 4.30 for 3 seeds), and the excess of A (and
A_dry) over the null, seed for seed (paired: the difference of each seed's
runs, its mean and t interval). Seeds are independent packings: their
spread is all that the interval rests on.

Standard library only.
"""
import csv
import math
import os
import re
import subprocess
import sys
from pathlib import Path

STUDY = Path(__file__).resolve().parent
CSV = STUDY / "core_baseline.csv"
TABLE = STUDY / "core_baseline.md"
BLOCKS = [(0, 1), (1, 2), (2, 4), (4, 8), (8, 16)]
LATE = (4, 16)  # revolutions [4, 16)
SHELLS = 6
# Student's t, two-sided 95 %, by degrees of freedom.
T95 = {1: 12.706, 2: 4.303, 3: 3.182, 4: 2.776, 5: 2.571, 6: 2.447, 7: 2.365, 8: 2.306, 9: 2.262, 10: 2.228,
       11: 2.201, 12: 2.179, 13: 2.160, 14: 2.145, 15: 2.131, 19: 2.093, 29: 2.045}
KINDS = ["null", "A", "A_dry", "settle_null", "settle_A"]


def core_runs():
    """[(name, kind, seed)] of runs.txt's core_* runs, in its order."""
    runs = []
    for line in (STUDY / "runs.txt").read_text().splitlines():
        match = re.match(r"core_(\w+?)_seed(\d+)\s", line + " ")
        if match:
            runs.append((f"core_{match.group(1)}_seed{match.group(2)}", match.group(1), int(match.group(2))))
    return runs


def turn(N):
    """The whole revolution a sample at N belongs to (a time a hair below N counts in N)."""
    return math.floor(N + 1e-9)


def mean(values):
    return sum(values) / len(values) if values else float("nan")


def revolution_means(rows, key):
    """{revolution: mean of the finite values of `key` over its samples}."""
    turns = {}
    for r in rows:
        value = float(r[key])
        if math.isfinite(value) and float(r["revolutions"]) >= 0:
            turns.setdefault(turn(float(r["revolutions"])), []).append(value)
    return {k: mean(v) for k, v in turns.items()}


def window(means, lo, hi):
    """The mean of the revolution means of revolutions lo .. hi - 1 (NaN if none)."""
    return mean([v for k, v in means.items() if lo <= k < hi])


def index_row(name, kind, seed, samples):
    """A run's row of the index from its bands.csv rows."""
    index = revolution_means(samples, "core_excess")
    row = {"run": name, "kind": kind, "seed": seed,
           "last_N": float(samples[-1]["revolutions"]),
           "index_N0": float(samples[0]["core_excess"]) if float(samples[0]["revolutions"]) == 0 else float("nan")}
    for lo, hi in BLOCKS:
        row[f"index_B_{lo}_{hi}"] = window(index, lo, hi)
    row["index_late"] = window(index, *LATE)
    return row


def collect():
    rows = []
    for name, kind, seed in core_runs():
        out = STUDY / "out" / name
        if not (out / "summary.json").is_file():
            print(f"{name}: not finished, left out")
            continue
        if not (out / "radial_shells.csv").is_file():  # analysed by a tumble before the radial shells
            subprocess.run([os.environ.get("TUMBLE", str(STUDY.parent.parent / "build" / "tumble")), "analyze",
                            str(out)], check=True, stdout=subprocess.DEVNULL)
        with open(out / "bands.csv") as f:
            row = index_row(name, kind, seed, list(csv.DictReader(f)))
        with open(out / "radial_shells.csv") as f:
            shell_rows = list(csv.DictReader(f))
        # Per snapshot: phi per shell; the shells hold equal volumes (to a
        # grain), so the inner and outer thirds are the means of two shells.
        snapshots = {}
        for r in shell_rows:
            snapshots.setdefault(float(r["revolutions"]), [None] * SHELLS)[int(r["shell"])] = float(r["small_fraction"])
        excess = {N: mean(phi[:2]) - mean(phi[-2:]) for N, phi in snapshots.items()}
        row["shells_N0"] = excess.get(0.0, float("nan"))
        late = [N for N in snapshots if LATE[0] <= turn(N) < LATE[1]]
        row["shells_late"] = mean([excess[N] for N in late])
        for k in range(SHELLS):
            row[f"phi_shell_{k}_late"] = mean([snapshots[N][k] for N in late])
        rows.append(row)
    fields = list(rows[0].keys()) if rows else ["run"]
    with open(CSV, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields, lineterminator="\n")
        w.writeheader()
        for row in rows:
            w.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in row.items()})
    print(f"{CSV.relative_to(STUDY.parent.parent)}: {len(rows)} runs")


def t_interval(values):
    """(mean, lo, hi, n): the mean of the finite values and its 95 % Student's t interval."""
    values = [v for v in values if math.isfinite(v)]
    n = len(values)
    m = mean(values)
    if n < 2:
        return m, float("nan"), float("nan"), n
    s = math.sqrt(sum((v - m) ** 2 for v in values) / (n - 1))
    t = T95.get(n - 1) or T95[max(k for k in T95 if k <= n - 1)]
    return m, m - t * s / math.sqrt(n), m + t * s / math.sqrt(n), n


def fmt(m, lo, hi, n, plain):
    """m [lo, hi] (n = N); signed unless plain (a fraction, not a difference)."""
    if not math.isfinite(m):
        return "-"
    f = ".3f" if plain else "+.3f"
    if not math.isfinite(lo):
        return f"{m:{f}} (n = {n})"
    return f"{m:{f}} [{lo:{f}}, {hi:{f}}] (n = {n})"


def table():
    with open(CSV) as f:
        rows = list(csv.DictReader(f))
    by_kind = {k: {int(r["seed"]): r for r in rows if r["kind"] == k} for k in KINDS}
    quantities = ["index_N0"] + [f"index_B_{lo}_{hi}" for lo, hi in BLOCKS] + ["index_late", "shells_N0", "shells_late"]
    quantities += [f"phi_shell_{k}_late" for k in range(SHELLS)]
    labels = {"index_N0": "index at N = 0 (settled)", "index_late": "index, N = 4-16", "shells_N0": "shells, N = 0",
              "shells_late": "shells, N = 4-16"}
    labels.update({f"index_B_{lo}_{hi}": f"index, N = {lo}-{hi}" for lo, hi in BLOCKS})
    labels.update({f"phi_shell_{k}_late": f"phi in shell {k + 1} of 6, N = 4-16" for k in range(SHELLS)})
    lines = ["# The radial core's baseline: the null against A",
             "",
             "Written by `python3 studies/bands/core_baseline.py` from core_baseline.csv; do not edit.",
             "Mean over seeds [95 % Student's t interval] (n seeds); excess: seed for seed, paired.",
             "The index is phi_core - phi_periphery per axial bin, pooled; shells: phi in the inner",
             "two of six equal-volume shells about the bed's centre less the outer two, whole drum.",
             ""]
    kinds = [k for k in KINDS if by_kind[k]]
    pairs = [(k, n) for k, n in (("A", "null"), ("A_dry", "null"), ("settle_A", "settle_null"))
             if by_kind[k] and by_kind[n]]
    lines.append("| " + " | ".join(["quantity"] + kinds + [f"{k} - {n}" for k, n in pairs]) + " |")
    lines.append("|---" * (1 + len(kinds) + len(pairs)) + "|")
    for q in quantities:
        # {seed: row} of a kind for q. A settling-only kind has N = 0 only
        # (its runs turn 0.3 revolutions), and also holds there the turned
        # runs' seeds (their N = 0 is a settled bed too; a seed once).
        def runs(k):
            if not k.startswith("settle_"):
                return by_kind[k]
            return by_kind[k] | by_kind[k[len("settle_"):]] if q.endswith("_N0") else {}
        cells = [fmt(*t_interval([float(r[q]) for r in runs(k).values()]), q.startswith("phi")) for k in kinds]
        for k, n in pairs:
            a, b = runs(k), runs(n)
            cells.append(fmt(*t_interval([float(a[s][q]) - float(b[s][q]) for s in sorted(set(a) & set(b))]), False))
        lines.append(f"| {labels[q]} | " + " | ".join(cells) + " |")
    lines += ["", "Seeds: " + "; ".join(f"{k} {', '.join(str(s) for s in sorted(by_kind[k]))}" for k in kinds)
              + " (the settle_* columns at N = 0 also hold the seeds of the turned runs of their kind).", ""]
    return "\n".join(lines)


def figure(path):
    """The index per block of N and phi per shell over N = 4-16, per kind
    of turned run: the mean over seeds with its 95 % t interval."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    with open(CSV) as f:
        rows = list(csv.DictReader(f))
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2))
    colours = {"null": "0.4", "A": "tab:blue", "A_dry": "tab:orange"}
    for k, (kind, colour) in enumerate(colours.items()):
        runs = [r for r in rows if r["kind"] == kind]
        if not runs:
            continue
        label = {"null": "null (one size, tags only)", "A": "A (paper's grains)", "A_dry": "A_dry (W = 0)"}[kind]
        shift = 1.0 + 0.04 * (k - 1)  # the kinds side by side
        xs = [0.5 * shift] + [math.sqrt(lo * hi) * shift for lo, hi in BLOCKS[1:]]
        stats = [t_interval([float(r["index_N0"]) for r in runs])] + \
                [t_interval([float(r[f"index_B_{lo}_{hi}"]) for r in runs]) for lo, hi in BLOCKS[1:]]
        for x, (m, lo, hi, n) in zip(xs, stats):
            if math.isfinite(lo):
                left.plot([x, x], [lo, hi], color=colour, lw=1.5)
        left.plot(xs, [st[0] for st in stats], "o-", color=colour, label=f"{label}, {len(runs)} seeds")
        shells = [t_interval([float(r[f"phi_shell_{j}_late"]) for r in runs]) for j in range(SHELLS)]
        if all(math.isfinite(st[0]) for st in shells):
            x = [j + 1 + 0.08 * (k - 1) for j in range(SHELLS)]
            for xi, (m, lo, hi, n) in zip(x, shells):
                if math.isfinite(lo):
                    right.plot([xi, xi], [lo, hi], color=colour, lw=1.5)
            right.plot(x, [st[0] for st in shells], "o-", color=colour, label=f"{label}, {shells[0][3]} seeds")
    left.axhline(0.0, color="k", lw=0.5)
    left.set_xscale("log", base=2)
    left.set_xticks([0.5, 1.41, 2.83, 5.66, 11.3], ["N = 0", "1-2", "2-4", "4-8", "8-16"])
    left.set_xlabel("revolutions (N = 0: the settled bed; then blocks of N)")
    left.set_ylabel("radial core index, phi_core - phi_periphery")
    left.legend(fontsize=8)
    right.axhline(0.5, color="k", lw=0.5)
    right.set_xlabel("shell of equal grain volume about the bed's centre (1: innermost)")
    right.set_ylabel("phi, N = 4-16")
    right.legend(fontsize=8)
    fig.suptitle("The radial core against its null: means over seeds, 95 % t intervals", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    print(f"{path}")


def main(args):
    if args == ["--check"]:  # the kept table is the one the kept summary gives (ctest core_baseline_table)
        if TABLE.read_text() != table():
            print(f"{TABLE}: not the table of {CSV.name}; run python3 studies/bands/core_baseline.py")
            return 1
        print(f"{TABLE.name}: the table of {CSV.name}")
        return 0
    if args == ["--figure"]:
        figure(STUDY.parent.parent / "docs" / "results" / "bands" / "core_baseline.png")
        return 0
    if args == ["collect"]:
        collect()
    elif args:
        print(__doc__)
        return 2
    TABLE.write_text(table())
    print(TABLE.read_text())
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
