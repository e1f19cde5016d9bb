#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Beverloo's law in a flat-bottomed silo: the runs and their flow rates.

One scenario per (orifice diameter D0, seed) from the template below: an
infinite cylinder of radius R_SILO (the silo's wall), a disc at z = 0 with a
hole of radius D0/2 (its floor and orifice), a rectangle just below the
floor that closes the orifice while the grains settle and then slides out
sideways at PLUG_SPEED (a [[motion]]: the orifice is fully open at T_OPEN),
and a catch plane far enough below that the heap never reaches the
orifice. The grains start at random (random_fill) in the silo above the
floor, fall and settle on the closed floor, then discharge.

The flow rate W: grains below the orifice plane (z < -d) against time from
the snapshots, a straight line fitted over the steady part of the
discharge (from T_OPEN + T_SKIP until the grains left above the floor
would fill less than H_MIN of the silo); the bulk density from the packing
in the middle of the settled column just before the orifice opens.

    python3 studies/beverloo/run.py --tumble build/tumble     # runs what is not done, then the table
    python3 studies/beverloo/analyze.py                       # the fit, results.json, beverloo.png

Each run writes into out/D<D0 in d>_s<seed>/ (git ignores it) and its
measured rate into flow_rates.csv (kept).
"""
import argparse
import csv
import glob
import json
import math
import os
import subprocess
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))

# The grains: the soft glass beads of examples/hopper.toml.
RADIUS = 2.0e-3                       # m
D = 2 * RADIUS                        # grain diameter d
RHO_S = 2500.0                        # kg/m^3
M_GRAIN = RHO_S * 4.0 / 3.0 * math.pi * RADIUS ** 3
G = 9.81

# The silo and the protocol (defaults; a reduced study may change them).
R_SILO = 0.050                        # m: diameter 25 d
N_GRAINS = 10000
PLUG_SPEED = 0.5                      # m/s
T_OPEN = 0.45                         # s: the orifice is fully open then
T_SKIP = 0.10                         # s after T_OPEN before the fit starts
H_MIN = 0.050                         # m: the fit stops when the fill is lower
T_WINDOW = 1.5                        # s: the longest measurement (small orifices)
SNAPSHOT_INTERVAL = 0.01              # s
ORIFICES = [4.0, 5.0, 6.0, 7.0, 8.0]  # D0 / d
SEEDS = [1, 2, 3]
PHI_GUESS = 0.60                      # to size the runs only

TEMPLATE = """\
# Beverloo study (studies/beverloo/run.py): a flat-bottomed silo of radius
# {r_silo} m with an orifice of diameter {d0} m ({d0_over_d} d) in its floor;
# {n} soft glass beads of radius {radius} m settle on the closed orifice,
# the plug slides out, the orifice is fully open at t = {t_open} s.

[simulation]
duration = {duration}
seed = {seed}
gravity = [0.0, 0.0, -9.81]

[time_step]
reference_speed = 1.5           # m/s: impacts on the settling bed and on the heap

[domain]
lo = [{mr}, {mr}, {z_catch}]
hi = [{r_silo}, {r_silo}, {z_top}]

[output]
time_series_interval = {snap}
snapshot_interval = {snap}

[[material]]
name = "glass"
E = 5.0e6        # Pa
G = 2.0e6        # Pa
nu = 0.25
xi = 20.0        # Pa s: restitution about 0.9 at 1 m/s
eta = 20.0       # Pa s
rho = {rho_s}     # kg/m^3
radius = {radius}  # m

[[material]]
name = "steel"
E = 1.0e7
G = 4.0e6
nu = 0.3
xi = 20.0
eta = 20.0
rho = 7800.0
radius = {radius}

[[pair]]
materials = ["glass", "glass"]
mu = 0.3
W = 0.0

[[pair]]
materials = ["glass", "steel"]
mu = 0.4
W = 0.0

[[pair]]
materials = ["steel", "steel"]
mu = 0.4
W = 0.0

[[motion]]
name = "plug"
velocity = [{plug_speed}, 0.0, 0.0]

[[wall]]
name = "silo"
shape = "cylinder"
material = "steel"
point = [0.0, 0.0, 0.0]
axis = [0.0, 0.0, 1.0]
radius = {r_silo}

[[wall]]
name = "floor"
shape = "disc"
material = "steel"
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
radius = {r_floor}
hole_radius = {r_hole}

# Closes the orifice from below until its edge passes the orifice's near
# rim at t = {t_start_open} s; the orifice is open at t = {t_open} s.
[[wall]]
name = "plug"
shape = "rectangle"
material = "steel"
motion = "plug"
point = [{plug_x}, 0.0, {z_plug}]
normal = [0.0, 0.0, 1.0]
edge = [1.0, 0.0, 0.0]
size = [{plug_a}, {plug_b}]

[[wall]]
name = "catch"
shape = "plane"
material = "steel"
point = [0.0, 0.0, {z_catch}]
normal = [0.0, 0.0, 1.0]

[[particles]]
kind = "random_fill"
material = "glass"
lo = [{mr}, {mr}, {z_fill_lo}]
hi = [{r_silo}, {r_silo}, {z_top}]
count = {n}
"""


def beverloo_guess(d0, c=0.58, k=1.5, phi=PHI_GUESS):
    """Mass flow rate (kg/s) by Beverloo's law, to size the runs."""
    return c * phi * RHO_S * math.sqrt(G) * max(d0 - k * D, 0.2 * D) ** 2.5


def scenario(d0_over_d, seed, n=N_GRAINS, r_silo=R_SILO, t_open=T_OPEN,
             h_min=H_MIN, duration=None, t_window=T_WINDOW):
    d0 = d0_over_d * D
    r_hole = d0 / 2
    # The loose random fill (about 0.27 of the cylinder) above the floor.
    v_grains = n * 4.0 / 3.0 * math.pi * RADIUS ** 3
    h_fill = v_grains / (0.27 * math.pi * r_silo ** 2)
    z_fill_lo = RADIUS * 1.1
    z_top = z_fill_lo + h_fill
    # The plug: its trailing edge (x = plug_x - a/2 + v t) reaches the
    # orifice's near rim (-r_hole) at t_start_open, the far rim at t_open.
    t_start_open = t_open - 2 * r_hole / PLUG_SPEED
    plug_a = 2 * r_hole + PLUG_SPEED * t_open + 4 * D
    plug_x = plug_a / 2 - r_hole - PLUG_SPEED * t_start_open
    # The settled column and the time to drain it to h_min.
    per_height = PHI_GUESS * math.pi * r_silo ** 2 / (4.0 / 3.0 * math.pi * RADIUS ** 3)
    n_end = h_min * per_height
    w = beverloo_guess(d0) / M_GRAIN               # grains/s
    if duration is None:
        duration = t_open + T_SKIP + min(1.1 * (n - n_end) / w - T_SKIP, t_window)
    duration = round(duration, 2)
    # The heap below: it must stay clear of the orifice. A column of the
    # whole bed in the silo's cylinder (which continues below the floor).
    h_heap = v_grains / (0.55 * math.pi * r_silo ** 2)
    z_catch = -(h_heap + 0.03)
    return TEMPLATE.format(
        r_silo=r_silo, mr=-r_silo, d0=round(d0, 6), d0_over_d=d0_over_d, n=n,
        radius=RADIUS, rho_s=RHO_S, t_open=t_open, duration=duration, seed=seed,
        z_catch=round(z_catch, 4), z_top=round(z_top, 4), snap=SNAPSHOT_INTERVAL,
        plug_speed=PLUG_SPEED, r_floor=round(r_silo + 2 * D, 4), r_hole=round(r_hole, 6),
        t_start_open=round(t_start_open, 3), plug_x=round(plug_x, 5),
        z_plug=-RADIUS / 4, plug_a=round(plug_a, 4), plug_b=round(2 * r_hole + 4 * D, 4),
        z_fill_lo=round(z_fill_lo, 5)), duration


def extract(out, d0_over_d, r_silo=R_SILO, t_open=T_OPEN):
    """From the snapshots: the times, the grains below the orifice plane
    (z < -d) and above the floor (z > 0), and the solid fraction of the
    settled column. Written to out/series.json; the snapshots then go
    (all but the first and the last), as they are large."""
    files = sorted(glob.glob(os.path.join(out, "snapshots", "*.csv")))
    d0 = d0_over_d * D
    t_settled = t_open - 2 * (d0 / 2) / PLUG_SPEED
    times, below, above = [], [], []
    phi = None
    for f in files:
        a = np.genfromtxt(f, delimiter=",", names=True, dtype=None, encoding=None,
                          usecols=("time", "x", "y", "z", "kinematic"))
        z = np.asarray(a["z"][a["kinematic"] == 0], float)
        r = np.hypot(a["x"], a["y"])[a["kinematic"] == 0]
        t = float(a["time"][0])
        times.append(t)
        below.append(int((z < -D).sum()))
        above.append(int((z > 0.0).sum()))
        if t < t_settled:
            # The settled column away from the wall (r < R - 2d), the floor
            # (z > 2d) and the free surface (2d below the 98th percentile).
            top = np.quantile(z[z > 0], 0.98)
            r_in, z_lo, z_hi = r_silo - 2 * D, 2 * D, top - 2 * D
            inside = (r < r_in) & (z > z_lo) & (z < z_hi)
            phi = float(inside.sum() * (4.0 / 3.0 * math.pi * RADIUS ** 3) / (math.pi * r_in ** 2 * (z_hi - z_lo)))
    series = {"time": times, "below": below, "above": above, "phi_settled": phi, "n": above[0] + below[0]}
    with open(os.path.join(out, "series.json"), "w") as f:
        json.dump(series, f)
    for f in glob.glob(os.path.join(out, "snapshots", "*")):
        if not (f.startswith(files[0][:-4]) or f.startswith(files[-1][:-4])):
            os.remove(f)
    return series


def measure(series, r_silo=R_SILO, t_open=T_OPEN, h_min=H_MIN, t_skip=T_SKIP):
    """The flow rate and the bulk density of one run from its series."""
    t = np.array(series["time"])
    below = np.array(series["below"])
    above = np.array(series["above"])
    phi = series["phi_settled"]
    rho_b = phi * RHO_S
    per_height = phi * math.pi * r_silo ** 2 / (4.0 / 3.0 * math.pi * RADIUS ** 3)
    n_end = h_min * per_height
    sel = (t >= t_open + t_skip) & (above >= n_end)
    if sel.sum() < 6:
        raise RuntimeError(f"only {sel.sum()} snapshots in the steady window")
    tt, nb = t[sel], below[sel]
    slope, icpt = np.polyfit(tt, nb, 1)
    resid = nb - (slope * tt + icpt)
    half = len(tt) // 2
    s1 = np.polyfit(tt[:half + 1], nb[:half + 1], 1)[0]
    s2 = np.polyfit(tt[half:], nb[half:], 1)[0]
    # A jam: no grain passes for 0.1 s in the window.
    gaps = np.diff(nb)
    jammed = bool(len(gaps) >= 10 and np.min(np.convolve(gaps, np.ones(10), "valid")) == 0)
    return {
        "w_kg_s": slope * M_GRAIN, "grains_per_s": slope, "phi": phi, "rho_b": rho_b,
        "t_start": float(tt[0]), "t_end": float(tt[-1]), "grains_in_window": int(nb[-1] - nb[0]),
        "fill_height_start": float(above[sel][0] / per_height), "fill_height_end": float(above[sel][-1] / per_height),
        "rms_residual_grains": float(np.sqrt(np.mean(resid ** 2))),
        "second_half_over_first": float(s2 / s1), "jammed": jammed, "n": int(series["n"]),
    }


FIELDS = ["d0_over_d", "d0_m", "seed", "n", "w_kg_s", "grains_per_s", "phi", "rho_b", "t_start", "t_end",
          "grains_in_window", "fill_height_start", "fill_height_end", "rms_residual_grains",
          "second_half_over_first", "jammed",
          "steps", "wall_s"]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--tumble", default=os.path.join(HERE, "..", "..", "build", "tumble"))
    ap.add_argument("--out", default=os.path.join(HERE, "out"), help="run directories (default studies/beverloo/out)")
    ap.add_argument("--csv", default=os.path.join(HERE, "flow_rates.csv"), help="the per-run rates")
    ap.add_argument("--orifices", type=float, nargs="+", default=ORIFICES, help="D0 / d")
    ap.add_argument("--seeds", type=int, nargs="+", default=SEEDS)
    ap.add_argument("--grains", type=int, default=N_GRAINS)
    ap.add_argument("--silo-radius", type=float, default=R_SILO, help="m")
    ap.add_argument("--h-min", type=float, default=H_MIN, help="m: the fit stops when the fill is lower")
    ap.add_argument("--t-window", type=float, default=T_WINDOW, help="s: the longest measurement")
    ap.add_argument("--duration", type=float, default=None, help="s (default: sized from Beverloo's law)")
    ap.add_argument("--only-scenarios", action="store_true", help="write the scenario files, run nothing")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    rows = []
    for d0d in args.orifices:
        for seed in args.seeds:
            name = f"D{d0d:g}_s{seed}"
            run_dir = os.path.join(args.out, name)
            toml, duration = scenario(d0d, seed, n=args.grains, r_silo=args.silo_radius,
                                      h_min=args.h_min, duration=args.duration, t_window=args.t_window)
            path = os.path.join(args.out, name + ".toml")
            with open(path, "w") as f:
                f.write(toml)
            if args.only_scenarios:
                continue
            wall = float("nan")
            if not os.path.exists(os.path.join(run_dir, "done")):
                print(f"beverloo: {name}: {duration} s simulated ...", flush=True)
                t0 = time.time()
                with open(os.path.join(args.out, name + ".log"), "w") as log:
                    rc = subprocess.call([args.tumble, "run", path, "--out", run_dir, "--force",
                                          "--progress-every", "60"], stdout=log, stderr=subprocess.STDOUT)
                if rc != 0:
                    sys.exit(f"beverloo: {name} failed (rc {rc}); see {args.out}/{name}.log")
                wall = time.time() - t0
                with open(os.path.join(run_dir, "done"), "w") as f:
                    f.write(f"{wall:.1f}\n")
            else:
                wall = float(open(os.path.join(run_dir, "done")).read())
            steps = json.load(open(os.path.join(run_dir, "run.json"))).get("steps", "")
            series_file = os.path.join(run_dir, "series.json")
            if os.path.exists(series_file):
                series = json.load(open(series_file))
            else:
                series = extract(run_dir, d0d, r_silo=args.silo_radius)
            m = measure(series, r_silo=args.silo_radius, h_min=args.h_min)
            m.update(d0_over_d=d0d, d0_m=d0d * D, seed=seed, steps=steps, wall_s=round(wall, 1))
            print(f"beverloo: {name}: W = {m['w_kg_s']*1e3:.2f} g/s ({m['grains_per_s']:.0f} grains/s, "
                  f"{m['grains_in_window']} grains over {m['t_end']-m['t_start']:.2f} s, fill "
                  f"{m['fill_height_start']*100:.1f} -> {m['fill_height_end']*100:.1f} cm), phi = {m['phi']:.3f}, "
                  f"{wall:.0f} s wall", flush=True)
            rows.append(m)
    if args.only_scenarios:
        return
    with open(args.csv, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=FIELDS, extrasaction="ignore")
        w.writeheader()
        for m in rows:
            w.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in m.items()})
    print(f"beverloo: {len(rows)} runs -> {args.csv}")


if __name__ == "__main__":
    main()
