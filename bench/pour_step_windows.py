#!/usr/bin/env python3
"""The largest global time step the grain pour (inputs/pour/in.pour) tolerates at each moment:
windows of the pour restarted from a stable fixed-step run and continued with larger fixed steps.
This is the bound of any global-step controller: over a window no global step above the window's
limit keeps the grains in contact stable, however the step is chosen.

  /usr/bin/python3 bench/pour_step_windows.py [--exe build/liggghts-spacetree] [--base-dt 1e-5]
        [--starts 0.01,0.02,...] [--window 0.01] [--dt 1.1e-5,1.2e-5,...]
        [--work /tmp/pour_step_windows] [--out bench/results/pour_step_windows]

The base run (fixed step --base-dt, stable over the whole pour) writes a restart file at every
start time; each window runs `inputs/pour/in.pour_restart` from it for --window seconds at a fixed
step dt. A window is *unstable* at dt when a grain is lost, or the largest halo penetration of
any contact reaches half the halo (eps/2: the base run stays below 0.07 eps over the whole pour;
a contact driven unstable by the step grows to the full halo within a few steps), or the kinetic
energy at the window's end exceeds 10 times the base run's. Columns: start, dt, state, the largest
halo penetration / eps, the kinetic energy at the end and the base run's, the contacts at the start.
Writes OUT.csv (one row per window and step) and OUT_limits.csv (per window: the largest step
tried that is stable together with every smaller one tried, and the contacts)."""
import argparse
import csv
import os
import shutil
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
POUR = os.path.join(ROOT, "inputs", "pour")
HALO = 1e-4          # pair_style trimesh eps of the deck


def history(path):
    rows = []
    for line in open(path):
        if not line.startswith("#"):
            rows.append([float(x) for x in line.split()])
    return rows    # step time dt ke zmean pen contacts


def prepare(work):
    os.makedirs(work, exist_ok=True)
    for f in ("in.pour", "pour_settings.in", "in.pour_restart"):
        shutil.copyfile(os.path.join(POUR, f), os.path.join(work, f))
    subprocess.run([sys.executable, os.path.join(POUR, "make_pour.py"), work], check=True,
                   stdout=subprocess.DEVNULL)


def lammps(a, work, args):
    env = dict(os.environ, OMP_NUM_THREADS="1")
    return subprocess.run([a.exe, "-echo", "none", "-log", os.path.join(work, "log.lammps")] + args, cwd=work,
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, errors="replace", env=env)


def base_run(a, starts):
    work = os.path.join(a.work, "base")
    steps = [int(round(t / a.base_dt)) for t in starts]
    if all(os.path.exists(os.path.join(work, "pour.%d.restart" % s)) for s in steps):
        return work, steps
    prepare(work)
    # restart files every --every steps (the starts are multiples of it), the history every step
    every = steps[0]
    for s in steps:
        if s % every:
            every = 1
    n = int(round((max(starts) + a.window) / a.base_dt))
    p = lammps(a, work, ["-in", "in.pour", "-var", "dt", "%.9g" % a.base_dt, "-var", "n", str(n),
                         "-var", "every", "1", "-var", "th", "1000",
                         "-var", "adapt", "restart %d %s/pour.*.restart" % (every, work)])
    if p.returncode != 0:
        raise RuntimeError("base run failed:\n" + p.stdout[-3000:])
    return work, steps


def window(a, base, step, t0, dt):
    name = "w%.4f_dt%g" % (t0, dt)
    work = os.path.join(a.work, name)
    hist = os.path.join(work, "pour_history.txt")
    if not os.path.exists(os.path.join(work, "done")):
        prepare(work)
        p = lammps(a, work, ["-in", "in.pour_restart", "-var", "file", os.path.join(base, "pour.%d.restart" % step),
                             "-var", "dt", "%.9g" % dt, "-var", "T", "%.9g" % a.window, "-var", "every", "1",
                             "-var", "th", "1000"])
        lost = "Lost atoms" in p.stdout
        if p.returncode != 0 and not lost:
            raise RuntimeError("%s failed:\n%s" % (name, p.stdout[-3000:]))
        open(os.path.join(work, "done"), "w").write("lost\n" if lost else "ok\n")
    lost = open(os.path.join(work, "done")).read().startswith("lost")
    return lost, history(hist)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "liggghts-spacetree"))
    ap.add_argument("--base-dt", type=float, default=1e-5)
    ap.add_argument("--starts", default=",".join("%.2f" % (0.01 * k) for k in range(1, 15)))
    ap.add_argument("--window", type=float, default=0.01)
    ap.add_argument("--dt", default="1e-5,1.1e-5,1.2e-5,1.4e-5,1.7e-5,2e-5,2.5e-5")
    ap.add_argument("--work", default="/tmp/pour_step_windows")
    ap.add_argument("--out", default=os.path.join(ROOT, "bench", "results", "pour_step_windows"))
    a = ap.parse_args()
    starts = [float(x) for x in a.starts.split(",")]
    dts = sorted(float(x) for x in a.dt.split(","))
    base, steps = base_run(a, starts)
    bh = history(os.path.join(base, "pour_history.txt"))

    def base_at(t):
        return min(bh, key=lambda r: abs(r[1] - t))

    rows, limits = [], []
    for t0, step in zip(starts, steps):
        ke_base = base_at(t0 + a.window)[3]
        contacts0 = int(base_at(t0)[6])
        largest = None
        for dt in dts:
            lost, h = window(a, base, step, t0, dt)
            pen = max(r[5] for r in h) / HALO
            ke_end = h[-1][3]
            if lost:
                state = "lost"
            elif pen >= 0.5:
                state = "penetrates"
            elif ke_end > 10 * ke_base:
                state = "heats"
            else:
                state = "stable"
            rows.append(dict(start=t0, dt=dt, state=state, pen_max=round(pen, 5), ke_end="%.4g" % ke_end,
                             ke_end_base="%.4g" % ke_base, contacts_start=contacts0, lost_at="%.5g" % h[-1][1] if lost else ""))
            print("t0 %.3f dt %-8g %-10s pen %.4f eps  KE end %.3g (base %.3g)  contacts %d" %
                  (t0, dt, state, pen, ke_end, ke_base, contacts0), flush=True)
            if state == "stable" and largest == (dts[dts.index(dt) - 1] if dts.index(dt) else None):
                largest = dt
        limits.append(dict(start=t0, end=round(t0 + a.window, 9), largest_stable_dt=largest or "", contacts_start=contacts0,
                           ke_start="%.4g" % base_at(t0)[3]))
    os.makedirs(os.path.dirname(a.out), exist_ok=True)
    for suffix, table in (("", rows), ("_limits", limits)):
        with open(a.out + suffix + ".csv", "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(table[0].keys()))
            w.writeheader()
            w.writerows(table)
    for l in limits:
        print("window %.3f-%.3f s: largest stable step %s s (contacts %d)" %
              (l["start"], l["end"], l["largest_stable_dt"] or "none tried", l["contacts_start"]))
    # the fewest steps any global step could take (each window at its largest stable step; the
    # time before the first start at the first window's, a window without one at --base-dt)
    steps = starts[0] / (limits[0]["largest_stable_dt"] or a.base_dt)
    steps += sum(a.window / (l["largest_stable_dt"] or a.base_dt) for l in limits)
    total = starts[0] + len(limits) * a.window
    print("every window at its largest stable step: %.0f steps for %.3g s (a fixed step of %g s: %.0f)"
          % (steps, total, a.base_dt, total / a.base_dt))
    with open(a.out + "_limits.csv", "a") as f:
        f.write("# every window at its largest stable step: %.0f steps for %.3g s\n" % (steps, total))
    return 0


if __name__ == "__main__":
    sys.exit(main())
