#!/usr/bin/env python3
"""The diffusion study: does the drum without end caps mix its two halves
faster than its grains diffuse? On a periodic axis neither the Hogg fit nor
the drift test applies (the mean of a wrapped coordinate follows no Hogg
law), so this takes the first Fourier mode of each component's
concentration profile (profiles.csv), a_1(N) = sum_z C(z, N) sin(2 pi z / L),
which diffusion at D alone makes decay as exp(-(2 pi / L)^2 D N). Fitted
from N = 1 to the end (least squares on log |a_1|, while it is above a tenth
of its start), the mode's D is set beside the grains' MSD D of the same run
(summary.json). A mode's D above the grains' means an axial flow mixes the
halves. Needs out/periodic_*/points/*/profiles.csv (not kept in git: the
table this writes, periodic_modes.md, is). /usr/bin/python3 (numpy, scipy, pandas)."""
import json
import math
import pathlib

import numpy as np
import pandas as pd
from scipy import stats

HERE = pathlib.Path(__file__).resolve().parent


def mode_D(profiles, component, L):
    t = profiles[(profiles.component == component) & (profiles.concentration >= 0)]
    N, a1 = [], []
    for n, g in t.groupby("revolutions"):
        N.append(n)
        a1.append(np.sum(g.concentration * np.sin(2 * math.pi * g.z / L)) * 2 / len(g))
    N, a1 = np.array(N), np.abs(np.array(a1))
    keep = (N >= 1) & (a1 > 0.1 * a1[0])
    fit = stats.linregress(N[keep], np.log(a1[keep]))
    return -fit.slope / (2 * math.pi / L) ** 2, N[keep].max()


def main():
    lines = ["# The first Fourier mode on a periodic axis", "",
             "Written by `periodic_modes.py`: per run, the D with which the first Fourier mode of the component's concentration decays (fitted from N = 1) against the grains' MSD D; 1e-5 m^2/rev. Ratio: mean over seeds [95 % Student interval].", "",
             "| sweep | component | seeds | mode D | grains' D | mode D / grains' D |", "|---|---|---|---|---|---|"]
    for sweep in ("periodic_self", "periodic_two-component"):
        runs = sorted((HERE / "out" / sweep / "points").glob("*/profiles.csv"))
        if not runs:
            continue
        per = {}
        for path in runs:
            summary = json.loads((path.parent / "summary.json").read_text())
            L = summary["bed_length"]
            profiles = pd.read_csv(path)
            for k, c in enumerate(summary["components"]):
                D_mode, _ = mode_D(profiles, k, L)
                per.setdefault(c["name"], []).append((D_mode, c["msd"]["D"]))
        for name, values in per.items():
            mode, msd = np.array(values).T
            ratio = mode / msd
            half = stats.t.ppf(0.975, len(ratio) - 1) * ratio.std(ddof=1) / math.sqrt(len(ratio))
            lines.append(f"| {sweep} | {name} | {len(ratio)} | {mode.mean() / 1e-5:.2f} | {msd.mean() / 1e-5:.2f} "
                         f"| {ratio.mean():.2f} [{ratio.mean() - half:.2f}, {ratio.mean() + half:.2f}] |")
    if len(lines) == 6:
        print("periodic_modes.py: no periodic run with profiles.csv under out/; periodic_modes.md left as it is")
        return
    (HERE / "periodic_modes.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
