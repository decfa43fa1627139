#!/usr/bin/env python3
"""Paper §7.1 two-particle run with `fix adapt/timestep`: the time step over time creeps to its
cap, collapses at impact (veto) and recovers.  Writes bench/results/timestep_two_particles.csv
(the columns of the fix's history file) and .png (--replot: only the PNG, from the stored CSV).

  /usr/bin/python3 bench/timestep_two_particles.py [--exe build/liggghts-spacetree] [--dtmax 2e-4] [--replot]
"""
import argparse
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def plot(results, dtmax):
    """Draws timestep_two_particles.png from timestep_two_particles.csv."""
    import csv
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    rows = list(csv.DictReader(open(os.path.join(results, "timestep_two_particles.csv"))))
    t = [float(r["time"]) for r in rows]
    dt = [float(r["dt"]) for r in rows]
    veto = [i for i, r in enumerate(rows) if r["vetoed"] == "1"]
    print("simulated %.4g s, dt from %.3g to %.3g, %d vetoed steps (first at t = %.4g s)"
          % (t[-1], min(dt), max(dt), len(veto), t[veto[0]] if veto else float("nan")))
    step = [int(r["step"]) for r in rows]
    fig, ax = plt.subplots(1, 3, figsize=(15, 4), gridspec_kw=dict(width_ratios=(1, 1.6, 1)))
    hit = step[veto[0]] if veto else step[len(step) // 2]
    end = next((k for k in range(len(dt)) if dt[k] >= float(dtmax)), len(dt) - 1)
    panels = ((ax[0], step, (0, step[end] + 10), "start: dt creeps by 1.1 per step to dtmax", "step"),
              (ax[1], t, None, "whole run: dt %.2g .. %.2g s" % (min(dt), max(dt)), "simulated time (s)"),
              (ax[2], [k - hit for k in step], (-10, 110), "impact: veto, then the creep back", "step - first vetoed step"))
    for axis, x, lim, title, label in panels:
        axis.semilogy(x, dt, "-", lw=1.2, drawstyle="steps-post", marker="." if lim else None, ms=3,
                      label="time step")
        axis.semilogy([x[i] for i in veto], [dt[i] for i in veto], "rv", ms=6, label="vetoed step (%d)" % len(veto))
        axis.axhline(float(dtmax), color="grey", ls=":", lw=1, label="dtmax %s s" % dtmax)
        if lim:
            axis.set_xlim(*lim)
        axis.set_xlabel(label)
        axis.set_title(title, fontsize=10)
        axis.grid(True, which="both", alpha=0.3)
    ax[0].set_ylabel("dt (s)")
    ax[1].legend(loc="lower right", fontsize=8)
    fig.suptitle("fix adapt/timestep on paper §7.1 (spheres d = 0.02 and 0.2 m, creep 1.1, dtmin 1e-7 s)",
                 fontsize=11)
    fig.tight_layout()
    png = os.path.join(results, "timestep_two_particles.png")
    fig.savefig(png, dpi=100)
    print("wrote", png)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "liggghts-spacetree"))
    ap.add_argument("--dtmax", default="2e-4")
    ap.add_argument("--results", default=os.path.join(ROOT, "bench", "results"))
    ap.add_argument("--replot", action="store_true", help="only redraw the PNG from the stored CSV")
    a = ap.parse_args()
    if a.replot:
        plot(a.results, a.dtmax)
        return 0
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
    names = next(l for l in open(hist) if l.startswith("#")).split()[1:]
    rows = [l.split() for l in open(hist) if not l.startswith("#")]
    csv_path = os.path.join(a.results, "timestep_two_particles.csv")
    vetoed = names.index("vetoed")
    with open(csv_path, "w") as f:
        f.write(",".join(names) + "\n")
        # every step where dt changes, plus every 500th (the file stays small)
        for i, r in enumerate(rows):
            if i % 500 == 0 or i + 1 == len(rows) or r[2] != rows[i - 1][2] or r[vetoed] == "1":
                f.write(",".join(r) + "\n")
    plot(a.results, a.dtmax)
    return 0


if __name__ == "__main__":
    sys.exit(main())
