#!/usr/bin/env python3
"""A heap of triangulated grains against spheres of the same volume: does it stand, and at what
angle?

Decks inputs/heap/in.heap_grains (pair_style trimesh, 40-triangle dented grains, rotation yes,
tangential history, rolling_friction epsd with coefficientRollingFriction 0.1, materials E 1e5
Pa, nu 0.3, e 0.3, mu 0.5; halo 0.1 mm) and
inputs/heap/in.heap_spheres (pair gran hertz with tangential history, the same materials, spheres
of the grains' volume-equivalent radius, no rolling friction): a side x side x side block
(spacing 6.4 mm; 10 = 1000 grains by default) released just above a 0.4 m square floor
collapses into a heap; each deck runs in chunks of `--chunk` steps of `--dt` until the kinetic
energy has stayed below 1e-9 of the largest one at a chunk end at `--held` consecutive chunk ends
(or `--chunks` chunks).

`spheres_rolling`: the same spheres with LIGGGHTS' rolling friction of the same model and
coefficient as the grains (`rolling_friction epsd`, coefficientRollingFriction 0.1,
coefficientRollingViscousDamping 0.36, the grains' default ratio at e 0.3): what the shape
adds to the same rolling resistance.

Measured per run: grains left (none may be lost for the grains; spheres that roll off the floor
leave the box), simulated time, kinetic energy at the end / its largest value over the whole
thermo record, whether it stands (below 1e-9 of the peak at the last `--held` chunk ends; how
many consecutive chunk ends were below at the end: `held`), heap height, and the angle of
repose: the
heap's axis is the vertical through the particles' mean x, y; particles are binned by their
distance from it (bins of one grain diameter); the surface is the highest particle top (z + r)
per bin, and the angle is the slope of a least-squares line through the surface points between
15 % and 85 % of the height above the one-particle layer that spreads over the floor (tops at one
diameter): the cone's flank, without the rounded top, the toe and the skirt. A heap no higher
than that layer has no angle (nan: "no heap").

    bench/heap_repose.py [--exe build/liggghts-spacetree] [--workdir build/heap_repose]
                         [--side 10] [--dt 7e-5] [--chunk 500] [--chunks 400] [--held 5]
                         [--only grains|spheres|spheres_rolling] [--analyze] [--replot]

Writes bench/results/heap_repose.csv (surface points of both heaps), heap_repose_summary.csv,
heap_repose_ke.csv (kinetic energy at every chunk end: J and over the peak so far) and
heap_repose.png. --analyze measures runs already in the work dir (a run stopped before it
stood: its last chunk's heap_latest.dump); --replot redraws the figure from the CSVs.
"""

import argparse
import csv
import math
import os
import re
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, os.path.join(ROOT, "inputs", "hopper"))
from make_hopper import write_stl  # noqa: E402

OUT = os.path.join(HERE, "results", "heap_repose")
DENSITY = 2500.0
# kind: (deck, extra variables)
KINDS = {"grains": ("in.heap_grains", {}), "spheres": ("in.heap_spheres", {}),
         "spheres_rolling": ("in.heap_spheres", {"rolling": "epsd", "murolling": 0.1})}


def floor_triangles():
    x0, y0, z0, x1, y1, z1 = -0.2, -0.2, -0.004, 0.2, 0.2, 0.0
    v = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
         (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    quads = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (2, 3, 7, 6), (1, 2, 6, 5), (3, 0, 4, 7)]
    tris = []
    for a, b, c, d in quads:
        tris += [(v[a], v[b], v[c]), (v[a], v[c], v[d])]
    return tris


def run(exe, deck, wd, tag, variables):
    cmd = [exe, "-in", os.path.join(ROOT, "inputs", "heap", deck), "-log", "log." + tag,
           "-echo", "none"]
    for k, v in variables.items():
        cmd += ["-var", k, str(v)]
    t0 = time.time()
    p = subprocess.run(cmd, cwd=wd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True)
    wall = time.time() - t0
    if p.returncode != 0:
        raise SystemExit("%s failed:\n%s" % (tag, p.stdout[-3000:]))
    return open(os.path.join(wd, "log." + tag)).read(), wall


def thermo_rows(log):
    """(time, atoms, ke) of every thermo line of every run in the log."""
    rows = []
    cols = None
    for line in log.splitlines():
        w = line.split()
        if w and w[0] == "Step":
            cols = w
            continue
        if cols and len(w) == len(cols):
            try:
                vals = [float(x) for x in w]
            except ValueError:
                cols = None
                continue
            rows.append((vals[cols.index("Time")], vals[cols.index("Atoms")], vals[cols.index("ke")]))
        elif line.startswith("Loop time"):
            cols = None
    return rows


def chunk_rows(log):
    """(chunk, time, ke, peak so far, consecutive chunk ends below 1e-9 of it or None) of every
    "HEAP chunk" line; the time is that of the last thermo line before it (the chunk's end)."""
    out = []
    cols, time_now = None, float("nan")
    for line in log.splitlines():
        w = line.split()
        if w and w[0] == "Step":
            cols = w
        elif cols and len(w) == len(cols):
            try:
                time_now = float(w[cols.index("Time")])
            except ValueError:
                pass
        elif line.startswith("HEAP chunk"):
            m = re.match(r"HEAP chunk (\d+) ke (\S+) peak (\S+)(?: below (\d+))?", line)
            out.append((int(m.group(1)), time_now, float(m.group(2)), float(m.group(3)),
                        int(m.group(4)) if m.group(4) is not None else None))
    return out


def positions(path):
    with open(path) as f:
        lines = f.read().split("ITEM: ATOMS")[1].splitlines()[1:]
    return [tuple(float(x) for x in l.split()[1:4]) for l in lines if l.strip()]


def repose(points, radius):
    """Surface points (r, z_top) and the angle of repose (degrees) of a heap of particles."""
    cx = sum(p[0] for p in points) / len(points)
    cy = sum(p[1] for p in points) / len(points)
    width = 2 * radius
    top = {}
    for x, y, z in points:
        b = int(math.hypot(x - cx, y - cy) / width)
        top[b] = max(top.get(b, -1.0), z + radius)
    surface = sorted(((b + 0.5) * width, z) for b, z in top.items())
    height = max(z for _, z in surface)
    # the flank above the one-particle layer that spreads over the floor around the heap (its top
    # at one diameter): between 15 % and 85 % of the height above that layer
    base = 2 * radius
    flank = [(r, z) for r, z in surface
             if base + 0.15 * (height - base) <= z <= base + 0.85 * (height - base)]
    if len(flank) < 3:
        return surface, height, float("nan")
    n = len(flank)
    mr = sum(r for r, _ in flank) / n
    mz = sum(z for _, z in flank) / n
    slope = sum((r - mr) * (z - mz) for r, z in flank) / sum((r - mr) ** 2 for r, _ in flank)
    return surface, height, math.degrees(math.atan(-slope))


def plot(summary, surfaces, series, out, released, held):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (ax, ke_ax) = plt.subplots(1, 2, figsize=(11.0, 4.0))
    for kind, style in (("grains", "o-"), ("spheres", "s--"), ("spheres_rolling", "^:")):
        pts = [(float(r), float(z)) for k, r, z in surfaces if k == kind]
        if not pts:
            continue
        s = summary[kind]
        angle = float(s["angle_deg"])
        shape = "no heap" if math.isnan(angle) else "%.1f deg" % angle
        stands = "stands" if int(float(s["stands"])) else "KE %.2g of peak" % float(s["ke_ratio"])
        ax.plot([1e3 * r for r, _ in pts], [1e3 * z for _, z in pts], style, ms=3,
                label="%s: %s, %d left, %s" % (kind, shape, int(float(s["particles"])), stands))
        ke = [(t, ke / peak) for k, _, t, ke, peak, _ in series if k == kind]
        if ke:
            ke_ax.semilogy([t for t, _ in ke], [r for _, r in ke], style, ms=2, label=kind)
    ke_ax.axhline(1e-9, color="k", lw=0.8, ls=":")
    ke_ax.set_xlabel("time (s)")
    ke_ax.set_ylabel("kinetic energy / its peak (chunk ends)")
    ke_ax.set_title("stands: below 1e-9 at %d consecutive chunk ends" % held)
    ke_ax.legend()
    ax.set_xlabel("distance from the heap axis (mm)")
    ax.set_ylabel("surface height (mm)")
    ax.set_title("Heap of %d dented grains vs spheres of the same volume" % released)
    ax.legend()
    fig.tight_layout()
    fig.savefig(out + ".png", dpi=120)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "liggghts-spacetree"))
    ap.add_argument("--workdir", default=os.path.join(ROOT, "build", "heap_repose"))
    ap.add_argument("--chunks", type=int, default=400)
    ap.add_argument("--side", type=int, default=10, help="grains per side of the released block (even)")
    ap.add_argument("--dt", type=float, default=7e-5, help="time step (s)")
    ap.add_argument("--chunk", type=int, default=500, help="steps per chunk")
    ap.add_argument("--held", type=int, default=5,
                    help="consecutive chunk ends below 1e-9 of the peak that count as standing")
    ap.add_argument("--only", choices=list(KINDS))
    ap.add_argument("--replot", action="store_true")
    ap.add_argument("--analyze", action="store_true",
                    help="run nothing: measure the logs and dumps already in the work dir (a run stopped "
                         "before it stood is measured on its last chunk's heap_latest.dump)")
    ap.add_argument("--out", default=OUT, help="path prefix of the CSVs and the PNG")
    a = ap.parse_args()
    a.exe = os.path.abspath(a.exe)
    out = a.out
    if a.replot:
        summary = {r["kind"]: r for r in csv.DictReader(open(out + "_summary.csv"))}
        surfaces = [(r["kind"], r["r_m"], r["z_m"]) for r in csv.DictReader(open(out + ".csv"))]
        released = int(float(summary["grains"]["particles"])) + int(float(summary["grains"]["lost"]))
        series = [(r["kind"], int(r["chunk"]), float(r["time_s"]), float(r["ke_J"]),
                   float(r["ke_J"]) / float(r["ke_over_peak"]), None)
                  for r in csv.DictReader(open(out + "_ke.csv"))] if os.path.exists(out + "_ke.csv") else []
        plot(summary, surfaces, series, out, released, a.held)
        return 0
    os.makedirs(a.workdir, exist_ok=True)
    summary, surfaces, series = {}, [], []
    if os.path.exists(out + "_summary.csv"):   # keep the other kind's stored result with --only
        summary = {r["kind"]: r for r in csv.DictReader(open(out + "_summary.csv"))}
        for r in summary.values():
            r.setdefault("held", "")
        surfaces = [(r["kind"], r["r_m"], r["z_m"]) for r in csv.DictReader(open(out + ".csv"))]
    if os.path.exists(out + "_ke.csv"):
        series = [(r["kind"], int(r["chunk"]), float(r["time_s"]), float(r["ke_J"]),
                   float(r["ke_J"]) / float(r["ke_over_peak"]), int(r["below"]) if r["below"] else None)
                  for r in csv.DictReader(open(out + "_ke.csv"))]
    grain_radius = None
    for kind in KINDS:
        if a.only and kind != a.only:
            continue
        wd = os.path.join(a.workdir, kind)
        os.makedirs(wd, exist_ok=True)
        write_stl(os.path.join(wd, "floor.stl"), floor_triangles())
        variables = dict(chunks=a.chunks, side=a.side, dt=a.dt, chunk=a.chunk, held=a.held, **KINDS[kind][1])
        if kind != "grains":
            if grain_radius is None:
                grain_radius = float(summary["grains"]["radius_m"])
            variables["r"] = grain_radius
        if a.analyze:
            log = open(os.path.join(wd, "log." + kind)).read()
            wall = sum(float(x) for x in re.findall(r"Loop time of ([0-9.eE+-]+)", log))  # the runs' loops
            load0 = load1 = float("nan")
        else:
            load0 = os.getloadavg()[0]
            log, wall = run(a.exe, KINDS[kind][0], wd, kind, variables)
            load1 = os.getloadavg()[0]
        mass = float(re.findall(r"grain mass ([0-9.eE+-]+)", log)[0])  # atom 1 may leave later
        radius = (3 * mass / (4 * math.pi * DENSITY)) ** (1.0 / 3.0)
        if kind == "grains":
            grain_radius = radius
        rows = thermo_rows(log)
        peak = max(ke for _, _, ke in rows)
        chunks = chunk_rows(log)
        series = [s for s in series if s[0] != kind] + [(kind,) + c for c in chunks]
        held = chunks[-1][4] if chunks and chunks[-1][4] is not None else int(rows[-1][2] < 1e-9 * peak)
        final = os.path.join(wd, "heap_final.dump")
        points = positions(final if os.path.exists(final) else os.path.join(wd, "heap_latest.dump"))
        surface, height, angle = repose(points, radius)
        surfaces = [s for s in surfaces if s[0] != kind] + [(kind, r, z) for r, z in surface]
        lost = a.side ** 3 - len(points)
        if "ERROR: Lost atoms" in log:  # the grains' deck stops when one leaves the box
            lost = max(lost, 1)
            print("%s: stopped by a lost particle after its last dump" % kind)
        summary[kind] = dict(kind=kind, particles=len(points), lost=lost,
                             time_s=rows[-1][0], ke_final_J=rows[-1][2], ke_peak_J=peak,
                             ke_ratio=rows[-1][2] / peak, stands=int(held >= a.held), held=held,
                             radius_m=radius, height_m=height,
                             angle_deg=angle, wall_s=wall, load="%.1f-%.1f" % (load0, load1))
        print("%s: %d left, %.3f s simulated, KE %.3g of its peak, height %.2f mm, angle %.1f deg, %.0f s"
              % (kind, len(points), rows[-1][0], rows[-1][2] / peak, 1e3 * height, angle, wall))
    os.makedirs(os.path.dirname(out), exist_ok=True)
    with open(out + ".csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["kind", "r_m", "z_m"])
        for k, r, z in surfaces:
            w.writerow([k, r, z])
    with open(out + "_summary.csv", "w", newline="") as f:
        fields = ["kind", "particles", "lost", "time_s", "ke_final_J", "ke_peak_J", "ke_ratio", "stands", "held", "radius_m",
                  "height_m", "angle_deg", "wall_s", "load"]
        w = csv.DictWriter(f, fieldnames=fields)
        w.writeheader()
        for kind in KINDS:
            if kind in summary:
                w.writerow({k: summary[kind][k] for k in fields})
    with open(out + "_ke.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["kind", "chunk", "time_s", "ke_J", "ke_over_peak", "below"])
        for kind, k, t, ke, peak_so_far, below in series:
            w.writerow([kind, k, t, ke, ke / peak_so_far, "" if below is None else below])
    plot(summary, surfaces, series, out, a.side ** 3, a.held)
    return 0


if __name__ == "__main__":
    sys.exit(main())
