#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The cohesion control: the paper's W = 0.2 J/m^2 against W = 0, per run
and pooled over the seeds (studies/bands/LOG.md, "Cohesion").

For each finished run (out/NAME, else the copy kept in results/NAME): the
radial core, phi_core - phi_periphery (the small grains' volume fraction in
the inner third of the bed about its centre, minus the outer third), per
block of N with its 95 % block interval; the mean over the blocks from N = 8
on (the settled start's own layering gone); the grains' axial MSD D per
component with its interval. Then, per W, the seeds' mean of the late core
excess and of D. Two seeds give a spread, not an interval: both values are
shown.

    python3 studies/cohesion/compare.py
    python3 studies/cohesion/compare.py --figure docs/results/bands/cohesion_radial_core.png
"""
import argparse
import json
from pathlib import Path

HERE = Path(__file__).resolve().parent
LATE = 8.0  # N from which the core excess is averaged


def run_dir(name):
    for base in (HERE / "out", HERE / "results"):
        if (base / name / "summary.json").is_file():
            return base / name
    return None


def figure(path, curves):
    """The core excess against N, one line per run, coloured by W, with the blocks' intervals."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 4))
    colours = {0.2: "tab:red", 0.0: "tab:blue"}
    for name, w, points in curves:
        x = [p[0] for p in points]
        y = [p[1] for p in points]
        err = [[p[1] - p[2] if p[2] is not None else 0.0 for p in points],
               [p[3] - p[1] if p[3] is not None else 0.0 for p in points]]
        ax.errorbar(x, y, yerr=err, marker="o", ms=4, capsize=3, color=colours.get(w, "0.3"),
                    ls="-" if name.endswith("seed1") else "--", label=f"{name} (W = {w:g} J/m$^2$)")
    ax.axhline(0.0, color="0.6", lw=0.8)
    ax.set_xscale("log")
    ax.set_xlabel("revolutions N (block of N: its geometric middle)")
    ax.set_ylabel("radial core: phi_core - phi_periphery")
    ax.set_title("Cohesion and the radial core: periodic drum 8 x 16 cm, fill 0.3, Froude 0.3", fontsize=10)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    print(f"figure: {path}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--figure", help="also draw the core excess against N into this PNG")
    args = parser.parse_args()
    curves = []
    names = sorted({p.name for base in (HERE / "out", HERE / "results") if base.is_dir()
                    for p in base.iterdir() if p.is_dir() and p.name.startswith("W")})
    late_by_w, d_by_w = {}, {}
    print("| run | W (J/m^2) | core excess per block of N: 1-2, 2-4, 4-8, 8-16, 16-32, 32-40 | mean from N = 8 |"
          " D small (m^2/rev) | D large |")
    print("|---|---|---|---|---|---|")
    for name in names:
        d = run_dir(name)
        if d is None:
            continue
        bands = json.loads((d / "bands.json").read_text())
        summary = json.loads((d / "summary.json").read_text())
        w = summary["surface_energy"]
        cells, late, weights, points = [], 0.0, 0, []
        for b in bands["radial_core"]["blocks"]:
            if b["from"] < 1.0 or b["core_excess"] is None:
                continue
            lo, hi = b["core_excess_lo"], b["core_excess_hi"]
            end = min(b["to"], b["from"] + b["revolutions"])
            points.append(((b["from"] * end) ** 0.5, b["core_excess"], lo, hi))
            cells.append(f"{b['core_excess']:+.3f}" + (f" [{lo:+.3f}, {hi:+.3f}]" if lo is not None else ""))
            if b["from"] >= LATE:
                late += b["core_excess"] * b["revolutions"]
                weights += b["revolutions"]
        late = late / weights if weights else float("nan")
        curves.append((name, w, points))
        late_by_w.setdefault(w, []).append(late)
        ds = {}
        for c in summary["components"]:
            msd = c.get("msd") or {}
            ds[c["name"]] = (msd.get("D"), (msd["D_lo"], msd["D_hi"]) if msd.get("D_lo") is not None else None)
        d_by_w.setdefault(w, []).append(ds)

        def show(name):
            D, ci = ds.get(name, (None, None))
            if D is None:
                return "-"
            return f"{D:.3g}" + (f" [{ci[0]:.3g}, {ci[1]:.3g}]" if ci else "")
        print(f"| {name} | {w:g} | {'; '.join(cells)} | {late:+.3f} | {show('material-2')} | {show('material-1')} |")
    print()
    for w in sorted(late_by_w, reverse=True):
        lates = ", ".join(f"{v:+.3f}" for v in late_by_w[w])
        small = ", ".join(f"{r['material-2'][0]:.3g}" for r in d_by_w[w] if r.get("material-2", (None,))[0])
        large = ", ".join(f"{r['material-1'][0]:.3g}" for r in d_by_w[w] if r.get("material-1", (None,))[0])
        print(f"- W = {w:g}: late core excess {lates} (seeds); D small {small}, large {large}")
    if args.figure:
        figure(args.figure, curves)


if __name__ == "__main__":
    main()
