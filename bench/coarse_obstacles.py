#!/usr/bin/env python3
"""Time per step of 500 grains settling in a box of slab obstacles (inputs/bench/in.obstacle_box)
whose five walls are meshed with about 12, 100 and 1000 triangles each: the same surfaces, so the
cost should not depend on the mesh. All configurations interleaved in every repetition, medians.

  coarse_obstacles.py --exe new=build/liggghts-spacetree [--exe old=/path/liggghts-spacetree]
                      [--triangles 12,100,1000] [--repeats 3] [--settle 15000] [--steps 500]
                      [--threads 1] [--nstyle spacetree] [--restart FILE]
                      [--out bench/results/coarse_obstacles]

Walls (written per resolution with inputs/hopper/make_hopper.py's slab(): closed boxes whose
faces are grids of squares): floor [-37, 37]^2 x [-5, 0] mm, four walls 5 mm thick and 50 mm high
around an inner 64 x 64 mm; each wall's grid cell is chosen so that its triangle count is nearest
the target (12 = two triangles per face). The grains (dented spheres of 40 triangles, radius
2.5 mm, bounding radius <= 3 mm) start on a 10 x 10 x 5 lattice (6.2 mm) at rest and fall under
gravity: `settle` steps (first executable, first resolution, untimed) are written to a restart
file (or --restart gives one), from which every timed run continues `steps` steps (the bed on
the floor, grains at the walls): the same start for every executable and resolution.

Per run: LIGGGHTS' loop and pair time of the timed run (wall clock), CPU seconds per step of
the process (less the CPU seconds of the same run with 0 steps: set-up; on a shared machine CPU
time does not count waiting for a core), the 1-minute load average, and the last thermo row of
compute trimesh/contacts (contacts, body pairs, triangle pairs checked, hybrid fallbacks,
largest penetration). Writes OUT.csv (one row per run), OUT_summary.csv (medians per executable
and resolution, and per executable the largest / smallest median time per step over the
resolutions) and OUT.png (--replot redraws it from OUT_summary.csv)."""
import argparse
import os
import re
import resource
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, os.path.join(ROOT, "inputs", "hopper"))
from make_hopper import slab, write_stl  # noqa: E402

DECK = os.path.join(ROOT, "inputs", "bench", "in.obstacle_box")
W, T, H, F = 0.032, 0.005, 0.05, 0.037   # inner half width, thickness, height, floor half width
WALLS = {
    "floor": ((-F, -F, -T), (F, F, 0.0)),
    "xlo": ((-W - T, -W, 0.0), (-W, W, H)),
    "xhi": ((W, -W, 0.0), (W + T, W, H)),
    "ylo": ((-W - T, -W - T, 0.0), (W + T, -W, H)),
    "yhi": ((-W - T, W, 0.0), (W + T, W + T, H)),
}


def mesh_with_about(lo, hi, target):
    """The slab whose triangle count is nearest `target` (cells from 1 per side up)."""
    best = None
    size = max(hi[d] - lo[d] for d in range(3))
    cell = size
    while cell > size / 200:
        tris = slab(lo, hi, cell)
        if best is None or abs(len(tris) - target) < abs(len(best) - target):
            best = tris
        if len(tris) > 2 * target:
            break
        cell /= 1.05
    return best


def write_walls(directory, target):
    counts = {}
    for name, (lo, hi) in WALLS.items():
        tris = mesh_with_about(lo, hi, target)
        write_stl(os.path.join(directory, name + ".stl"), tris)
        counts[name] = len(tris)
    return counts


def run_once(exe, meshdir, a, workdir, steps, restart, read=1):
    log = os.path.join(workdir, "log.lammps")
    cmd = [exe, "-in", DECK, "-log", log, "-echo", "none", "-var", "meshdir", meshdir,
           "-var", "settle", str(a.settle), "-var", "steps", str(steps), "-var", "nstyle", a.nstyle,
           "-var", "threads", str(a.threads), "-var", "read", str(read), "-var", "restart", restart]
    env = dict(os.environ, OMP_NUM_THREADS="1")
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    load = float(open("/proc/loadavg").read().split()[0])
    t0 = time.time()
    p = subprocess.run(cmd, cwd=workdir, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                       errors="replace", env=env)
    wall = time.time() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if p.returncode != 0:
        raise SystemExit("run failed (%s):\n%s" % (" ".join(cmd), p.stdout[-3000:]))
    text = open(log, errors="replace").read()
    loops = re.findall(r"Loop time of ([0-9.eE+-]+) on \d+ procs for (\d+) steps", text)
    pairs = re.findall(r"Pair\s+time \(%\) = ([0-9.eE+-]+)", text)
    loop, steps = float(loops[-1][0]), int(loops[-1][1])
    rows = []
    for line in text.split("\n"):
        f = line.split()
        if len(f) == 9 and f[0].isdigit():
            try:
                rows.append([float(v) for v in f])
            except ValueError:
                pass
    last = rows[-1]
    return dict(loop_s=loop, steps=steps, pair_s=float(pairs[-1]), s_per_step=loop / max(1, steps),
                pair_s_per_step=float(pairs[-1]) / max(1, steps),
                cpu_s=(after.ru_utime + after.ru_stime) - (before.ru_utime + before.ru_stime),
                wall_s=wall, load1=load, atoms=int(last[1]), contacts=int(last[2]),
                body_pairs=int(last[3]), triangle_pairs=int(last[4]), fallbacks=int(last[5]),
                max_penetration=last[6], zmax=last[7], kinetic_energy=last[8])


def plot(summary, out):
    """OUT.png: median wall and CPU ms per step per executable and resolution."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib not available: no PNG")
        return
    labels = list(dict.fromkeys(s["executable"] for s in summary))
    targets = list(dict.fromkeys(int(s["target"]) for s in summary))
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    width = 0.8 / len(labels)
    for ax, key, title in ((axes[0], "cpu_ms_per_step", "CPU time per step"),
                           (axes[1], "ms_per_step", "wall time per step (shared machine)")):
        for k, label in enumerate(labels):
            ss = [s for s in summary if s["executable"] == label]
            values = [float(s[key]) for s in ss]
            x = [i + k * width for i in range(len(ss))]
            ax.bar(x, values, width, label=label)
            for xi, v in zip(x, values):  # the claim: time relative to the coarsest walls
                ax.text(xi, v, "%.1f ms\n%.2fx" % (v, v / values[0]), ha="center", va="bottom", fontsize=8)
        ax.set_xticks([i + 0.4 - width / 2 for i in range(len(targets))])
        ax.set_xticklabels(["~%d triangles\nper wall" % t for t in targets])
        ax.set_ylabel("ms per step (median)")
        ax.set_ylim(0, 1.25 * max(float(s[key]) for s in summary))
        ax.set_title(title + "; label: ratio to 12 triangles", fontsize=10)
        if len(labels) > 1:
            ax.legend(loc="lower right")
    fig.suptitle("500 grains in a box of 5 slab obstacles")
    fig.tight_layout()
    fig.savefig(out + ".png", dpi=120)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", action="append", default=[], help="LABEL=PATH (or PATH), repeatable")
    ap.add_argument("--triangles", default="12,100,1000")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--settle", type=int, default=15000)
    ap.add_argument("--steps", type=int, default=500)
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--nstyle", default="spacetree")
    ap.add_argument("--out", default=os.path.join(ROOT, "bench", "results", "coarse_obstacles"))
    ap.add_argument("--restart", default="", help="a settled bed from an earlier run (skips the settling)")
    ap.add_argument("--replot", action="store_true", help="only redraw OUT.png from OUT_summary.csv")
    a = ap.parse_args()
    if a.replot:
        import csv
        with open(a.out + "_summary.csv") as f:
            plot(list(csv.DictReader(f)), a.out)
        return
    if not a.exe:
        ap.error("--exe is required")
    exes = []
    for e in a.exe:
        label, _, path = e.rpartition("=")
        exes.append((label or os.path.basename(os.path.dirname(os.path.abspath(path))), os.path.abspath(path)))
    targets = [int(t) for t in a.triangles.split(",")]
    tmp = tempfile.mkdtemp(prefix="coarse_obstacles_")
    meshes = {}
    for t in targets:
        d = os.path.join(tmp, "mesh_%d" % t)
        os.makedirs(d)
        meshes[t] = (d, write_walls(d, t))
        print("walls of about %d triangles: %s" % (t, meshes[t][1]), flush=True)
    # One settled bed (the first executable, the first resolution), the start of every timed
    # run: the walls are the same surfaces at every resolution.
    work = os.path.join(tmp, "settle")
    os.makedirs(work)
    restart = a.restart or os.path.join(work, "settled.restart")
    if not a.restart:
        res = run_once(exes[0][1], meshes[targets[0]][0], a, work, a.steps, restart, read=0)
        print("settled %d steps on walls of about %d triangles: %d contacts, highest grain %.4f m"
              % (a.settle, targets[0], res["contacts"], res["zmax"]), flush=True)
    restarts = {t: restart for t in targets}
    results = []
    for r in range(a.repeats):
        for label, exe in exes:
            for t in targets:
                work = os.path.join(tmp, "run_%s_%d_%d" % (label, t, r))
                os.makedirs(work)
                # the same deck without steps: the set-up's CPU time, subtracted
                setup = run_once(exe, meshes[t][0], a, work, 0, restarts[t])
                res = run_once(exe, meshes[t][0], a, work, a.steps, restarts[t])
                res["setup_cpu_s"] = setup["cpu_s"]
                res["cpu_s_per_step"] = (res["cpu_s"] - setup["cpu_s"]) / a.steps
                res.update(executable=label, target=t, wall_triangles=sum(meshes[t][1].values()),
                           repeat=r)
                results.append(res)
                print("%-6s %5d tri/wall repeat %d: %.3f ms/step (pair %.3f), CPU %.3f ms/step, contacts %d, "
                      "triangle pairs %d, fallbacks %d, load %.1f"
                      % (label, t, r, 1e3 * res["s_per_step"], 1e3 * res["pair_s_per_step"], 1e3 * res["cpu_s_per_step"],
                         res["contacts"], res["triangle_pairs"], res["fallbacks"], res["load1"]), flush=True)
    os.makedirs(os.path.dirname(a.out), exist_ok=True)
    cols = ["executable", "target", "wall_triangles", "repeat", "atoms", "steps", "loop_s", "pair_s",
            "s_per_step", "pair_s_per_step", "cpu_s", "setup_cpu_s", "cpu_s_per_step", "wall_s", "load1",
            "contacts", "body_pairs",
            "triangle_pairs", "fallbacks", "max_penetration", "zmax", "kinetic_energy"]
    with open(a.out + ".csv", "w") as f:
        f.write(",".join(cols) + "\n")
        for res in results:
            f.write(",".join(str(res[c]) for c in cols) + "\n")
    summary = []
    for label, _ in exes:
        per = {}
        for t in targets:
            rs = [x for x in results if x["executable"] == label and x["target"] == t]
            per[t] = dict(executable=label, target=t, wall_triangles=rs[0]["wall_triangles"],
                          ms_per_step=1e3 * statistics.median(x["s_per_step"] for x in rs),
                          pair_ms_per_step=1e3 * statistics.median(x["pair_s_per_step"] for x in rs),
                          cpu_ms_per_step=1e3 * statistics.median(x["cpu_s_per_step"] for x in rs),
                          triangle_pairs=statistics.median(x["triangle_pairs"] for x in rs),
                          fallback_percent=100.0 * statistics.median(
                              x["fallbacks"] / max(1, x["triangle_pairs"]) for x in rs),
                          contacts=statistics.median(x["contacts"] for x in rs))
        spread = max(p["ms_per_step"] for p in per.values()) / min(p["ms_per_step"] for p in per.values())
        cpu_spread = (max(p["cpu_ms_per_step"] for p in per.values()) /
                      min(p["cpu_ms_per_step"] for p in per.values()))
        for t in targets:
            per[t]["max_over_min_ms_per_step"] = spread
            per[t]["max_over_min_cpu_ms_per_step"] = cpu_spread
            summary.append(per[t])
        print("%s: median ms/step %s; largest / smallest %.3f (CPU ms/step %s; %.3f)" % (
            label, ", ".join("%d tri: %.3f" % (t, per[t]["ms_per_step"]) for t in targets), spread,
            ", ".join("%.3f" % per[t]["cpu_ms_per_step"] for t in targets), cpu_spread))
    scols = ["executable", "target", "wall_triangles", "ms_per_step", "pair_ms_per_step", "cpu_ms_per_step",
             "triangle_pairs", "fallback_percent", "contacts", "max_over_min_ms_per_step",
             "max_over_min_cpu_ms_per_step"]
    with open(a.out + "_summary.csv", "w") as f:
        f.write(",".join(scols) + "\n")
        for s in summary:
            f.write(",".join(("%.6g" % s[c]) if isinstance(s[c], float) else str(s[c]) for c in scols) + "\n")
    plot(summary, a.out)
    print("wrote %s.csv, %s_summary.csv" % (a.out, a.out))


if __name__ == "__main__":
    main()
