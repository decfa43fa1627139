#!/usr/bin/env python3
"""Meshes of the hopper deck (paper §7.3): a conical hopper as a closed thin-walled shell and a
floor slab, both closed and outward-oriented ASCII STL in metres (obstacles of pair_style trimesh
are closed solids of infinite mass).

  make_hopper.py HOPPER.stl FLOOR.stl [--segments 48]

Hopper: outlet radius 0.015 at z = 0.04, top radius 0.05 at z = 0.10, wall 0.002 thick.
Floor: the slab [-0.08, 0.08]^2 x [-0.01, 0] (top face at z = 0)."""
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


def hopper(segments, r_out=0.015, r_top=0.05, z_out=0.04, z_top=0.10, wall=0.002):
    # inner cone surface (r_in) and outer cone surface (r_in + wall) joined by two annuli
    def ring(r, z):
        return [(r * math.cos(2 * math.pi * k / segments), r * math.sin(2 * math.pi * k / segments), z)
                for k in range(segments)]
    ib, it = ring(r_out, z_out), ring(r_top, z_top)
    ob, ot = ring(r_out + wall, z_out), ring(r_top + wall, z_top)
    tris = []
    for k in range(segments):
        n = (k + 1) % segments
        tris += quad(ob[k], ob[n], ot[n], ot[k])   # outer surface, normal away from the axis
        tris += quad(ib[n], ib[k], it[k], it[n])   # inner surface, normal towards the axis
        tris += quad(it[k], ot[k], ot[n], it[n])   # top annulus, normal +z
        tris += quad(ib[n], ob[n], ob[k], ib[k])   # bottom annulus, normal -z
    return tris


def slab(lo, hi):
    x0, y0, z0 = lo
    x1, y1, z1 = hi
    v = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
         (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    tris = []
    for a, b, c, d in [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (2, 3, 7, 6), (1, 2, 6, 5), (3, 0, 4, 7)]:
        tris += quad(v[a], v[b], v[c], v[d])
    return tris


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("hopper")
    ap.add_argument("floor")
    ap.add_argument("--segments", type=int, default=48)
    a = ap.parse_args()
    write_stl(a.hopper, hopper(a.segments))
    write_stl(a.floor, slab((-0.08, -0.08, -0.01), (0.08, 0.08, 0.0)))


if __name__ == "__main__":
    main()
