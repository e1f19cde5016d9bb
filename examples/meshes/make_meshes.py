#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Writes the triangle meshes of the examples as binary STL files, in mm.

    python3 examples/meshes/make_meshes.py             # rewrites chute.stl, v_blender.stl and drum_lifters.stl here
    python3 examples/meshes/make_meshes.py --out DIR   # writes them into DIR instead

Python 3, standard library only; the same files on every run (no dates, no
randomness: the 80-byte header is fixed text). Each vertex is computed once
and reused by every triangle that has it, so that the corners shared by
triangles carry the same float32 numbers and tumble joins them into one
vertex (walls/mesh.hpp, weld_triangles: exact equality).

chute.stl (examples/chute.toml): an open trough, a flat base and two side
walls, open at both ends and on top. In the file it lies level along +x:
    base    z = 0, 0 <= x <= LENGTH, -WIDTH/2 <= y <= WIDTH/2
    sides   y = +-WIDTH/2, 0 <= z <= HEIGHT
The scenario tilts it (rotation about y) and places it (offset).

v_blender.stl (examples/v_blender.toml): two tubes of radius RADIUS joined
in a V, closed: the apex at the origin, the arms' axes in the x-z plane at
+-ALPHA from the vertical (+z), each ARM mm long from the apex to the
centre of its flat end cap. The tubes are mitred where they meet, in the
plane x = 0 (each tube cut by the V's plane of symmetry; both cuts are the
same ellipse, whose vertices the two arms share), so the surface is one
closed mesh: every edge has two faces. SEGMENTS facets round a tube.

drum_lifters.stl (examples/drum_lifters.toml): the mantle of the paper's
drum (80 mm across, 120 mm long, the axis along z through the origin, open
at z = +-60 mm where tumble drum puts its smooth caps) with six lifters:
bars 3 mm thick standing 8 mm in from the mantle along its whole length,
each three faces (two sides and a top; their ends meet the caps), the sides
reaching 1 mm into the mantle so that no gap opens between them.
"""
import argparse
import math
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))

# The chute, mm.
CHUTE_LENGTH = 200.0
CHUTE_WIDTH = 30.0
CHUTE_HEIGHT = 25.0
CHUTE_PANELS = 10  # panels along the length (each 20 mm)

# The V-blender, mm and degrees.
BLENDER_RADIUS = 25.0
BLENDER_ARM = 100.0  # apex to the centre of an end cap, along the arm's axis
BLENDER_ALPHA = 40.0  # each arm from the vertical: 80 degrees between the arms
BLENDER_SEGMENTS = 32  # round a tube
BLENDER_RINGS = 12  # facets along a tube, from the mitre to the cap

# The drum with lifters, mm.
DRUM_RADIUS = 40.0
DRUM_LENGTH = 120.0
DRUM_SEGMENTS = 120  # round the mantle: its faces within 0.014 mm of the circle
DRUM_PANELS = 4  # along the axis
LIFTERS = 6
LIFTER_HEIGHT = 8.0  # in from the mantle
LIFTER_THICKNESS = 3.0


def f32(v):
    """The point as the float32 numbers the file will hold."""
    return tuple(struct.unpack("<f", struct.pack("<f", c))[0] for c in v)


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def write_stl(path, name, triangles):
    """Binary STL: an 80-byte header, the count, then per triangle its unit
    normal (right-hand rule of the corner order), three corners and a zero
    attribute word, all little-endian."""
    header = ("tumble example mesh: " + name + ", mm").encode("ascii")[:80].ljust(80, b" ")
    with open(path, "wb") as f:
        f.write(header)
        f.write(struct.pack("<I", len(triangles)))
        for a, b, c in triangles:
            n = cross(sub(b, a), sub(c, a))
            length = math.sqrt(n[0] ** 2 + n[1] ** 2 + n[2] ** 2)
            n = (n[0] / length, n[1] / length, n[2] / length)
            f.write(struct.pack("<12fH", *n, *a, *b, *c, 0))
    return len(triangles)


def quad(triangles, a, b, c, d):
    """The quadrilateral a b c d (in order round it) as two triangles."""
    triangles.append((a, b, c))
    triangles.append((a, c, d))


def chute():
    h = CHUTE_WIDTH / 2.0
    xs = [CHUTE_LENGTH * i / CHUTE_PANELS for i in range(CHUTE_PANELS + 1)]
    base_l = [f32((x, -h, 0.0)) for x in xs]  # the base's edges, which the sides share
    base_r = [f32((x, h, 0.0)) for x in xs]
    top_l = [f32((x, -h, CHUTE_HEIGHT)) for x in xs]
    top_r = [f32((x, h, CHUTE_HEIGHT)) for x in xs]
    triangles = []
    for i in range(CHUTE_PANELS):
        # The base (normal +z, into the trough), then the sides (normals +y and -y).
        quad(triangles, base_l[i], base_l[i + 1], base_r[i + 1], base_r[i])
        quad(triangles, base_l[i], top_l[i], top_l[i + 1], base_l[i + 1])
        quad(triangles, base_r[i], base_r[i + 1], top_r[i + 1], top_r[i])
    return triangles


def v_blender():
    r, arm, n, m = BLENDER_RADIUS, BLENDER_ARM, BLENDER_SEGMENTS, BLENDER_RINGS
    a = math.radians(BLENDER_ALPHA)
    sa, ca = math.sin(a), math.cos(a)
    axis = (sa, 0.0, ca)  # the arm at x > 0, from the apex
    e1 = (ca, 0.0, -sa)  # across it, in the V's plane (outwards and down)
    e2 = (0.0, 1.0, 0.0)

    def point(s, phi):
        c, d = r * math.cos(phi), r * math.sin(phi)
        return tuple(s * axis[k] + c * e1[k] + d * e2[k] for k in range(3))

    # rings[k][j]: the j-th point round the tube, k-th from the mitre (k = 0,
    # in the plane x = 0) to the end cap (k = m, at s = arm).
    rings = [[None] * n for _ in range(m + 1)]
    for j in range(n):
        phi = 2.0 * math.pi * j / n
        s0 = -r * math.cos(phi) * ca / sa  # where the line along the tube crosses x = 0
        for k in range(m + 1):
            p = point(s0 + (arm - s0) * k / m, phi)
            if k == 0:
                p = (0.0, p[1], p[2])  # on the mitre: exactly in the plane of symmetry
            rings[k][j] = f32(p)
    cap_centre = f32(tuple(arm * axis[k] for k in range(3)))

    right = []
    for k in range(m):
        for j in range(n):
            jn = (j + 1) % n
            quad(right, rings[k][j], rings[k + 1][j], rings[k + 1][jn], rings[k][jn])
    for j in range(n):
        right.append((cap_centre, rings[m][(j + 1) % n], rings[m][j]))
    # The other arm, the mirror image in x = 0 (corner order reversed, so
    # that the normals keep their side; the mitre's vertices are shared).
    def mirror(p):
        return (0.0 - p[0], p[1], p[2])  # 0.0 - 0.0 is +0.0

    left = [(mirror(t[0]), mirror(t[2]), mirror(t[1])) for t in right]
    return right + left


def drum_lifters():
    r, n, half = DRUM_RADIUS, DRUM_SEGMENTS, DRUM_LENGTH / 2.0
    zs = [-half + DRUM_LENGTH * k / DRUM_PANELS for k in range(DRUM_PANELS + 1)]
    rings = [[f32((r * math.cos(2.0 * math.pi * j / n), r * math.sin(2.0 * math.pi * j / n), z))
              for j in range(n)] for z in zs]
    triangles = []
    for k in range(DRUM_PANELS):  # the mantle, normals towards the axis
        for j in range(n):
            quad(triangles, rings[k][j], rings[k][(j + 1) % n], rings[k + 1][(j + 1) % n], rings[k + 1][j])
    for i in range(LIFTERS):
        phi = 2.0 * math.pi * i / LIFTERS
        u = (math.cos(phi), math.sin(phi), 0.0)  # from the axis
        t = (-math.sin(phi), math.cos(phi), 0.0)  # across the bar
        def at(rho, side, z):
            w = side * LIFTER_THICKNESS / 2.0
            return f32((rho * u[0] + w * t[0], rho * u[1] + w * t[1], z))
        outer, inner = r + 1.0, r - LIFTER_HEIGHT
        for k in range(DRUM_PANELS):
            z0, z1 = zs[k], zs[k + 1]
            quad(triangles, at(outer, -1, z0), at(inner, -1, z0), at(inner, -1, z1), at(outer, -1, z1))
            quad(triangles, at(inner, -1, z0), at(inner, 1, z0), at(inner, 1, z1), at(inner, -1, z1))
            quad(triangles, at(inner, 1, z0), at(outer, 1, z0), at(outer, 1, z1), at(inner, 1, z1))
    return triangles


def main():
    parser = argparse.ArgumentParser(
        description="Writes the examples' STL files (chute.stl, v_blender.stl, drum_lifters.stl).")
    parser.add_argument("--out", default=HERE, help="directory to write them into (default: beside this script)")
    out = parser.parse_args().out
    os.makedirs(out, exist_ok=True)
    for name, triangles in (("chute", chute()), ("v_blender", v_blender()), ("drum_lifters", drum_lifters())):
        path = os.path.join(out, name + ".stl")
        count = write_stl(path, name, triangles)
        print(f"{path}: {count} triangles, {os.path.getsize(path)} bytes")


if __name__ == "__main__":
    main()
