#!/usr/bin/env python3
"""Meshes of the grain pour (in.pour): an L-shaped prism grain and an open box of five slab
obstacles, closed outward-oriented ASCII STL in metres.

  make_pour.py DIR [--arm 0.005] [--width 0.002] [--depth 0.0025] [--half 0.04] [--height 0.1]

L prism (defaults): the L of outer size arm x arm with arms `width` wide, extruded `depth`
(volume (2 arm - width) width depth = 4e-8 m^3, 20 triangles; concave). Box: a floor slab
[-(half+t), half+t]^2 x [-t, 0] and four walls `t` = 5 mm thick and `height` high around the
inner square [-half, half]^2 (the slabs of inputs/hopper/make_hopper.py)."""
import argparse
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "hopper"))
from make_hopper import quad, slab, write_stl  # noqa: E402


def l_prism(arm, width, depth):
    """The L polygon (0,0) (arm,0) (arm,w) (w,w) (w,arm) (0,arm), counter-clockwise, extruded
    from z = 0 to depth; caps split into the two convex quads (0,0)(arm,0)(arm,w)(w,w) and
    (0,0)(w,w)(w,arm)(0,arm)."""
    poly = [(0, 0), (arm, 0), (arm, width), (width, width), (width, arm), (0, arm)]
    lo = [(x, y, 0.0) for x, y in poly]
    hi = [(x, y, depth) for x, y in poly]
    tris = []
    for a, b, c, d in ((0, 1, 2, 3), (0, 3, 4, 5)):
        tris += quad(hi[a], hi[b], hi[c], hi[d])        # top, +z
        tris += quad(lo[d], lo[c], lo[b], lo[a])        # bottom, -z
    n = len(poly)
    for k in range(n):                                   # sides, outward for a ccw polygon
        m = (k + 1) % n
        tris += quad(lo[k], lo[m], hi[m], hi[k])
    return tris


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("dir")
    ap.add_argument("--arm", type=float, default=0.005)
    ap.add_argument("--width", type=float, default=0.002)
    ap.add_argument("--depth", type=float, default=0.0025)
    ap.add_argument("--half", type=float, default=0.04)
    ap.add_argument("--height", type=float, default=0.1)
    a = ap.parse_args()
    if not 0 < a.width < a.arm or a.depth <= 0 or a.half <= 0 or a.height <= 0:
        ap.error("need 0 < width < arm, depth > 0, half > 0, height > 0")
    os.makedirs(a.dir, exist_ok=True)
    write_stl(os.path.join(a.dir, "lprism.stl"), l_prism(a.arm, a.width, a.depth))
    h, t, H = a.half, 0.005, a.height
    walls = {
        "floor": ((-h - t, -h - t, -t), (h + t, h + t, 0.0)),
        "xlo": ((-h - t, -h, 0.0), (-h, h, H)),
        "xhi": ((h, -h, 0.0), (h + t, h, H)),
        "ylo": ((-h - t, -h - t, 0.0), (h + t, -h, H)),
        "yhi": ((-h - t, h, 0.0), (h + t, h + t, H)),
    }
    for name, (lo, hi) in walls.items():
        write_stl(os.path.join(a.dir, name + ".stl"), slab(lo, hi, 1.0))   # 12 triangles each


if __name__ == "__main__":
    main()
