#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Start of the pour (bench/peers/lammps_pour.in, bench/peers/tumble_pour.toml):
the same grains, positions and velocities for tumble and LAMMPS.

  pour_start.py --seed S --out DIR [--grains N]

writes DIR/start.csv (tumble's particle CSV, docs/SCENARIO.md) and
DIR/start.data (LAMMPS read_data, atom_style sphere), the same grains in the
same order (tumble's global id k is LAMMPS atom id k + 1):

  N grains (default 300), half of the paper's material 1 (R = 3.6 mm), half
  of material 2 (R = 2.4 mm), in random order, placed by random sequential
  addition (no overlaps, at least 0.2 mm apart and from the walls) in
  x, y in [0, 4 cm], z in [0, 12 cm] of the box [0, 4 cm]^2 x [0, 20 cm];
  each with speed 0.1 m/s in a uniformly random direction, no spin.

Deterministic: Python's Mersenne Twister seeded with S, only random.random(),
and numbers written with repr (shortest round-trip), so a seed gives the same
files on every machine. Standard library only.
"""
import argparse
import math
import os
import random
import sys

BOX = (0.04, 0.04, 0.20)        # box edges, m (flat walls on all six faces)
FILL_TOP = 0.12                 # grains start below this height, m
RADII = {1: 3.6e-3, 2: 2.4e-3}  # paper's material 1 and 2, m
RHO = 1000.0                    # kg/m^3, both materials
GAP = 2.0e-4                    # least gap between two grains, and to a wall, m
SPEED = 0.1                     # initial speed, m/s
NAMES = {1: "material-1", 2: "material-2"}


def generate(seed, grains):
    rng = random.Random(seed)
    kinds = [1] * (grains // 2) + [2] * (grains - grains // 2)
    rng.shuffle(kinds)
    placed = []  # (x, y, z, r)
    for kind in kinds:
        r = RADII[kind]
        lo = r + GAP
        for _ in range(100000):
            p = (lo + rng.random() * (BOX[0] - 2 * lo),
                 lo + rng.random() * (BOX[1] - 2 * lo),
                 lo + rng.random() * (FILL_TOP - 2 * lo))
            if all((p[0] - q[0]) ** 2 + (p[1] - q[1]) ** 2 + (p[2] - q[2]) ** 2 >= (r + q[3] + GAP) ** 2
                   for q in placed):
                placed.append((p[0], p[1], p[2], r))
                break
        else:
            sys.exit(f"pour_start.py: cannot place grain {len(placed)} (seed {seed})")
    out = []
    for kind, (x, y, z, r) in zip(kinds, placed):
        cos_t = 2.0 * rng.random() - 1.0
        sin_t = math.sqrt(max(0.0, 1.0 - cos_t * cos_t))
        phi = 2.0 * math.pi * rng.random()
        v = (SPEED * sin_t * math.cos(phi), SPEED * sin_t * math.sin(phi), SPEED * cos_t)
        out.append((kind, r, (x, y, z), v))
    return out


def write(grains, directory):
    os.makedirs(directory, exist_ok=True)
    with open(os.path.join(directory, "start.csv"), "w", encoding="ascii") as f:
        f.write("# bench/peers/pour_start.py; row k = global id k = LAMMPS atom id k + 1\n")
        f.write("x,y,z,vx,vy,vz,material\n")
        for kind, r, p, v in grains:
            f.write(",".join(repr(c) for c in (*p, *v)) + f",{NAMES[kind]}\n")
    with open(os.path.join(directory, "start.data"), "w", encoding="ascii") as f:
        f.write("# bench/peers/pour_start.py: the pour's start (same grains as start.csv)\n\n")
        f.write(f"{len(grains)} atoms\n2 atom types\n\n")
        f.write(f"0.0 {BOX[0]!r} xlo xhi\n0.0 {BOX[1]!r} ylo yhi\n0.0 {BOX[2]!r} zlo zhi\n\n")
        f.write("Atoms # sphere\n\n")  # id type diameter density x y z
        for k, (kind, r, p, v) in enumerate(grains):
            f.write(f"{k + 1} {kind} {2 * r!r} {RHO!r} {p[0]!r} {p[1]!r} {p[2]!r}\n")
        f.write("\nVelocities\n\n")  # id vx vy vz wx wy wz
        for k, (kind, r, p, v) in enumerate(grains):
            f.write(f"{k + 1} {v[0]!r} {v[1]!r} {v[2]!r} 0.0 0.0 0.0\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--seed", type=int, required=True)
    ap.add_argument("--out", required=True, help="directory for start.csv and start.data")
    ap.add_argument("--grains", type=int, default=300)
    a = ap.parse_args()
    if a.grains < 1 or a.grains > 2000:
        sys.exit("pour_start.py: --grains must lie in [1, 2000]")
    write(generate(a.seed, a.grains), a.out)


if __name__ == "__main__":
    main()
