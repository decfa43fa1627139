#!/usr/bin/env python3
"""Meshes and start positions of the rotating-drum deck (in.drum): a closed drum as a
thick-walled can (a closed, outward-oriented solid: the outer can minus the inner cavity, whose
surface faces the cavity), axis along y through the origin, and a lattice of particle centres
inside the cavity, alternately spheres (type 1) and triangulated grains (type 2).

  make_drum.py DRUM.stl POSITIONS.in [--radius 0.035] [--length 0.02] [--wall 0.003]
               [--segments 72] [--particles 600] [--particle-radius 0.002] [--spacing 0.0046]

The cavity: radius R, y in [-L/2, L/2]; the inner cylinder in rings along y and the end disks in
concentric rings, so that no triangle is much longer than the facets (2 pi R / segments).
POSITIONS.in: `create_atoms T single x y z units box` lines, lowest first."""
import argparse
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "hopper"))
from make_hopper import write_stl, quad  # noqa: E402  (one ASCII STL writer)


def can(radius, half_length, segments, rings, layers):
    """Closed cylinder about the y axis, outward-oriented: side in `layers` bands, end disks in
    `rings` rings (a fan in the middle)."""
    def point(r, y, k):
        a = 2 * math.pi * k / segments
        return (r * math.cos(a), y, r * math.sin(a))

    tris = []
    for l in range(layers):
        y0 = -half_length + 2 * half_length * l / layers
        y1 = -half_length + 2 * half_length * (l + 1) / layers
        for k in range(segments):
            n = (k + 1) % segments
            # normal away from the axis: (point at y0, k) -> (y1, k) -> (y1, n) -> (y0, n)
            tris += quad(point(radius, y0, k), point(radius, y1, k), point(radius, y1, n),
                         point(radius, y0, n))
    for side in (-1, 1):
        y = side * half_length
        for ring in range(rings):
            r0 = radius * ring / rings
            r1 = radius * (ring + 1) / rings
            for k in range(segments):
                n = (k + 1) % segments
                if ring == 0:
                    t = ((0.0, y, 0.0), point(r1, y, k), point(r1, y, n))
                    tris.append(t if side < 0 else (t[0], t[2], t[1]))
                else:
                    q = quad(point(r0, y, k), point(r1, y, k), point(r1, y, n), point(r0, y, n))
                    tris += q if side < 0 else [(a, c, b) for a, b, c in q]
    return tris


def flipped(tris):
    return [(a, c, b) for a, b, c in tris]


def lattice(R, L, r, spacing, count):
    """Simple cubic lattice points whose sphere of radius r (plus a margin) fits the cavity,
    lowest first (ties by x, y), the first `count`."""
    margin = 0.1 * r
    pts = []
    n = int(R / spacing) + 1
    ny = int(L / 2 / spacing) + 1
    for i in range(-n, n + 1):
        for j in range(-ny, ny + 1):
            for k in range(-n, n + 1):
                x, y, z = i * spacing, (j + 0.5) * spacing, k * spacing
                if math.hypot(x, z) + r + margin <= R and abs(y) + r + margin <= L / 2:
                    pts.append((z, x, y))
    pts.sort()
    if len(pts) < count:
        raise SystemExit("only %d lattice positions fit the cavity, %d asked" % (len(pts), count))
    return [(x, y, z) for z, x, y in pts[:count]]


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("drum")
    p.add_argument("positions")
    p.add_argument("--radius", type=float, default=0.035)
    p.add_argument("--length", type=float, default=0.02)
    p.add_argument("--wall", type=float, default=0.003)
    p.add_argument("--segments", type=int, default=72)
    p.add_argument("--particles", type=int, default=600)
    p.add_argument("--particle-radius", type=float, default=0.002)
    p.add_argument("--spacing", type=float, default=0.0046)
    a = p.parse_args()
    R, L, t = a.radius, a.length, a.wall
    facet = 2 * math.pi * R / a.segments
    layers = max(1, round(L / facet))
    rings = max(1, round(R / facet / 2))
    outer = can(R + t, L / 2 + t, a.segments, rings, max(1, round((L + 2 * t) / facet)))
    inner = flipped(can(R, L / 2, a.segments, rings, layers))
    write_stl(a.drum, outer + inner)
    pts = lattice(R, L, a.particle_radius, a.spacing, a.particles)
    with open(a.positions, "w") as f:
        for i, (x, y, z) in enumerate(pts):
            f.write("create_atoms %d single %.9g %.9g %.9g units box\n" % (1 + i % 2, x, y, z))
    print("drum: %d triangles (cavity radius %g m, length %g m); %d particles"
          % (len(outer) + len(inner), R, L, len(pts)))


if __name__ == "__main__":
    main()
