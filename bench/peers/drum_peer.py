#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The LAMMPS peer on tumble's long drum (bench/compare_drum.sh,
bench/peers/lammps_drum.in; docs/BENCHMARKS.md, "LAMMPS on the same drum").
Standard library only.

  drum_peer.py data SNAPSHOT.csv OUT.data
        the settled bed that `tumble bench --case long-drum --export DIR` wrote
        (DIR/snapshots/000000.csv) as a LAMMPS data file (atom_style sphere):
        type 1 material-1, 2 material-2, 3 the wall spheres; atom id = tumble
        id + 1; velocities and spins as tumble has them
  drum_peer.py lammps LOG CONFIG TIMING [ROUND]    one JSON result line from a LAMMPS log
  drum_peer.py tumble STDOUT CONFIG TIMING [ROUND] one JSON result line from `tumble bench --json`
  drum_peer.py table RESULTS.jsonl         medians per configuration and the ratios,
                                           and the ratios round by round with intervals

A result line has: code, law, config, procs (cores: threads x ranks; tumble
also gives ranks), grains, steps, seconds,
grain_updates_per_second (grains x timed steps / wall time of the timed
steps), cpu_seconds (CPU time of the timed steps, all threads or ranks),
kinetic_translational and kinetic_rotational (J, grains, at the end),
contacts, neighbor_builds, the whole process's cpu/wall (peerlib.py), and
the round it ran in (when given).
law is LAMMPS's own for LAMMPS ("peer") and `tumble bench --law`'s for
tumble: "drum" (the paper's) or "peer" (the deck's law: the same work).
On a loaded machine grains x steps / cpu_seconds is the steadier measure
of the work per update: a code that waited for a core loses wall time, not
CPU time (but a thread spinning at a barrier burns CPU time).
"""
import csv
import json
import re
import statistics
import sys

import peerlib

# The paper's materials as tumble's drum uses them (src/tumble/setup/
# paper_materials.hpp): LAMMPS type, radius (m); rho = 1000 kg/m^3 for all.
TYPES = {"material-1": (1, 3.6e-3), "material-2": (2, 2.4e-3), "wall": (3, 3.0e-3)}
RHO = 1000.0
MARGIN = 2  # the box reaches this many largest radii beyond every sphere

# thermo of lammps_drum.in: Step Atoms c_kgrain c_rgrain v_contacts v_rmax v_zmax
THERMO_HEAD = re.compile(r"^\s*Step\s+Atoms\s+c_kgrain\s+c_rgrain\s+v_contacts\s+v_rmax\s+v_zmax\s*$")
GRAINS = re.compile(r"TUMBLE_PEER drum grains=(\d+)")
IMBALANCE = re.compile(r"initial/final imbalance factor\s*=\s*[0-9.]+\s+([0-9.]+)")
CPU_USE = re.compile(r"([0-9.]+)% CPU use with (\d+) MPI tasks")


def write_data(snapshot, out):
    with open(snapshot, encoding="ascii") as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    if not rows:
        peerlib.fail(f"{snapshot}: no particles")
    spheres = []
    for r in rows:
        if r["material"] not in TYPES:
            peerlib.fail(f"{snapshot}: material '{r['material']}' is not one of the drum's {sorted(TYPES)}")
        kind, radius = TYPES[r["material"]]
        if float(r["radius"]) != radius or (r["kinematic"] == "1") != (kind == 3):
            peerlib.fail(f"{snapshot}: particle {r['id']} is not the paper's drum (radius {r['radius']}, "
                         f"kinematic {r['kinematic']}, material {r['material']})")
        spheres.append((int(r["id"]) + 1, kind, r))
    largest = max(radius for _, radius in TYPES.values())
    reach = [max(abs(float(r[c])) for _, _, r in spheres) + MARGIN * largest for c in "xyz"]
    # the wall turns about z: its spheres sweep the circle through the farthest one
    reach[0] = reach[1] = max(reach[0], reach[1])
    with open(out, "w", encoding="ascii") as f:
        f.write(f"# bench/peers/drum_peer.py from {snapshot}\n\n")
        f.write(f"{len(spheres)} atoms\n3 atom types\n\n")
        for c, half in zip("xyz", reach):
            f.write(f"{-half!r} {half!r} {c}lo {c}hi\n")
        f.write("\nAtoms # sphere\n\n")  # id type diameter density x y z
        for i, kind, r in spheres:
            f.write(f"{i} {kind} {2 * float(r['radius'])!r} {RHO!r} {r['x']} {r['y']} {r['z']}\n")
        f.write("\nVelocities\n\n")  # id vx vy vz wx wy wz
        for i, _, r in spheres:
            f.write(f"{i} {r['vx']} {r['vy']} {r['vz']} {r['wx']} {r['wy']} {r['wz']}\n")
    grains = sum(1 for _, kind, _ in spheres if kind != 3)
    print(f"{out}: {grains} grains, {len(spheres) - grains} wall spheres")


def parse_lammps(path, config):
    text = open(path, encoding="utf-8", errors="replace").read()
    error = next((l for l in text.splitlines() if l.startswith("ERROR")), None)
    if error:
        peerlib.fail(f"{path}: LAMMPS stopped: {error.strip()}")
    loops = peerlib.LOOP.findall(text)
    grains = GRAINS.findall(text)
    if not loops or not grains:
        peerlib.fail(f"{path}: no 'Loop time' or TUMBLE_PEER line (did LAMMPS finish?)")
    seconds, procs, steps, _ = loops[-1]  # the last run is the timed one
    last = None
    lines = text.splitlines()
    for i, l in enumerate(lines):
        if THERMO_HEAD.match(l):
            j = i + 1
            while j < len(lines) and re.match(r"^\s*\d+\s", lines[j]):
                last = lines[j].split()
                j += 1
    imbalance = IMBALANCE.findall(text)
    builds = peerlib.BUILDS.findall(text)
    cpu_use = CPU_USE.findall(text)  # per rank, averaged over the ranks
    n, seconds, steps, procs = int(grains[-1]), float(seconds), int(steps), int(procs)
    return {"code": "lammps", "law": "peer", "config": config, "procs": procs, "grains": n, "steps": steps,
            "seconds": seconds, "grain_updates_per_second": n * steps / seconds,
            "cpu_seconds": seconds * procs * float(cpu_use[-1][0]) / 100.0,
            "neighbor_builds": int(builds[-1]),
            "kinetic_translational": float(last[2]), "kinetic_rotational": float(last[3]),
            "contacts": float(last[4]), "largest_axis_distance": float(last[5]),
            "largest_abs_z": float(last[6]),
            "imbalance": float(imbalance[-1]) if imbalance else None}


def parse_tumble(path, config):
    lines = [l for l in open(path, encoding="utf-8", errors="replace").read().splitlines() if l.strip()]
    try:
        d = json.loads(lines[-1])
    except (IndexError, json.JSONDecodeError):
        peerlib.fail(f"{path}: the last line of `tumble bench --case long-drum --json` is not JSON")
    ranks = int(d.get("ranks", 1))
    return {"code": "tumble", "law": d.get("law", "drum"), "config": config, "procs": int(d["threads"]) * ranks,
            "ranks": ranks, "grains": int(d["grains"]),
            "steps": int(d["steps"]), "seconds": float(d["seconds"]),
            "grain_updates_per_second": float(d["grain_updates_per_second"]),
            "cpu_seconds": float(d["cpu_seconds"]),
            "kinetic_translational": float(d["kinetic_translational"]),
            "kinetic_rotational": float(d["kinetic_rotational"]), "contacts": float(d["contacts"]),
            "dt": float(d["dt"]), "neighbor_builds": d["neighbor_builds"]}


def split(r):
    """How a run's cores were used: "" on one core, else "threads" or "ranks"."""
    if r["procs"] == 1:
        return ""
    return "ranks" if r["code"] == "lammps" or r.get("ranks", 1) > 1 else "threads"


def print_rounds(rows):
    """The ratios paired within each round (every round runs every
    configuration once, one after the other), with their geometric mean and
    95 % t interval (peerlib.ratio_interval): tumble against LAMMPS on as
    many cores, and each code's several cores against its one."""
    rounds = {}
    for r in rows:
        if "round" in r:
            rounds.setdefault(r["round"], {})[(r["code"], r.get("law", "drum"), r["procs"], split(r))] = r
    configs = sorted({k for runs in rounds.values() for k in runs}, key=lambda k: (k[0] != "tumble", k[1], k[2], k[3]))
    pairs = []
    for k in configs:
        code, law, procs, how = k
        if code == "tumble":
            pairs.append((f"tumble {law} law, {f'{procs} {how}'.strip()} / LAMMPS {procs}", k,
                          ("lammps", "peer", procs, "ranks" if procs > 1 else "")))
        if procs > 1:
            pairs.append((f"{code} {law} law, {procs} {how} / 1 core", k, (code, law, 1, "")))
    peerlib.print_round_ratios(rounds, pairs, "grain_updates_per_second")


def table(path):
    rows = [json.loads(l) for l in open(path, encoding="utf-8") if l.strip()]
    groups = {}
    for r in rows:
        r["per_cpu_second"] = r["grains"] * r["steps"] / r["cpu_seconds"]
        groups.setdefault((r["code"], r.get("law", "drum"), r["procs"], split(r)), []).append(r)
    med = lambda rs, key: statistics.median(r[key] for r in rs)
    wall = {k: med(rs, "grain_updates_per_second") for k, rs in groups.items()}
    cpu = {k: med(rs, "per_cpu_second") for k, rs in groups.items()}
    hdr = ("code", "law", "cores", "runs", "grain updates/s", "per core", "min..max", "wall s", "cpu/wall",
           "per CPU s", "KE trans J", "KE rot J", "contacts", "nbr builds", "tumble/LAMMPS", "by CPU s")
    out = []
    order = lambda kv: (kv[0][0] != "tumble", kv[0][1], kv[0][2], kv[0][3])
    for (code, law, procs, how), rs in sorted(groups.items(), key=order):
        k, peer = (code, law, procs, how), ("lammps", "peer", procs, "ranks" if procs > 1 else "")
        ups = [r["grain_updates_per_second"] for r in rs]
        use = [r["cpu_seconds"] / (r["seconds"] * procs) for r in rs]
        against = code == "tumble" and peer in wall
        out.append((code, law, f"{procs} {how}".strip(), str(len(rs)), peerlib.fmt_rate(wall[k]),
                    peerlib.fmt_rate(wall[k] / procs),
                    f"{peerlib.fmt_rate(min(ups))}..{peerlib.fmt_rate(max(ups))}", f"{med(rs, 'seconds'):.1f}",
                    f"{min(use):.2f}..{max(use):.2f}", peerlib.fmt_rate(cpu[k]),
                    f"{rs[-1]['kinetic_translational']:.3g}", f"{rs[-1]['kinetic_rotational']:.3g}",
                    f"{rs[-1]['contacts']:.0f}", str(rs[-1]["neighbor_builds"]),
                    f"{wall[k] / wall[peer]:.2f}" if against else "-", f"{cpu[k] / cpu[peer]:.2f}" if against else "-"))
    peerlib.print_table(hdr, out)
    print_rounds(rows)
    for (code, law, procs, how), rs in sorted(groups.items()):
        if procs > 1 and (code, law, 1, "") in wall:
            print(f"{code} ({law} law): {procs} {how} {wall[(code, law, procs, how)] / wall[(code, law, 1, '')]:.2f}x"
                  " one core (wall time)")
        imbalance = [r["imbalance"] for r in rs if r.get("imbalance") is not None]
        if procs > 1 and imbalance:
            print(f"{code} {procs} ranks: load imbalance after the balance command "
                  f"{min(imbalance):.2f}..{max(imbalance):.2f}")
    print("grain updates/s = grains x timed steps / wall time of the timed steps (wall spheres not counted);"
          " per CPU s: the same over the CPU time of the timed steps; cpu/wall: CPU time over wall time x cores"
          " in the timed steps (below 1: it waited for a core); tumble/LAMMPS: medians against LAMMPS on as"
          " many MPI ranks as tumble has cores (threads or ranks; per core alike); law: drum = the paper's"
          " (attraction, saw-tooth shear), peer = the LAMMPS deck's (no attraction, shear = spring), the same"
          " work in both codes; KE, contacts (touching pairs, wall included) and neighbour builds of the last run")


def main(argv):
    if len(argv) == 4 and argv[1] == "data":
        write_data(argv[2], argv[3])
    elif len(argv) in (5, 6) and argv[1] in ("lammps", "tumble"):
        f = parse_lammps if argv[1] == "lammps" else parse_tumble
        result = peerlib.add_timing(f(argv[2], argv[3]), argv[4])
        if len(argv) == 6:
            result["round"] = int(argv[5])
        print(json.dumps(result))
    elif len(argv) == 3 and argv[1] == "table":
        table(argv[2])
    else:
        peerlib.fail(__doc__)


if __name__ == "__main__":
    main(sys.argv)
