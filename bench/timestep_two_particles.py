#!/usr/bin/env python3
"""Paper §7.1 two-particle run with `fix adapt/timestep`: the time step over time creeps to its
cap, collapses at impact (veto) and recovers.  Writes bench/results/timestep_two_particles.csv
(step, time, dt, critical pairs, vetoed, floored) and .png.

  /usr/bin/python3 bench/timestep_two_particles.py [--exe build/liggghts-spacetree] [--dtmax 2e-4]
"""
import argparse
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "liggghts-spacetree"))
    ap.add_argument("--dtmax", default="2e-4")
    ap.add_argument("--results", default=os.path.join(ROOT, "bench", "results"))
    a = ap.parse_args()
    work = os.path.join(ROOT, "build", "bench_timestep_two_particles")
    os.makedirs(work, exist_ok=True)
    os.makedirs(a.results, exist_ok=True)
    hist = os.path.join(work, "dt_history.txt")
    p = subprocess.run([a.exe, "-in", os.path.join(ROOT, "inputs", "paper71", "in.two_spheres"),
                        "-var", "history", hist, "-var", "dtmax", a.dtmax,
                        "-log", os.path.join(work, "log.two_spheres"), "-echo", "none"],
                       cwd=work, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, errors="replace")
    if p.returncode != 0:
        print(p.stdout[-3000:])
        return 1
    rows = [l.split() for l in open(hist) if not l.startswith("#")]
    csv = os.path.join(a.results, "timestep_two_particles.csv")
    with open(csv, "w") as f:
        f.write("step,time,dt,critical_pairs,vetoed,floored\n")
        # every step where dt changes, plus every 500th (the file stays small)
        for i, r in enumerate(rows):
            if i % 500 == 0 or i + 1 == len(rows) or r[2] != rows[i - 1][2] or r[4] == "1":
                f.write(",".join(r) + "\n")
    t = [float(r[1]) for r in rows]
    dt = [float(r[2]) for r in rows]
    veto = [i for i, r in enumerate(rows) if r[4] == "1"]
    print("steps %d, simulated %.4g s, dt from %.3g to %.3g, %d vetoed steps (first at t = %.4g s)"
          % (len(rows), t[-1], min(dt), max(dt), len(veto), t[veto[0]] if veto else float("nan")))
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 4))
    ax.semilogy(t, dt, "-", lw=1.2, label="time step")
    ax.semilogy([t[i] for i in veto], [dt[i] for i in veto], "rv", ms=5, label="vetoed step")
    ax.set_xlabel("simulated time (s)")
    ax.set_ylabel("dt (s)")
    ax.set_title("Paper §7.1: spheres d = 0.02 and 0.2, creep 1.1, dtmax " + a.dtmax)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    png = os.path.join(a.results, "timestep_two_particles.png")
    fig.savefig(png, dpi=100)
    print("wrote", csv, "and", png)
    return 0


if __name__ == "__main__":
    sys.exit(main())
