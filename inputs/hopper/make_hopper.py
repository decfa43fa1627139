#!/usr/bin/env python3
"""Meshes of the hopper deck (paper §7.3): a conical hopper as a closed thin-walled shell and a
floor slab, both closed and outward-oriented ASCII STL in metres (obstacles of pair_style trimesh
are closed solids of infinite mass).

  make_hopper.py HOPPER.stl FLOOR.stl [--segments 32] [--layers 5] [--cell 0.01]
                [--outlet-radius 0.015] [--lift 0] [--floor-half 0.06]

Hopper (defaults): outlet radius 0.015 at z = 0.04, top radius 0.05 at z = 0.10, wall 0.002 thick.
`--lift H` moves the hopper up by H (outlet at z = 0.04 + H).
Floor (defaults): the slab [-0.06, 0.06]^2 x [-0.01, 0] (top face at z = 0).
The defaults write the meshes of the regression deck; the pile run (README) uses a wider outlet
and a wider floor."""
import argparse
import math


def write_stl(path, tris):
    with open(path, "w") as f:
        f.write("solid s\n")
        for t in tris:
            f.write(" facet normal 0 0 0\n  outer loop\n")
            for v in t:
                f.write("   vertex %.17g %.17g %.17g\n" % tuple(v))
            f.write("  endloop\n endfacet\n")
        f.write("endsolid s\n")


def quad(a, b, c, d):
    """Two triangles of the quad a b c d (counter-clockwise seen from outside)."""
    return [(a, b, c), (a, c, d)]


def hopper(segments, layers, r_out=0.015, r_top=0.05, z_out=0.04, z_top=0.10, wall=0.002):
    """Inner and outer cone surfaces (`layers` rings along the height) joined by two annuli.
    Small triangles keep the contact search's triangle pruning tight."""
    def point(r, z, k):
        a = 2 * math.pi * k / segments
        return (r * math.cos(a), r * math.sin(a), z)

    def radius(inner, layer):
        r = r_out + (r_top - r_out) * layer / layers
        return r if inner else r + wall

    def z(layer):
        return z_out + (z_top - z_out) * layer / layers

    tris = []
    for l in range(layers):
        for k in range(segments):
            n = (k + 1) % segments
            # outer surface, normal away from the axis; inner surface, normal towards it
            tris += quad(point(radius(False, l), z(l), k), point(radius(False, l), z(l), n),
                         point(radius(False, l + 1), z(l + 1), n), point(radius(False, l + 1), z(l + 1), k))
            tris += quad(point(radius(True, l), z(l), n), point(radius(True, l), z(l), k),
                         point(radius(True, l + 1), z(l + 1), k), point(radius(True, l + 1), z(l + 1), n))
    for k in range(segments):
        n = (k + 1) % segments
        top, bot = layers, 0
        tris += quad(point(radius(True, top), z(top), k), point(radius(False, top), z(top), k),
                     point(radius(False, top), z(top), n), point(radius(True, top), z(top), n))   # +z
        tris += quad(point(radius(True, bot), z(bot), n), point(radius(False, bot), z(bot), n),
                     point(radius(False, bot), z(bot), k), point(radius(True, bot), z(bot), k))   # -z
    return tris


def slab(lo, hi, cell):
    """Closed box whose faces are grids of squares of about `cell` (shared edges match)."""
    n = [max(1, int(round((hi[d] - lo[d]) / cell))) for d in range(3)]

    def coord(d, i):
        return lo[d] + (hi[d] - lo[d]) * i / n[d]

    tris = []
    # for each axis d and side, a grid over the two other axes (u, v) with outward orientation
    for d in range(3):
        u, v = (d + 1) % 3, (d + 2) % 3
        for side, fixed in ((0, 0), (1, n[d])):
            for i in range(n[u]):
                for j in range(n[v]):
                    def p(a, b):
                        q = [0.0, 0.0, 0.0]
                        q[d], q[u], q[v] = coord(d, fixed), coord(u, a), coord(v, b)
                        return tuple(q)
                    c = [p(i, j), p(i + 1, j), p(i + 1, j + 1), p(i, j + 1)]
                    # (u x v) = +d: counter-clockwise in (u, v) faces +d
                    tris += quad(*(c if side == 1 else c[::-1]))
    return tris


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("hopper")
    ap.add_argument("floor")
    ap.add_argument("--segments", type=int, default=32)
    ap.add_argument("--layers", type=int, default=5)
    ap.add_argument("--cell", type=float, default=0.01, help="floor grid cell size")
    ap.add_argument("--outlet-radius", type=float, default=0.015, help="inner radius at the outlet (m)")
    ap.add_argument("--lift", type=float, default=0.0, help="raise the hopper by this height (m)")
    ap.add_argument("--floor-half", type=float, default=0.06, help="half width of the floor slab (m)")
    a = ap.parse_args()
    if not 0 < a.outlet_radius < 0.05:
        ap.error("--outlet-radius must lie in (0, 0.05), the top radius")
    if a.floor_half <= 0:
        ap.error("--floor-half must be > 0")
    write_stl(a.hopper, hopper(a.segments, a.layers, r_out=a.outlet_radius,
                               z_out=0.04 + a.lift, z_top=0.10 + a.lift))
    h = a.floor_half
    write_stl(a.floor, slab((-h, -h, -0.01), (h, h, 0.0), a.cell))


if __name__ == "__main__":
    main()
