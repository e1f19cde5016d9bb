#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The positive control's verdict (PLAN.md, "The test and its verdict";
docs/BANDS.md, "A positive control: a short drum of glass-like beads bands").

    python3 studies/band_control/analyse.py collect   # out/<case>_seed<k> -> results.csv (kept in git)
    python3 studies/band_control/analyse.py           # results.csv -> results.md (the table)
    python3 studies/band_control/analyse.py --check   # results.md is results.csv's table (a test)
    python3 studies/band_control/analyse.py --figure  # docs/images/band_control.png (the runs' kymographs)

`collect` reads every finished run (summary.json) of out/, and every run
stopped before its end whose revolutions `tumble analyze RUN --so-far`
has analysed (so_far/bands.json): its bands.json
(tumble's band analysis of the small grains, docs/BAND-ANALYSIS.md) gives
one row per run: the end layers' excess (phi, the small grains' volume
fraction, in the 2 cm next to each cap less the bed's mean; negative: rich
in large grains) in each block of revolutions, the band count at the end,
the revolution at which bands first appeared (null: none) and the radial
core at the end.

The table gives, per case (control: caps of the wall's friction; nocap:
frictionless caps; cohesive: the control with the paper's attraction), each number's mean over the seeds with its 95 %
Student's t interval (n - 1 degrees of freedom; 4.30 for 3 seeds; with two
seeds the two values, a spread, not an interval). The seeds are independent
mixed packings: their spread is all that an interval rests on.

Standard library only (matplotlib for --figure).
"""
import csv
import json
import re
import sys
from pathlib import Path

STUDY = Path(__file__).resolve().parent
ROOT = STUDY.parents[1]
sys.path.insert(0, str(STUDY.parent))
from seeds import interval  # noqa: E402
OUT = STUDY / "out"
CSV = STUDY / "results.csv"
TABLE = STUDY / "results.md"
FIGURE = ROOT / "docs" / "images" / "band_control.png"
CASES = {"control": "caps of the wall's friction (0.4)", "nocap": "frictionless caps",
         "cohesive": "the paper's attraction, W = 0.2 J/m^2"}
BLOCKS = [(0, 1), (1, 2), (2, 4), (4, 8), (8, 16), (16, 32)]
FIELDS = (["case", "seed", "revolutions", "bands_end", "onset_revolution", "core_end"] +
          [f"{side}_{a}_{b}" for a, b in BLOCKS for side in ("left", "right")])


def block_name(a, b):
    return f"{a}_{b}"


def collect():
    """Each finished run of out/ replaces its row; the rows of runs not here (made on another machine, kept
    in results.csv) stay. A run stopped before its end (kill -INT) counts with the revolutions it turned,
    once `tumble analyze RUN --so-far` has analysed them (RUN/so_far/bands.json)."""
    kept = {(r["case"], int(r["seed"])): r for r in read_rows()} if CSV.exists() else {}
    rows = []
    for run in sorted(OUT.glob("*_seed*")):
        analysed = run / "bands.json" if (run / "summary.json").exists() else run / "so_far" / "bands.json"
        if not run.is_dir() or not analysed.exists():
            continue
        case, seed = run.name.rsplit("_seed", 1)
        bands = json.loads(analysed.read_text())
        row = {"case": case, "seed": int(seed), "revolutions": round(bands["final"]["revolutions"], 3),
               "bands_end": bands["final"]["bands"], "onset_revolution": bands["onset_revolution"],
               "core_end": round(bands["final"]["core_fraction"] - bands["final"]["periphery_fraction"], 4)}
        for side in ("left", "right"):
            for block in bands["end_layers"][side]:
                a, b = int(block["from"]), int(block["to"])
                name = next((f"{side}_{x}_{y}" for x, y in BLOCKS if x == a), None)
                if name is not None:
                    row[name] = round(block["excess"], 4)
        rows.append(row)
        kept.pop((case, int(seed)), None)
    rows = sorted(list(kept.values()) + rows, key=lambda r: (list(CASES).index(r["case"]), int(r["seed"])))
    with CSV.open("w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=FIELDS, lineterminator="\n")
        writer.writeheader()
        for row in rows:
            writer.writerow({k: ("" if row.get(k) is None else row.get(k)) for k in FIELDS})
    print(f"{len(rows)} finished runs into {CSV.relative_to(ROOT)} ({len(kept)} of them kept from before)")


def read_rows():
    with CSV.open() as f:
        return list(csv.DictReader(f))


def summary(values, digits=3):
    """Mean with its 95 % t interval over the seeds; two seeds: both values."""
    values = [v for v in values if v is not None]
    n = len(values)
    if n == 0:
        return "-"
    mean = sum(values) / n
    if n == 1:
        return f"{mean:+.{digits}f} (one seed)"
    if n == 2:
        return f"{mean:+.{digits}f} ({values[0]:+.{digits}f}, {values[1]:+.{digits}f}: two seeds, a spread)"
    _, lo, hi = interval(values)
    return f"{mean:+.{digits}f} [{lo:+.{digits}f}, {hi:+.{digits}f}]"


def number(text):
    return None if text in ("", None) else float(text)


def table(rows):
    lines = ["| case | seeds | revolutions | end layers' excess, N = 16 to the end (both caps) | "
             "the same, N = 8 to 16 | bands at the end | bands appeared at N | radial core at the end |",
             "|---|---|---|---|---|---|---|---|"]
    for case, what in CASES.items():
        runs = [r for r in rows if r["case"] == case]
        if not runs:
            continue
        seeds = ", ".join(r["seed"] for r in sorted(runs, key=lambda r: int(r["seed"])))
        caps = lambda a, b: [(number(r[f"left_{a}_{b}"]) + number(r[f"right_{a}_{b}"])) / 2 for r in runs
                             if number(r[f"left_{a}_{b}"]) is not None and number(r[f"right_{a}_{b}"]) is not None]
        onsets = [number(r["onset_revolution"]) for r in runs]
        onset = (", ".join("none" if x is None else f"{x:.1f}" for x in onsets))
        turned = ", ".join(f"{number(r['revolutions']):.0f}" for r in runs)
        lines.append(f"| {case}: {what} | {seeds} | {turned} | "
                     f"{summary(caps(16, 32))} | {summary(caps(8, 16))} | "
                     f"{', '.join(str(int(number(r['bands_end']))) for r in runs)} | {onset} | "
                     f"{summary([number(r['core_end']) for r in runs])} |")
    return "\n".join(lines) + "\n"


HEADER = """# The positive control's table

Made by `python3 studies/band_control/analyse.py` from results.csv (one row
per finished run, `analyse.py collect`); the test `band_control_table`
checks that it is. The end layers' excess is phi (small grains' volume
fraction) in the 2 cm next to a cap less the bed's mean, the mean of both
caps per run: negative where the large grains gather. Mean over the seeds
with its 95 % t interval.

"""


SECTION = "### A positive control"


def quoted_numbers():
    """The intervals "X [LO, HI]", spreads "X (A, B: two seeds", single values +-X.XXX and onset revolutions
    that docs/BANDS.md's positive control quotes."""
    text = (ROOT / "docs" / 'BANDS.md').read_text()
    section = text[text.index(SECTION):]
    section = " ".join(section[:section.find("\n#", 1)].split())  # an interval may run over a line's end
    return (re.findall(r"[+-]\d+\.\d+ \[[+-]\d+\.\d+, [+-]\d+\.\d+\]", section) +
            re.findall(r"[+-]\d+\.\d+ \([+-]\d+\.\d+, [+-]\d+\.\d+: two seeds", section) +
            re.findall(r"[+-]\d\.\d{3}\b", section) +  # every number of three decimals, one seed's too
            re.findall(r"\b\d+\.\d\b(?= on\b|,| and)", section))  # the revolutions at which bands appeared


def main():
    args = sys.argv[1:]
    if args == ["collect"]:
        collect()
        return 0
    text = HEADER + table(read_rows())
    if args == ["--check"]:
        if TABLE.read_text() != text:
            print(f"{TABLE.relative_to(ROOT)} is not the table of {CSV.relative_to(ROOT)}: run analyse.py")
            return 1
        table_text = " ".join(text.split())
        missing = [q for q in quoted_numbers() if q not in table_text]
        for q in missing:
            print(f"docs/BANDS.md, {SECTION}: {q}: not in studies/band_control/results.md")
        if missing:
            return 1
        print(f"results.md is results.csv's table, and the {len(quoted_numbers())} intervals docs/BANDS.md's "
              "positive control quotes are in it")
        return 0
    if args == ["--figure"]:
        figure()
        return 0
    if args:
        print(__doc__)
        return 2
    TABLE.write_text(text)
    print(text)
    return 0


def figure():
    """The kymographs of phi(z, N) of seed 1 of each case, side by side."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, len(CASES), figsize=(3 + 3 * len(CASES), 4.2), sharey=True, constrained_layout=True)
    image = None
    for ax, case in zip(axes, CASES):
        run = OUT / f"{case}_seed1"
        rows = [r for r in csv.DictReader((run / "band_profile.csv").open()) if r["quantity"] == "small_fraction"]
        times = [float(r["revolutions"]) for r in rows]
        bins = [k for k in rows[0] if k.startswith("bin_")]
        grid = [[float(r[k]) for k in bins] for r in rows]
        half = 100 * json.loads((run / "bands.json").read_text())["bin_width"] * len(bins) / 2  # cm
        image = ax.imshow(grid, origin="lower", aspect="auto", cmap="RdBu", vmin=0.2, vmax=0.8,
                          extent=[-half, half, times[0], times[-1]])
        ax.set_title(f"{case}: {CASES[case]}", fontsize=9)
        ax.set_xlabel("z along the axis (cm)")
    axes[0].set_ylabel("revolutions N")
    fig.colorbar(image, ax=axes, label="phi, small grains' volume fraction")
    fig.savefig(FIGURE, dpi=120)
    print(f"wrote {FIGURE.relative_to(ROOT)}")


if __name__ == "__main__":
    sys.exit(main())
