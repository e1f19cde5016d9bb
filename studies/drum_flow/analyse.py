#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The flowing layer of the drum of Alizadeh et al. (AIChE J. 59, 1894,
2013) against their measured velocity profile (alizadeh_rpt.csv).

Each run's depth profile (flowing_layer/profile.csv: the fields in the
drum's frame along the middle fifth of the surface, docs/FIELDS.md, "The
drum's frame") is placed on the experiment's line: y = level - d, the
position on the normal to the surface through the drum's axis (0 on the
axis, negative into the bed), with level the surface's (drum_frame.json).
The same estimators then read the experiment's points and each run:

- the layer's lower edge y0: where the velocity along the surface, going
  down from the top, first turns from downhill (> 0) to uphill (linear
  between points);
- the velocity gradient in the layer, du/dy: the least-squares line
  through the points above y0;
- the velocity at the surface: that line at the surface (the run's fitted
  surface; the experiment's highest point, since where its surface lies
  was not read);
- the flowing layer's thickness: the surface less y0;
- the bed's rotation: u = w y fitted through the axis to the points
  deeper than y = -0.09 m (well below the layer: the bed turning with the
  drum gives the drum's omega, 1.2147 rad/s);
- the difference of the profiles: the root mean square of the run's u,
  linear between its nodes, less the experiment's, over the experiment's
  points; on the experiment's line, and with each profile put below its
  own surface (the experiment's highest point, the run's fitted surface).

A column per bead friction run at the experiment's 11.6 rpm (run.sh: 0.3,
the Lethe project's model of this experiment; 0.5, which follows Jop et
al.'s mu(I) in studies/mu_i, when asked for); the seeds are the
independent samples: mean and 95 % t interval (studies/seeds.py).

A second table, the layer against the drum's speed (run.sh SPEEDS, bead
friction 0.3): the same measures at each speed, and the exponents of
h ~ omega^a, u(0) ~ omega^b and du/dy ~ omega^c, each fitted by least
squares on the logarithms over the speeds for each seed (seed k of every
speed: the seeds are independent, so the exponents of seeds 1, 2, 3 are
three independent samples), then mean and 95 % t interval.

Writes the tables between their markers in README.md and docs/FIELDS.md,
and the figures docs/images/fields_drum_rpt.png and fields_drum_speed.png.

    python3 studies/drum_flow/analyse.py --keep OUT  (what the analysis reads of OUT's runs, into kept/)
    python3 studies/drum_flow/analyse.py [--figure]  (the table from kept/, and the figure)
    python3 studies/drum_flow/analyse.py --check     (the estimators on a made-up profile; the tables are the kept runs')
"""

import csv
import json
import math
import re
import shutil
import sys
import tempfile
import tomllib
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent.parent
sys.path.insert(0, str(HERE.parent))
from seeds import interval  # noqa: E402

EXPERIMENT = HERE / "alizadeh_rpt.csv"
FIGURE = ROOT / "docs" / "images" / "fields_drum_rpt.png"
SPEED_FIGURE = ROOT / "docs" / "images" / "fields_drum_speed.png"
DOCS = [HERE / 'README.md', ROOT / 'docs' / 'FIELDS.md']
BEGIN, END = "<!-- table: studies/drum_flow/analyse.py -->", "<!-- end of table -->"
SPEED_BEGIN = "<!-- speed table: studies/drum_flow/analyse.py -->"
SETTINGS = tomllib.loads((HERE / "alizadeh.toml").read_text())
OMEGA = SETTINGS["rotation"]["omega"]  # rad/s, the drum's
RPM = 11.6  # the experiment's speed, rpm: OMEGA's
GRAVITY = 9.81  # m/s^2
RADIUS = SETTINGS["drum"]["diameter"] / 2  # m
BEAD = 2 * SETTINGS["material"][0]["radius"]  # m
DEEP = -0.09  # m: the bed below this turns with the drum
ANGLE_REPORTED = 27.0  # degrees: the experiment's angle as Lethe's example quotes it (not read in the paper)
PROFILE_COLUMNS = ["d", "velocity_s", "solid_fraction", "shear_rate", "inertial_number", "friction"]


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def experiment():
    """The measured points, (y, u) from the top down."""
    rows = read_csv(EXPERIMENT)
    return sorted(((float(r["y_m"]), float(r["u_m_per_s"])) for r in rows), key=lambda p: -p[0])


def run_profile(kept, name):
    """A run's profile on the experiment's line, (y, u) from the top down, and its surface."""
    frame = json.loads((kept / f"{name}_drum_frame.json").read_text())
    level = frame["surface_level_m"]
    points = [(level - float(r["d"]), float(r["velocity_s"])) for r in read_csv(kept / f"{name}_profile.csv")
              if float(r["d"]) >= 0.0]  # inside the bed: from the surface down
    return sorted(points, key=lambda p: -p[0]), frame


def lower_edge(points):
    """y where u first turns from > 0 to <= 0 going down (linear between points), or None."""
    for (y1, u1), (y2, u2) in zip(points, points[1:]):
        if u1 > 0.0 >= u2:
            return y1 + (y2 - y1) * u1 / (u1 - u2)
    return None


def line(points):
    """Least-squares u = a + b y: (a, b)."""
    n = len(points)
    my = sum(y for y, _ in points) / n
    mu = sum(u for _, u in points) / n
    b = sum((y - my) * (u - mu) for y, u in points) / sum((y - my) ** 2 for y, _ in points)
    return mu - b * my, b


def measures(points, surface):
    """The estimators of the docstring on one profile (y, u from the top down) with its surface's y."""
    y0 = lower_edge(points)
    a, b = line([p for p in points if p[0] > y0])
    deep = [p for p in points if p[0] < DEEP]
    w = sum(y * u for y, u in deep) / sum(y * y for y, _ in deep)
    return {"surface_y": surface, "lower_edge_y": y0, "thickness": surface - y0, "gradient": b,
            "surface_velocity": a + b * surface, "bed_rotation": w}


def at(points, y):
    """u at y, linear between the profile's points, or None outside them."""
    for (y1, u1), (y2, u2) in zip(points, points[1:]):
        if y2 <= y <= y1:
            return u1 if y1 == y2 else u1 + (u2 - u1) * (y - y1) / (y2 - y1)
    return None


def rms_difference(points, reference):
    diffs = [v - u for v, u in ((at(points, y), u) for y, u in reference) if v is not None]
    return math.sqrt(sum(d * d for d in diffs) / len(diffs))


def parts(name):
    """(bead friction, rpm, stiffness factor, seed) of a run's name: mu0.3_seed1 (the experiment's speed,
    the beads of alizadeh.toml), mu0.3_rpm5.8_seed2, mu0.3_E10x_seed1 (E ten times alizadeh.toml's)."""
    words = name.split("_")
    rpm, stiffness = RPM, 1.0
    for w in words[1:-1]:
        if w.startswith("rpm"):
            rpm = float(w.removeprefix("rpm"))
        elif w.startswith("E") and w.endswith("x"):
            stiffness = float(w[1:-1])
        else:
            raise ValueError(f"{name}: not a run's name")
    return words[0].removeprefix("mu"), rpm, stiffness, int(words[-1].removeprefix("seed"))


def kept_names(kept):
    return sorted(p.name.removesuffix("_drum_frame.json") for p in kept.glob("mu*_seed*_drum_frame.json"))


def group_label(friction, stiffness):
    """A column's name: the bead friction, and the stiffness where it is not alizadeh.toml's."""
    return f"bead friction {friction}" + ("" if stiffness == 1.0 else f", E x{stiffness:g}")


def runs_in(kept):
    """The kept runs at the experiment's speed by bead friction and stiffness, in that order:
    {"bead friction 0.3": ["mu0.3_seed1", ...], "bead friction 0.3, E x10": [...], ...}."""
    groups = {}
    for name in sorted(kept_names(kept), key=lambda n: parts(n)[:3]):
        friction, rpm, stiffness, _ = parts(name)
        if rpm == RPM:
            groups.setdefault(group_label(friction, stiffness), []).append(name)
    return dict(sorted(groups.items(), key=lambda g: (parts(g[1][0])[0], parts(g[1][0])[2])))


def speeds_in(kept, friction="0.3"):
    """The kept runs of one bead friction by speed: {5.8: ["mu0.3_rpm5.8_seed1", ...], 11.6: [...], ...}."""
    groups = {}
    for name in kept_names(kept):
        f, rpm, stiffness, _ = parts(name)
        if f == friction and stiffness == 1.0:
            groups.setdefault(rpm, []).append(name)
    return dict(sorted(groups.items()))


def analyse(kept):
    """The experiment's measures, and each run's by bead friction."""
    exp = experiment()
    measured = measures(exp, exp[0][0])
    runs = {friction: [run_measures(kept, name, exp) for name in names] for friction, names in runs_in(kept).items()}
    return measured, runs


def run_measures(kept, name, exp):
    """The measures of one kept run, and its profile's differences from the experiment's points `exp`."""
    points, frame = run_profile(kept, name)
    m = measures(points, frame["surface_level_m"])
    m["angle"] = frame["angle_of_repose_deg"]
    m["rms_difference"] = rms_difference(points, exp)
    level, top = frame["surface_level_m"], exp[0][0]
    m["rms_below_surface"] = rms_difference([(y - level, u) for y, u in points], [(y - top, u) for y, u in exp])
    return m


def exponent(xs, ys):
    """The least-squares slope of log y against log x."""
    lx, ly = [math.log(x) for x in xs], [math.log(y) for y in ys]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    return sum((a - mx) * (b - my) for a, b in zip(lx, ly)) / sum((a - mx) ** 2 for a in lx)


def speed_table(kept):
    """The layer at each speed (bead friction 0.3), and the exponents over the speeds; "" with one speed."""
    groups = speeds_in(kept)
    if len(groups) < 2:
        return ""
    exp = experiment()
    runs = {rpm: {parts(n)[3]: run_measures(kept, n, exp) for n in names} for rpm, names in groups.items()}
    rpms = list(runs)
    rows = [("Froude number omega^2 R / g", lambda r, rpm: (rpm * math.pi / 30) ** 2 * RADIUS / GRAVITY, 1, 4, False),
            ("dynamic angle of repose (degrees)", lambda r, rpm: r["angle"], 1, 1, True),
            ("flowing layer's thickness (mm)", lambda r, rpm: r["thickness"], 1e3, 1, True),
            ("velocity at the surface (m/s)", lambda r, rpm: r["surface_velocity"], 1, 3, True),
            ("velocity gradient in the layer, du/dy (1/s)", lambda r, rpm: r["gradient"], 1, 2, True)]
    lines = ["| quantity | " + " | ".join(f"{rpm:g} rpm, {len(runs[rpm])} seeds" for rpm in rpms) + " |",
             "|---|" + "---|" * len(rpms)]
    for q, value, scale, digits, seeded in rows:
        cells = [fmt([value(r, rpm) for r in runs[rpm].values()], scale, digits) if seeded
                 else f"{value(None, rpm) * scale:.{digits}f}" for rpm in rpms]
        lines.append(f"| {q} | " + " | ".join(cells) + " |")
    seeds = sorted(set.intersection(*(set(r) for r in runs.values())))
    omegas = [rpm * math.pi / 30 for rpm in rpms]
    fits = [("thickness, a in h ~ omega^a", "thickness"), ("surface velocity, b in u(0) ~ omega^b", "surface_velocity"),
            ("du/dy, c in du/dy ~ omega^c", "gradient")]
    lines += ["", f"| exponent over {rpms[0]:g} to {rpms[-1]:g} rpm ({len(seeds)} seeds) | fitted |", "|---|---|"]
    for q, key in fits:
        lines.append(f"| {q} | " + fmt([exponent(omegas, [runs[rpm][k][key] for rpm in rpms]) for k in seeds], 1, 2)
                     + " |")
    return "\n".join(lines) + "\n\ntumble, bead friction 0.3: mean over the seeds [95 % t interval]."


def fmt(values, scale=1.0, digits=3):
    """The mean [95 % t interval]; one seed: its value; two: both, a spread and not an interval."""
    values = [v * scale for v in values]
    m, lo, hi = interval(values)
    if len(values) < 3:
        return f"{m:.{digits}f} ({', '.join(f'{v:.{digits}f}' for v in values)}: a spread, not an interval)"
    return f"{m:.{digits}f} [{lo:.{digits}f}, {hi:.{digits}f}]"


def table(measured, runs):
    """One row a measure: the experiment's value, then tumble's mean [95 % t] over the seeds, per bead friction."""
    rows = [  # quantity, the experiment's value as printed, tumble's per run, scale, digits
        ("dynamic angle of repose (degrees)", f"{ANGLE_REPORTED:.0f} (as quoted by Lethe's example)",
         lambda r: r["angle"], 1, 1),
        ("the surface, below the axis (mm)", f"{-1e3 * measured['surface_y']:.1f} (the highest point)",
         lambda r: -r["surface_y"], 1e3, 1),
        ("the layer's lower edge (u = 0), below the axis (mm)", f"{-1e3 * measured['lower_edge_y']:.1f}",
         lambda r: -r["lower_edge_y"], 1e3, 1),
        ("flowing layer's thickness (mm)", f"{1e3 * measured['thickness']:.1f}", lambda r: r["thickness"], 1e3, 1),
        ("the same in bead diameters", f"{measured['thickness'] / BEAD:.1f}", lambda r: r["thickness"], 1 / BEAD, 1),
        ("velocity at the surface (m/s)", f"{measured['surface_velocity']:.3f}",
         lambda r: r["surface_velocity"], 1, 3),
        ("velocity gradient in the layer, du/dy (1/s)", f"{measured['gradient']:.2f}", lambda r: r["gradient"], 1, 2),
        (f"the bed's rotation below y = {DEEP} m (rad/s; the drum's {OMEGA})", f"{measured['bed_rotation']:.3f}",
         lambda r: r["bed_rotation"], 1, 3),
        ("root mean square of tumble's u less the measured, on the line (m/s)", "",
         lambda r: r["rms_difference"], 1, 3),
        ("the same, each profile below its own surface (m/s)", "", lambda r: r["rms_below_surface"], 1, 3),
    ]
    frictions = list(runs)  # the columns, in runs_in's order
    lines = ["| quantity | Alizadeh et al. (2013) | " +
             " | ".join(f"tumble, {f}, {len(runs[f])} seeds" for f in frictions) + " |",
             "|---|---|" + "---|" * len(frictions)]
    for q, e, value, scale, digits in rows:
        lines.append(f"| {q} | {e} | " +
                     " | ".join(fmt([value(r) for r in runs[f]], scale, digits) for f in frictions) + " |")
    return "\n".join(lines) + "\n\ntumble: mean over the seeds [95 % t interval]."


SECTION = "## A drum against glass beads measured by particle tracking"  # of docs/FIELDS.md


def quoted_intervals():
    """The intervals "X [LO, HI]" that README.md and docs/FIELDS.md's section quote, tables included."""
    fields = DOCS[1].read_text()
    section = fields[fields.index(SECTION):]
    section = section[:section.find("\n## ", 1)]
    text = " ".join((DOCS[0].read_text() + section).split())  # an interval may run over a line's end
    return re.findall(r"-?\d+\.\d+ \[-?\d+\.\d+, -?\d+\.\d+\]", text)


def with_table(text, tab, begin=BEGIN):
    """The text with `tab` between `begin` and the next END (unchanged without `begin`)."""
    if begin not in text:
        return text
    i = text.index(begin) + len(begin)
    j = text.index(END, i)
    return text[:i] + "\n" + tab + "\n" + text[j:]


def with_tables(text, tab, speeds):
    return with_table(with_table(text, tab), speeds, SPEED_BEGIN)


def keep(out):
    """Each finished run's drum frame and a few columns of its depth profile, into kept/."""
    kept = HERE / "kept"
    kept.mkdir(exist_ok=True)
    for run in sorted(out.glob("mu*_seed*")):
        source = run / "flowing_layer"
        if not (source / "drum_frame.json").exists():
            continue
        shutil.copyfile(source / "drum_frame.json", kept / f"{run.name}_drum_frame.json")
        rows = read_csv(source / "profile.csv")
        with open(kept / f"{run.name}_profile.csv", "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(PROFILE_COLUMNS)
            w.writerows([[r[c] for c in PROFILE_COLUMNS] for r in rows])
        summary = json.loads((run / "summary.json").read_text())
        (kept / f"{run.name}_run.json").write_text(json.dumps(
            {k: summary[k] for k in ("grains", "fill_fraction", "angle_of_repose", "grain_updates_per_second")},
            indent=1) + "\n")


def figure(kept, path):
    """Left: the profiles on the experiment's line; right: against the depth below each one's own surface."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    exp = experiment()
    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 5.2), sharex=True)
    for (friction, names), colour in zip(runs_in(kept).items(), ["C0", "C3", "C2", "C1"]):
        runs = [run_profile(kept, name) for name in names]
        for ax, shifted in ((left, False), (right, True)):
            # each run on the depth below its own surface (right), or where it lies (left)
            profiles = [[(y - frame["surface_level_m"] if shifted else y, u) for y, u in p] for p, frame in runs]
            top = min(p[0][0] for p in profiles)
            bands = []
            for y in (top - 0.0005 * k for k in range(int((top + 0.118) / 0.0005))):
                got = [at(p, y) for p in profiles]
                if None not in got:  # two seeds: their range, a spread and not an interval
                    bands.append((y, *interval(got)) if len(got) > 2 else (y, sum(got) / len(got), min(got), max(got)))
            ax.fill_betweenx([b[0] for b in bands], [b[2] for b in bands], [b[3] for b in bands], color=colour,
                             alpha=0.3, lw=0)
            ax.plot([b[1] for b in bands], [b[0] for b in bands], "-", color=colour,
                    label=f"tumble, {friction}: mean of {len(profiles)} seeds, " +
                    ("95 %" if len(profiles) > 2 else "their range"))
    left.plot([u for _, u in exp], [y for y, _ in exp], "kx", label="Alizadeh et al. 2013 (RPT)")
    right.plot([u for _, u in exp], [y - exp[0][0] for y, _ in exp], "kx",
               label="Alizadeh et al. 2013, below its highest point")
    left.plot([OMEGA * y for y in (-0.12, 0.0)], [-0.12, 0.0], "k:", lw=0.8, label="the drum's rotation, omega y")
    for ax in (left, right):
        ax.axvline(0.0, color="0.6", lw=0.6)
        ax.set_xlim(-0.2, 0.45)
        ax.set_xlabel("velocity along the surface, downhill (m/s)")
        ax.legend(fontsize=8, loc="lower right")
    left.set_ylim(-0.12, -0.02)
    right.set_ylim(-0.09, 0.01)
    left.set_ylabel("y: position on the normal through the axis (m)")
    right.set_ylabel("below the surface (m)")
    fig.suptitle("3 mm glass beads, a drum 24 cm across at 11.6 rpm: the velocity along the surface")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def speed_figure(kept, path):
    """The flowing layer's thickness and surface velocity against the drum's speed, with the measurement."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    exp = experiment()
    measured = measures(exp, exp[0][0])
    runs = {rpm: [run_measures(kept, n, exp) for n in names] for rpm, names in speeds_in(kept).items()}
    rpms = list(runs)
    fig, axes = plt.subplots(1, 3, figsize=(12, 4))
    # The two limits of the flux through the layer growing as omega (1/2 u(0) h for a linear profile, u(0) =
    # h du/dy): a layer of fixed shear rate (h and u(0) as omega^(1/2)) or of fixed thickness (u(0), du/dy as omega).
    for ax, key, scale, label, limits in (
            (axes[0], "thickness", 1e3, "flowing layer's thickness (mm)", (0.5, 0.0)),
            (axes[1], "surface_velocity", 1, "velocity at the surface (m/s)", (0.5, 1.0)),
            (axes[2], "gradient", 1, "du/dy in the layer (1/s)", (0.0, 1.0))):
        stats = [interval([r[key] * scale for r in runs[rpm]]) for rpm in rpms]
        ax.errorbar(rpms, [m for m, _, _ in stats], yerr=[[m - lo for m, lo, _ in stats], [hi - m for m, _, hi in stats]],
                    fmt="o-", color="C0", capsize=3, label="tumble, bead friction 0.3: mean, 95 % over seeds")
        ax.plot([RPM], [measured[key] * scale], "kx", ms=9, label="Alizadeh et al. 2013 (RPT)")
        m0 = stats[rpms.index(RPM)][0]
        for power, style, limit in zip(limits, ("--", ":"), ("a fixed shear rate", "a fixed thickness")):
            ax.plot(rpms, [m0 * (rpm / RPM) ** power for rpm in rpms], style, color="0.5", lw=0.9,
                    label=f"{limit}: omega^{power:g} through tumble's 11.6 rpm")
        ax.legend(fontsize=7, loc="lower right")
        ax.set_xlabel("drum speed (rpm)")
        ax.set_ylabel(label)
        ax.set_ylim(bottom=0)
    fig.suptitle("3 mm glass beads, a drum 24 cm across: the flowing layer against the drum's speed")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def synthetic_problem():
    """The estimators on a made-up run whose answers are known, or what they got wrong.

    Surface 30 mm below the axis; u = 12 (y - y0) above y0 = -60 mm, the
    drum's rotation omega y below y = -90 mm and a straight line between,
    on a 1 mm grid of depths; the kept files as --keep writes them."""
    level, y0, grad = -0.030, -0.060, 12.0

    def u(y):
        if y >= y0:
            return grad * (y - y0)
        if y <= DEEP:
            return OMEGA * y
        return OMEGA * DEEP * (y - y0) / (DEEP - y0)

    with tempfile.TemporaryDirectory() as tmp:
        kept = Path(tmp)
        (kept / "mu0.3_seed1_drum_frame.json").write_text(json.dumps({"surface_level_m": level, "angle_of_repose_deg": 27.0}))
        with open(kept / "mu0.3_seed1_profile.csv", "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(PROFILE_COLUMNS)
            for k in range(-3, 90):
                d = 1e-3 * k
                w.writerow([repr(d), repr(u(level - d)), "0.6", "0", "0", "0"])
        points, frame = run_profile(kept, "mu0.3_seed1")
    got = measures(points, frame["surface_level_m"])
    want = {"surface_y": level, "lower_edge_y": y0, "thickness": level - y0, "gradient": grad,
            "surface_velocity": grad * (level - y0), "bed_rotation": OMEGA}
    wrong = [f"{k} {got[k]!r} where the profile has {v!r}" for k, v in want.items() if abs(got[k] - v) > 1e-9]
    if points[0][0] > level:
        wrong.append("took points above the surface")
    # The exponent of a power law with noise-free values, and the names' parts.
    a = exponent([0.6, 1.2, 1.8], [0.03 * x ** 0.37 for x in (0.6, 1.2, 1.8)])
    if abs(a - 0.37) > 1e-12:
        wrong.append(f"exponent {a!r} of a power 0.37")
    if (parts("mu0.3_rpm5.8_seed2") != ("0.3", 5.8, 1.0, 2) or parts("mu0.5_seed3") != ("0.5", RPM, 1.0, 3)
            or parts("mu0.3_E10x_seed1") != ("0.3", RPM, 10.0, 1)):
        wrong.append("misread a run's name")
    return "; ".join(wrong)


def main(argv):
    if "--keep" in argv:
        keep(Path([a for a in argv if not a.startswith("--")][0]))
    kept = HERE / "kept"
    measured, runs = analyse(kept)
    tab, speeds = table(measured, runs), speed_table(kept)
    if "--check" in argv:
        problem = synthetic_problem()
        if problem:
            print(f"studies/drum_flow/analyse.py on a made-up profile: {problem}")
            return 1
        stale = [str(p.relative_to(ROOT)) for p in DOCS if with_tables(p.read_text(), tab, speeds) != p.read_text()]
        if stale:
            print(f"{', '.join(stale)}: the table is not the kept runs' (python3 studies/drum_flow/analyse.py)")
            return 1
        missing = [q for q in quoted_intervals() if q not in tab + speeds]
        if missing:
            print(f"studies/drum_flow/README.md or docs/FIELDS.md quotes {', '.join(missing)}: not in the table")
            return 1
        print(f"studies/drum_flow: the estimators find a made-up profile's answers; the tables are the "
              f"{sum(len(v) for v in runs.values())} kept runs'")
        return 0
    for p in DOCS:
        p.write_text(with_tables(p.read_text(), tab, speeds))
    print(tab + "\n\n" + speeds)
    if "--figure" in argv:
        figure(kept, FIGURE)
        print(f"wrote {FIGURE.relative_to(ROOT)}")
        if speeds:
            speed_figure(kept, SPEED_FIGURE)
            print(f"wrote {SPEED_FIGURE.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
