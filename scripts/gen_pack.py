#!/usr/bin/env python3
"""Deterministic generator of LIGGGHTS data files (atom_style granular) for sphere packs.

Pure Python (no numpy), seeded, so the same command always writes the same file.
All lengths are in metres (LIGGGHTS `units si`).

Sub-commands
------------
bidisperse   small spheres (diameter --d) on a jittered cubic lattice, plus --K big spheres of
             diameter --R * d on a coarse lattice; lattice sites whose small sphere would overlap
             a big one are removed.  Without overlaps by construction: the lattice spacing is
             s = d (1 + gap) and each coordinate is jittered by at most jitter * (s - d) / 2.
continuous   radii log-uniform in [rmin, rmax] (--law loguniform) or with a number density
             proportional to r^-exponent (--law power; with --exponent 3 each doubling of the
             radius holds 4 times fewer spheres, and every size holds the same solid volume per
             unit radius), random sequential non-overlapping
             placement (largest first) with a multi-class cell grid for the overlap test.
crowded      one big sphere (diameter R * d) at the box centre, densely surrounded by a shell of
             small spheres (a Fibonacci sphere, thousands of them, all within --gap of contact)
             and optionally a jittered lattice of small ones in the rest of the box: the big
             sphere then has thousands of neighbours (tests neighbour-page overflow).
stl-funnel   an ASCII STL of a square funnel / tray: a square floor plus four sloped sides.

Common options: --boundary p (periodic: box = lattice/placement box, minimum-image overlap test)
or f (walled: box bounds are the walls, all spheres lie inside), --vel V (uniform random
velocity components in [-V, V], plus --vz0 added to vz), --seed, --density, --out.

The data file header (comment lines) records the atom count and the exact command line.
"""

import argparse
import math
import random
import sys

# ----------------------------------------------------------------------------------------------
# helpers


def fmt(v):
    return repr(float(v))


class Box:
    def __init__(self, lo, hi, periodic):
        self.lo = list(lo)
        self.hi = list(hi)
        self.periodic = periodic
        self.L = [h - l for l, h in zip(self.lo, self.hi)]

    def delta(self, a, b):
        """b - a, minimum image when periodic."""
        d = [b[k] - a[k] for k in range(3)]
        if self.periodic:
            for k in range(3):
                L = self.L[k]
                d[k] -= L * round(d[k] / L)
        return d

    def dist2(self, a, b):
        d = self.delta(a, b)
        return d[0] * d[0] + d[1] * d[1] + d[2] * d[2]

    def wrap(self, p):
        if not self.periodic:
            return p
        q = list(p)
        for k in range(3):
            L = self.L[k]
            q[k] = self.lo[k] + (q[k] - self.lo[k]) % L
            if q[k] >= self.hi[k]:  # (x % L) may round up to L
                q[k] = self.lo[k]
        return q


class MultiGrid:
    """Cell grids per size class (factor 4 in radius per class) for overlap queries among
    spheres of very different sizes.  A query scans, in each class, the cells within reach;
    when that is more cells than the class holds spheres it scans the class list instead."""

    def __init__(self, box, rmin, clearance=0.0):
        self.box = box
        self.rmin = rmin
        self.clear = clearance
        self.classes = {}  # k -> dict(cs, n[3], cells{}, members[], rmax)

    def _class(self, r):
        k = 0
        if r > self.rmin:
            k = int(math.floor(math.log(r / self.rmin, 4.0) + 1e-12))
        c = self.classes.get(k)
        if c is None:
            rmax = self.rmin * 4.0 ** (k + 1)
            h = 2.0 * rmax + self.clear
            n = [max(1, int(self.box.L[d] // h)) for d in range(3)]
            cs = [self.box.L[d] / n[d] for d in range(3)]
            c = {"cs": cs, "n": n, "cells": {}, "members": [], "rmax": rmax}
            self.classes[k] = c
        return c

    def _cell(self, c, p):
        idx = []
        for d in range(3):
            i = int(math.floor((p[d] - self.box.lo[d]) / c["cs"][d]))
            idx.append(min(max(i, 0), c["n"][d] - 1))
        return tuple(idx)

    def add(self, p, r, payload):
        c = self._class(r)
        c["members"].append((p, r, payload))
        c["cells"].setdefault(self._cell(c, p), []).append((p, r, payload))

    def overlaps(self, p, r, skip=None):
        """True if a sphere (p, r) overlaps (closer than r + rj + clearance) any stored sphere."""
        box = self.box
        for c in self.classes.values():
            if not c["members"]:
                continue
            reach = r + c["rmax"] + self.clear
            ranges = []
            ncells = 1
            for d in range(3):
                cs, n = c["cs"][d], c["n"][d]
                i0 = int(math.floor((p[d] - reach - box.lo[d]) / cs))
                i1 = int(math.floor((p[d] + reach - box.lo[d]) / cs))
                if box.periodic:
                    if i1 - i0 + 1 >= n:
                        rng = range(n)
                    else:
                        rng = sorted(set(i % n for i in range(i0, i1 + 1)))
                else:
                    rng = range(max(i0, 0), min(i1, n - 1) + 1)
                ranges.append(rng)
                ncells *= len(rng)
            if ncells >= len(c["members"]):
                cand = c["members"]
            else:
                cand = []
                cells = c["cells"]
                for i in ranges[0]:
                    for j in ranges[1]:
                        for k in ranges[2]:
                            lst = cells.get((i, j, k))
                            if lst:
                                cand.extend(lst)
            for (q, rq, payload) in cand:
                if skip is not None and payload == skip:
                    continue
                lim = r + rq + self.clear
                if box.dist2(p, q) < lim * lim:
                    return True
        return False


def wrap(text, width):
    """Split text at blanks into pieces of at most width characters (longer words stay whole)."""
    out, cur = [], ""
    for w in text.split(" "):
        if cur and len(cur) + 1 + len(w) > width:
            out.append(cur)
            cur = w
        else:
            cur = (cur + " " + w) if cur else w
    out.append(cur)
    return out


def velocities(rng, n, vmax, vz0):
    out = []
    for _ in range(n):
        if vmax > 0:
            v = [rng.uniform(-vmax, vmax) for _ in range(3)]
        else:
            v = [0.0, 0.0, 0.0]
        v[2] += vz0
        out.append(v)
    return out


def write_data(path, box, spheres, vels, header_lines, density):
    """spheres: list of (diameter, x, y, z, type)."""
    n = len(spheres)
    ntypes = max([s[4] for s in spheres] + [1])
    with open(path, "w") as f:
        f.write("LIGGGHTS data file written by spacetree-dem scripts/gen_pack.py\n")
        f.write("# atoms: %d\n" % n)
        # read_data reads header lines into 256-character buffers: wrap long comment lines
        for h in ["command: " + " ".join(sys.argv)] + list(header_lines):
            for k, part in enumerate(wrap(h, 180)):
                f.write("# %s%s\n" % ("  " if k else "", part))
        f.write("\n%d atoms\n%d atom types\n\n" % (n, ntypes))
        for k, (a, b) in enumerate(("xlo xhi", "ylo yhi", "zlo zhi")[i].split() for i in range(3)):
            f.write("%s %s %s %s\n" % (fmt(box.lo[k]), fmt(box.hi[k]), a, b))
        f.write("\nAtoms\n\n")
        for i, (dia, x, y, z, t) in enumerate(spheres):
            f.write("%d %d %s %s %s %s %s\n" % (i + 1, t, fmt(dia), fmt(density), fmt(x), fmt(y), fmt(z)))
        if vels is not None and any(v[0] or v[1] or v[2] for v in vels):
            f.write("\nVelocities\n\n")
            for i, v in enumerate(vels):
                f.write("%d %s %s %s 0 0 0\n" % (i + 1, fmt(v[0]), fmt(v[1]), fmt(v[2])))
    return n


def summary(spheres):
    d = [s[0] for s in spheres]
    vol = sum(math.pi / 6.0 * x ** 3 for x in d)
    return d, vol


def check_inside(box, spheres):
    if box.periodic:
        return
    for (dia, x, y, z, t) in spheres:
        r = 0.5 * dia
        for k, c in enumerate((x, y, z)):
            if c - r < box.lo[k] - 1e-12 or c + r > box.hi[k] + 1e-12:
                raise SystemExit("internal error: sphere outside the walled box")


# ----------------------------------------------------------------------------------------------
# (a) bidisperse


def jittered_lattice(rng, n, s, J, lo, region=None):
    """Sites (i+0.5)*s + U(-J,J) per coordinate; region: [[x0,x1],[y0,y1],[z0,z1]] absolute bounds
    on the unjittered site centres (None: all)."""
    out = []
    rngs = []
    for d in range(3):
        if region is None:
            rngs.append(range(n[d]))
        else:  # indices whose unjittered centre lies in [region lo, region hi]
            i0 = max(0, int(math.ceil((region[d][0] - lo[d]) / s - 0.5)))
            i1 = min(n[d] - 1, int(math.floor((region[d][1] - lo[d]) / s - 0.5)))
            rngs.append(range(i0, i1 + 1))
    u = rng.uniform
    for i in rngs[0]:
        x0 = lo[0] + (i + 0.5) * s
        for j in rngs[1]:
            y0 = lo[1] + (j + 0.5) * s
            for k in rngs[2]:
                out.append((x0 + u(-J, J), y0 + u(-J, J), lo[2] + (k + 0.5) * s + u(-J, J)))
    return out


def cmd_bidisperse(a):
    rng = random.Random(a.seed)
    d = a.d
    s = d * (1.0 + a.gap)
    J = a.jitter * 0.5 * (s - d)
    n = a.n if len(a.n) == 3 else [a.n[0]] * 3
    lo = [0.0, 0.0, 0.0]
    box = Box(lo, [n[k] * s for k in range(3)], a.boundary == "p")
    D = a.R * d
    # big spheres on a coarse kx*ky*kz lattice (first K sites), or explicit fractional positions
    bigs = []
    if a.big_at:
        for t in a.big_at:
            bigs.append([box.lo[k] + t[k] * box.L[k] for k in range(3)])
    elif a.K > 0:
        kk = a.big_lattice if a.big_lattice else [int(math.ceil(a.K ** (1.0 / 3.0) - 1e-9))] * 3
        sites = []
        for i in range(kk[0]):
            for j in range(kk[1]):
                for k in range(kk[2]):
                    sites.append([box.lo[0] + (i + 0.5) * box.L[0] / kk[0],
                                  box.lo[1] + (j + 0.5) * box.L[1] / kk[1],
                                  box.lo[2] + (k + 0.5) * box.L[2] / kk[2]])
        if len(sites) < a.K:
            raise SystemExit("big lattice %s has fewer than K=%d sites" % (kk, a.K))
        bigs = sites[:a.K]
    for b in bigs:
        if not box.periodic:
            for k in range(3):
                if b[k] - D / 2 < box.lo[k] or b[k] + D / 2 > box.hi[k]:
                    raise SystemExit("big sphere (D=%g) does not fit in the walled box (L=%g)" % (D, box.L[k]))
        else:
            for k in range(3):
                if box.L[k] < D:
                    raise SystemExit("periodic box %g smaller than the big diameter %g" % (box.L[k], D))
    for i in range(len(bigs)):
        for j in range(i):
            if box.dist2(bigs[i], bigs[j]) < D * D:
                raise SystemExit("big spheres overlap: box too small for K=%d bigs of D=%g" % (len(bigs), D))
    region = None
    if a.lattice_region:
        f = a.lattice_region
        region = [[box.lo[k] + f[2 * k] * box.L[k], box.lo[k] + f[2 * k + 1] * box.L[k]] for k in range(3)]
    sites = jittered_lattice(rng, n, s, J, lo, region)
    lim = 0.5 * (D + d) + a.clearance * d
    lim2 = lim * lim
    small = []
    removed = 0
    if bigs and a.R != 1.0:
        for p in sites:
            hit = False
            for b in bigs:
                if box.dist2(p, b) < lim2:
                    hit = True
                    break
            if hit:
                removed += 1
                continue
            if a.shell is not None:
                near = min(math.sqrt(box.dist2(p, b)) for b in bigs) - 0.5 * (D + d)
                if near > a.shell * d:
                    continue
            small.append(p)
    else:
        small = sites
        bigs = [] if a.R == 1.0 else bigs
    big_sph = [(D, b[0], b[1], b[2], a.big_type) for b in bigs]
    small_sph = [(d, p[0], p[1], p[2], 1) for p in small]
    spheres = big_sph + small_sph if a.bigs_first else small_sph + big_sph
    check_inside(box, spheres)
    vels = velocities(rng, len(spheres), a.vel, a.vz0)
    dd, vol = summary(spheres)
    hdr = ["bidisperse: %d small (d=%g) + %d big (D=%g, R=%g); lattice %dx%dx%d spacing %g, jitter %g; "
           "%d sites removed by bigs" % (len(small), d, len(bigs), D, a.R, n[0], n[1], n[2], s, J, removed),
           "boundary %s, box %g x %g x %g, solid fraction %.4f" % (a.boundary, box.L[0], box.L[1], box.L[2],
                                                                  vol / (box.L[0] * box.L[1] * box.L[2]))]
    N = write_data(a.out, box, spheres, vels, hdr, a.density)
    print("%s: %d atoms (%d small, %d big)" % (a.out, N, len(small), len(bigs)))


# ----------------------------------------------------------------------------------------------
# (b) continuous


def cmd_continuous(a):
    rng = random.Random(a.seed)
    rmin, rmax = a.rmin, a.rmax
    if rmax < rmin:
        raise SystemExit("rmax < rmin")
    lr = math.log(rmax / rmin)

    def draw():
        u = rng.random()
        if a.law == "loguniform" or a.exponent == 1.0:
            return rmin * math.exp(lr * u)
        e = 1.0 - a.exponent  # inverse of the cumulative distribution of r^-exponent
        return (rmin ** e + u * (rmax ** e - rmin ** e)) ** (1.0 / e)

    radii = []
    if a.n is not None:
        radii = [draw() for _ in range(a.n)]
        # always include the extremes so the size ratio is exact
        if a.n >= 2 and rmax > rmin:
            radii[0], radii[1] = rmax, rmin
        vol = sum(4.0 / 3.0 * math.pi * r ** 3 for r in radii)
        if a.box:
            L = a.box if len(a.box) == 3 else a.box * 3
        else:
            asp = a.aspect
            V = vol / a.fill
            u = (V / (asp[0] * asp[1] * asp[2])) ** (1.0 / 3.0)
            L = [u * asp[k] for k in range(3)]
    else:
        if not a.box:
            raise SystemExit("continuous: give --n (with --fill or --box) or --box with --fill")
        L = a.box if len(a.box) == 3 else a.box * 3
        Vt = a.fill * L[0] * L[1] * L[2]
        vol = 0.0
        while vol < Vt:
            r = draw()
            if not radii and rmax > rmin:
                r = rmax
            radii.append(r)
            vol += 4.0 / 3.0 * math.pi * r ** 3
    origin = a.origin if a.origin else [0.0, 0.0, 0.0]
    box = Box(origin, [origin[k] + L[k] for k in range(3)], a.boundary == "p")
    for k in range(3):
        if box.L[k] < 2 * max(radii):
            raise SystemExit("box %g smaller than the largest diameter %g" % (box.L[k], 2 * max(radii)))
    order = sorted(range(len(radii)), key=lambda i: -radii[i])
    grid = MultiGrid(box, rmin, clearance=a.clearance * 2 * rmin)
    placed = []
    attempts = 0
    for idx in order:
        r = radii[idx]
        ok = False
        for _ in range(a.maxattempt):
            attempts += 1
            if box.periodic:
                p = [box.lo[k] + rng.random() * box.L[k] for k in range(3)]
            else:
                p = [box.lo[k] + r + rng.random() * (box.L[k] - 2 * r) for k in range(3)]
            if not grid.overlaps(p, r):
                ok = True
                break
        if not ok:
            raise SystemExit("continuous: could not place sphere %d of %d (r=%g) in %d attempts; lower --fill"
                             % (len(placed) + 1, len(radii), r, a.maxattempt))
        grid.add(p, r, len(placed))
        placed.append((2 * r, p[0], p[1], p[2], 1))
    # shuffle the output order (deterministically) unless the bigs should come first
    if not a.bigs_first:
        rng2 = random.Random(a.seed + 1)
        rng2.shuffle(placed)
    spheres = placed
    if a.domain:
        dm = a.domain
        dbox = Box([dm[0], dm[2], dm[4]], [dm[1], dm[3], dm[5]], box.periodic)
        for k in range(3):
            if dbox.lo[k] > box.lo[k] + 1e-15 or dbox.hi[k] < box.hi[k] - 1e-15:
                raise SystemExit("--domain must contain the placement box")
        box = dbox
    check_inside(box, spheres)
    vels = velocities(rng, len(spheres), a.vel, a.vz0)
    dd, vol = summary(spheres)
    law = "log-uniform" if a.law == "loguniform" else "number density ~ r^-%g" % a.exponent
    hdr = ["continuous: %d spheres, radii %s in [%g, %g] (ratio %g), %d attempts"
           % (len(spheres), law, rmin, rmax, rmax / rmin, attempts),
           "boundary %s, box %g x %g x %g, solid fraction %.4f" % (a.boundary, box.L[0], box.L[1], box.L[2],
                                                                  vol / (box.L[0] * box.L[1] * box.L[2]))]
    N = write_data(a.out, box, spheres, vels, hdr, a.density)
    print("%s: %d atoms, d in [%g, %g], solid fraction %.3f" % (a.out, N, min(dd), max(dd),
                                                                vol / (box.L[0] * box.L[1] * box.L[2])))


# ----------------------------------------------------------------------------------------------
# (c) crowded big particle


def fibonacci_sphere(n, rho, c):
    pts = []
    ga = math.pi * (3.0 - math.sqrt(5.0))
    for i in range(n):
        z = 1.0 - 2.0 * (i + 0.5) / n
        rr = math.sqrt(max(0.0, 1.0 - z * z))
        th = ga * i
        pts.append((c[0] + rho * rr * math.cos(th), c[1] + rho * rr * math.sin(th), c[2] + rho * z))
    return pts


def min_spacing(pts, h):
    """Smallest pairwise distance among pts (cell grid with cell size h, assumes it is < h)."""
    cells = {}
    for i, p in enumerate(pts):
        cells.setdefault(tuple(int(math.floor(p[k] / h)) for k in range(3)), []).append(i)
    best = float("inf")
    for key, lst in cells.items():
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for dz in (-1, 0, 1):
                    other = cells.get((key[0] + dx, key[1] + dy, key[2] + dz))
                    if not other:
                        continue
                    for i in lst:
                        for j in other:
                            if j <= i:
                                continue
                            p, q = pts[i], pts[j]
                            d2 = (p[0] - q[0]) ** 2 + (p[1] - q[1]) ** 2 + (p[2] - q[2]) ** 2
                            if d2 < best:
                                best = d2
    return math.sqrt(best)


def cmd_crowded(a):
    rng = random.Random(a.seed)
    d = a.d
    D = a.R * d
    rho = 0.5 * (D + d) + a.gap * d  # centre distance of the shell spheres
    need = d * (1.0 + a.min_gap)
    # densest Fibonacci shell with all spacings >= need
    area = 4.0 * math.pi * rho * rho
    n = int(area / (0.5 * math.sqrt(3.0) * need * need))
    while True:
        c = (0.0, 0.0, 0.0)
        pts = fibonacci_sphere(n, rho, c)
        if min_spacing(pts, 2.0 * need) >= need:
            break
        n = int(n * 0.98)
    margin = a.margin * d
    half = rho + 0.5 * d + margin
    L = 2.0 * half
    s = d * (1.0 + a.lattice_gap)
    nl = int(L // s)
    L = nl * s  # the box is a whole number of lattice cells
    if L < 2.0 * (rho + 0.5 * d):
        nl += 1
        L = nl * s
    box = Box([0.0] * 3, [L] * 3, False)
    ctr = [0.5 * L] * 3
    shell = [(p[0] + ctr[0], p[1] + ctr[1], p[2] + ctr[2]) for p in pts]
    small = list(shell)
    if a.fill_lattice:
        J = a.jitter * 0.5 * (s - d)
        sites = jittered_lattice(rng, [nl] * 3, s, J, [0.0] * 3)
        grid = MultiGrid(box, 0.5 * d)
        for p in shell:
            grid.add(p, 0.5 * d, None)
        lim = 0.5 * (D + d) + 0.01 * d
        for p in sites:
            if box.dist2(p, ctr) < lim * lim:
                continue
            if grid.overlaps(p, 0.5 * d):
                continue
            small.append(p)
    spheres = [(D, ctr[0], ctr[1], ctr[2], 1)] + [(d, p[0], p[1], p[2], 1) for p in small]
    check_inside(box, spheres)
    vels = velocities(rng, len(spheres), a.vel, a.vz0)
    dd, vol = summary(spheres)
    hdr = ["crowded: 1 big (D=%g, id 1) + %d shell spheres (d=%g) at centre distance %g "
           "(surface gap %g) + %d lattice spheres" % (D, len(shell), d, rho, a.gap * d, len(small) - len(shell)),
           "walled box %g^3, solid fraction %.4f" % (L, vol / L ** 3)]
    N = write_data(a.out, box, spheres, vels, hdr, a.density)
    print("%s: %d atoms (1 big, %d in the shell, %d lattice)" % (a.out, N, len(shell), len(small) - len(shell)))


# ----------------------------------------------------------------------------------------------
# STL


def cmd_stl_funnel(a):
    """Square floor [-a,a]^2 at z0, four sides rising outwards to half-width b at z0+h."""
    lo, hi, z0, z1 = a.bottom, a.top, a.z0, a.z0 + a.height
    P = lambda x, y, z: (x, y, z)
    bot = [P(-lo, -lo, z0), P(lo, -lo, z0), P(lo, lo, z0), P(-lo, lo, z0)]
    top = [P(-hi, -hi, z1), P(hi, -hi, z1), P(hi, hi, z1), P(-hi, hi, z1)]
    tris = [(bot[0], bot[1], bot[2]), (bot[0], bot[2], bot[3])]
    for i in range(4):
        j = (i + 1) % 4
        tris.append((bot[i], top[i], top[j]))
        tris.append((bot[i], top[j], bot[j]))

    def normal(t):
        u = [t[1][k] - t[0][k] for k in range(3)]
        v = [t[2][k] - t[0][k] for k in range(3)]
        n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
        ln = math.sqrt(sum(c * c for c in n)) or 1.0
        return [c / ln for c in n]

    with open(a.out, "w") as f:
        f.write("solid funnel\n")
        for t in tris:
            n = normal(t)
            f.write("  facet normal %s %s %s\n    outer loop\n" % tuple(fmt(c) for c in n))
            for p in t:
                f.write("      vertex %s %s %s\n" % tuple(fmt(c) for c in p))
            f.write("    endloop\n  endfacet\n")
        f.write("endsolid funnel\n")
    print("%s: %d triangles" % (a.out, len(tris)))


# ----------------------------------------------------------------------------------------------


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)

    def common(p):
        p.add_argument("--out", required=True, help="output data file")
        p.add_argument("--seed", type=int, default=12345)
        p.add_argument("--boundary", choices=["p", "f"], default="f",
                       help="p: periodic box; f: walled (box bounds are the walls)")
        p.add_argument("--density", type=float, default=2500.0, help="particle density (kg/m^3)")
        p.add_argument("--vel", type=float, default=0.0, help="random velocity components in [-V,V] (m/s)")
        p.add_argument("--vz0", type=float, default=0.0, help="added to every vz (m/s)")
        p.add_argument("--bigs-first", action="store_true",
                       help="write the biggest spheres first (lowest IDs; a half list then stores all "
                            "their pairs under them)")

    b = sub.add_parser("bidisperse", help="small lattice spheres + K big spheres")
    common(b)
    b.add_argument("--d", type=float, default=1e-3, help="small diameter (m)")
    b.add_argument("--R", type=float, default=10.0, help="big/small diameter ratio")
    b.add_argument("--n", type=int, nargs="+", default=[20], help="lattice sites per dimension (1 or 3 values)")
    b.add_argument("--gap", type=float, default=0.1, help="lattice spacing = d*(1+gap)")
    b.add_argument("--jitter", type=float, default=0.8, help="jitter amplitude as a fraction of gap/2 (<=1)")
    b.add_argument("--K", type=int, default=1, help="number of big spheres")
    b.add_argument("--big-lattice", type=int, nargs=3, help="coarse lattice for the bigs (default: cube)")
    b.add_argument("--big-at", type=float, nargs=3, action="append",
                   help="explicit big centre in box fractions (repeatable; overrides --K)")
    b.add_argument("--big-type", type=int, default=1, help="atom type of the big spheres")
    b.add_argument("--clearance", type=float, default=0.0, help="extra big/small clearance (units of d)")
    b.add_argument("--lattice-region", type=float, nargs=6,
                   help="keep lattice sites only inside x0 x1 y0 y1 z0 z1 (box fractions)")
    b.add_argument("--shell", type=float, default=None,
                   help="keep only small spheres within this surface distance (units of d) of a big one")
    b.set_defaults(func=cmd_bidisperse)

    c = sub.add_parser("continuous", help="log-uniform or power-law radii, random placement")
    common(c)
    c.add_argument("--law", choices=["loguniform", "power"], default="loguniform",
                   help="radius distribution: log-uniform, or number density ~ r^-exponent")
    c.add_argument("--exponent", type=float, default=3.0, help="exponent of --law power")
    c.add_argument("--rmin", type=float, required=True)
    c.add_argument("--rmax", type=float, required=True)
    c.add_argument("--n", type=int, default=None, help="number of spheres")
    c.add_argument("--fill", type=float, default=0.3, help="solid volume fraction of the box")
    c.add_argument("--box", type=float, nargs="+", help="box lengths (1 or 3 values)")
    c.add_argument("--aspect", type=float, nargs=3, default=[1.0, 1.0, 1.0],
                   help="box aspect ratio when the box is derived from --n and --fill")
    c.add_argument("--origin", type=float, nargs=3, help="lower corner of the placement box")
    c.add_argument("--domain", type=float, nargs=6,
                   help="simulation box xlo xhi ylo yhi zlo zhi written to the file (contains the placement box)")
    c.add_argument("--clearance", type=float, default=0.0, help="minimum surface gap (units of 2*rmin)")
    c.add_argument("--maxattempt", type=int, default=2000)
    c.set_defaults(func=cmd_continuous)

    k = sub.add_parser("crowded", help="one big sphere surrounded by thousands of small ones")
    common(k)
    k.add_argument("--d", type=float, default=1e-3)
    k.add_argument("--R", type=float, default=40.0, help="big/small diameter ratio")
    k.add_argument("--gap", type=float, default=0.05, help="shell surface gap to the big one (units of d)")
    k.add_argument("--min-gap", type=float, default=0.02, help="minimum gap between shell spheres (units of d)")
    k.add_argument("--margin", type=float, default=1.0, help="box margin outside the shell (units of d)")
    k.add_argument("--fill-lattice", action="store_true", help="fill the rest of the box with a jittered lattice")
    k.add_argument("--lattice-gap", type=float, default=0.1)
    k.add_argument("--jitter", type=float, default=0.8)
    k.set_defaults(func=cmd_crowded)

    s = sub.add_parser("stl-funnel", help="ASCII STL: square floor + 4 sloped sides")
    s.add_argument("--out", required=True)
    s.add_argument("--bottom", type=float, required=True, help="half-width of the floor (m)")
    s.add_argument("--top", type=float, required=True, help="half-width at the top rim (m)")
    s.add_argument("--z0", type=float, default=0.0, help="floor height (m)")
    s.add_argument("--height", type=float, required=True, help="height of the sides (m)")
    s.set_defaults(func=cmd_stl_funnel)

    a = ap.parse_args(argv)
    a.func(a)


if __name__ == "__main__":
    main()
