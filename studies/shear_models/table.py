#!/usr/bin/env python3
"""The shear-model study: the comparison table of the three shear models.

Re-analyses every finished point with the current `build/tumble analyze`
(the estimators of docs/DRUM.md), then prints, per mode and shear model,
the mean over the seeds with a 95 % Student-t interval (the seed is the
statistical unit; n = 3 seeds: t = 4.30) of: D from the grains' axial MSD
per component, the Hogg D with free amplitude (N >= 1) per component, the
dynamic angle of repose, and the kinetic-energy ratio per grain.
"""
import json
import math
import pathlib
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
OUT = ROOT / "studies/shear_models/out"
T95 = {2: 12.71, 3: 4.303, 4: 3.182, 5: 2.776, 6: 2.571}


def interval(values):
    values = [v for v in values if v is not None and math.isfinite(v)]
    n = len(values)
    if n == 0:
        return "-"
    mean = sum(values) / n
    if n < 2:
        return f"{mean:.3g} (1 seed)"
    sd = math.sqrt(sum((v - mean) ** 2 for v in values) / (n - 1))
    half = T95[n] * sd / math.sqrt(n)
    return f"{mean:.3g} ± {half:.2g} ({n})"


def points(model, mode):
    for summary in sorted((OUT / f"{model}_{mode}" / "points").glob("*/summary.json")):
        if "--no-reanalyse" not in sys.argv:
            subprocess.run([str(ROOT / "build/tumble"), "analyze", str(summary.parent)], check=True,
                           stdout=subprocess.DEVNULL)
        yield json.loads(summary.read_text())


def main():
    print("| mode | shear model | D (MSD), first component | D (MSD), second | D (Hogg free), first | "
          "D (Hogg free), second | angle of repose (deg) | KE ratio per grain |")
    print("|---|---|---|---|---|---|---|---|")
    for mode in ("self", "two-component"):
        for model in ("paper", "coulomb", "spring"):
            runs = list(points(model, mode))
            if not runs:
                continue
            cells = []
            for estimator in ("msd", "hogg_free"):
                for k in (0, 1):
                    values = []
                    for r in runs:
                        c = r["components"][k][estimator]
                        values.append(c["D"] * 1e5 if c.get("determined") else None)
                    cells.append(interval(values))
            angle = interval([r["angle_of_repose"] for r in runs])
            ke = interval([r["kinetic_energy_ratio_per_grain"] for r in runs]) if mode != "self" else "-"
            print(f"| {mode} | {model} | " + " | ".join(cells) + f" | {angle} | {ke} |")
    print("\nD in 1e-5 m^2 per revolution; mean ± half-width of the 95 % t interval over the seeds (number of seeds).")


if __name__ == "__main__":
    main()
