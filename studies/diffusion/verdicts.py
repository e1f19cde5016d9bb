#!/usr/bin/env python3
"""The diffusion study: the verdicts on the paper's four claims from the
diffusion study (studies/diffusion/README.md). Reads the sweep tables
out/SWEEP/sweep.csv (one row per seed) and the long runs' summary.json, and
writes results.md beside this file. Run with /usr/bin/python3 (numpy, scipy).

Statistics: the seeds are the independent samples. A mean comes with a 95 %
Student interval (n - 1 degrees of freedom); a difference of two means with
Welch's interval; a trend with the least-squares slope over all seeds and its
Student interval (n - 2). In the self-diffusion drum the two halves (left,
right) are measured in the same run, so they are averaged per seed before
any statistics. D is the grains' axial mean-squared-displacement estimate
(docs/DRUM.md, "Analysis"), in m^2 per revolution.
"""
import csv
import json
import math
import pathlib

import numpy as np
from scipy import stats

HERE = pathlib.Path(__file__).resolve().parent
OUT = HERE / "out"
DIAMETER = {"material 1": 7.2e-3, "material 2": 4.8e-3}  # m, 2 x the paper's radii 3.6 and 2.4 mm
KE_EQUAL_VELOCITY = (2.4 / 3.6) ** 3  # material 2 / material 1 per grain at equal mean velocities


def sweep(name):
    path = OUT / name / "sweep.csv"
    if not path.exists():
        return []
    rows = [r for r in csv.DictReader(open(path)) if r["status"] == "finished"]
    for r in rows:
        for k, v in r.items():
            try:
                r[k] = float(v)
            except ValueError:
                pass
    return rows


def drift_verdicts(name):
    """{(omega, component index): [verdict per seed]} from the points' summary.json."""
    found = {}
    for path in sorted((OUT / name / "points").glob("*/summary.json")):
        s = json.loads(path.read_text())
        for k, c in enumerate(s["components"]):
            found.setdefault((s["omega"], k), []).append(c["drift"]["verdict"])
    return found


def mean_interval(x):
    x = np.asarray(x, float)
    n = len(x)
    m = x.mean()
    if n < 2:
        return m, math.nan, math.nan, n
    half = stats.t.ppf(0.975, n - 1) * x.std(ddof=1) / math.sqrt(n)
    return m, m - half, m + half, n


def welch(a, b):
    """Difference mean(b) - mean(a), its 95 % Welch interval and p-value."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    va, vb = a.var(ddof=1) / len(a), b.var(ddof=1) / len(b)
    se = math.sqrt(va + vb)
    dof = (va + vb) ** 2 / (va**2 / (len(a) - 1) + vb**2 / (len(b) - 1))
    d = b.mean() - a.mean()
    half = stats.t.ppf(0.975, dof) * se
    p = 2 * stats.t.sf(abs(d) / se, dof)
    return d, d - half, d + half, p


def slope(x, y):
    """Least-squares slope of y on x with its 95 % interval and p-value."""
    r = stats.linregress(x, y)
    half = stats.t.ppf(0.975, len(x) - 2) * r.stderr
    return r.slope, r.slope - half, r.slope + half, r.pvalue


def column(row, base, component):
    """A component's column: BASE_left / BASE_right (self), BASE_material_1
    (two-component; BASE_material-1 in tables written before the column names
    lost their hyphens)."""
    for suffix in (component, component.replace("_", "-")):
        if f"{base}_{suffix}" in row:
            return row[f"{base}_{suffix}"]
    raise KeyError(f"{base}_{component}")


SIDES = {"material 1": "material_1", "material 2": "material_2"}


def components(rows, mode):
    """Per seed: {component: value} of a column base (D_msd, surface_share)."""
    names = ["material 1", "material 2"] if mode == "two-component" else ["both halves"]

    def values(row, base):
        if mode == "two-component":
            return {name: column(row, base, SIDES[name]) for name in names}
        return {"both halves": 0.5 * (row[f"{base}_left"] + row[f"{base}_right"])}

    return names, values


def fmt_interval(m, lo, hi, scale=1.0, digits=2):
    return f"{m / scale:.{digits}f} [{lo / scale:.{digits}f}, {hi / scale:.{digits}f}]"


def by_omega(rows):
    groups = {}
    for r in rows:
        groups.setdefault(r["omega"], []).append(r)
    return dict(sorted(groups.items()))


def table_D(lines, title, rows, mode, sweep_name):
    names, values = components(rows, mode)
    drift = drift_verdicts(sweep_name)
    lines += [f"### {title}", "",
              "D from the grains' axial MSD, mean over seeds [95 % interval]; D/d^2 per revolution and D/(omega d^2) (d: the grain diameter; the self drum's grains are material 1)", "",
              "| omega (rad/s) | Froude | seeds | component | D (1e-5 m^2/rev) | D/d^2 per rev | D/(omega d^2) | D per second (1e-5 m^2/s) | surface share | angle of repose (deg) | <z> convecting (seeds) |",
              "|---|---|---|---|---|---|---|---|---|---|---|"]
    for omega, group in by_omega(rows).items():
        for index, name in enumerate(names):
            d = DIAMETER["material 1" if name == "both halves" else name]
            verdicts = drift.get((omega, 0), []) + drift.get((omega, 1), []) if mode == "self" else drift.get((omega, index), [])
            tested = [v for v in verdicts if v != "undetermined"]  # undetermined on a periodic axis
            convecting = (f"{tested.count('convecting')} of {len(tested)}" + (" halves" if mode == "self" else "")
                          if tested else "not applicable")
            D = [values(r, "D_msd")[name] for r in group]
            share = [values(r, "surface_share")[name] for r in group]
            m, lo, hi, n = mean_interval(D)
            per_second = [x * omega / (2 * math.pi) for x in D]
            lines.append(
                f"| {omega:g} | {group[0]['froude']:.3f} | {n} | {name} | {fmt_interval(m, lo, hi, 1e-5)} "
                f"| {fmt_interval(m, lo, hi, d * d)} | {fmt_interval(m, lo, hi, 2 * math.pi * d * d, 3)} "
                f"| {fmt_interval(*mean_interval(per_second)[:3], 1e-5)} | {fmt_interval(*mean_interval(share)[:3], 1.0)} "
                f"| {fmt_interval(*mean_interval([r['angle_of_repose'] for r in group])[:3], 1.0, 1)} | {convecting} |")
    lines.append("")


def claim_i(lines, self_rows):
    lines += ["## (i) Self-diffusion: faster at higher rotation speeds", ""]
    if not self_rows:
        lines += ["No data yet.", ""]
        return
    D = [0.5 * (r["D_msd_left"] + r["D_msd_right"]) for r in self_rows]
    omega = [r["omega"] for r in self_rows]
    per_second = [x * w / (2 * math.pi) for x, w in zip(D, omega)]
    s_rev = slope(omega, D)
    s_sec = slope(omega, per_second)
    groups = by_omega(self_rows)
    lo_w, hi_w = min(groups), max(groups)
    d_rev = welch([0.5 * (r["D_msd_left"] + r["D_msd_right"]) for r in groups[lo_w]],
                  [0.5 * (r["D_msd_left"] + r["D_msd_right"]) for r in groups[hi_w]])
    hogg = [0.5 * (r["D_hogg_free_left"] + r["D_hogg_free_right"]) for r in self_rows]
    s_hogg = slope(omega, hogg)
    lines += [
        f"- Per revolution, the slope of D against omega over {len(D)} runs: "
        f"{s_rev[0] / 1e-7:.2f} [{s_rev[1] / 1e-7:.2f}, {s_rev[2] / 1e-7:.2f}] 1e-7 m^2/rev per rad/s (p = {s_rev[3]:.2g}); "
        f"D({hi_w:g}) - D({lo_w:g}) = {d_rev[0] / 1e-5:.2f} [{d_rev[1] / 1e-5:.2f}, {d_rev[2] / 1e-5:.2f}] 1e-5 m^2/rev (p = {d_rev[3]:.2g}).",
        f"- Per revolution, with the Hogg fit's D instead (amplitude free, N >= 1; the paper's kind of D): "
        f"{s_hogg[0] / 1e-7:.2f} [{s_hogg[1] / 1e-7:.2f}, {s_hogg[2] / 1e-7:.2f}] 1e-7 m^2/rev per rad/s (p = {s_hogg[3]:.2g}).",
        f"- Per second, the slope of D against omega: {s_sec[0] / 1e-6:.2f} [{s_sec[1] / 1e-6:.2f}, {s_sec[2] / 1e-6:.2f}] 1e-6 m^2/s per rad/s (p = {s_sec[3]:.2g}).",
        ""]


def claim_ii(lines, two_rows):
    lines += ["## (ii) Two-component: nearly the same at two speeds, slightly smaller at the higher", ""]
    if not two_rows:
        lines += ["No data yet.", ""]
        return
    groups = by_omega(two_rows)
    speeds = list(groups)
    for base, what in (("D_msd", "the grains' MSD D"),
                       ("D_hogg_free", "the Hogg fit to <z>(N) (amplitude free, N >= 1), the paper's kind of D")):
        lines += [f"Change of {what} between neighbouring speeds (higher minus lower), 1e-5 m^2/rev [95 % Welch interval], and relative to the lower speed's mean:", "",
                  "| from -> to (rad/s) | component | difference | relative | p |", "|---|---|---|---|---|"]
        for a, b in zip(speeds, speeds[1:]):
            for name, side in SIDES.items():
                x = [column(r, base, side) for r in groups[a]]
                y = [column(r, base, side) for r in groups[b]]
                d, lo, hi, p = welch(x, y)
                ref = np.mean(x)
                lines.append(f"| {a:g} -> {b:g} | {name} | {d / 1e-5:+.2f} [{lo / 1e-5:+.2f}, {hi / 1e-5:+.2f}] "
                             f"| {d / ref:+.0%} [{lo / ref:+.0%}, {hi / ref:+.0%}] | {p:.2g} |")
        lines.append("")
    lines += ["The Hogg fit's D against the MSD D at each speed (means over seeds [95 %]; their ratio):", "",
              "| omega (rad/s) | component | Hogg D (1e-5 m^2/rev) | MSD D | Hogg / MSD |", "|---|---|---|---|---|"]
    for omega, group in groups.items():
        for name, side in SIDES.items():
            hogg = mean_interval([column(r, "D_hogg_free", side) for r in group])
            msd = mean_interval([column(r, "D_msd", side) for r in group])
            lines.append(f"| {omega:g} | {name} | {fmt_interval(*hogg[:3], 1e-5)} | {fmt_interval(*msd[:3], 1e-5)} | {hogg[0] / msd[0]:.2f} |")
    lines.append("")


def claim_iii(lines, two_rows):
    lines += ["## (iii) The small grains carry more kinetic energy than equal mean velocities would give", "",
              f"Material 2 / material 1, translational kinetic energy per grain (equal mean velocities: {KE_EQUAL_VELOCITY:.3f}):", "",
              "| omega (rad/s) | seeds | ratio per grain | ratio / equal-velocity value |", "|---|---|---|---|"]
    for omega, group in by_omega(two_rows).items():
        m, lo, hi, n = mean_interval([r["ke_ratio_per_grain"] for r in group])
        lines.append(f"| {omega:g} | {n} | {fmt_interval(m, lo, hi, 1.0, 3)} | {fmt_interval(m, lo, hi, KE_EQUAL_VELOCITY)} |")
    lines.append("")


def claim_iv(lines, self_rows, two_rows):
    lines += ["## (iv) Where the axial motion happens", "",
              "Surface share: the fraction of a component's axial MSD made less than one mean grain diameter below the free surface. Two-component minus self at the same speed:", "",
              "| omega (rad/s) | component | difference of surface share | p |", "|---|---|---|---|"]
    self_groups, two_groups = by_omega(self_rows), by_omega(two_rows)
    for omega in sorted(set(self_groups) & set(two_groups)):
        base = [0.5 * (r["surface_share_left"] + r["surface_share_right"]) for r in self_groups[omega]]
        for name, side in SIDES.items():
            d, lo, hi, p = welch(base, [column(r, "surface_share", side) for r in two_groups[omega]])
            lines.append(f"| {omega:g} | {name} | {d:+.3f} [{lo:+.3f}, {hi:+.3f}] | {p:.2g} |")
    lines.append("")


def ends(lines, caps, periodic, mode):
    names, values = components(caps, mode)
    omegas = {r["omega"] for r in periodic}
    lines += [f"### End caps against a periodic axis, {mode}", "",
              "| omega (rad/s) | component | D periodic - D caps (1e-5 m^2/rev) | relative | p |", "|---|---|---|---|---|"]
    for omega in sorted(omegas):
        for name in names:
            x = [values(r, "D_msd")[name] for r in caps if r["omega"] == omega]
            y = [values(r, "D_msd")[name] for r in periodic if r["omega"] == omega]
            if len(x) < 2 or len(y) < 2:
                continue
            d, lo, hi, p = welch(x, y)
            ref = np.mean(x)
            lines.append(f"| {omega:g} | {name} | {d / 1e-5:+.2f} [{lo / 1e-5:+.2f}, {hi / 1e-5:+.2f}] "
                         f"| {d / ref:+.0%} [{lo / ref:+.0%}, {hi / ref:+.0%}] | {p:.2g} |")
    lines.append("")


def long_runs(lines):
    lines += ["## The long runs: the Hogg shape beyond its linear start", "",
              "One seed per mode (so the intervals are the run's own block bootstrap, not seeds): the MSD D, the Hogg fit with a free amplitude from N >= 1, and the rms difference between the measured concentration profile and the Hogg solution with the MSD D at three times.", "",
              "| mode | revolutions | component | MSD D [95 %] | Hogg D (free) [95 %] | drift verdict | profile rms (N) |", "|---|---|---|---|---|---|---|"]
    for mode in ("two-component", "self"):
        for summary_path in sorted((OUT / f"long_{mode}" / "points").glob("*/summary.json")):
            s = json.loads(summary_path.read_text())
            profile = ", ".join(("-" if p["rms_difference"] is None else f"{p['rms_difference']:.3f}")
                                + f" ({p['revolutions']:.0f})" for p in s["profile_comparison"])
            for c in s["components"]:
                msd, hogg = c["msd"], c["hogg_free"]
                lines.append(f"| {mode} | {s['revolutions']:.0f} | {c['name']} | {fmt_interval(msd['D'], msd['D_lo'], msd['D_hi'], 1e-5)} "
                             f"| {fmt_interval(hogg['D'], hogg['D_lo'], hogg['D_hi'], 1e-5)} | {c['drift']['verdict']} | {profile} |")
    lines.append("")


def main():
    caps_self, caps_two = sweep("caps_self"), sweep("caps_two-component")
    periodic_self, periodic_two = sweep("periodic_self"), sweep("periodic_two-component")
    lines = ["# The diffusion study: numbers for the verdicts", "",
             "Written by `verdicts.py` from `out/*/sweep.csv` and the long runs (do not edit by hand). "
             "Intervals are 95 %: Student over seeds for means, Welch for differences, least squares for slopes.", ""]
    lines += ["## The runs", ""]
    for name, rows in (("caps_self", caps_self), ("caps_two-component", caps_two),
                       ("periodic_self", periodic_self), ("periodic_two-component", periodic_two)):
        lines.append(f"- {name}: {len(rows)} finished points")
    lines.append("")
    table_D(lines, "Self-diffusion, end caps", caps_self, "self", "caps_self")
    table_D(lines, "Two-component, end caps", caps_two, "two-component", "caps_two-component")
    if periodic_self:
        table_D(lines, "Self-diffusion, periodic axis", periodic_self, "self", "periodic_self")
        ends(lines, caps_self, periodic_self, "self")
    if periodic_two:
        table_D(lines, "Two-component, periodic axis", periodic_two, "two-component", "periodic_two-component")
        ends(lines, caps_two, periodic_two, "two-component")
    claim_i(lines, caps_self)
    claim_ii(lines, caps_two)
    claim_iii(lines, caps_two)
    claim_iv(lines, caps_self, caps_two)
    long_runs(lines)
    (HERE / "results.md").write_text("\n".join(lines))
    print("\n".join(lines))


if __name__ == "__main__":
    main()
