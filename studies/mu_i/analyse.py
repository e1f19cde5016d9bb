#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""mu(I) in the drum's flowing layer, set beside Jop, Forterre & Pouliquen
(Nature 441, 727, 2006): mu(I) = mu_s + (mu_2 - mu_s) / (I_0 / I + 1) with
mu_s = tan 20.9 deg, mu_2 = tan 32.76 deg, I_0 = 0.279 (glass beads).

Reads each run's cross-section (flowing_layer/fields.csv: the fields
averaged along the axis, with the strain rate from the whole velocity
gradient in the plane) and free surface (drum_frame.json), as kept by
`analyse.py --keep` (run.sh) in studies/mu_i/kept: node by node, not the
depth profile's mean along the surface. Each node of the cross-section is placed in the drum's
coordinates (s along the surface, d the depth below it; docs/FIELDS.md,
"The drum's frame"). Kept: the nodes over the middle part of the surface
(|s| within the span the surface was fitted over), below the surface,
whose solid fraction is at least 0.8 of the bed's (not the dilute grains
over the surface), and more than two bead diameters plus the kernel's
reach (3 widths) above the wall (where the coarse-graining would take in
the wall spheres). They are put in bins of I; per run the mean friction
and I of each bin; the runs (seeds) are the independent samples: mean and
95 % t interval over the seeds.
Writes results.json beside this script, the figure
docs/images/fields_mu_i.png, and the table between the markers of
README.md.

    python3 studies/mu_i/analyse.py --keep RUNS (keep what the analysis reads of RUNS' runs)
    python3 studies/mu_i/analyse.py [KEPT]      (default studies/mu_i/kept)
    python3 studies/mu_i/analyse.py --check     (the estimator on a made-up run with a known answer; README's table is the kept runs' own)
"""

import csv
import json
import math
import re
import sys
import tomllib
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))
from seeds import interval  # noqa: E402
MU_S, MU_2, I_0 = math.tan(math.radians(20.9)), math.tan(math.radians(32.76)), 0.279
BINS = [(0.001, 0.01), (0.01, 0.03), (0.03, 0.1), (0.1, 0.3), (0.3, 1.0)]
DENSE = 0.8  # of the bed's solid fraction
MIN_NODES = 5  # a bin's nodes in a run (1 mm apart: about a bead's area of the cross-section each) to count
SETTINGS = tomllib.loads((HERE / "drum.toml").read_text())
R_DRUM = SETTINGS["drum"]["diameter"] / 2  # m, to the wall spheres' inner side
BEAD = 2 * SETTINGS["material"][0]["radius"]  # m
WIDTH = BEAD / 2  # m: the kernel's width, fields' default (the mean radius)


def jop(I):
    return MU_S + (MU_2 - MU_S) / (I_0 / I + 1.0)


KEPT_COLUMNS = ["x", "y", "solid_fraction", "inertial_number", "friction"]


def keep(runs):
    """Each finished run's surface and the cross-section's nodes that hold grains, a few columns, into kept/."""
    for run in sorted(runs.glob("mu*_seed*")):
        source = run / "flowing_layer"
        if not (source / "drum_frame.json").exists():
            continue
        target = HERE / "kept" / run.name / "flowing_layer"
        target.mkdir(parents=True, exist_ok=True)
        (target / "drum_frame.json").write_text((source / "drum_frame.json").read_text())
        with open(source / "fields.csv") as f, open(target / "cross_section.csv", "w", newline="") as out:
            w = csv.writer(out)
            w.writerow(KEPT_COLUMNS)
            for r in csv.DictReader(f):
                if float(r["solid_fraction"]) > 0.0:
                    w.writerow([f"{float(r[c]):.6g}" for c in KEPT_COLUMNS])


def layer_points(run):
    """The drum frame's numbers, and (I, mu) at the kept nodes of the cross-section."""
    frame = json.loads((run / "flowing_layer" / "drum_frame.json").read_text())
    a = math.radians(frame["angle_of_repose_deg"])
    t, n = (-math.cos(a), -math.sin(a)), (-math.sin(a), math.cos(a))  # downhill along the surface; its normal out of the bed
    level, s_end = frame["surface_level_m"], frame["span"] * frame["surface_half_length_m"]
    dense = DENSE * frame["bed_solid_fraction"]
    points = []
    with open(run / "flowing_layer" / "cross_section.csv") as f:
        for r in csv.DictReader(f):
            x, y = float(r["x"]), float(r["y"])
            s, d = t[0] * x + t[1] * y, level - (n[0] * x + n[1] * y)
            if abs(s) > s_end or d <= 0.0 or float(r["solid_fraction"]) < dense:
                continue
            if d > math.sqrt(R_DRUM**2 - s**2) + level - 2 * BEAD - 3 * WIDTH:  # the wall's depth at s, less the margin
                continue
            points.append((float(r["inertial_number"]), float(r["friction"])))
    return frame, points


def run_bins(run):
    """Per bin of I: (mean I, mean mu, nodes) over the kept nodes; None with fewer than MIN_NODES there."""
    frame, points = layer_points(run)
    out = []
    for lo, hi in BINS:
        pts = [p for p in points if lo <= p[0] < hi]
        enough = len(pts) >= MIN_NODES
        out.append((sum(p[0] for p in pts) / len(pts), sum(p[1] for p in pts) / len(pts), len(pts)) if enough else None)
    return frame, out


def analyse(runs):
    groups = {}
    for run in sorted(p for p in runs.iterdir() if (p / "flowing_layer" / "cross_section.csv").exists()):
        friction = run.name.split("_")[0].removeprefix("mu")
        groups.setdefault(friction, []).append(run)
    results = {}
    for friction, members in groups.items():
        per_run = [run_bins(r) for r in members]
        angle = interval([f["angle_of_repose_deg"] for f, _ in per_run])
        rows = []
        for b, (lo, hi) in enumerate(BINS):
            got = [bins[b] for _, bins in per_run if bins[b] is not None]
            if len(got) < len(per_run):
                continue  # a seed without nodes there: no interval over the seeds
            I = interval([g[0] for g in got])
            mu = interval([g[1] for g in got])
            rows.append({"I_bin": [lo, hi], "I": I, "mu": mu, "jop": jop(I[0]), "nodes": [g[2] for g in got]})
        results[friction] = {"seeds": [r.name for r in members], "angle_of_repose_deg": angle, "bins": rows}
    return results


def fmt(x, digits=3):
    return f"{x[0]:.{digits}f} [{x[1]:.{digits}f}, {x[2]:.{digits}f}]"


def table(results):
    lines = ["| bead friction | seeds | I (bin) | I | mu, tumble | mu, Jop et al. at that I |",
             "|---|---|---|---|---|---|"]
    for friction in sorted(results, key=float, reverse=True):
        r = results[friction]
        for row in r["bins"]:
            lines.append(f"| {friction} | {len(r['seeds'])} | {row['I_bin'][0]:g}-{row['I_bin'][1]:g} | "
                         f"{fmt(row['I'])} | {fmt(row['mu'])} | {row['jop']:.3f} |")
    lines.append("")
    for friction in sorted(results, key=float, reverse=True):
        lines.append(f"The surface's slope over the middle half of its length, bead friction {friction}: "
                     f"{fmt(results[friction]['angle_of_repose_deg'], 1)} degrees.")
    return "\n".join(lines)


BEGIN, END = "<!-- table: analyse.py -->", "<!-- end of table -->"
SECTION = "## mu(I) in a drum's flowing layer"


def quoted_intervals():
    """The intervals "X [LO, HI]" that docs/FIELDS.md's mu(I) section quotes."""
    text = (HERE.parent.parent / "docs" / 'FIELDS.md').read_text()
    section = text[text.index(SECTION):]
    section = " ".join(section[:section.find("\n## ", 1)].split())  # an interval may run over a line's end
    return re.findall(r"\d+\.\d+ \[\d+\.\d+, \d+\.\d+\]", section)


def readme_with(text, results):
    i, j = text.index(BEGIN) + len(BEGIN), text.index(END)
    return text[:i] + "\n" + table(results) + "\n" + text[j:]


def figure(results, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6, 4.2))
    I = [10 ** (k / 50) for k in range(-150, 1)]
    ax.plot(I, [jop(x) for x in I], "k-", label="Jop et al. 2006 (glass beads)")
    for (friction, r), colour in zip(sorted(results.items(), key=lambda t: -float(t[0])), ["C0", "C3", "C2"]):
        xs = [row["I"][0] for row in r["bins"]]
        ys = [row["mu"][0] for row in r["bins"]]
        err = [[row["mu"][0] - row["mu"][1] for row in r["bins"]], [row["mu"][2] - row["mu"][0] for row in r["bins"]]]
        ax.errorbar(xs, ys, yerr=err, fmt="o", color=colour, capsize=3,
                    label=f"tumble, bead friction {friction} ({len(r['seeds'])} seeds, 95 %)")
    ax.set_xscale("log")
    ax.set_xlabel("inertial number I")
    ax.set_ylabel("mu = |tau| / p")
    ax.set_ylim(0, 1)
    ax.legend(fontsize=8)
    ax.set_title("mu(I) in a drum's flowing layer")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def synthetic_problem():
    """The estimator on a made-up run whose answer is known, or what it got wrong.

    A bed under a surface at 30 degrees, 5 mm below the axis, on a 1 mm
    grid: phi 0.6 in the bed, I = 0.5 exp(-d / 3 mm) and mu = jop(I) at
    each node. The nodes kept must be exactly those over the middle half of
    the surface, below it and more than the margin above the wall (counted
    here from (s, d) worked out independently by turning the grid back),
    and each bin's mu the mean of jop over its nodes, to round-off."""
    import tempfile
    a, level, half = math.radians(30.0), -0.005, math.sqrt(R_DRUM**2 - 0.005**2)
    frame = {"angle_of_repose_deg": 30.0, "surface_level_m": level, "surface_half_length_m": half,
             "span": 0.5, "bed_solid_fraction": 0.6}
    expected, rows = [], []
    for i in range(-40, 41):
        for j in range(-40, 41):
            s, d = 1e-3 * i, 1e-3 * j  # the node's drum coordinates, then its place
            x = -s * math.cos(a) - (level - d) * math.sin(a)
            y = -s * math.sin(a) + (level - d) * math.cos(a)
            if math.hypot(x, y) > R_DRUM or d <= 0.0:
                continue
            I = 0.5 * math.exp(-d / 3e-3)
            rows.append((x, y, 0.6, I, jop(I)))
            if abs(s) <= 0.5 * half and d <= math.sqrt(R_DRUM**2 - s**2) + level - 2 * BEAD - 3 * WIDTH:
                expected.append(I)
    with tempfile.TemporaryDirectory() as tmp:
        run = Path(tmp) / "mu0.5_seed1" / "flowing_layer"
        run.mkdir(parents=True)
        (run / "drum_frame.json").write_text(json.dumps(frame))
        with open(run / "cross_section.csv", "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(KEPT_COLUMNS)
            w.writerows([[repr(v) for v in r] for r in rows])
        _, points = layer_points(run.parent)
        _, bins = run_bins(run.parent)
    if sorted(p[0] for p in points) != sorted(expected):
        return f"kept {len(points)} nodes, not the {len(expected)} over the span, below the surface, above the wall"
    for (lo, hi), got in zip(BINS, bins):
        inside = [I for I in expected if lo <= I < hi]
        if len(inside) < MIN_NODES:
            continue
        want = sum(jop(I) for I in inside) / len(inside)
        if got is None or abs(got[1] - want) > 1e-12:
            return f"bin {lo}-{hi}: mu {got and got[1]} where the nodes give {want}"
    return ""


def main(argv):
    check = "--check" in argv
    args = [a for a in argv if not a.startswith("--")]
    if "--keep" in argv:
        keep(Path(args[0]))
        return 0
    runs = Path(args[0]) if args else HERE / "kept"
    results = analyse(runs)
    readme = (HERE / 'README.md').read_text()
    if check:
        problem = synthetic_problem()
        if problem:
            print(f"studies/mu_i/analyse.py on a made-up run: {problem}")
            return 1
        if readme_with(readme, results) != readme:
            print("studies/mu_i/README.md: its table is not the kept runs' (python3 studies/mu_i/analyse.py)")
            return 1
        quoted = quoted_intervals()
        missing = [q for q in quoted if q not in readme]
        for q in missing:
            print(f"docs/FIELDS.md, {SECTION}: {q}: not in studies/mu_i/README.md's table")
        if missing or not quoted:
            return 1
        print(f"studies/mu_i/analyse.py finds a made-up run's answer; studies/mu_i/README.md: the table is the kept runs' own, "
              f"and docs/FIELDS.md's {len(quoted)} intervals are in it")
        return 0
    (HERE / "results.json").write_text(json.dumps(results, indent=1) + "\n")
    (HERE / 'README.md').write_text(readme_with(readme, results))
    figure(results, HERE.parent.parent / "docs" / "images" / "fields_mu_i.png")
    print(table(results))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
