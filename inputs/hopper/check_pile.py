#!/usr/bin/env python3
"""Checks the result of a hopper pile run (README "Pile run") from its own output files and
optionally draws the final pile.

  check_pile.py RUNDIR [--log log.hopper [log.continue ...]] [--eps 5e-5] [--z-outlet 0.04] [--floor-half 0.08]
                [--ke-ratio 1e-3] [--png pile.png] [--json pile.json]

Reads the logs (thermo: step atoms contacts penetration zmean KE nbelow ztop; the logs of
in.hopper and of in.hopper_continue are joined by step), RUNDIR/hopper_pen*.txt (largest
penetration at every step, `-var penevery 1`) and the last RUNDIR/hopper_atoms_*.txt (grain
centres). Checks: the atom count never changes (grains plus the
two obstacles), the largest penetration of every step stays below eps (the rigid surfaces never
touch), every grain centre lies below the outlet plane and above the floor, inside the floor's
footprint, and the kinetic energy at the end is below ke-ratio times its peak. Prints the pile's
height and radius and the grains per height band; exit status 1 if a check fails."""
import argparse
import glob
import json
import math
import os
import re
import sys

import numpy as np

OK = True


def check(cond, what):
    global OK
    print(("PASS " if cond else "FAIL ") + what, flush=True)
    OK = OK and bool(cond)


def thermo(path):
    """Rows of the thermo table(s) of a LIGGGHTS log (lines of numbers after a 'Step' header)."""
    rows, inside = [], False
    for line in open(path):
        f = line.split()
        if f and f[0] == "Step":
            inside = True
            continue
        if inside:
            try:
                rows.append([float(x) for x in f])
            except ValueError:
                inside = False
    return np.array([r for r in rows if len(r) == len(rows[0])])


def last_atom_dump(rundir):
    files = glob.glob(os.path.join(rundir, "hopper_atoms_*.txt"))
    if not files:
        sys.exit("check_pile.py: no hopper_atoms_*.txt in %s" % rundir)
    step = lambda p: int(re.search(r"hopper_atoms_(\d+)\.txt$", p).group(1))
    path = max(files, key=step)
    lines = open(path).read().splitlines()
    i = next(k for k, l in enumerate(lines) if l.startswith("ITEM: ATOMS"))
    cols = lines[i].split()[2:]
    data = np.array([[float(x) for x in l.split()] for l in lines[i + 1:] if l.strip()])
    return step(path), {c: data[:, k] for k, c in enumerate(cols)}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("rundir")
    ap.add_argument("--log", nargs="+", default=["log.hopper"])
    ap.add_argument("--eps", type=float, default=5e-5)
    ap.add_argument("--z-outlet", type=float, default=0.04)
    ap.add_argument("--floor-half", type=float, default=0.08)
    ap.add_argument("--grains", type=int, default=1000)
    ap.add_argument("--radius", type=float, default=0.0025, help="grain bounding radius")
    ap.add_argument("--ke-ratio", type=float, default=1e-3)
    ap.add_argument("--outlet-radius", type=float, default=0.025, help="for the drawing only")
    ap.add_argument("--png")
    ap.add_argument("--json")
    a = ap.parse_args()

    t = np.vstack([thermo(os.path.join(a.rundir, f)) for f in a.log])
    t = t[np.unique(t[:, 0], return_index=True)[1]]   # a continuation repeats its first step
    step, atoms, ncont, ke = t[:, 0], t[:, 1], t[:, 2], t[:, 5]
    check(atoms.min() == atoms.max() == a.grains + 2,
          "atoms %d..%d at %d thermo samples, steps 0..%d (%d grains + hopper + floor)"
          % (atoms.min(), atoms.max(), len(step), step[-1], a.grains))

    pen = np.vstack([np.loadtxt(f, comments="#", ndmin=2)
                     for f in sorted(glob.glob(os.path.join(a.rundir, "hopper_pen*.txt")))])
    pen = pen[np.unique(pen[:, 0], return_index=True)[1]]
    consecutive = np.all(np.diff(pen[:, 0]) == 1)
    check(consecutive and pen[-1, 0] == step[-1],
          "penetration recorded at every step 1..%d (%d lines)" % (pen[-1, 0], len(pen)))
    k = int(np.argmax(pen[:, 1]))
    check(pen[k, 1] < a.eps, "largest penetration over the run %.3g m = %.3f eps (step %d)"
          % (pen[k, 1], pen[k, 1] / a.eps, pen[k, 0]))

    kpeak = int(np.argmax(ke))
    check(ke[-1] < a.ke_ratio * ke[kpeak],
          "kinetic energy at the end %.3g J = %.2e of its peak %.3g J (step %d)"
          % (ke[-1], ke[-1] / ke[kpeak], ke[kpeak], step[kpeak]))

    dstep, d = last_atom_dump(a.rundir)
    x, y, z = d["x"], d["y"], d["z"]
    check(dstep == step[-1], "last grain dump at step %d (the last thermo step)" % dstep)
    check(len(z) == a.grains, "%d grains in the dump" % len(z))
    check(z.max() < a.z_outlet, "all grains below the outlet: highest centre z = %.4f m < %.3f m"
          % (z.max(), a.z_outlet))
    check(z.min() > 0, "all grains above the floor: lowest centre z = %.4f m" % z.min())
    check(np.abs(x).max() < a.floor_half and np.abs(y).max() < a.floor_half,
          "all grains over the floor: max |x| %.4f, max |y| %.4f < %.3f m"
          % (np.abs(x).max(), np.abs(y).max(), a.floor_half))
    v = np.sqrt(d["vx"] ** 2 + d["vy"] ** 2 + d["vz"] ** 2)
    print("grain speeds at the end: max %.3g m/s, median %.3g m/s" % (v.max(), np.median(v)))

    r = np.hypot(x - x.mean(), y - y.mean())
    height = z.max() + a.radius
    print("pile: height %.4f m (highest centre + radius), centre of mass (%.4f, %.4f, %.4f) m"
          % (height, x.mean(), y.mean(), z.mean()))
    print("pile footprint: radius of the outermost centre %.4f m, 90 %% of the grains within %.4f m"
          % (r.max(), np.percentile(r, 90)))
    bands = [(0, 0.005), (0.005, 0.010), (0.010, 0.015), (0.015, 0.020), (0.020, 0.030),
             (0.030, a.z_outlet), (a.z_outlet, 1.0)]
    counts = [int(np.sum((z >= lo) & (z < hi))) for lo, hi in bands]
    print("grains per height band of the centre (m): " +
          ", ".join("[%.3f,%.3f) %d" % (lo, min(hi, 0.2), c) for (lo, hi), c in zip(bands, counts)))
    ring = [(0, 0.01), (0.01, 0.02), (0.02, 0.03), (0.03, 0.04), (0.04, 0.06), (0.06, 1.0)]
    rc = [int(np.sum((r >= lo) & (r < hi))) for lo, hi in ring]
    print("grains per radial ring about the pile axis (m): " +
          ", ".join("[%.2f,%.2f) %d" % (lo, min(hi, 0.2), c) for (lo, hi), c in zip(ring, rc)))

    if a.json:
        json.dump(dict(steps=int(step[-1]), atoms_min=int(atoms.min()), atoms_max=int(atoms.max()),
                       max_penetration_m=float(pen[k, 1]), max_penetration_eps=float(pen[k, 1] / a.eps),
                       max_penetration_step=int(pen[k, 0]), ke_peak_J=float(ke[kpeak]),
                       ke_peak_step=int(step[kpeak]), ke_final_J=float(ke[-1]),
                       max_contacts=int(ncont.max()), final_contacts=int(ncont[-1]),
                       highest_centre_m=float(z.max()), pile_height_m=float(height),
                       footprint_radius_max_m=float(r.max()), footprint_radius_p90_m=float(np.percentile(r, 90)),
                       height_bands=[[lo, hi, c] for (lo, hi), c in zip(bands, counts)],
                       radial_rings=[[lo, hi, c] for (lo, hi), c in zip(ring, rc)], ok=OK),
                  open(a.json, "w"), indent=1)
    if a.png:
        draw(a, x, y, z, t, pen, dstep)
    return 0 if OK else 1


def draw(a, x, y, z, t, pen, dstep):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    # Two views on top, the history in two panels below sharing the step axis (no twin axes, so
    # no legend or second scale covers a curve).
    fig = plt.figure(figsize=(13, 9))
    grid = fig.add_gridspec(2, 2, height_ratios=(1.2, 1))
    ax = [fig.add_subplot(grid[0, 0]), fig.add_subplot(grid[0, 1]), fig.add_subplot(grid[1, 0])]
    ax.append(fig.add_subplot(grid[1, 1], sharex=ax[2]))
    s = 4 * (a.radius / 0.0025) ** 2
    # side view: grain centres, hopper cross-section (inner wall) and floor top
    ax[0].scatter(x, z, s=s, c=y, cmap="viridis", edgecolors="none")
    ro, rt, zo, zt = a.outlet_radius, 0.05, a.z_outlet, 0.10
    for sg in (-1, 1):
        ax[0].plot([sg * ro, sg * rt], [zo, zt], "k-", lw=2)
    ax[0].plot([-a.floor_half, a.floor_half], [0, 0], "k-", lw=3)
    ax[0].axhline(zo, color="grey", ls=":", lw=1)
    ax[0].set_aspect("equal")
    ax[0].set_xlabel("x (m)")
    ax[0].set_ylabel("z (m)")
    ax[0].set_title("side view at step %d (colour: y; dotted: outlet plane)" % dstep)
    ax[1].scatter(x, y, s=s, c=z, cmap="viridis", edgecolors="none")
    ax[1].add_patch(plt.Circle((0, 0), ro, fill=False, ls="--", color="k"))
    h = a.floor_half
    ax[1].plot([-h, h, h, -h, -h], [-h, -h, h, h, -h], "k-")
    ax[1].set_aspect("equal")
    ax[1].set_xlabel("x (m)")
    ax[1].set_ylabel("y (m)")
    ax[1].set_title("top view (colour: z; dashed: outlet; square: floor)")
    for view in ax[:2]:
        view.xaxis.set_major_locator(plt.MaxNLocator(5))
    ax[2].semilogy(t[:, 0], np.maximum(t[:, 5], 1e-12), label="kinetic energy (J)")
    # largest penetration per thermo interval (the per-step record is too dense to draw)
    edges = np.searchsorted(pen[:, 0], t[:, 0])
    blocks = [pen[lo:hi, 1].max() if hi > lo else 0.0 for lo, hi in zip(edges[:-1], edges[1:])]
    ax[2].semilogy(t[1:, 0], np.maximum(np.array(blocks) / a.eps, 1e-12), lw=0.8,
                   label="largest penetration / eps (per thermo interval)")
    ax[2].set_ylim(1e-6, 2)
    ax[2].set_xlabel("step")
    ax[2].set_title("kinetic energy and largest penetration")
    ax[2].legend(loc="upper right", fontsize=8, framealpha=0.9)
    ax[3].plot(t[:, 0], t[:, 6], "g-")
    ax[3].set_xlabel("step")
    ax[3].set_ylabel("grains")
    ax[3].set_title("grains below the outlet plane")
    for panel in ax[2:]:
        panel.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(a.png, dpi=110)
    print("wrote", a.png)


if __name__ == "__main__":
    sys.exit(main())
