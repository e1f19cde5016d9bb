#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The band study's figures across runs (studies/bands/LOG.md, "Experiment A complete").

Each run's own figure (fig_bands.png of `tumble analyze`) shows one run;
these put the runs of an experiment side by side:

- experiment_b_band_count.png: experiment B's band count against log N, one
  panel per starting count K, small or large grains at the ends, both
  seeds; a cross where the analysis records a change of count.
- experiment_a.png: experiment A per speed (columns), seeds and the runs
  without attraction overlaid: band contrast and number of bands, the
  small grains' share in the 2 cm next to each cap and in the bed's radial
  core (each minus the bed's mean, per block of N with its 95 % block
  interval: the revolution means as a correlated series), and the dominant
  wavelength of C(z).

A finished run is read from out/NAME or kept/NAME.tar.gz; an unfinished A
run from out/NAME/so_far (`tumble analyze --so-far`, which
experiment_a.py --analyze runs). Two seeds are drawn as two curves, never
pooled into an interval.

    python3 studies/bands/figures.py                      # into docs/results/bands/
    python3 studies/bands/figures.py --out /tmp/figures
"""
import argparse
import csv
import io
import json
import re
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from experiment_a import REPO, a_runs  # noqa: E402
from pool_edges import STUDY, run_file, study_runs  # noqa: E402

SEED_STYLE = {"1": "-", "2": "--"}
ENDS_COLOUR = {"small": "tab:blue", "large": "tab:orange"}


def run_files(name):
    """(bands.csv rows, bands.json, 'finished' | 'so far') of a run, or None."""
    text, data = run_file(name, "bands.csv"), run_file(name, "bands.json")
    state = "finished"
    if text is None or data is None:
        so_far = STUDY / "out" / name / "so_far"
        if not (so_far / "bands.csv").is_file() or not (so_far / "bands.json").is_file():
            return None
        text, data, state = (so_far / "bands.csv").read_bytes(), (so_far / "bands.json").read_bytes(), "so far"
    rows = list(csv.DictReader(io.StringIO(text.decode())))
    series = {key: [float(r[key]) for r in rows] for key in rows[0]}
    return series, json.loads(data), state


def blocks(block_list, key):
    """(N mid, value, lower error, upper error) of the blocks of 3 or more revolutions with an interval."""
    kept = [b for b in block_list if b.get(f"{key}_lo") is not None and b["revolutions"] >= 3]
    mid = [(b["from"] + min(b["to"], b["from"] + b["revolutions"])) / 2 for b in kept]
    value = [b[key] for b in kept]
    return mid, value, [b[key] - b[f"{key}_lo"] for b in kept], [b[f"{key}_hi"] - b[key] for b in kept]


def figure_b(out):
    names = study_runs()
    fig, axes = plt.subplots(2, 2, figsize=(11, 7), sharex=True)
    for k, ax in zip((2, 3, 4, 5), axes.flat):
        for name in names:
            match = re.fullmatch(rf"B_k{k}_(small|large)_seed(\d)", name)  # not the equal-width runs
            found = run_files(name) if match else None
            if found is None:
                continue
            series, bands, _ = found
            ends, seed = match.groups()
            # A small offset per run keeps equal counts apart; the ticks are the counts.
            shift = (0.06 if ends == "large" else -0.06) + (0.02 if seed == "2" else -0.02)
            n = [max(v, 0.1) for v in series["revolutions"]]
            ax.step(n, [b + shift for b in series["bands"]], where="post", color=ENDS_COLOUR[ends],
                    linestyle=SEED_STYLE[seed], linewidth=1.2, label=f"{ends} ends, seed {seed}")
            for event in bands["events"]:
                ax.plot(event["revolutions"], event["after"] + shift, "x", color=ENDS_COLOUR[ends], markersize=8)
        ax.set_xscale("log")
        ax.set_xlim(0.1, 300)
        ax.set_ylim(-0.3, 6)
        ax.set_yticks(range(0, 6))
        ax.set_title(f"start: {k} bands")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, loc="lower left")
    for ax in axes[1]:
        ax.set_xlabel("revolutions N")
    for ax in axes[:, 0]:
        ax.set_ylabel("number of bands")
    fig.suptitle("Experiment B: band count against log N (x: a change of count; curves offset by up to 0.08)")
    fig.tight_layout()
    path = out / "experiment_b_band_count.png"
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def figure_a(out):
    speeds = a_runs()
    columns = sorted({label.split(",")[0] for label in speeds})
    fig, axes = plt.subplots(4, len(columns), figsize=(6 * len(columns), 13), sharex=True, squeeze=False)
    colours = iter(plt.rcParams["axes.prop_cycle"].by_key()["color"])
    for label, names in speeds.items():
        column = columns.index(label.split(",")[0])
        dry = "no attraction" in label
        for name in names:
            found = run_files(name)
            if found is None:
                continue
            series, bands, state = found
            seed = name.rsplit("seed", 1)[1]
            colour = next(colours)
            tag = f"{'no attraction, ' if dry else ''}seed {seed}" + (f" (to N = {series['revolutions'][-1]:.0f})"
                                                                       if state == "so far" else "")
            n = [max(v, 0.1) for v in series["revolutions"]]
            ax = axes[0, column]
            ax.plot(n, series["contrast"], color=colour, linestyle=SEED_STYLE[seed], linewidth=0.8, label=tag)
            ax.plot(n, [0.02 * b for b in series["bands"]], color=colour, linestyle=":", linewidth=1.0)
            layers, core = bands["end_layers"], bands["radial_core"]["blocks"]
            for row, block_list, key, side, marker in ((1, layers["left"], "excess", "left cap", "<"),
                                                       (1, layers["right"], "excess", "right cap", ">"),
                                                       (2, core, "core_excess", "core", "o")):
                mid, value, lo, hi = blocks(block_list, key)
                axes[row, column].errorbar(mid, value, yerr=[lo, hi], color=colour, marker=marker,
                                           linestyle=SEED_STYLE[seed], linewidth=0.8, capsize=2, markersize=4,
                                           label=f"{tag}, {side}")
            axes[3, column].plot(n, [100 * w for w in series["dominant_wavelength"]], color=colour,
                                 linestyle="none", marker=".", markersize=1.5, label=tag)
        axes[0, column].set_title(f"{columns[column]}: contrast (dotted: 0.02 x number of bands)")
    for column in range(len(columns)):
        axes[0, column].set_ylabel("mean |phi - mean| along z")
        axes[1, column].set_ylabel("small grains' share in the 2 cm\nnext to each cap, minus the mean")
        axes[2, column].set_ylabel("small grains' share, radial core\nminus periphery")
        axes[3, column].set_ylabel("dominant wavelength of C(z) (cm)")
        axes[3, column].set_yscale("log")
        axes[3, column].set_xlabel("revolutions N")
        for row in range(4):
            ax = axes[row, column]
            ax.set_xscale("log")
            ax.grid(alpha=0.3)
            ax.legend(fontsize=7, loc="best")
        for row in (1, 2):
            axes[row, column].axhline(0, color="grey", linewidth=0.6)
    fig.suptitle("Experiment A, mixed start: per-block values with 95 % block intervals (blocks of 3 or more "
                 "revolutions)")
    fig.tight_layout()
    path = out / "experiment_a.png"
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--out", type=Path, default=REPO / "docs" / "results" / "bands",
                        help="folder for the figures (default docs/results/bands)")
    out = parser.parse_args().out
    out.mkdir(parents=True, exist_ok=True)
    for path in (figure_b(out), figure_a(out)):
        print(path)


if __name__ == "__main__":
    main()
