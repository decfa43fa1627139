#!/usr/bin/env python3
"""Largest fixed time step at which an L-shaped prism of the grain pour stays at rest lying flat on
the floor (6 contact points), and two such prisms stacked (inputs/pour/in.resting), against the
stability limit of the linearised contact law.

  /usr/bin/python3 bench/resting_stability.py [--exe build/liggghts-spacetree]
        [--dt 4e-6,5e-6,...] [--work /tmp/resting_stability] [--out bench/results/resting_stability]

Each run starts 0.1 mm above contact, lands, and runs to T = 0.04 s. It *rests* when the grains'
kinetic energy over the second half of the run stays below 1e-20 J (a damped rest decays far
below that; a grain at rest under gravity has none); otherwise it *rattles* (the contacts keep
their points, kinetic energy up to ~1e-12 J: a limit cycle of a linearly unstable step) or *hops*
(contact points lost: the grain leaves the floor).

Linearised law (one prism on the floor): velocity Verlet, as fix nve/trimesh, of a rigid prism
(mass m, inertia of the L prism) on 6 corner springs k = S/2 each (pair_style trimesh eq. (1)),
each damped while it approaches with 2 D sqrt(m) v (damping approach); the step above which a
small perturbation grows is found by bisection. Its rocking mode, omega = 8.9e4 rad/s, has the
damping ratio D sqrt(m) omega / k = 2.1: the explicit dashpot, not the spring, sets the limit
(undamped it would be 2/omega = 2.2e-5 s).

Writes OUT.csv (layers, dt, state, largest kinetic energy of the second half, fewest contact
points there, and the predicted limit for one layer)."""
import argparse
import csv
import os
import subprocess
import sys

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DECK = os.path.join(ROOT, "inputs", "pour", "in.resting")

# the deck's prism (inputs/pour/make_pour.py defaults) and contact law
ARM, WIDTH, DEPTH, RHO = 0.005, 0.002, 0.0025, 2500.0
STIFFNESS, DAMPING = 1.25e5, 150.0


def prism():
    """Mass, centre (x, y) and the inertia about horizontal axes (Ixx, Iyy, Ixy) of the L prism."""
    rects = [(0, ARM, 0, WIDTH), (0, WIDTH, WIDTH, ARM)]
    area = sum((x1 - x0) * (y1 - y0) for x0, x1, y0, y1 in rects)
    cx = sum((x1 - x0) * (y1 - y0) * (x0 + x1) / 2 for x0, x1, y0, y1 in rects) / area
    cy = sum((x1 - x0) * (y1 - y0) * (y0 + y1) / 2 for x0, x1, y0, y1 in rects) / area

    def second(a, b, c):
        return ((b - c) ** 3 - (a - c) ** 3) / 3

    ixx = iyy = ixy = 0.0
    for x0, x1, y0, y1 in rects:
        a = (x1 - x0) * (y1 - y0)
        ixx += RHO * DEPTH * ((x1 - x0) * second(y0, y1, cy) + a * DEPTH ** 2 / 12)
        iyy += RHO * DEPTH * ((y1 - y0) * second(x0, x1, cx) + a * DEPTH ** 2 / 12)
        ixy += RHO * DEPTH * ((x1 ** 2 - x0 ** 2) / 2 - cx * (x1 - x0)) * ((y1 ** 2 - y0 ** 2) / 2 - cy * (y1 - y0))
    return area * DEPTH * RHO, (cx, cy), (ixx, iyy, ixy)


def linear_limit():
    """Bisection on the step: the prism on its 6 corners, z and the two tilts, per-corner approach
    damping; unstable when a 1e-9 m perturbation has grown after 20 000 steps."""
    m, (cx, cy), (ixx, iyy, ixy) = prism()
    corners = [(0, 0), (ARM, 0), (ARM, WIDTH), (WIDTH, WIDTH), (WIDTH, ARM), (0, ARM)]
    g = np.array([[1.0, y - cy, -(x - cx)] for x, y in corners])   # corner sink per (z, tilt x, tilt y)
    mass = np.array([[m, 0, 0], [0, ixx, -ixy], [0, -ixy, iyy]])
    inv = np.linalg.inv(mass)
    k, c = STIFFNESS / 2, 2 * DAMPING * np.sqrt(m)

    def accel(q, v):
        sink, rate = g @ q, g @ v               # corner overlap growth > 0: approaching
        f = -k * sink - c * np.where(rate > 0, rate, 0.0)
        return inv @ (g.T @ f)

    def grows(dt, steps=20000):
        q, v = np.array([1e-9, 0, 0]), np.zeros(3)
        a = accel(q, v)
        for _ in range(steps):
            vh = v + 0.5 * dt * a
            q = q + dt * vh
            a = accel(q, vh)
            v = vh + 0.5 * dt * a
            if not np.all(np.isfinite(q)) or np.abs(q).max() > 1e-6:
                return True
        return np.abs(q).max() > 1e-9

    modes = np.sqrt(np.linalg.eigvals(inv @ (k * g.T @ g)).real)
    lo, hi = 1e-6, 4e-5
    for _ in range(30):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if not grows(mid) else (lo, mid)
    return 0.5 * (lo + hi), sorted(modes)


def run(a, layers, dt):
    work = os.path.join(a.work, "layers%d_dt%g" % (layers, dt))
    os.makedirs(work, exist_ok=True)
    subprocess.run([sys.executable, os.path.join(ROOT, "inputs", "pour", "make_pour.py"), work], check=True)
    p = subprocess.run([a.exe, "-in", DECK, "-echo", "none", "-log", os.path.join(work, "log.lammps"),
                        "-var", "meshdir", work, "-var", "dt", "%.9g" % dt, "-var", "layers", str(layers),
                        "-var", "T", "%g" % a.time, "-var", "th", "10"],
                       cwd=work, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, errors="replace")
    if p.returncode != 0:
        raise RuntimeError(p.stdout[-2000:])
    rows = []
    for line in p.stdout.splitlines():
        v = line.split()
        if len(v) == 6 and v[0].isdigit():
            rows.append([float(x) for x in v])
    late = [r for r in rows if r[1] >= 0.5 * a.time]
    ke = max(r[5] for r in late)
    fewest = int(min(r[2] for r in late))
    state = "rests" if ke < 1e-20 else ("hops" if fewest == 0 else "rattles")
    return dict(layers=layers, dt=dt, state=state, ke_max_late="%.3g" % ke, fewest_contacts=fewest)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "liggghts-spacetree"))
    ap.add_argument("--dt", default="3e-6,4e-6,5e-6,6e-6,6.5e-6,7e-6,7.5e-6,8e-6,9e-6,1e-5,1.2e-5")
    ap.add_argument("--time", type=float, default=0.04)
    ap.add_argument("--work", default="/tmp/resting_stability")
    ap.add_argument("--out", default=os.path.join(ROOT, "bench", "results", "resting_stability"))
    a = ap.parse_args()
    limit, modes = linear_limit()
    print("linearised prism on 6 corners: modes %s rad/s; unstable above dt = %.3g s"
          % (", ".join("%.4g" % w for w in modes), limit))
    rows = []
    for layers in (1, 2):
        for dt in [float(x) for x in a.dt.split(",")]:
            r = run(a, layers, dt)
            r["predicted_limit"] = "%.3g" % limit if layers == 1 else ""
            rows.append(r)
            print("layers %d dt %-8g %-8s largest KE of the second half %s J, fewest contact points %d"
                  % (layers, dt, r["state"], r["ke_max_late"], r["fewest_contacts"]), flush=True)
    with open(a.out + ".csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    for layers in (1, 2):
        ok = [r["dt"] for r in rows if r["layers"] == layers and r["state"] == "rests"]
        bad = [r["dt"] for r in rows if r["layers"] == layers and r["state"] != "rests"]
        print("layers %d: rests up to %s s, not from %s s" % (layers, max(ok) if ok else "-", min(bad) if bad else "-"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
