#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""tumble against LAMMPS on the smooth drum (bench/compare_smooth_drum.sh,
bench/peers/lammps_smooth_drum.in, bench/peers/tumble_smooth_drum.toml;
docs/BENCHMARKS.md, "LAMMPS on the same smooth drum"). Standard library only.

  smooth_drum_peer.py data SNAPSHOT.csv OUT.data
        tumble drum's settled bed (its snapshots/000000.csv, the start of the
        rotation) as a LAMMPS data file (drum_peer.py's writer: type 1
        material-1, type 2 material-2, atom id = tumble id + 1)
  smooth_drum_peer.py plan TUMBLE_RUN_DIR
        "STEPS EVERY DT SKIN": the steps tumble turned, its steps between
        snapshots, its step and skin, for the LAMMPS run
  smooth_drum_peer.py measure CODE DIR SEED OMEGA [--from N] [--timing T] [--log LOG]
        one JSON result line for one run: CODE tumble (DIR: tumble drum's
        run directory) or lammps (DIR: the dump directory, LOG its log):
        the angle of repose, the flowing layer's depth, the speed
  smooth_drum_peer.py table RESULTS.jsonl
        the means with 95 % t intervals over the seeds, the differences and
        the speed ratio, paired by seed

Both codes' snapshots go through the same functions below, so the two
measures are defined alike:

- Dynamic angle of repose: tumble's (src/tumble/analysis/drum_measure.cpp):
  the inclination of the principal (long) axis of the grains' positions in
  the cross-section (x, y), mass-weighted, positive when the surface is
  raised toward +x, where the bottom of a drum turning counter-clockwise
  about +z moves. Per run: the mean over the snapshots at revolutions
  N >= --from (default 1).
- Flowing layer's depth: in each snapshot the frame of its own surface:
  t along the principal axis (up the slope), n normal to it (up); the grains
  whose centres lie within STRIP (1 cm) of the line through the drum's axis
  along n, binned by s = r . n in bins of BIN (1 mm), pooled over the same
  snapshots. The free surface s_f is where the bins' solid (grain volume
  by centre) falls to half of the bed's bulk (the median of the bins in the
  lower half of the occupied range); the layer's base s_0 is where the
  mass-weighted mean downhill velocity u = -v . t, in the lab frame, changes
  sign, the first change from the bottom up (linear between bins: the
  grains below are carried up by the drum, those above creep or flow down
  the slope). Depth = s_f - s_0.
  Also reported: the surface speed u(s_f) (linear between the bins'
  centres, or the highest bin's) and the half-speed depth s_f - s_h, where u first falls to
  u(s_f) / 2 below s_f: a steeper part of the profile than its foot, where
  the grains creep and the sign of u is noisy.
"""
import csv
import glob
import json
import math
import os
import re
import statistics
import sys

import drum_peer
import peerlib

STRIP = 0.01   # m: half-width of the strip about the line through the axis
BIN = 0.001    # m: bin width along the surface normal


# ------------------------------------------------------------------ snapshots
def read_tumble(run_dir, omega):
    """tumble drum's snapshots: [(N, [(x, y, z, vx, vy, vz, r), ...]), ...]
    with N the revolutions since the start of the rotation (snapshot 0)."""
    files = sorted(glob.glob(os.path.join(run_dir, "snapshots", "[0-9]*.csv")))
    out, t0 = [], None
    for f in files:
        with open(f, encoding="ascii") as fh:
            rows = [r for r in csv.DictReader(fh) if r["kinematic"] == "0"]
        if not rows:
            continue
        t = float(rows[0]["time"])
        t0 = t if t0 is None else t0
        grains = [tuple(float(r[k]) for k in ("x", "y", "z", "vx", "vy", "vz", "radius")) for r in rows]
        out.append(((t - t0) * omega / (2.0 * math.pi), grains))
    if not out:
        peerlib.fail(f"{run_dir}: no snapshots")
    return out


def read_lammps(dump_dir, omega, dt):
    """LAMMPS dump custom files (id type x y z vx vy vz radius), the rotation
    starting at step 0."""
    out = []
    for f in sorted(glob.glob(os.path.join(dump_dir, "*.txt"))):
        with open(f, encoding="ascii") as fh:
            lines = fh.read().splitlines()
        step = int(lines[lines.index("ITEM: TIMESTEP") + 1])
        head = next(i for i, l in enumerate(lines) if l.startswith("ITEM: ATOMS"))
        cols = lines[head].split()[2:]
        idx = [cols.index(k) for k in ("x", "y", "z", "vx", "vy", "vz", "radius")]
        grains = []
        for l in lines[head + 1:]:
            f_ = l.split()
            if f_:
                grains.append(tuple(float(f_[i]) for i in idx))
        out.append((step * dt * omega / (2.0 * math.pi), grains))
    if not out:
        peerlib.fail(f"{dump_dir}: no dumps")
    out.sort(key=lambda s: s[0])
    return out


# ------------------------------------------------------------------ measures
def angle_of_repose(grains):
    """(degrees, centre x, centre y): the mass-weighted principal axis of the
    cross-section, as tumble's drum_measure.cpp (counter-clockwise drum)."""
    m = [g[6] ** 3 for g in grains]  # one density
    mt = sum(m)
    cx = sum(mi * g[0] for mi, g in zip(m, grains)) / mt
    cy = sum(mi * g[1] for mi, g in zip(m, grains)) / mt
    xx = sum(mi * (g[0] - cx) ** 2 for mi, g in zip(m, grains))
    yy = sum(mi * (g[1] - cy) ** 2 for mi, g in zip(m, grains))
    xy = sum(mi * (g[0] - cx) * (g[1] - cy) for mi, g in zip(m, grains))
    return math.degrees(0.5 * math.atan2(2.0 * xy, xx - yy)), cx, cy


def layer_profile(snapshots):
    """Pooled over the snapshots, each in its own surface frame: {bin:
    [grain volume, mass, mass x downhill velocity]}."""
    bins = {}
    for _, grains in snapshots:
        a = math.radians(angle_of_repose(grains)[0])
        tx, ty = math.cos(a), math.sin(a)   # up the slope
        nx, ny = -ty, tx                    # up, out of the bed
        for x, y, _, vx, vy, _, r in grains:
            if abs(x * tx + y * ty) > STRIP:
                continue
            k = math.floor((x * nx + y * ny) / BIN)
            b = bins.setdefault(k, [0.0, 0.0, 0.0])
            m = r ** 3
            b[0] += 4.0 / 3.0 * math.pi * m
            b[1] += m
            b[2] += -m * (vx * tx + vy * ty)
    return bins


def flowing_layer(snapshots):
    """(depth m, surface s_f m, base s_0 m, surface speed m/s, half-speed
    depth m) from the pooled profile (see the module's text)."""
    bins = layer_profile(snapshots)
    ks = sorted(bins)
    lo, hi = ks[0], ks[-1]
    solid = {k: bins[k][0] if k in bins else 0.0 for k in range(lo, hi + 2)}  # none above hi
    lower = [solid[k] for k in range(lo, lo + (hi - lo + 1) // 2 + 1)]
    half = 0.5 * statistics.median(lower)
    # the free surface: the highest crossing of half the bulk's solid, from above
    s_f = None
    for k in range(hi + 1, lo, -1):
        if solid[k] < half <= solid[k - 1]:
            w = (half - solid[k - 1]) / (solid[k] - solid[k - 1])
            s_f = (k - 0.5 + w) * BIN  # bin centres at (k + 1/2) BIN
            break
    if s_f is None:
        peerlib.fail("no free surface in the profile")
    u = {k: bins[k][2] / bins[k][1] for k in bins if bins[k][1] > 0.0}
    k_f = math.floor(s_f / BIN)
    # the layer's base: the top of the grains carried up the slope, the
    # first change of sign of u from the bottom up (scanned down from the
    # surface, the sign of u in the creeping grains just above it, within a
    # few mm/s of 0, would decide between places 3 mm apart)
    s_0 = None
    for k in range(lo, k_f):
        if k in u and k + 1 in u and u[k] <= 0.0 < u[k + 1]:
            w = -u[k] / (u[k + 1] - u[k])
            s_0 = (k + 0.5 + w) * BIN
            break
    if s_0 is None:
        peerlib.fail("the downhill velocity does not change sign below the surface")
    # the surface speed: u at s_f, linear between the bins' centres (the
    # highest bin's where s_f lies above its centre and no grain above)
    k = math.floor(s_f / BIN - 0.5)
    if k not in u:
        peerlib.fail("no velocity at the free surface")
    w = s_f / BIN - 0.5 - k
    u_f = (1.0 - w) * u[k] + w * u[k + 1] if k + 1 in u else u[k]
    # where u falls to half the surface speed, from the surface down
    s_h = None
    for k in range(k_f, lo, -1):
        if k in u and k - 1 in u and u[k] > 0.5 * u_f >= u[k - 1]:
            s_h = (k + 0.5 - (u[k] - 0.5 * u_f) / (u[k] - u[k - 1])) * BIN
            break
    if s_h is None or s_h > s_f:
        peerlib.fail("the downhill velocity does not fall to half the surface speed below the surface")
    return s_f - s_0, s_f, s_0, u_f, s_f - s_h


def measure(code, directory, seed, omega, start, timing=None, log=None, dt=None):
    if code == "tumble":
        snaps = read_tumble(directory, omega)
        summary = json.load(open(os.path.join(directory, "summary.json")))
        speed = float(summary["grain_updates_per_second"])
        cpu_speed = None
        if timing and os.path.exists(timing):
            # per CPU second of the whole process: settling, turning, writing
            # and the analysis (a lower bound of the turning's)
            with open(os.path.join(directory, "time_series.csv"), encoding="ascii") as fh:
                steps = int(list(csv.DictReader(fh))[-1]["step"])
            cpu_speed = int(summary["grains"]) * steps / json.load(open(timing))["cpu"]
    else:
        text = open(log, encoding="utf-8", errors="replace").read()
        err = next((l for l in text.splitlines() if l.startswith("ERROR")), None)
        if err:
            peerlib.fail(f"{log}: LAMMPS stopped: {err}")
        loops = peerlib.LOOP.findall(text)
        if not loops:
            peerlib.fail(f"{log}: no 'Loop time' line (did LAMMPS finish?)")
        seconds, _, steps, atoms = loops[-1]
        steps = int(steps)
        speed = int(atoms) * steps / float(seconds)
        cpu_use = re.findall(r"([0-9.]+)% CPU use with", text)  # of the turning's loop
        cpu_speed = speed / (float(cpu_use[-1]) / 100.0) if cpu_use else None
        dt = float(re.findall(r"TUMBLE_PEER smooth_drum .* dt=([0-9.eE+-]+)", text)[-1])
        snaps = read_lammps(directory, omega, dt)
    used = [s for s in snaps if s[0] >= start - 1e-9]
    if len(used) < 2:
        peerlib.fail(f"{directory}: fewer than 2 snapshots at N >= {start}")
    angles = [angle_of_repose(g)[0] for _, g in used]
    depth, s_f, s_0, u_f, half = flowing_layer(used)
    r = {"code": code, "seed": int(seed), "snapshots": len(used), "from": start,
         "revolutions": round(snaps[-1][0], 4), "grains": len(used[-1][1]),
         "angle_of_repose": statistics.fmean(angles),
         "angle_sd_over_snapshots": statistics.stdev(angles),
         "layer_depth": depth, "surface": s_f, "layer_base": s_0, "surface_speed": u_f, "half_speed_depth": half,
         "grain_updates_per_second": speed, "grain_updates_per_cpu_second": cpu_speed}
    return peerlib.add_timing(r, timing)


# ------------------------------------------------------------------ table
def t_interval(xs):
    """(mean, half-width of the 95 % t interval); half None for one value."""
    m = statistics.fmean(xs)
    if len(xs) < 2:
        return m, None
    dof = len(xs) - 1
    t = peerlib.T_975[dof - 1] if dof <= len(peerlib.T_975) else 1.96
    return m, t * statistics.stdev(xs) / math.sqrt(len(xs))


def fmt(mean, half, scale=1.0, digits=2):
    if half is None:
        return f"{mean * scale:.{digits}f}"
    return f"{mean * scale:.{digits}f} +- {half * scale:.{digits}f}"


def table(path):
    rows = [json.loads(l) for l in open(path, encoding="utf-8") if l.strip()]
    by = {}
    for r in rows:
        by.setdefault(r["code"], {})[r["seed"]] = r
    if set(by) != {"tumble", "lammps"}:
        peerlib.fail(f"{path}: need results of both codes, have {sorted(by)}")
    seeds = sorted(set(by["tumble"]) & set(by["lammps"]))
    if not seeds:
        peerlib.fail(f"{path}: no seed run by both codes")
    quantities = (("angle_of_repose", "angle of repose, degrees", 1.0, 2),
                  ("layer_depth", "flowing layer depth, mm", 1e3, 2),
                  ("half_speed_depth", "half-speed depth, mm", 1e3, 2),
                  ("surface_speed", "surface speed, m/s", 1.0, 3))
    out = []
    verdict = {}
    for key, name, scale, digits in quantities:
        t = [by["tumble"][s][key] for s in seeds]
        l = [by["lammps"][s][key] for s in seeds]
        d = [a - b for a, b in zip(t, l)]
        (mt, ht), (ml, hl), (md, hd) = t_interval(t), t_interval(l), t_interval(d)
        overlap = ht is not None and (mt - ht) <= (ml + hl) and (ml - hl) <= (mt + ht)
        zero_in = hd is not None and abs(md) <= hd
        verdict[key] = (overlap, zero_in)
        out.append((name, fmt(mt, ht, scale, digits), fmt(ml, hl, scale, digits), fmt(md, hd, scale, digits),
                    "yes" if overlap else "no", "yes" if zero_in else "no",
                    " ".join(f"{x * scale:.{digits}f}" for x in t), " ".join(f"{x * scale:.{digits}f}" for x in l)))
    print(f"seeds: {' '.join(str(s) for s in seeds)}; measured over revolutions "
          f"{by['tumble'][seeds[0]]['from']:g} to {by['tumble'][seeds[0]]['revolutions']:g} "
          f"({by['tumble'][seeds[0]]['snapshots']} and {by['lammps'][seeds[0]]['snapshots']} snapshots per run); "
          "mean +- 95 % t half-width over the seeds")
    peerlib.print_table(("quantity", "tumble", "LAMMPS", "tumble - LAMMPS (paired)", "intervals overlap",
                         "difference holds 0", "tumble by seed", "LAMMPS by seed"), out)
    ratios = [by["tumble"][s]["grain_updates_per_second"] / by["lammps"][s]["grain_updates_per_second"]
              for s in seeds]
    print()
    print("speed (grain updates per second = grains x steps / wall time of the turning, one core each, "
          "one after the other):")
    for s in seeds:
        t, l = by["tumble"][s], by["lammps"][s]
        print(f"  seed {s}: tumble {peerlib.fmt_rate(t['grain_updates_per_second'])}"
              f" (cpu/wall {t.get('cpu_per_wall', float('nan')):.2f}), LAMMPS"
              f" {peerlib.fmt_rate(l['grain_updates_per_second'])} (cpu/wall {l.get('cpu_per_wall', float('nan')):.2f}),"
              f" ratio {ratios[-len(seeds) + seeds.index(s)]:.2f}")
    print(f"  tumble / LAMMPS: {peerlib.fmt_interval(ratios)} (geometric mean [95 % t interval], paired by seed)")
    cpu = [by["tumble"][s].get("grain_updates_per_cpu_second") and by["lammps"][s].get("grain_updates_per_cpu_second")
           and by["tumble"][s]["grain_updates_per_cpu_second"] / by["lammps"][s]["grain_updates_per_cpu_second"]
           for s in seeds]
    if all(cpu):
        print(f"  per CPU second (tumble: its whole process, settling and analysis included; LAMMPS: its turning"
              f" loop): tumble {peerlib.fmt_rate(statistics.median(by['tumble'][s]['grain_updates_per_cpu_second'] for s in seeds))},"
              f" LAMMPS {peerlib.fmt_rate(statistics.median(by['lammps'][s]['grain_updates_per_cpu_second'] for s in seeds))}"
              f" (medians); tumble / LAMMPS {peerlib.fmt_interval(cpu)}")
    print(json.dumps({"verdict": {k: {"intervals_overlap": v[0], "difference_holds_zero": v[1]}
                                  for k, v in verdict.items()},
                      "speed_ratio": peerlib.ratio_interval(ratios),
                      "cpu_speed_ratio": peerlib.ratio_interval(cpu) if all(cpu) else None}))


# ------------------------------------------------------------------ plan
def plan(run_dir):
    info = open(os.path.join(run_dir, "drum_run.toml"), encoding="utf-8").read()
    dt = re.search(r"^dt = ([0-9.eE+-]+)$", info, re.M).group(1)
    skin = re.search(r"^skin = ([0-9.eE+-]+)$", info, re.M).group(1)
    steps = []
    for f in sorted(glob.glob(os.path.join(run_dir, "snapshots", "[0-9]*.csv"))):
        with open(f, encoding="ascii") as fh:
            fh.readline()
            steps.append(int(fh.readline().split(",")[1]))
    if len(steps) < 2:
        peerlib.fail(f"{run_dir}: fewer than 2 snapshots")
    every = steps[1] - steps[0]
    # the turning's steps: the time series' last step less the start's
    with open(os.path.join(run_dir, "time_series.csv"), encoding="ascii") as fh:
        last = list(csv.DictReader(fh))[-1]
    print(int(last["step"]) - steps[0], every, dt, skin)


def main(argv):
    if len(argv) == 4 and argv[1] == "data":
        drum_peer.write_data(argv[2], argv[3])
    elif len(argv) == 3 and argv[1] == "plan":
        plan(argv[2])
    elif len(argv) >= 6 and argv[1] == "measure" and argv[2] in ("tumble", "lammps"):
        opts = dict(zip(argv[6::2], argv[7::2]))
        print(json.dumps(measure(argv[2], argv[3], argv[4], float(argv[5]), float(opts.get("--from", 1.0)),
                                 opts.get("--timing"), opts.get("--log"))))
    elif len(argv) == 3 and argv[1] == "table":
        table(argv[2])
    else:
        peerlib.fail(__doc__)


if __name__ == "__main__":
    main(sys.argv)
