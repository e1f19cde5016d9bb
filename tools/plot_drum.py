#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Plot the figures of Kohring's rotating-drum paper from `tumble drum` output.

    python3 tools/plot_drum.py run DIR [--out FIGDIR]
    python3 tools/plot_drum.py sweep TABLE.csv [--out FIGDIR]
    python3 tools/plot_drum.py compare DIR1 DIR2 ... [--out FIGDIR]

See tools/README.md for the figures and the files and columns they read.
Needs numpy and matplotlib (Agg backend) and the standard library only.
Exit codes: 0 figures written (some may be skipped with a note), 2 missing or
unreadable input, 3 numpy/matplotlib not available.
"""

import argparse
import csv
import json
import math
import os
import re
import sys


def _import_plotting():
    """numpy and matplotlib; if this interpreter lacks them, try the system one."""
    try:
        import numpy  # noqa: F401
        import matplotlib  # noqa: F401
        return
    except ImportError as error:
        system = "/usr/bin/python3"
        if (os.path.exists(system) and os.path.realpath(sys.executable) != os.path.realpath(system)
                and not os.environ.get("PLOT_DRUM_REEXEC")):
            os.environ["PLOT_DRUM_REEXEC"] = "1"
            os.execv(system, [system, os.path.abspath(__file__)] + sys.argv[1:])
        sys.stderr.write(f"plot_drum.py: error: numpy and matplotlib are needed ({error}); "
                         "install python3-matplotlib and python3-numpy\n")
        sys.exit(3)


_import_plotting()

import numpy as np  # noqa: E402
import matplotlib  # noqa: E402
import matplotlib.ticker  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import PatchCollection  # noqa: E402
from matplotlib.patches import Circle  # noqa: E402

DPI = 150


def read_palette():
    """The grain colours, one per species (component or tag index), from
    tools/palette.txt, which `tumble render` is built with too: a species has
    the same colour in the figures and in the movie."""
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "palette.txt")
    try:
        with open(path) as f:
            return ["#" + line.split()[0] for line in f if line.strip() and not line.startswith("#")]
    except OSError as error:
        sys.stderr.write(f"plot_drum.py: error: cannot read the palette {path}: {error}\n")
        sys.exit(2)


COLOURS = read_palette()
WALL_COLOUR = "0.85"
RPM_PER_RAD_S = 60.0 / (2.0 * math.pi)


def legend_outside(ax, **kwargs):
    """The legend to the right of the axes, where it covers no data."""
    return ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0, **kwargs)


def label_log_axis(axis):
    """At least two labelled ticks on a log axis (call after the data are drawn):
    labels at 1, 2 and 5 times the powers of ten, or at every integer multiple
    over less than a decade; if the range still holds fewer than two, it is
    widened to the nearest ticks around it."""
    lo, hi = sorted(axis.get_view_interval())
    decades = math.log10(hi / lo) if lo > 0 else 0.0
    subs = (1.0,) if decades >= 3 else (1.0, 2.0, 5.0) if decades >= 0.8 else tuple(range(1, 10))
    locator = matplotlib.ticker.LogLocator(base=10.0, subs=subs, numticks=12)
    ticks = [t for t in locator.tick_values(lo, hi) if lo <= t <= hi]
    if len(ticks) < 2:
        around = locator.tick_values(lo / 10.0, hi * 10.0)
        below, above = [t for t in around if t <= lo], [t for t in around if t >= hi]
        if below and above:
            axis.set_view_interval(below[-1], above[0], ignore=True)
    axis.set_major_locator(locator)
    axis.set_major_formatter(matplotlib.ticker.FuncFormatter(lambda v, _: f"{v:.2g}"))
    axis.set_minor_formatter(matplotlib.ticker.NullFormatter())


class InputError(Exception):
    """A missing or unreadable input file: reported with its name, exit code 2."""


# --------------------------------------------------------------------------- reading

def read_toml(path):
    if not os.path.isfile(path):
        raise InputError(f"missing file: {path}")
    try:
        try:
            import tomllib
            with open(path, "rb") as f:
                return tomllib.load(f)
        except ImportError:
            return _read_simple_toml(path)
    except InputError:
        raise
    except Exception as error:  # noqa: BLE001 - any parse failure names the file
        raise InputError(f"cannot read {path}: {error}")


def _read_simple_toml(path):
    """The flat subset `tumble drum` writes: key = value, [[component]] tables."""
    data, table = {}, None
    with open(path) as f:
        for line in f:
            line = line.strip()
            if not line or line.startswith("#"):
                continue
            if line.startswith("[[") and line.endswith("]]"):
                table = {}
                data.setdefault(line[2:-2].strip(), []).append(table)
                continue
            key, _, value = line.partition("=")
            key, value = key.strip(), value.strip()
            if value[:1] in ("'", '"'):
                parsed = value[1:-1]
            elif value in ("true", "false"):
                parsed = value == "true"
            else:
                try:
                    parsed = int(value)
                except ValueError:
                    parsed = float(value)
            (table if table is not None else data)[key] = parsed
    return data


def read_json(path):
    if not os.path.isfile(path):
        raise InputError(f"missing file: {path}")
    try:
        with open(path) as f:
            return json.load(f)
    except Exception as error:  # noqa: BLE001
        raise InputError(f"cannot read {path}: {error}")


def _number(text):
    text = text.strip()
    if text == "" or text.lower() in ("nan", "null", "none", "-"):
        return math.nan
    return float(text)


def column_name(name):
    """A name as tumble writes it into CSV column names: "mean_z_material-1" -> "mean_z_material_1"."""
    return re.sub(r"[^0-9A-Za-z_]", "_", name)


class Columns(dict):
    """The columns of a CSV file by name, looked up as tumble writes names into column
    names (column_name), so tables written before names lost their '-' read alike."""

    def __getitem__(self, name):
        return super().__getitem__(column_name(name))

    def __setitem__(self, name, value):
        super().__setitem__(column_name(name), value)

    def __contains__(self, name):
        return super().__contains__(column_name(name))

    def get(self, name, default=None):
        return super().get(column_name(name), default)


def read_csv(path, comment_lines=False):
    """Columns of a CSV file as a Columns dict: numeric columns as float arrays, others as lists."""
    if not os.path.isfile(path):
        raise InputError(f"missing file: {path}")
    try:
        with open(path, newline="") as f:
            lines = [line for line in f if not (comment_lines and line.startswith("#"))]
        rows = list(csv.reader(lines))
        if not rows:
            raise ValueError("empty file")
        header = [h.strip() for h in rows[0]]
        body = [r for r in rows[1:] if r]
        columns = Columns()
        for i, name in enumerate(header):
            values = [r[i] if i < len(r) else "" for r in body]
            try:
                columns[name] = np.array([_number(v) for v in values], dtype=float)
            except ValueError:
                columns[name] = [v.strip() for v in values]
        return columns
    except InputError:
        raise
    except Exception as error:  # noqa: BLE001
        raise InputError(f"cannot read {path}: {error}")


def snapshot_time(path, table):
    """", t = T s" of a particle snapshot: its time column, or the first line of one written
    before that column."""
    if "time" in table and len(table["time"]):
        return f", t = {table['time'][0]:.3g} s"
    with open(path) as f:
        first = f.readline()
    # "# time = 0.256 s, step = 34304"
    if first.startswith("#") and "time" in first:
        try:
            value = float(first.split("=")[1].split()[0].rstrip(","))
            return f", t = {value:.3g} s"
        except (IndexError, ValueError):
            pass
    return ""


# --------------------------------------------------------------------------- physics

def hogg_mean_z(n_rev, d, length, terms=400):
    """<z>(N) of the Hogg solution for a component starting in one half of a bed of length L.

    <z>(N) = 8L/pi^3 sum_{n>=1} (-1)^(n+1)/(2n-1)^3 exp(-(2n-1)^2 pi^2 D N / L^2),
    which is L/4 at N = 0 and decays to 0.
    """
    n_rev = np.asarray(n_rev, dtype=float)
    k = 2.0 * np.arange(1, terms + 1) - 1.0
    signs = np.where(np.arange(terms) % 2 == 0, 1.0, -1.0)
    decay = np.exp(-np.outer(n_rev, k ** 2) * math.pi ** 2 * d / length ** 2)
    return 8.0 * length / math.pi ** 3 * (decay * (signs / k ** 3)).sum(axis=1)


# --------------------------------------------------------------------------- output

class Writer:
    def __init__(self, outdir):
        self.outdir = outdir
        self.written = []
        self.skipped = []

    def save(self, fig, name):
        os.makedirs(self.outdir, exist_ok=True)
        for ext in ("png", "svg"):
            path = os.path.join(self.outdir, f"{name}.{ext}")
            fig.savefig(path, dpi=DPI, metadata={"Date": None} if ext == "svg" else None)
            self.written.append(path)
        plt.close(fig)

    def skip(self, name, reason):
        print(f"note: {name} skipped: {reason}")
        self.skipped.append(name)

    def report(self):
        print(f"{len(self.written)} files written:")
        for path in self.written:
            print(f"  {path}")


# --------------------------------------------------------------------------- one run

class Run:
    """A `tumble drum` run directory."""

    def __init__(self, directory):
        if not os.path.isdir(directory):
            raise InputError(f"run directory not found: {directory}")
        if not os.path.isfile(os.path.join(directory, "drum_run.toml")) and \
                os.path.isfile(os.path.join(directory, "run.json")):
            raise InputError(f"{directory} is a run of a scenario (tumble run: it has run.json), not of tumble drum; "
                             "the figures are drawn from a drum run directory (it has drum_run.toml). A scenario "
                             "run's files are read as they are: time_series.csv and snapshots/*.csv with numpy or "
                             "pandas, particles.pvd in ParaView, and tumble render DIR draws a movie")
        self.dir = directory
        self.config = read_toml(self.path("drum_run.toml"))
        self.series = read_csv(self.path("drum_series.csv"))
        self.summary = read_json(self.path("summary.json")) if os.path.isfile(
            self.path("summary.json")) else None
        comps = self.config.get("component") or []
        if not comps and self.summary:
            comps = self.summary.get("components", [])
        if not comps:
            raise InputError(f"no [[component]] tables in {self.path('drum_run.toml')}")
        self.components = [c["name"] for c in comps]
        self.start_side = [float(c.get("start_side", -1.0 if i == 0 else 1.0))
                           for i, c in enumerate(comps)]
        self.mode = str(self.config.get("mode", "")) or (self.summary or {}).get("mode", "")
        self.omega = float(self.config.get("omega", math.nan))
        self.froude = float(self.config.get("froude", math.nan))
        self.length = float((self.summary or {}).get("bed_length")
                            or self.config.get("inner_length", 0.12))

    def path(self, name):
        return os.path.join(self.dir, name)

    def component_summary(self, index):
        for c in (self.summary or {}).get("components", []):
            if c.get("name") == self.components[index]:
                return c
        return None

    def fit(self, index):
        """(D, D_stderr, amplitude) of the free-amplitude Hogg fit of a component from
        summary.json (of an earlier tumble: the pinned fit, amplitude L/4), or None where
        D was not determined: an undetermined value is never drawn."""
        c = self.component_summary(index)
        if c is None:
            return None
        h = c.get("hogg_free")
        if h is not None:
            if not h.get("determined") or h.get("D") is None:
                return None
            return (float(h["D"]), h.get("D_stderr"), float(h["amplitude"]))
        if c.get("D") is None or not c.get("determined", True):
            return None
        return (float(c["D"]), c.get("D_stderr"), self.length / 4.0)

    def msd(self, index):
        """The grains' MSD estimate of a component (dict with D, D_lo, D_hi, fit lags),
        or None where it was not determined."""
        c = self.component_summary(index)
        m = (c or {}).get("msd")
        return m if m and m.get("determined") and m.get("D") is not None else None

    def label(self):
        return f"\u03c9 = {self.omega:g} rad/s ({self.omega * RPM_PER_RAD_S:.3g} rpm)"

    def paper_z_figure(self):
        return "Fig. 2 (self-diffusion)" if self.mode == "self" else "Fig. 4 (two-component)"


def fig_setup(run, w):
    name = "fig1_setup"
    snap = run.path(os.path.join("snapshots", "000000.csv"))
    if not os.path.isfile(snap):
        w.skip(name, f"no initial snapshot {snap}")
        return
    s = read_csv(snap, comment_lines=True)
    needed = ("x", "y", "z", "radius", "tag", "kinematic")
    if any(k not in s for k in needed):
        raise InputError(f"{snap}: expected columns {', '.join(needed)}")
    wall = (s["kinematic"] > 0) | (s["tag"] < 0)
    fig, (side, end) = plt.subplots(1, 2, figsize=(12, 4.8),
                                    gridspec_kw={"width_ratios": [1.45, 1]})
    handles = []
    # The wall is drawn behind all grains (a cut-away view); the grains are drawn far to
    # near: side view (z, y) seen from +x, end view (x, y) seen from +z.
    for ax, (h, v, depth) in ((side, ("z", "y", "x")), (end, ("x", "y", "z"))):
        for group, zorder in ((wall, 1), (~wall, 2)):
            idx = np.flatnonzero(group)
            idx = idx[np.argsort(s[depth][idx], kind="stable")]
            patches = [Circle((s[h][i] * 1e3, s[v][i] * 1e3), s["radius"][i] * 1e3) for i in idx]
            colours = [WALL_COLOUR if wall[i] else COLOURS[int(s["tag"][i]) % len(COLOURS)]
                       for i in idx]
            if patches:
                ax.add_collection(PatchCollection(patches, facecolors=colours,
                                                  edgecolors="0.55" if zorder == 1 else "0.2",
                                                  linewidths=0.2 if zorder == 1 else 0.3,
                                                  zorder=zorder))
        ax.set_aspect("equal")
        ax.autoscale_view()
        ax.set_xlabel(f"{h} (mm)")
        ax.set_ylabel(f"{v} (mm)")
    side.set_title("side view (drum axis z horizontal)")
    end.set_title("end view (seen along the axis)")
    for i, cname in enumerate(run.components):
        count = int(np.sum(~wall & (s["tag"] == i)))
        handles.append(Circle((0, 0), 1, facecolor=COLOURS[i % len(COLOURS)], edgecolor="0.3",
                              label=f"C{i + 1}: {cname} ({count} grains)"))
    handles.append(Circle((0, 0), 1, facecolor=WALL_COLOUR, edgecolor="0.3",
                          label=f"wall ({int(np.sum(wall))} particles)"))
    fig.legend(handles=handles, loc="lower center", ncol=len(handles), frameon=False)
    fig.suptitle(f"Fig. 1: set-up, {run.mode} mode, initial state "
                 f"(snapshots/000000.csv{snapshot_time(snap, s)}); wall drawn behind the grains")
    fig.tight_layout(rect=(0, 0.07, 1, 0.95))
    w.save(fig, name)


def _plot_z(ax, run, colour_for, label_prefix="", marker_for=None):
    n = run.series["revolutions"]
    n_fine = np.linspace(0.0, max(float(np.nanmax(n)), 1e-9), 400)
    drew_any = False
    for i, cname in enumerate(run.components):
        col = f"mean_z_{cname}"
        if col not in run.series:
            continue
        drew_any = True
        colour = colour_for(i)
        z = run.series[col] * 1e3
        err = run.series.get(f"mean_z_stderr_{cname}")
        marker = marker_for(i) if marker_for else "o"
        ax.plot(n, z, marker, ms=3, color=colour, label=f"{label_prefix}{cname} (measured)")
        if err is not None:
            ax.errorbar(n, z, yerr=err * 1e3, fmt="none", ecolor=colour, alpha=0.3, lw=0.8)
        fit = run.fit(i)
        if fit is None:
            continue
        d, d_err, amplitude = fit
        curve = run.start_side[i] * amplitude * 4.0 / run.length * hogg_mean_z(n_fine, d, run.length) * 1e3
        err_text = f" \u00b1 {1.96 * d_err:.2g} (95 %)" if d_err is not None else ""
        ax.plot(n_fine, curve, "-", color=colour, lw=1.2,
                label=f"{label_prefix}{cname}: Hogg, amplitude free, D = {d:.3g}{err_text} m\u00b2/rev")
    return drew_any


def fig_z(run, w):
    name = "fig_z"
    fig, ax = plt.subplots(figsize=(10.5, 5))
    if not _plot_z(ax, run, lambda i: COLOURS[i % len(COLOURS)]):
        plt.close(fig)
        w.skip(name, f"no mean_z_ columns in {run.path('drum_series.csv')}")
        return
    if not run.summary:
        print(f"note: {name}: no {run.path('summary.json')}, Hogg curves left out")
    ax.axhline(0.0, color="0.6", lw=0.6)
    ax.set_xlabel("revolutions N")
    ax.set_ylabel("<z> (mm)")
    ax.set_title(f"{run.paper_z_figure()}: average position, {run.label()}\n"
                 f"bed length L = {run.length * 1e3:g} mm", fontsize=10)
    legend_outside(ax, fontsize=7)
    fig.tight_layout()
    w.save(fig, name)


def fig_profiles(run, w):
    name = "fig_profiles"
    path = run.path("profile_comparison.csv")
    if not os.path.isfile(path):
        w.skip(name, f"no {path}")
        return
    p = read_csv(path)
    if any(k not in p for k in ("revolutions", "z", "measured", "hogg")) or len(p["z"]) == 0:
        w.skip(name, f"{path} has no revolutions, z, measured, hogg data")
        return
    # The component compared is the one that started on the right (DRUM.md).
    right = [c for c, side in zip(run.components, run.start_side) if side > 0]
    cname = right[0] if right else run.components[-1]
    fig, ax = plt.subplots(figsize=(10, 5))
    levels = sorted(set(np.round(p["revolutions"], 9)))
    cmap = plt.get_cmap("viridis")
    z_step = np.array([-run.length / 2, 0, 0, run.length / 2]) * 1e3
    ax.plot(z_step, [0, 0, 1, 1], ":", color="0.5", lw=1, label="N = 0 (Hogg initial step)")
    for k, level in enumerate(levels):
        sel = np.round(p["revolutions"], 9) == level
        z = p["z"][sel] * 1e3
        order = np.argsort(z)
        measured, hogg = p["measured"][sel][order], p["hogg"][sel][order]
        z = z[order]
        colour = cmap(0.1 + 0.8 * k / max(len(levels) - 1, 1))
        ok = measured >= 0  # -1: empty bin
        ax.plot(z[ok], measured[ok], "o", color=colour, ms=5, label=f"N = {level:.3g} measured")
        ax.plot(z, hogg, "-", color=colour, lw=1.3, label=f"N = {level:.3g} Hogg")
    ax.set_xlim(-run.length / 2 * 1e3, run.length / 2 * 1e3)
    ax.set_ylim(-0.05, 1.05)
    ax.set_xlabel("z (mm)")
    ax.set_ylabel(f"concentration C(z, N) of {cname}")
    collapse = (run.summary or {}).get("profile_collapse") or {}
    d_text = f", D = {collapse['D']:.3g} m\u00b2/rev ({collapse.get('D_source', '')})" \
        if collapse.get("D") is not None else ""
    ax.set_title(f"Axial concentration profile against the Hogg solution\n"
                 f"{run.mode} mode, {run.label()}{d_text}", fontsize=10)
    legend_outside(ax, fontsize=7)
    fig.tight_layout()
    w.save(fig, name)


def fig_energy(run, w):
    name = "fig_energy"
    n = run.series["revolutions"]
    cols = [f"kinetic_per_grain_{c}" for c in run.components]
    if any(c not in run.series for c in cols):
        w.skip(name, f"no kinetic_per_grain_ columns in {run.path('drum_series.csv')}")
        return
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(10.5, 7), sharex=True)
    for i, cname in enumerate(run.components):
        top.plot(n, run.series[cols[i]], "-o", ms=2.5, lw=1, color=COLOURS[i % len(COLOURS)],
                 label=cname)
    top.set_yscale("log")
    label_log_axis(top.yaxis)
    top.set_ylabel("kinetic energy per grain (J)")
    legend_outside(top, fontsize=8)
    top.set_title(f"Translational kinetic energy, {run.mode} mode, {run.label()}", fontsize=10)
    if len(run.components) >= 2:
        a, b = run.components[0], run.components[1]
        rotating = n > 0
        with np.errstate(divide="ignore", invalid="ignore"):
            per_grain = run.series[f"kinetic_per_grain_{b}"] / run.series[f"kinetic_per_grain_{a}"]
            total_b, total_a = (run.series.get(f"kinetic_energy_{b}"),
                                run.series.get(f"kinetic_energy_{a}"))
            total = total_b / total_a if total_b is not None and total_a is not None else None
        s = run.summary or {}
        lines = [("per grain", per_grain, "kinetic_energy_ratio_per_grain", "tab:green"),
                 ("total", total, "kinetic_energy_ratio_total", "tab:purple")]
        for label, ratio, key, colour in lines:
            if ratio is None:
                continue
            bottom.plot(n[rotating], ratio[rotating], "o", ms=2.5, color=colour,
                        label=f"{label}: {b} / {a}")
            if s.get(key) is not None:
                bottom.axhline(s[key], color=colour, lw=1.2,
                               label=f"{label}: mean over the rotation, {s[key]:.3g}")
            ref = s.get(f"{key}_equal_velocity")
            if ref is not None:
                bottom.axhline(ref, color=colour, ls="--", lw=1.2,
                               label=f"{label}: equal velocities, {ref:.3g}")
        bottom.set_yscale("log")
        label_log_axis(bottom.yaxis)
        bottom.set_ylabel(f"kinetic energy ratio {b} / {a}")
        legend_outside(bottom, fontsize=7)
        bottom.set_title("Fig. 6 quantity for one speed: ratio (points), "
                         "equal-velocity reference (dashed)", fontsize=9)
    bottom.set_xlabel("revolutions N")
    fig.tight_layout()
    w.save(fig, name)


def fig_depth(run, w):
    """Where the axial motion happens: <dz^2> per revolution and the share of
    it by depth below the free surface (depth_mobility.csv)."""
    name = "fig_depth"
    path = run.path("depth_mobility.csv")
    if not os.path.isfile(path):
        w.skip(name, f"no {path} (the run has fewer than two particle snapshots: tumble drum --snapshots)")
        return
    table = read_csv(path)
    layers = table["layer"]
    labels = [f"{int(k)}-{int(k) + 1}" for k in layers]
    labels[0] = "< 1"
    labels[-1] = f"> {int(layers[-1])}"
    fig, (left, right) = plt.subplots(1, 2, figsize=(13, 4.2), sharey=True)
    for i, cname in enumerate(run.components):
        colour = COLOURS[i % len(COLOURS)]
        msd = table[f"msd_per_rev_{cname}"]
        left.plot(msd, layers, "-o", color=colour, label=cname)
        right.plot(table[f"share_{cname}"], layers, "-o", color=colour,
                   label=f"{cname}: share of <\u0394z\u00b2>")
        right.plot(table[f"occupancy_{cname}"], layers, ":", marker="s", ms=3, color=colour,
                   label=f"{cname}: share of grains")
    left.set_xscale("log")
    label_log_axis(left.xaxis)
    left.set_xlabel("axial mean squared displacement per revolution <\u0394z\u00b2>/\u0394N (m\u00b2/rev)")
    left.set_ylabel("depth below the free surface (grain diameters)")
    left.set_yticks(layers)
    left.set_yticklabels(labels)
    left.invert_yaxis()
    left.legend(fontsize=8)
    right.set_xlabel("fraction")
    right.set_xlim(0, 1)
    legend_outside(right, fontsize=7)
    fig.suptitle(f"Axial motion by depth, {run.mode} mode, {run.label()}", fontsize=10)
    fig.tight_layout()
    w.save(fig, name)


def fig_msd(run, w):
    """The grains' axial mean squared displacement against lag (axial_msd.csv), with
    the long-lag line of the fitted D and its 95 % interval."""
    name = "fig_msd"
    path = run.path("axial_msd.csv")
    if not os.path.isfile(path):
        w.skip(name, f"no {path} (the run has too few particle snapshots: tumble drum --snapshots)")
        return
    table = read_csv(path)
    fig, ax = plt.subplots(figsize=(11, 5))
    for i, cname in enumerate(run.components):
        col = f"msd_{cname}"
        if col not in table:
            continue
        colour = COLOURS[i % len(COLOURS)]
        lag, msd = table["lag"], table[col]
        m = run.msd(i)
        label = f"{cname}" + ("" if m else ": D not determined")
        ax.plot(lag, msd * 1e6, "o", ms=3, color=colour, label=label)
        if m:
            lo, hi = float(m["fit_lag_lo"]), float(m["fit_lag_hi"])
            anchor = np.interp(lo, lag, msd)
            x = np.array([lo, hi])
            ax.plot(x, (anchor + 2.0 * m["D"] * (x - lo)) * 1e6, "-", color=colour, lw=2,
                    label=f"{cname}: D = {m['D']:.3g} m\u00b2/rev, 95 % [{m['D_lo']:.3g}, {m['D_hi']:.3g}]"
                          f" (lags {lo:.3g}-{hi:.3g} rev)")
    ax.set_xlabel("lag (revolutions)")
    ax.set_ylabel("axial mean squared displacement (mm\u00b2)")
    ax.set_title(f"Grains' axial MSD, {run.mode} mode, {run.label()}", fontsize=10)
    legend_outside(ax, fontsize=7)
    fig.tight_layout()
    w.save(fig, name)


def fig_collapse(run, w):
    """C(z, N) against z / sqrt(N) for every sample after the start-up: while the
    mixing front is far from the caps the profiles fall on 1/2 (1 + erf(u / 2 sqrt(D)))."""
    name = "fig_collapse"
    collapse = (run.summary or {}).get("profile_collapse")
    path = run.path("profiles.csv")
    if not collapse or collapse.get("D") is None or not os.path.isfile(path):
        w.skip(name, "no profile_collapse in summary.json or no profiles.csv")
        return
    p = read_csv(path)
    index = run.components.index(collapse["component"])
    first = float(collapse.get("first_revolution", 1.0))
    sel = (p["component"] == index) & (p["revolutions"] >= first) & (p["concentration"] >= 0)
    d = float(collapse["D"])
    if not np.any(sel) or not d > 0:
        w.skip(name, f"no profiles after N = {first:g} or no positive D")
        return
    u = p["z"][sel] / np.sqrt(p["revolutions"][sel]) * 1e3
    fig, ax = plt.subplots(figsize=(7.5, 5))
    points = ax.scatter(u, p["concentration"][sel], c=p["revolutions"][sel], s=8, cmap="viridis")
    fig.colorbar(points, ax=ax, label="revolutions N")
    grid = np.linspace(u.min(), u.max(), 300)
    erf = np.vectorize(math.erf)
    ax.plot(grid, 0.5 * (1.0 + erf(grid * 1e-3 / (2.0 * math.sqrt(d)))), "k-",
            label=f"1/2 (1 + erf(u / 2\u221aD)), D = {d:.3g} m\u00b2/rev ({collapse.get('D_source', '')})")
    ax.set_xlabel("u = z / \u221aN (mm per \u221arevolution)")
    ax.set_ylabel(f"C(z, N) of {collapse['component']}")
    ax.set_title(f"Profile collapse, N >= {first:g}: rms difference {collapse['rms']:.3f}\n"
                 f"{run.mode} mode, {run.label()}", fontsize=10)
    ax.legend(fontsize=7, loc="upper left")  # C is near 0 on the left, near 1 on the right
    fig.tight_layout()
    w.save(fig, name)


def _finite_mean(values):
    """The mean of the finite values; NaN (not drawn) if there are none."""
    finite = values[np.isfinite(values)]
    return float(np.mean(finite)) if len(finite) else math.nan


def fig_bed_structure(run, w):
    """Segregation and the free surface along the axis (bed_structure.csv): the bed's
    grain volume per slice relative to a uniform bed at several N; per slice, over the
    snapshots, each kind's mean distance from the slice's centroid and the surface angle."""
    name = "fig_bed_structure"
    path = run.path("bed_structure.csv")
    if not os.path.isfile(path):
        w.skip(name, f"no {path} (tumble analyze, needs snapshots after the start-up)")
        return
    t = read_csv(path)
    n_values = sorted(set(np.round(t["revolutions"], 9)))
    fig, (volume, radial, angle) = plt.subplots(1, 3, figsize=(14, 4.2))
    cmap = plt.get_cmap("viridis")
    for k, n in enumerate(n_values[:: max(1, len(n_values) // 6)]):
        sel = np.round(t["revolutions"], 9) == n
        volume.plot(t["z"][sel] * 1e3, t["relative_volume"][sel], "-o", ms=3,
                    color=cmap(k / 6.0), label=f"N = {n:.3g}")
    volume.axhline(1.0, color="0.6", lw=0.8)
    volume.set_xlabel("z (mm)")
    volume.set_ylabel("grain volume / uniform bed")
    volume.set_title("bed volume along the axis", fontsize=9)
    volume.legend(fontsize=7)
    slices = sorted(set(t["slice"]))
    z = np.array([np.mean(t["z"][t["slice"] == s]) for s in slices]) * 1e3
    for i, cname in enumerate(run.components):
        col = f"mean_distance_{cname}"
        if col in t:
            radial.plot(z, [_finite_mean(t[col][t["slice"] == s]) * 1e3 for s in slices], "-o", ms=3,
                        color=COLOURS[i % len(COLOURS)], label=cname)
    radial.set_xlabel("z (mm)")
    radial.set_ylabel("mean distance from the slice's centroid (mm)")
    radial.set_title("radial composition (lower: nearer the core)", fontsize=9)
    radial.legend(fontsize=7)
    if "surface_angle" in t:
        angle.plot(z, [_finite_mean(t["surface_angle"][t["slice"] == s]) for s in slices], "-o", ms=3, color="0.3")
    angle.set_xlabel("z (mm)")
    angle.set_ylabel("free-surface inclination (degrees)")
    angle.set_title("free surface per axial slice", fontsize=9)
    fig.suptitle(f"Bed structure after the start-up, {run.mode} mode, {run.label()}", fontsize=10)
    fig.tight_layout()
    w.save(fig, name)


def fig_flowing_layer(run, w):
    """The flowing layer described by its coarse-grained fields (flowing_layer/
    of `tumble fields DIR --frame drum`, which `tumble plot` computes where it
    is missing; docs/FIELDS.md "The drum's frame"): the
    cross-section's solid fraction and velocity with the fitted free surface,
    and against depth below it the velocity along the surface, the solid
    fraction, the shear rate, the pressure, mu and I."""
    name = "fig_flowing_layer"
    folder = run.path("flowing_layer")
    numbers = os.path.join(folder, "drum_frame.json")
    if not os.path.isfile(numbers):
        w.skip(name, f"no {numbers} (tumble fields {run.dir} --frame drum)")
        return
    surface = read_json(numbers)
    section = read_csv(os.path.join(folder, "fields.csv"))
    profile = read_csv(os.path.join(folder, "profile.csv"))
    x, y = np.unique(section["x"]), np.unique(section["y"])
    shape = (len(y), len(x))  # the rows run x fastest, then y
    phi = section["solid_fraction"].reshape(shape)
    fig = plt.figure(figsize=(14, 7.5))
    grid = fig.add_gridspec(2, 4, width_ratios=[2.2, 1, 1, 1])
    cut = fig.add_subplot(grid[:, 0])
    image = cut.pcolormesh(x * 1e3, y * 1e3, phi, cmap="Greys", vmin=0.0, vmax=max(0.65, phi.max()),
                           shading="nearest")
    fig.colorbar(image, ax=cut, shrink=0.5, location="bottom", label="solid fraction \u03c6")
    every = max(1, len(x) // 25)
    vx = section["velocity_x"].reshape(shape)
    vy = section["velocity_y"].reshape(shape)
    held = phi > 0.5 * surface["surface_solid_fraction"]
    X, Y = np.meshgrid(x * 1e3, y * 1e3)
    sel = (slice(None, None, every), slice(None, None, every))
    cut.quiver(X[sel][held[sel]], Y[sel][held[sel]], vx[sel][held[sel]], vy[sel][held[sel]], color="tab:blue",
               angles="xy", scale_units="xy", scale=None, width=0.003)
    a = math.radians(surface["angle_of_repose_deg"])
    t, n = np.array([-math.cos(a), -math.sin(a)]), np.array([-math.sin(a), math.cos(a)])
    half = surface["surface_half_length_m"]
    for span, style in ((1.0, ":"), (surface["span"], "-")):
        ends = np.array([surface["surface_level_m"] * n + s * t for s in (-span * half, span * half)]) * 1e3
        cut.plot(ends[:, 0], ends[:, 1], style, color="tab:red", lw=1.5)
    cut.set_aspect("equal")
    cut.set_xlabel("x (mm)")
    cut.set_ylabel("y (mm)")
    cut.set_title(f"\u03c6 and velocity; free surface at {surface['angle_of_repose_deg']:.1f}\u00b0\n"
                  "(red: its chord; solid: the part averaged)", fontsize=9)
    d = profile["d"] * 1e3
    thickness = surface["layer_thickness_m"]
    panels = [("velocity_s", "u along the surface, downhill (m/s)"),
              ("solid_fraction", "solid fraction \u03c6"),
              ("shear_rate", "shear rate \u03b3\u0307 (1/s)"),
              ("pressure", "pressure p (Pa)"),
              ("friction", "\u03bc = \u03c4 / p"),
              ("inertial_number", "inertial number I")]
    # mu and I are ratios of vanishing stresses where the grains thin out
    # above the surface: drawn where phi is a quarter of the surface's or more.
    dense = profile["solid_fraction"] >= 0.25 * surface["surface_solid_fraction"]
    for k, (column, label) in enumerate(panels):
        ax = fig.add_subplot(grid[k // 3, 1 + k % 3])
        values = profile[column]
        if column in ("friction", "inertial_number"):
            values = np.where(dense, values, np.nan)
        ax.plot(values, d, "-", color="0.2")
        ax.axhline(0.0, color="tab:red", lw=0.8)
        if thickness is not None:
            ax.axhline(thickness * 1e3, color="tab:blue", lw=0.8, ls="--")
        if column == "velocity_s":
            ax.axvline(0.0, color="0.6", lw=0.8)
        ax.set_xlabel(label, fontsize=8)
        ax.set_ylabel("depth below the surface d (mm)", fontsize=8)
        ax.set_ylim(d.max(), d.min())
        ax.tick_params(labelsize=7)
    layer = "no flowing layer found" if thickness is None else (
        f"flowing layer {thickness * 1e3:.1f} mm ({surface['layer_thickness_diameters']:.1f} d) deep")
    fig.suptitle(f"The flowing layer, {run.mode} mode, {run.label()}: surface velocity "
                 f"{surface['surface_velocity_m_per_s']:.3g} m/s, {layer}", fontsize=10)
    fig.tight_layout(rect=(0, 0, 1, 0.96))
    w.save(fig, name)


def _band_rows(path):
    """band_profile.csv as ({quantity: N of its samples}, {quantity: array [sample, bin]})."""
    t = read_csv(path)
    bins = sorted((int(k[4:]) for k in t if k.startswith("bin_")))
    quantity = np.array(t["quantity"])
    table = np.column_stack([t[f"bin_{b}"] for b in bins]) if bins else np.zeros((len(quantity), 0))
    rows = {q: table[quantity == q] for q in set(quantity)}
    return {q: t["revolutions"][quantity == q] for q in set(quantity)}, rows


def fig_bands(run, w):
    """Axial bands (docs/BAND-ANALYSIS.md): the kymograph C(z, N) with the merges, the radial
    core per slice (phi in the inner minus the outer third about the bed's centre)
    against z and N, the band count against log N, the dominant wavelength, the
    contrast, the radial core of the whole bed per sample and per block of N, the
    composition of the end bands, and how fast the start's boundaries blur, D at
    three compositions per block of N (band_profile.csv, bands.csv, bands.json,
    band_edges.csv)."""
    name = "fig_bands"
    profile, series = run.path("band_profile.csv"), run.path("bands.csv")
    if not (os.path.isfile(profile) and os.path.isfile(series)):
        w.skip(name, f"no {profile} or {series} (a run from before the band analysis; tumble analyze)")
        return
    n_of, rows = _band_rows(profile)
    n_rev = n_of["small_fraction"]
    phi = rows["small_fraction"]
    t = read_csv(series)
    info = read_json(run.path("bands.json")) if os.path.isfile(run.path("bands.json")) else {}
    small = info.get("species", run.components[-1])
    large = info.get("other", run.components[0])
    fig, axes = plt.subplots(3, 3, figsize=(16, 12.5))
    kymo, core_kymo, count, wave, contrast, core, blocks, ends, blur = axes.ravel()
    from matplotlib.colors import LinearSegmentedColormap, TwoSlopeNorm
    cmap = LinearSegmentedColormap.from_list("species", [COLOURS[0], "#ffffff", COLOURS[1 % len(COLOURS)]])
    mean = float(np.nanmean(t["mean"])) if len(t["mean"]) and np.isfinite(t["mean"]).any() else 0.5
    mean = min(max(mean, 1e-3), 1.0 - 1e-3)
    edges_z = np.linspace(-0.5, 0.5, phi.shape[1] + 1) * run.length * 1e3
    edges_n = np.concatenate([n_rev, [n_rev[-1] + (n_rev[-1] - n_rev[-2] if len(n_rev) > 1 else 1.0)]])
    mesh = kymo.pcolormesh(edges_z, edges_n, np.ma.masked_invalid(phi), cmap=cmap,
                           norm=TwoSlopeNorm(vmin=0.0, vcenter=mean, vmax=1.0), shading="flat")
    fig.colorbar(mesh, ax=kymo, label=f"volume fraction of {small}")
    for e in info.get("events", []):
        if e.get("kind") in ("merge", "end", "vanish"):
            kymo.plot(e["z"] * 1e3, e["revolutions"], "kx", ms=6)
    kymo.set_xlabel("z (mm)")
    kymo.set_ylabel("revolutions N")
    kymo.set_title("kymograph C(z, N) (x: a band vanishes)", fontsize=9)
    # Per slice, core minus periphery; the samples of an older tumble
    # (core_fraction, wall_fraction: from the axis) are not shown.
    if "bed_core_fraction" in rows and "bed_periphery_fraction" in rows:
        n_core = n_of["bed_core_fraction"]
        excess = rows["bed_core_fraction"] - rows["bed_periphery_fraction"]
        edges_c = np.concatenate([n_core, [n_core[-1] + (n_core[-1] - n_core[-2] if len(n_core) > 1 else 1.0)]])
        from matplotlib.colors import Normalize
        mesh_c = core_kymo.pcolormesh(edges_z, edges_c, np.ma.masked_invalid(excess), cmap=cmap,
                                      norm=Normalize(vmin=-1.0, vmax=1.0), shading="flat")
        fig.colorbar(mesh_c, ax=core_kymo, label=f"core minus periphery, volume fraction of {small}")
    core_kymo.set_xlim(edges_z[0], edges_z[-1])
    core_kymo.set_ylim(edges_n[0], edges_n[-1])
    core_kymo.set_xlabel("z (mm)")
    core_kymo.set_ylabel("revolutions N")
    core_kymo.set_title("radial core per slice: inner minus outer third about the bed's centre", fontsize=9)
    later = t["revolutions"] > 0
    count.step(t["revolutions"][later], t["bands"][later], where="post", color="0.2")
    count.set_xscale("log")
    count.set_xlabel("revolutions N")
    count.set_ylabel("number of bands")
    # Below 0 and above the largest count, so that a run of no bands shows its line.
    count.set_ylim(-0.3, max(1.0, float(np.max(t["bands"], initial=0))) + 0.5)
    count.yaxis.set_major_locator(matplotlib.ticker.MaxNLocator(integer=True))
    count.set_title("bands against log N (0: none above the threshold)", fontsize=9)
    spectrum_path = run.path("band_spectrum.csv")
    if os.path.isfile(spectrum_path):
        sp = read_csv(spectrum_path)
        modes = sorted(int(k[len("wavelength_"):]) for k in sp if k.startswith("wavelength_"))
        if modes and len(sp["revolutions"]):
            power = np.column_stack([sp[f"wavelength_{m}"] for m in modes])
            peak = power.max(axis=1, keepdims=True)
            power = np.divide(power, peak, out=np.zeros_like(power), where=peak > 0)
            factor = 1.0 if info.get("spectrum", {}).get("transform") == "fourier" else 2.0
            k_edges = np.arange(len(modes) + 1) + 0.5
            n_sp = sp["revolutions"]
            n_edges = np.concatenate([n_sp, [n_sp[-1] + (n_sp[-1] - n_sp[-2] if len(n_sp) > 1 else 1.0)]])
            wave.pcolormesh(n_edges, factor * run.length / k_edges * 1e3, power.T, cmap="Greys", shading="flat")
            wave.set_yscale("log")
    wave.plot(t["revolutions"], t["dominant_wavelength"] * 1e3, "o", ms=3, color=COLOURS[1 % len(COLOURS)],
              label="dominant")
    wave.axhline(2.0 * run.config.get("inner_radius", math.nan) * 1e3, color="0.6", lw=0.8, ls="--",
                 label="drum diameter")
    wave.set_xlabel("revolutions N")
    wave.set_ylabel("wavelength (mm)")
    wave.set_title("spectrum of C(z) - mean (grey: power / largest)", fontsize=9)
    wave.legend(fontsize=7)
    contrast.plot(t["revolutions"], t["contrast"], "-", color="0.2", label="mean |phi - mean|")
    contrast.plot(t["revolutions"], t["band_contrast"], "o", ms=3, color=COLOURS[1 % len(COLOURS)],
                  label=f"{small}-rich minus {large}-rich bands")
    contrast.set_xlabel("revolutions N")
    contrast.set_ylabel("contrast in volume fraction")
    contrast.set_title("band contrast", fontsize=9)
    contrast.legend(fontsize=7)
    core.plot(t["revolutions"], t["core_fraction"], "-", color=COLOURS[1 % len(COLOURS)],
              label="inner third (the core)")
    core.plot(t["revolutions"], t["periphery_fraction"], "-", color=COLOURS[0],
              label="outer third (wall and surface)")
    core.set_xlabel("revolutions N")
    core.set_ylabel(f"volume fraction of {small}")
    core.set_title("radial core: composition by distance from the bed's centre", fontsize=9)
    core.legend(fontsize=7)
    if _plot_blocks(blocks, info.get("radial_core", {}).get("blocks", []), "core_excess", "0.2", "o",
                    "95 % interval (correlated revolutions)"):
        blocks.set_xscale("log")
        blocks.xaxis.set_major_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
        blocks.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
        blocks.legend(fontsize=7)
    blocks.axhline(0.0, color="0.6", lw=0.8)
    blocks.set_xlabel("revolutions N (blocks [1, 2), [2, 4), ...)")
    blocks.set_ylabel("core minus periphery")
    blocks.set_title("radial core per block of N (bands.json)", fontsize=9)
    for column, marker, label in (("left_end_fraction", "<", "left end band"),
                                  ("right_end_fraction", ">", "right end band")):
        ends.plot(t["revolutions"], t[column], marker, ms=4, ls="none", color="0.3" if marker == "<" else "0.6",
                  label=label)
    layers = info.get("end_layers") or {}
    for side, colour, marker in (("left", COLOURS[0], "<"), ("right", COLOURS[1 % len(COLOURS)], ">")):
        _plot_blocks(ends, layers.get(side, []), "excess", colour, marker,
                     f"{side} end layer ({100 * layers.get('width', 0.02):.3g} cm) minus the mean, per block",
                     shift=mean)
    ends.axhline(mean, color="0.6", lw=0.8, ls="--", label="mean")
    ends.set_ylim(0, 1.6)  # the legend above the fractions (0 to 1)
    ends.set_yticks(np.linspace(0, 1, 6))
    ends.set_xlabel("revolutions N")
    ends.set_ylabel(f"volume fraction of {small}")
    ends.set_title("composition of the end bands, and of the layers at the caps", fontsize=9)
    ends.legend(fontsize=6, loc="upper center")
    _plot_edge_blur(blur, run.path("band_edges.csv"), small, large)
    fig.suptitle(f"Axial bands, {run.mode} mode, {run.label()}", fontsize=10)
    fig.tight_layout()
    w.save(fig, name)


def _plot_edge_blur(ax, path, small, large):
    """D of the start's boundaries per block of N at u = 0.25, 0.5, 0.75
    (band_edges.csv; docs/BAND-ANALYSIS.md, Boltzmann-Matano): one colour per
    composition, one marker per boundary. A constant D is Fickian blur."""
    ax.set_xlabel("revolutions N (block means)")
    ax.set_ylabel("D (m$^2$ per revolution)")
    ax.set_title("blur of the start's boundaries: D by composition (Boltzmann-Matano)", fontsize=9)
    if not os.path.isfile(path):
        ax.text(0.5, 0.5, "no boundaries at the start", ha="center", va="center", transform=ax.transAxes)
        return
    e = read_csv(path)
    levels = ((25, f"u = 0.25 (among {large})"), (50, "u = 0.5"), (75, f"u = 0.75 (among {small})"))
    markers = "os^vD<>"
    plotted = False
    for k, (u, label) in enumerate(levels):
        column = f"D_u{u}"
        if column not in e:
            continue
        for b in sorted(set(e["boundary"].astype(int))):
            rows = (e["boundary"] == b) & np.isfinite(e[column]) & (e[column] > 0)
            if rows.any():
                ax.plot(e["revolutions"][rows], e[column][rows], markers[b % len(markers)], ms=4,
                        color=COLOURS[k % len(COLOURS)], label=label if b == 0 else None)
                plotted = True
    if plotted:
        ax.set_yscale("log")
        ax.legend(fontsize=7, title="markers: boundaries", title_fontsize=7)


def _plot_blocks(ax, blocks, key, colour, marker, label, shift=0.0):
    """A quantity per block of N (bands.json's radial_core and end_layers
    blocks: KEY, KEY_lo, KEY_hi), at the geometric middle of each block, with
    its 95 % interval where it has one (3 revolutions or more), plus
    `shift`. Returns whether there was anything to plot."""
    blocks = [b for b in blocks if b.get(key) is not None]
    if not blocks:
        return False
    mid = np.array([math.sqrt(max(b["from"], 0.5) * b["to"]) for b in blocks])
    value = np.array([b[key] for b in blocks]) + shift
    lo = np.array([b[key + "_lo"] if b[key + "_lo"] is not None else math.nan for b in blocks]) + shift
    hi = np.array([b[key + "_hi"] if b[key + "_hi"] is not None else math.nan for b in blocks]) + shift
    has = np.isfinite(lo) & np.isfinite(hi)
    if has.any():
        ax.errorbar(mid[has], value[has], yerr=[value[has] - lo[has], hi[has] - value[has]], fmt=marker, ms=4,
                    color=colour, capsize=3, label=label)
    if (~has).any():
        ax.plot(mid[~has], value[~has], marker, ms=4, mfc="none", color=colour,
                label=label.replace("95 % interval (correlated revolutions)", "block") + ": under 3 independent revolutions, no interval")
    return True


def bands_reported(run):
    """Whether the run's summary reports bands (a banded start, a watch on the band count, bands that formed);
    a summary from before it said so: yes."""
    bands = (run.summary or {}).get("bands") or {}
    return bands.get("reported", True)


def do_run(args):
    run = Run(args.dir)
    w = Writer(args.out or os.path.join(args.dir, "figures"))
    makers = [fig_setup, fig_z, fig_profiles, fig_energy, fig_depth, fig_msd, fig_collapse, fig_bed_structure,
              fig_flowing_layer]
    # The band figure for a run with bands, or when asked (--band-report).
    if args.band_report or bands_reported(run):
        makers.append(fig_bands)
    for make in makers:
        make(run, w)
    return w


def do_compare(args):
    runs = [Run(d) for d in args.dirs]
    w = Writer(args.out or "drum_compare_figures")
    fig, ax = plt.subplots(figsize=(11.5, 5.5))
    markers = ["o", "s", "^", "v", "D", "x"]
    for k, run in enumerate(runs):
        _plot_z(ax, run, lambda i, k=k: COLOURS[(2 * k + i) % len(COLOURS)],
                label_prefix=f"\u03c9 = {run.omega:g} rad/s, ",
                marker_for=lambda i, k=k: markers[k % len(markers)])
    modes = {r.mode for r in runs}
    figure = runs[0].paper_z_figure() if len(modes) == 1 else "Figs. 2/4"
    ax.axhline(0.0, color="0.6", lw=0.6)
    ax.set_xlabel("revolutions N")
    ax.set_ylabel("<z> (mm)")
    ax.set_title(f"{figure}: average position for {len(runs)} rotation speeds", fontsize=10)
    legend_outside(ax, fontsize=6.5)
    fig.tight_layout()
    w.save(fig, "fig_z_compare")
    return w


# --------------------------------------------------------------------------- sweep

def _sweep_components(table):
    return [col[len("D_stderr_"):] for col in table if col.startswith("D_stderr_")]


def _mean_interval(v, rng):
    """95 % bootstrap percentile interval of the mean of independent values (seeds);
    None from fewer than 3 (two values say nothing about a spread)."""
    if len(v) < 3:
        return None
    means = rng.choice(v, size=(2000, len(v)), replace=True).mean(axis=1)
    return float(np.percentile(means, 2.5)), float(np.percentile(means, 97.5))


def _group(x, values, lo=None, hi=None):
    """Per distinct x: the mean over seeds of the finite values, its 95 % interval
    (bootstrap over seeds from 3 seeds on; the seed's own interval lo-hi with one
    seed; none with two), the seed values. NaN values (not determined) are left out."""
    out = []
    rng = np.random.default_rng(20261130)
    keys = sorted(set(np.round(x[np.isfinite(x)], 9)))
    for key in keys:
        sel = (np.round(x, 9) == key) & np.isfinite(values)
        v = values[sel]
        if len(v) == 0:
            continue
        interval = _mean_interval(v, rng)
        if interval is None and len(v) == 1 and lo is not None and hi is not None \
                and np.isfinite(lo[sel][0]) and np.isfinite(hi[sel][0]):
            interval = (float(lo[sel][0]), float(hi[sel][0]))
        out.append((key, float(np.mean(v)), interval, v))
    return out


def _plot_grouped(ax, x, values, colour, label, marker="o", lo=None, hi=None):
    groups = _group(x, values, lo, hi)
    if not groups:
        return False
    gx = np.array([g[0] for g in groups])
    gy = np.array([g[1] for g in groups])
    below = [g[1] - g[2][0] if g[2] else 0.0 for g in groups]
    above = [g[2][1] - g[1] if g[2] else 0.0 for g in groups]
    ax.errorbar(gx, gy, yerr=[below, above], fmt=marker + "-", color=colour, capsize=3, ms=5, lw=1.2,
                label=label + " (95 % interval)")
    for g in groups:
        ax.plot(np.full(len(g[3]), g[0]), g[3], marker, color=colour, alpha=0.25, ms=3)
    return True


def _d_columns(table, c):
    """D of a component and its 95 % interval per row, and which rows' D is not
    determined: the grains' MSD estimate where the table has it (empty
    where not determined), else the old pinned Hogg fit +- 1.96 standard errors
    (where `determined_` is false, D is only the best estimate)."""
    finished = np.array([s == "finished" for s in table["status"]]) if "status" in table \
        else np.ones(len(table["omega"]), dtype=bool)
    if f"D_msd_{c}" in table and np.any(np.isfinite(table[f"D_msd_{c}"])):
        d = table[f"D_msd_{c}"]
        return d, table[f"D_msd_lo_{c}"], table[f"D_msd_hi_{c}"], finished & ~np.isfinite(d)
    d = table[f"D_{c}"]
    e = table.get(f"D_stderr_{c}", np.full(len(d), math.nan))
    flags = table.get(f"determined_{c}")
    undetermined = np.array([str(f).lower() == "false" for f in flags]) if flags is not None \
        else np.zeros(len(d), dtype=bool)
    return d, d - 1.96 * e, d + 1.96 * e, finished & undetermined


def _plot_undetermined(ax, x, d, colour, label, marker):
    """The points whose D is not determined, apart from the means: open markers at
    their best estimate, without an interval; those without any estimate are
    counted in the legend."""
    has_value = np.isfinite(d)
    if np.any(has_value):
        ax.plot(x[has_value], d[has_value], marker, ls="none", mfc="none", color=colour, ms=6,
                label=f"{label}: D not determined (best estimate, left out of the mean)")
    if np.any(~has_value):
        ax.plot([], [], marker, ls="none", mfc="none", color=colour,
                label=f"{label}: {int(np.sum(~has_value))} point(s) with D not determined, not drawn")


def _d_axis(ax):
    """D in m^2/rev written out (no offset text, which would collide with the rpm axis)."""
    ax.yaxis.set_major_formatter(matplotlib.ticker.FuncFormatter(lambda v, _: f"{v:.3g}"))
    ax.set_ylim(bottom=0)


def _rpm_axis(ax):
    sec = ax.secondary_xaxis("top", functions=(lambda o: o * RPM_PER_RAD_S,
                                               lambda r: r / RPM_PER_RAD_S))
    sec.set_xlabel("rotation speed (rpm)")


def _components_with_data(table, rows, comps):
    return [c for c in comps if np.any(np.isfinite(_d_columns(table, c)[0][rows]))]


def do_sweep(args):
    table = read_csv(args.table)
    missing = [c for c in ("omega", "mode") if c not in table]
    if missing:
        raise InputError(f"{args.table}: missing column(s) {', '.join(missing)}")
    if not isinstance(table["mode"], list):
        table["mode"] = [str(v) for v in table["mode"]]
    w = Writer(args.out or os.path.join(os.path.dirname(os.path.abspath(args.table)), "figures"))
    omega = table["omega"]
    modes = np.array(table["mode"])
    comps = _sweep_components(table)
    self_rows = modes == "self"
    two_rows = modes == "two-component"
    self_comps = _components_with_data(table, self_rows, comps) if self_rows.any() else []
    two_comps = _components_with_data(table, two_rows, comps) if two_rows.any() else []

    def plot_d(ax, x, rows, c, colour, label, marker):
        d, lo, hi, undetermined = _d_columns(table, c)
        determined = np.where(undetermined, math.nan, d)
        _plot_grouped(ax, x[rows], determined[rows], colour, label, marker, lo[rows], hi[rows])
        _plot_undetermined(ax, x[rows & undetermined], d[rows & undetermined], colour, label, marker)

    # Fig. 3: self-diffusion
    if self_comps:
        fig, ax = plt.subplots(figsize=(10, 5))
        for i, c in enumerate(self_comps):
            plot_d(ax, omega, self_rows, c, COLOURS[i % len(COLOURS)], f"started {c}, mean over seeds", "os"[i % 2])
        ax.set_xlabel("rotation speed \u03c9 (rad/s)")
        ax.set_ylabel("self-diffusion coefficient D (m\u00b2/rev)")
        _rpm_axis(ax)
        _d_axis(ax)
        ax.set_title("Fig. 3: self-diffusion coefficient against rotation speed", fontsize=10)
        legend_outside(ax, fontsize=8)
        fig.tight_layout()
        w.save(fig, "fig3_self_D_vs_omega")
    else:
        w.skip("fig3_self_D_vs_omega", f"no self-mode rows with D in {args.table}")

    # Fig. 5: two-component diffusion
    if two_comps:
        fig, ax = plt.subplots(figsize=(10, 5))
        for i, c in enumerate(two_comps):
            plot_d(ax, omega, two_rows, c, COLOURS[i % len(COLOURS)], f"{c}, mean over seeds", "os^v"[i % 4])
        ax.set_xlabel("rotation speed \u03c9 (rad/s)")
        ax.set_ylabel("diffusion coefficient D (m\u00b2/rev)")
        _rpm_axis(ax)
        _d_axis(ax)
        ax.set_title("Fig. 5: two-component diffusion coefficients against rotation speed",
                     fontsize=10)
        legend_outside(ax, fontsize=8)
        fig.tight_layout()
        w.save(fig, "fig5_two_component_D_vs_omega")
    else:
        w.skip("fig5_two_component_D_vs_omega", f"no two-component rows with D in {args.table}")

    # Fig. 6: kinetic-energy ratio
    ke_cols = [("per grain", "ke_ratio_per_grain", "tab:green"),
               ("total", "ke_ratio_total", "tab:purple")]
    present = [k for k in ke_cols if k[1] in table and two_rows.any()
               and np.any(np.isfinite(table[k[1]][two_rows]))]
    if present:
        fig, ax = plt.subplots(figsize=(10, 5))
        for label, col, colour in present:
            _plot_grouped(ax, omega[two_rows], table[col][two_rows], colour,
                          f"{label}: material 2 / material 1, mean over seeds")
            ref_col = f"{col}_ref"
            if ref_col in table:
                groups = _group(omega[two_rows], table[ref_col][two_rows])
                if groups:
                    gx = [g[0] for g in groups]
                    gy = [g[1] for g in groups]
                    if len(gx) == 1:
                        ax.axhline(gy[0], color=colour, ls="--", lw=1.2,
                                   label=f"{label}: equal velocities")
                    else:
                        ax.plot(gx, gy, "--", color=colour, lw=1.2,
                                label=f"{label}: equal velocities")
        ax.set_xlabel("rotation speed \u03c9 (rad/s)")
        ax.set_ylabel("kinetic energy ratio, material 2 / material 1")
        _rpm_axis(ax)
        ax.set_ylim(bottom=0)
        ax.set_title("Fig. 6: kinetic energy ratio against rotation speed", fontsize=10)
        legend_outside(ax, fontsize=8)
        fig.tight_layout()
        w.save(fig, "fig6_ke_ratio_vs_omega")
    else:
        w.skip("fig6_ke_ratio_vs_omega", f"no two-component rows with ke_ratio_ in {args.table}")

    # D against Froude number, both modes
    if "froude" in table and (self_comps or two_comps):
        froude = table["froude"]
        fig, ax = plt.subplots(figsize=(10, 5))
        for i, c in enumerate(self_comps):
            plot_d(ax, froude, self_rows, c, "tab:blue", f"self-diffusion: started {c}", "Dd"[i % 2])
        for i, c in enumerate(two_comps):
            plot_d(ax, froude, two_rows, c, COLOURS[(i + 1) % len(COLOURS)], f"two-component: {c}", "os^v"[i % 4])
        ax.set_xlabel("Froude number Fr = \u03c9\u00b2R/g")
        ax.set_ylabel("diffusion coefficient D (m\u00b2/rev)")
        _d_axis(ax)
        ax.set_title("Diffusion coefficients against Froude number (both modes)", fontsize=10)
        legend_outside(ax, fontsize=8)
        fig.tight_layout()
        w.save(fig, "fig_D_vs_froude")
    else:
        w.skip("fig_D_vs_froude", f"no froude column or no D values in {args.table}")

    # Where the axial motion happens, against rotation speed
    share_comps = [c for c in comps if f"surface_share_{c}" in table
                   and np.any(np.isfinite(table[f"surface_share_{c}"]))]
    if share_comps:
        fig, ax = plt.subplots(figsize=(10, 5))
        for i, c in enumerate(share_comps):
            rows = np.isfinite(table[f"surface_share_{c}"])
            _plot_grouped(ax, omega[rows], table[f"surface_share_{c}"][rows],
                          COLOURS[i % len(COLOURS)], f"{c}, mean over seeds", "os^v"[i % 4])
        ax.set_xlabel("rotation speed \u03c9 (rad/s)")
        ax.set_ylabel("share of axial <\u0394z\u00b2> in the top grain layer")
        _rpm_axis(ax)
        ax.set_ylim(0, 1.05)
        ax.set_title("Where the axial motion happens: surface share against rotation speed",
                     fontsize=10)
        legend_outside(ax, fontsize=8)
        fig.tight_layout()
        w.save(fig, "fig_surface_share_vs_omega")
    else:
        w.skip("fig_surface_share_vs_omega", f"no surface_share_ values in {args.table}")
    return w


# --------------------------------------------------------------------------- main

def main(argv=None):
    parser = argparse.ArgumentParser(
        prog="plot_drum.py",
        description="Figures of Kohring's rotating-drum paper from tumble drum output.")
    sub = parser.add_subparsers(dest="command", required=True)
    p = sub.add_parser("run", help="figures of one drum run directory")
    p.add_argument("dir")
    p.add_argument("--out", help="figure directory (default DIR/figures)")
    p.add_argument("--band-report", action="store_true",
                   help="draw fig_bands even for a run without bands (default: only when the summary reports bands)")
    p = sub.add_parser("sweep", help="figures of a sweep table (tools/README.md)")
    p.add_argument("table")
    p.add_argument("--out", help="figure directory (default: figures/ beside the table)")
    p = sub.add_parser("compare", help="<z>(N) of several runs in one figure")
    p.add_argument("dirs", nargs="+")
    p.add_argument("--out", help="figure directory (default ./drum_compare_figures)")
    args = parser.parse_args(argv)
    try:
        writer = {"run": do_run, "sweep": do_sweep, "compare": do_compare}[args.command](args)
    except InputError as error:
        sys.stderr.write(f"plot_drum.py: error: {error}\n")
        return 2
    writer.report()
    return 0


if __name__ == "__main__":
    sys.exit(main())
