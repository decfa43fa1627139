#!/usr/bin/env python3
"""The grain pour (inputs/pour/in.pour: 486 L-shaped prisms and dented spheres dropped into a box)
with fixed time steps and with `fix adapt/timestep`: steps needed for the same simulated time at
the same accuracy.

  /usr/bin/python3 bench/pour_timestep.py [--exe build/liggghts-spacetree] [--time 0.15]
        [--ref 2e-6] [--fixed 2.5e-6,8e-6,...] [--adaptive NAME=ARGS ...] [--only NAME,...]
        [--work /tmp/pour_timestep] [--out bench/results/pour_timestep] [--analyse]

Every run starts from the same lattice and runs until the simulated time `--time`; each writes
its history (step, time, dt, kinetic energy, mean grain height, largest halo penetration,
contacts) at intervals of about 1e-5 s (every step for the adaptive runs). Runs whose history is
complete in the work directory are not repeated (`--analyse`: none is run).

Accuracy of a run, against the reference (the smallest fixed step, `--ref`):
  ke_err    integral of |KE(t) - KE_ref(t)| over the run / integral of KE_ref(t) (the kinetic
            energy history: impacts, their dissipation, the settling);
  z_err     |zmean(T) - zmean_ref(T)| / (zmean_ref(T) - z_floor) (the bed's mean height at T);
  pen_err   |pen_max - pen_max_ref| / eps, pen_max the largest halo penetration of any contact over
            the run (eps the halo: pen_max < eps, the rigid surfaces never met).
The pour is chaotic: a run with a step only 1.25 times the reference's (`--floor`, default the
fixed step 1.25 ref) differs from the reference by the noise floor of each error. A fixed step is
"as accurate" as an adaptive run when each of its errors is at most the adaptive run's plus that
floor. For each adaptive run the summary gives the largest fixed step as accurate, its steps and
the ratio adaptive steps / fixed steps, and the ratio to the fixed step equal to `dtcontact` (the
step that resolves the fastest contact as the adaptive run does).

A run that loses a grain (LIGGGHTS stops: "Lost atoms") is unstable: its row says when
(`lost_at`), its errors are inf, and it is never "as accurate".

Phases (from the reference): free fall to the first contact, impacts to the peak of the kinetic
energy, dense flow until it is down to a tenth of the peak, settling to the end. Per run and
phase: the steps, the mean step, the phase's part of the KE-history error, and for adaptive runs
the share of the steps each bound set (the `limit` column of the fix's file dt.txt: creep, dtmax,
contact, rest, stable, veto, other).

Writes OUT.csv (one row per run), OUT_summary.csv (per adaptive run: the matching fixed step and
the step ratio), OUT_phases.csv and OUT.png (KE histories; adaptive steps against time with the
fixed step as accurate, the fixed steps and the resting-stability limits of
bench/results/resting_stability.csv; error against steps)."""
import argparse
import csv
import math
import os
import shutil
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DECK = os.path.join(ROOT, "inputs", "pour", "in.pour")
SETTINGS = os.path.join(ROOT, "inputs", "pour", "pour_settings.in")
HALO = 1e-4          # pair_style trimesh eps of the deck
Z_FLOOR = 0.0        # top face of the floor slab

DEFAULT_ADAPTIVE = [
    # the README line: creep, veto and (pair_style trimesh's default) the stability ceiling
    "readme=creep 1.1 veto yes",
    # the largest fixed step that keeps every grain in the box, as the contact ceiling
    "dtcontact12=creep 1.1 dtcontact 1.2e-5 veto yes",
]


def run(a, name, dt, adapt, every):
    work = os.path.join(a.work, name)
    hist = os.path.join(work, "pour_history.txt")
    done = os.path.join(work, "done")
    if any(os.path.exists(os.path.join(work, f)) for f in ("done", "unstable", "stopped")) or a.analyse:
        return hist
    os.makedirs(work, exist_ok=True)
    deck = os.path.join(work, "in.pour")     # a copy: LIGGGHTS reads its input while it runs
    shutil.copyfile(DECK, deck)
    shutil.copyfile(SETTINGS, os.path.join(work, "pour_settings.in"))
    make = [sys.executable, os.path.join(ROOT, "inputs", "pour", "make_pour.py"), work]
    subprocess.run(make, check=True)
    chunk = max(100, int(round(0.01 / dt))) if adapt else int(math.ceil(a.time / dt - 1e-9))
    cmd = [a.exe, "-in", deck, "-log", os.path.join(work, "log.lammps"), "-echo", "none",
           "-var", "meshdir", work, "-var", "dt", "%.9g" % dt, "-var", "n", str(chunk),
           "-var", "every", str(every), "-var", "th", "1000", "-var", "zlo", str(a.zlo),
           "-var", "out", "pour"]
    if adapt:
        # the fix's own record of every decision (which criterion set the step: its `limit` column)
        cmd += ["-var", "adapt", "fix dtv all adapt/timestep " + adapt + " file " + os.path.join(work, "dt.txt"),
                "-var", "tend", "%.9g" % a.time]
    env = dict(os.environ, OMP_NUM_THREADS="1")
    try:
        p = subprocess.run(cmd, cwd=work, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                           errors="replace", env=env, timeout=a.timeout)
    except subprocess.TimeoutExpired:
        # too slow to finish (e.g. a step collapsed to its floor): kept as how far it got
        open(os.path.join(work, "stopped"), "w").write("stopped after %g s of wall time\n" % a.timeout)
        return hist
    if p.returncode != 0:
        if "Lost atoms" in p.stdout:
            # unstable: a grain was shot out of the box (kept as a result, never "as accurate")
            open(os.path.join(work, "unstable"), "w").write(p.stdout[-2000:])
            return hist
        raise RuntimeError("%s failed:\n%s" % (name, p.stdout[-3000:]))
    open(done, "w").write("ok\n")
    return hist


def history(path, tmax):
    rows = []
    for line in open(path):
        if line.startswith("#"):
            continue
        v = [float(x) for x in line.split()]
        if rows and v[0] <= rows[-1][0]:
            continue           # the first row of a chunk repeats the last of the one before
        rows.append(v)
    cols = list(zip(*rows))
    h = dict(zip(("step", "time", "dt", "ke", "zmean", "pen", "contacts"), [list(c) for c in cols]))
    # the steps to reach tmax: the first row at or past it
    k = next((i for i, t in enumerate(h["time"]) if t >= tmax - 1e-12), len(h["time"]) - 1)
    h["steps_to_T"] = h["step"][k]
    return h


def interp(ts, xs, t):
    import bisect
    k = bisect.bisect_left(ts, t)
    if k <= 0:
        return xs[0]
    if k >= len(ts):
        return xs[-1]
    f = (t - ts[k - 1]) / (ts[k] - ts[k - 1])
    return xs[k - 1] + f * (xs[k] - xs[k - 1])


def errors(h, ref, tmax, n=3000):
    grid = [tmax * (k + 0.5) / n for k in range(n)]
    num = sum(abs(interp(h["time"], h["ke"], t) - interp(ref["time"], ref["ke"], t)) for t in grid)
    den = sum(interp(ref["time"], ref["ke"], t) for t in grid)
    zr = interp(ref["time"], ref["zmean"], tmax)
    z = interp(h["time"], h["zmean"], tmax)
    return {"ke_err": num / den, "z_err": abs(z - zr) / (zr - Z_FLOOR),
            "pen_err": abs(pen_max(h, tmax) - pen_max(ref, tmax)) / HALO, "pen_max": pen_max(h, tmax) / HALO}


def pen_max(h, tmax):
    return max(p for p, t in zip(h["pen"], h["time"]) if t <= tmax + 1e-12)


def cpu_seconds(work):
    log = os.path.join(work, "log.lammps")
    if not os.path.exists(log):
        return float("nan")
    return sum(float(l.split()[3]) for l in open(log, errors="replace") if l.startswith("Loop time of"))


METRICS = ("ke_err", "z_err", "pen_err")


def as_accurate(fixed, adaptive, floor):
    return all(fixed[m] <= adaptive[m] + floor[m] for m in METRICS)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "liggghts-spacetree"))
    ap.add_argument("--time", type=float, default=0.15)
    ap.add_argument("--zlo", type=float, default=0.006, help="lowest lattice layer (m)")
    ap.add_argument("--ref", type=float, default=2e-6)
    ap.add_argument("--dtmax", type=float, default=1e-4, help="the deck's timestep in the adaptive runs (their ceiling)")
    ap.add_argument("--fixed", default="2.5e-6,8e-6,9e-6,1e-5,1.1e-5,1.2e-5,1.3e-5,1.4e-5,1.7e-5,2e-5")
    ap.add_argument("--adaptive", action="append", default=None, help="NAME=fix adapt/timestep arguments")
    ap.add_argument("--only", default="", help="comma-separated run names (ref, fixed_<dt>, adaptive names)")
    ap.add_argument("--work", default="/tmp/pour_timestep")
    ap.add_argument("--out", default=os.path.join(ROOT, "bench", "results", "pour_timestep"))
    ap.add_argument("--analyse", action="store_true", help="run nothing, analyse what is there")
    ap.add_argument("--timeout", type=float, default=None, help="stop a run after this many seconds of wall time")
    ap.add_argument("--floor", default=None, help="the run that gives the noise floor (default fixed_<1.25 ref>)")
    a = ap.parse_args()
    adaptive = [s.split("=", 1) for s in (a.adaptive or DEFAULT_ADAPTIVE)]
    fixed = [float(x) for x in a.fixed.split(",") if x]
    runs = [("ref", a.ref, None)] + [("fixed_%g" % dt, dt, None) for dt in fixed] + \
           [(name, a.dtmax, args) for name, args in adaptive]
    only = set(a.only.split(",")) if a.only else None

    hists = {}
    for name, dt, adapt in runs:
        if only and name not in only:
            continue
        every = 1 if adapt else max(1, int(round(1e-5 / dt)))
        path = run(a, name, dt, adapt, every)
        if os.path.exists(path):
            hists[name] = (dt, adapt, history(path, a.time))
            print("%-12s %s steps %d" % (name, "dt %.3g" % dt if not adapt else adapt, hists[name][2]["steps_to_T"]),
                  flush=True)
    if "ref" not in hists:
        return 0
    ref = hists["ref"][2]
    rows = []
    for name, (dt, adapt, h) in hists.items():
        unstable = os.path.exists(os.path.join(a.work, name, "unstable"))
        if h["time"][-1] < a.time - 1e-9 and not unstable:
            print("%s: incomplete (t = %.4g)" % (name, h["time"][-1]))
            continue
        # an unstable run (a grain lost at time t_lost) is never as accurate as anything
        e = {m: float("inf") for m in METRICS + ("pen_max",)} if unstable else errors(h, ref, a.time)
        steps = int(round(a.time / dt)) if unstable and not adapt else int(h["steps_to_T"])
        rows.append(dict(name=name, kind="adaptive" if adapt else "fixed", dt=dt if not adapt else "",
                         args=adapt or "", steps=steps, lost_at="%.4g" % h["time"][-1] if unstable else "",
                         loop_s="%.1f" % cpu_seconds(os.path.join(a.work, name)),
                         ke_err="%.4g" % e["ke_err"], z_err="%.4g" % e["z_err"], pen_err="%.4g" % e["pen_err"],
                         pen_max="%.4g" % e["pen_max"]))
    os.makedirs(os.path.dirname(a.out), exist_ok=True)
    with open(a.out + ".csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    floor_name = a.floor or "fixed_%g" % (1.25 * a.ref)
    floor_row = next((r for r in rows if r["name"] == floor_name), None)
    floor = {m: float(floor_row[m]) if floor_row else 0.0 for m in METRICS}
    summary = []
    fixed_rows = sorted((r for r in rows if r["kind"] == "fixed" and r["name"] not in ("ref", floor_name)),
                        key=lambda r: -float(r["dt"]))
    for r in rows:
        if r["kind"] != "adaptive":
            continue
        ad = {m: float(r[m]) for m in METRICS}
        # an adaptive run that lost a grain matches nothing (nor does an unstable fixed run)
        match = None if r["lost_at"] else next(
            (f for f in fixed_rows if not f["lost_at"] and as_accurate({m: float(f[m]) for m in METRICS}, ad, floor)),
            None)
        dtc = r["args"].split("dtcontact")[1].split()[0] if "dtcontact" in r["args"] else None
        dtc = float(dtc) if dtc not in (None, "stable", "none") else None
        summary.append(dict(adaptive=r["name"], args=r["args"], adaptive_steps=r["steps"],
                            ke_err=r["ke_err"], z_err=r["z_err"], pen_err=r["pen_err"],
                            floor_ke=floor["ke_err"], floor_z=floor["z_err"], floor_pen=floor["pen_err"],
                            fixed_dt=match["dt"] if match else "", fixed_steps=match["steps"] if match else "",
                            fixed_ke_err=match["ke_err"] if match else "", fixed_z_err=match["z_err"] if match else "",
                            fixed_pen_err=match["pen_err"] if match else "",
                            step_ratio="%.3f" % (r["steps"] / match["steps"]) if match else "",
                            ratio_to_dtcontact="%.3f" % (r["steps"] / (a.time / dtc)) if dtc else ""))
    with open(a.out + "_summary.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(summary[0].keys()) if summary else ["adaptive"])
        w.writeheader()
        w.writerows(summary)
    for r in rows:
        print("%-14s steps %7d  ke_err %-9s z_err %-9s pen_err %-8s pen_max %-8s loop %s s%s" %
              (r["name"], r["steps"], r["ke_err"], r["z_err"], r["pen_err"], r["pen_max"], r["loop_s"],
               "  UNSTABLE: grain lost at t = %s s" % r["lost_at"] if r["lost_at"] else ""))
    print("noise floor (%s): %s" % (floor_name, floor))
    for s_ in summary:
        print("%s: %s steps; largest fixed step as accurate %s (%s steps): ratio %s; to a fixed step of "
              "dtcontact: %s" % (s_["adaptive"], s_["adaptive_steps"], s_["fixed_dt"] or "none",
                                 s_["fixed_steps"], s_["step_ratio"], s_["ratio_to_dtcontact"]))
    table = phase_table(a, hists, ref)
    if table:
        with open(a.out + "_phases.csv", "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(table[0].keys()))
            w.writeheader()
            w.writerows(table)
        print("phases (steps, mean dt, part of the KE error; adaptive: shares of the bounds that set the step):")
        for r in table:
            lims = " ".join("%s %s" % (l, r["limit_" + l]) for l in LIMITS + ("other",) if r["limit_" + l] not in ("", "0.000"))
            print("  %-14s %-10s %s-%s s  steps %6d  mean dt %-8s ke_err part %s  %s" %
                  (r["run"], r["phase"], r["t_from"], r["t_to"], r["steps"], r["mean_dt"], r["ke_err_part"], lims))
    plot(a, hists, rows, summary)
    return 0


LIMITS = ("creep", "dtmax", "contact", "rest", "stable", "veto")


def phases(ref, tmax):
    """Phases of the pour from the reference: free fall (to the first contact), impacts (to the
    peak of the kinetic energy: grains land while the upper layers still fall), dense flow (until
    the kinetic energy is down to a tenth of its peak) and settling (to the end)."""
    t, ke = ref["time"], ref["ke"]
    t1 = next(x for x, c in zip(t, ref["contacts"]) if c > 0)
    k = max(range(len(ke)), key=lambda i: ke[i])
    t3 = next((t[i] for i in range(k, len(t)) if ke[i] < 0.1 * ke[k]), tmax)
    return [("free fall", 0.0, t1), ("impacts", t1, t[k]), ("dense flow", t[k], t3), ("settling", t3, tmax)]


def decisions(work):
    """The fix's file (adaptive runs): (time, dt, limit) per step."""
    path = os.path.join(work, "dt.txt")
    if not os.path.exists(path):
        return None
    rows = []
    for line in open(path):
        if line.startswith("#"):
            continue
        v = line.split()
        rows.append((float(v[1]), float(v[2]), v[-1]))
    return rows


def phase_table(a, hists, ref):
    """Per run and phase: steps, mean step, the bounds that set the adaptive steps (shares), and
    the phase's part of the kinetic-energy error."""
    table = []
    for name, (dt, adapt, h) in hists.items():
        if name == "ref" or os.path.exists(os.path.join(a.work, name, "unstable")):
            continue
        dec = decisions(os.path.join(a.work, name)) if adapt else None
        n = 3000
        grid = [a.time * (k + 0.5) / n for k in range(n)]
        den = sum(interp(ref["time"], ref["ke"], t) for t in grid)
        for phase, t0, t1 in phases(ref, a.time):
            if adapt:
                # a step belongs to the phase it ends in (the history's time is the step's end)
                steps = sum(1 for t in h["time"] if t0 < t <= t1 + 1e-12)
            else:
                steps = int(round((t1 - t0) / dt))
            part = sum(abs(interp(h["time"], h["ke"], t) - interp(ref["time"], ref["ke"], t))
                       for t in grid if t0 <= t < t1) / den
            row = dict(run=name, phase=phase, t_from="%.4f" % t0, t_to="%.4f" % t1, steps=steps,
                       mean_dt="%.3g" % ((t1 - t0) / steps if steps else float("nan")), ke_err_part="%.4f" % part)
            for lim in LIMITS + ("other",):
                row["limit_" + lim] = ""
            if dec:
                chosen = [d for d in dec if t0 <= d[0] < t1]   # the decision taken at the step's end
                for lim in LIMITS:
                    row["limit_" + lim] = "%.3f" % (sum(1 for d in chosen if d[2] == lim) / max(len(chosen), 1))
                row["limit_other"] = "%.3f" % (sum(1 for d in chosen if d[2] not in LIMITS) / max(len(chosen), 1))
            table.append(row)
    return table


def plot(a, hists, rows, summary):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return
    fig, ax = plt.subplots(1, 3, figsize=(16, 4.8))
    for name, (dt, adapt, h) in sorted(hists.items(), key=lambda kv: (kv[1][1] is not None, -kv[1][0])):
        t = h["time"]
        style = dict(lw=2.2, color="k") if name == "ref" else (dict(lw=1.4, ls="--") if adapt else dict(lw=0.8))
        label = ("reference dt %.3g s" % dt) if name == "ref" else (name if adapt else "fixed dt %.3g s" % dt)
        ax[0].plot(t, h["ke"], label=label, **style)
        if adapt:
            line, = ax[1].semilogy(t, h["dt"], label=name, **style)
            match = next((s_ for s_ in summary if s_["adaptive"] == name and s_["fixed_dt"]), None)
            if match:   # the fixed step as accurate as this run
                ax[1].axhline(float(match["fixed_dt"]), color=line.get_color(), lw=1.0, ls=":",
                              label="fixed step as accurate as %s: %g s" % (name, float(match["fixed_dt"])))
    for r in rows:
        if r["kind"] == "fixed" and r["name"] != "ref":
            ax[1].axhline(float(r["dt"]), color="0.85" if not r["lost_at"] else "r", lw=0.6)
    # the largest fixed steps at which flat-lying prisms stay at rest (bench/resting_stability.py)
    rest = os.path.join(os.path.dirname(a.out), "resting_stability.csv")
    if os.path.exists(rest):
        rr = list(csv.DictReader(open(rest)))
        for layers, color in (("1", "C4"), ("2", "C5")):
            ok = [float(r["dt"]) for r in rr if r["layers"] == layers and r["state"] == "rests"]
            if ok:
                ax[1].axhline(max(ok), color=color, lw=1.2, ls="-.",
                              label="%s flat prism%s at rest up to %g s" % (
                                  "one" if layers == "1" else "two stacked", "" if layers == "1" else "s", max(ok)))
    ax[0].set_xlabel("simulated time (s)")
    ax[0].set_ylabel("kinetic energy of the grains (J)")
    if "ref" in hists:   # an unstable run's blow-up (a grain shot out) leaves the scale
        ax[0].set_ylim(0, 1.3 * max(hists["ref"][2]["ke"]))
    ax[0].set_title("kinetic energy history (unstable runs leave the scale)")
    ax[0].legend(fontsize=7)
    ax[1].set_xlabel("simulated time (s)")
    ax[1].set_ylabel("time step (s)")
    ax[1].set_title("adaptive step (grey: the fixed steps; red: unstable)")
    ax[1].legend(fontsize=7)
    fx = sorted((r for r in rows if r["kind"] == "fixed" and r["name"] != "ref" and not r["lost_at"]),
                key=lambda r: r["steps"])
    ax[2].loglog([r["steps"] for r in fx], [float(r["ke_err"]) for r in fx], "o-", color="C0", label="fixed: KE history error")
    ax[2].loglog([r["steps"] for r in fx], [float(r["z_err"]) for r in fx], "s-", color="C1", label="fixed: bed height error")
    ax[2].loglog([r["steps"] for r in fx], [max(float(r["pen_err"]), 1e-4) for r in fx], "^-", color="C2",
                 label="fixed: peak penetration error / eps")
    for r in rows:
        if r["kind"] == "adaptive":
            ax[2].loglog([r["steps"]], [float(r["ke_err"])], "*", color="C0", ms=14)
            ax[2].loglog([r["steps"]], [float(r["z_err"])], "*", color="C1", ms=14)
            ax[2].loglog([r["steps"]], [max(float(r["pen_err"]), 1e-4)], "*", color="C2", ms=14)
            ax[2].annotate(r["name"], (r["steps"], float(r["ke_err"])), fontsize=7)
    ax[2].set_xlabel("steps for %.3g s" % a.time)
    ax[2].set_ylabel("error against the reference")
    ax[2].set_title("error against steps (stars: adaptive)")
    ax[2].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(a.out + ".png", dpi=110)


if __name__ == "__main__":
    sys.exit(main())
