#!/usr/bin/env python3
"""The diffusion study: does the grains' axial D depend on the lag? From the
snapshots of the long runs (8 per revolution, 120 revolutions; run before
keep.sh, which deletes them): the mean-squared axial displacement of the
grains over lags of 1 to 64 revolutions (from N = 1), and the D that a
random walk between reflecting ends (the end caps, a uniform start) would
need to give it: MSD(N) = L^2/6 - (16 L^2 / pi^4) sum_{k odd} exp(-k^2 pi^2 D N / L^2) / k^4.
A D that falls with the lag means axial motion slower than diffusion at one
D over long times (grains slowed near the end caps, or subdiffusion).
Writes msd_lags.md beside this file; /usr/bin/python3 (numpy, scipy, pandas)."""
import pathlib

import numpy as np
import pandas as pd
from scipy.optimize import brentq

HERE = pathlib.Path(__file__).resolve().parent
L = 0.12  # m, the bed length
PER_REV = 8  # snapshots per revolution
LAGS = [1, 2, 4, 8, 16, 32, 64]


def bounded_msd(D, N):
    k = np.arange(1, 400, 2)
    return L**2 / 6 - 16 * L**2 / np.pi**4 * np.sum(np.exp(-k**2 * np.pi**2 * D * N / L**2) / k**4)


def positions(run):
    """Axial positions (snapshots x grains, in id order) and each grain's component."""
    zs, kind = [], None
    for f in sorted((run / "snapshots").glob("[0-9]*.csv")):
        t = pd.read_csv(f, comment="#")
        t = t[t.kinematic == 0].sort_values("id")
        zs.append(t.z.to_numpy())
        kind = t.material.to_numpy() if t.material.nunique() > 1 else np.where(t.tag.to_numpy() == t.tag.min(), "left", "right")
    return np.array(zs)[PER_REV:], kind  # from N = 1


def main():
    lines = ["# Axial MSD against the lag (long runs)", "",
             "Written by `msd_lags.py`. D_free = MSD / (2 N); D_walls: the D of a random walk between the end caps that gives the same MSD.", "",
             "| mode | component | lag N (rev) | MSD (1e-5 m^2) | D_free (1e-5 m^2/rev) | D_walls (1e-5 m^2/rev) |", "|---|---|---|---|---|---|"]
    for mode in ("self", "two-component"):
        for run in sorted((HERE / "out" / f"long_{mode}" / "points").glob("*")):
            if not (run / "snapshots").is_dir():
                continue
            Z, kind = positions(run)
            for name in sorted(set(kind)):
                z = Z[:, kind == name]
                for lag in LAGS:
                    m = lag * PER_REV
                    msd = float(np.mean((z[m:] - z[:-m]) ** 2))
                    d_walls = brentq(lambda D: bounded_msd(D, lag) - msd, 1e-10, 1e-2)
                    lines.append(f"| {mode} | {name} | {lag} | {msd / 1e-5:.2f} | {msd / (2 * lag) / 1e-5:.2f} | {d_walls / 1e-5:.2f} |")
    if len(lines) == 6:  # no long run with its snapshots: keep the table made when it had them
        print("msd_lags.py: no long run with snapshots under out/; msd_lags.md left as it is")
        return
    (HERE / "msd_lags.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
