#!/usr/bin/env python3
"""Three comparisons behind the verdicts (ii)-(iv) of docs/RESULTS.md, from
the finished runs kept in git (kept/caps_*/POINT.tar.gz: each point's
summary.json), so they need no run: writes comparisons.md beside this file.

- (ii) the two-component drum's D over the self-diffusion drum's at the same
  speed, by the grains' MSD and by the Hogg fit (amplitude free): the ratio
  of the seed means, its 95 % interval from the two means' standard errors
  on the log scale (Welch's degrees of freedom);
- (iii) the small grains' kinetic energy per grain over the large ones',
  divided by the equal-velocity value (2.4/3.6)^3: in the lab frame (the
  whole velocity) and about the local mean flow (the fluctuation energy in
  cells of two grain diameters, bed_structure.species);
- (iv) the top layer's share of the axial <dz^2> beside the share of the
  grains found there, and their ratio, with the layer's thickness: one mean
  grain diameter of the bed, which differs between the modes.

Means over the 6 seeds with 95 % Student intervals (verdicts.py). Run with
/usr/bin/python3 (numpy, scipy).
"""
import json
import math
import pathlib
import tarfile

import numpy as np
from scipy import stats

from verdicts import KE_EQUAL_VELOCITY, fmt_interval, mean_interval

HERE = pathlib.Path(__file__).resolve().parent
SPEEDS = (3.0, 5.0, 8.0, 12.0)


def summaries(sweep):
    """{omega: [summary.json of each seed]} of a kept sweep."""
    found = {}
    for archive in sorted((HERE / "kept" / sweep).glob("*.tar.gz")):
        with tarfile.open(archive) as tar:
            member = next(m for m in tar.getmembers() if m.name.endswith("/summary.json"))
            s = json.load(tar.extractfile(member))
        found.setdefault(s["omega"], []).append(s)
    return found


def mean_diameter(s):
    """The bed's mean grain diameter, m: the unit of the depth layers (and of the flowing layer's thickness)."""
    b = s["bed_structure"]
    return b["flowing_layer_thickness"] / b["flowing_layer_thickness_diameters"]


def ratio_interval(a, b):
    """mean(a) / mean(b) and its 95 % interval (log scale, Welch)."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    va, vb = a.var(ddof=1) / len(a) / a.mean() ** 2, b.var(ddof=1) / len(b) / b.mean() ** 2
    dof = (va + vb) ** 2 / (va**2 / (len(a) - 1) + vb**2 / (len(b) - 1))
    r, half = a.mean() / b.mean(), stats.t.ppf(0.975, dof) * math.sqrt(va + vb)
    return f"{r:.2f} [{r * math.exp(-half):.2f}, {r * math.exp(half):.2f}]"


def self_mean(s, key):
    """The two halves of a self-diffusion run averaged (they are not independent)."""
    return 0.5 * (s["components"][0][key]["D"] + s["components"][1][key]["D"])


def interval(values, digits=2):
    return fmt_interval(*mean_interval(values)[:3], digits=digits)


def main():
    two, one = summaries("caps_two-component"), summaries("caps_self")
    lines = ["# The diffusion study: comparisons for the verdicts (ii)-(iv)", "",
             "Written by `comparisons.py` from the kept runs (do not edit by hand). Means over the seeds with "
             "95 % Student intervals; a ratio of two means with its interval on the log scale (Welch).", ""]

    lines += ["## (ii) Two-component D over self-diffusion D, same speed", "",
              "| omega (rad/s) | component | by the grains' MSD | by the Hogg fit |", "|---|---|---|---|"]
    for w in SPEEDS:
        for k, name in enumerate(("material 1", "material 2")):
            cells = [ratio_interval([s["components"][k][key]["D"] for s in two[w]],
                                    [self_mean(s, key) for s in one[w]]) for key in ("msd", "hogg_free")]
            lines.append(f"| {w:g} | {name} | {cells[0]} | {cells[1]} |")
    lines.append("")

    lines += ["## (iii) Kinetic energy per grain, material 2 over material 1, over the equal-velocity value", "",
              "| omega (rad/s) | seeds | lab frame | about the local mean flow |", "|---|---|---|---|"]
    for w in SPEEDS:
        lab = [s["kinetic_energy_ratio_per_grain"] / KE_EQUAL_VELOCITY for s in two[w]]
        local = [s["bed_structure"]["species"][1]["fluctuation_energy_per_grain"]
                 / s["bed_structure"]["species"][0]["fluctuation_energy_per_grain"] / KE_EQUAL_VELOCITY
                 for s in two[w]]
        lines.append(f"| {w:g} | {len(lab)} | {interval(lab)} | {interval(local)} |")
    lines.append("")

    thickness = {mode: 1e3 * mean_diameter(runs[SPEEDS[0]][0]) for mode, runs in (("self", one), ("two", two))}
    lines += ["## (iv) The top layer: share of the axial <dz^2> and of the grains", "",
              f"The top layer is one mean grain diameter of the bed thick: {thickness['self']:.2f} mm in the "
              f"self-diffusion drum, {thickness['two']:.2f} mm in the two-component drum.", "",
              "| omega (rad/s) | mode | component | share of <dz^2> | share of grains | ratio |",
              "|---|---|---|---|---|---|"]
    for w in SPEEDS:
        rows = [("self", "both halves", [[c["depth_mobility"][k] for k in (0, 1)] for c in one[w]])]
        rows += [("two-component", f"material {k + 1}", [[c["depth_mobility"][k]] for c in two[w]]) for k in (0, 1)]
        for mode, name, layers in rows:
            share = [np.mean([c["surface_share"] for c in seed]) for seed in layers]
            grains = [np.mean([c["surface_occupancy"] for c in seed]) for seed in layers]
            ratio = [s / g for s, g in zip(share, grains)]
            lines.append(f"| {w:g} | {mode} | {name} | {interval(share)} | {interval(grains)} | {interval(ratio)} |")
    lines.append("")
    (HERE / "comparisons.md").write_text("\n".join(lines))
    print("\n".join(lines))


if __name__ == "__main__":
    main()
