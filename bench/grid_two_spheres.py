#!/usr/bin/env python3
"""Paper §7.1 with the three grids of `fix spacetree`: two spheres (d 0.02 and 0.2) on collision
course in the unit cube (inputs/paper71/in.two_spheres_grid, dt 1e-4, 40 000 steps, list and grid
rebuilt every step). Per step: pair comparisons (candidate pairs of the sweep), cells of all
levels, leaf cells, deepest level, grid-update time; per run: loop wall time (median of
--repeats runs per grid, alternating, with thermo output only at the start and the end).

  /usr/bin/python3 bench/grid_two_spheres.py [--exe build/liggghts-spacetree] [--repeats 3]

Writes bench/results/grid_two_spheres.csv (every 20th step plus every step with comparisons,
refinements or coarsenings), grid_two_spheres_summary.csv and grid_two_spheres.png (--replot:
only the PNG, from the stored CSVs).
"""
import argparse
import os
import re
import statistics
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DECK = os.path.join(ROOT, "inputs", "paper71", "in.two_spheres_grid")
GRIDS = ["regular", "adaptive", "reluctant"]
COLS = ["step", "time", "comparisons", "refinements", "coarsenings", "deepest", "cells", "leaf_cells",
        "update_s", "distance"]


def run(exe, work, grid, tag, steps, every=1):
    log = os.path.join(work, "log." + tag)
    p = subprocess.run([exe, "-in", DECK, "-log", log, "-echo", "none", "-var", "grid", grid,
                        "-var", "nsteps", str(steps), "-var", "every", str(every)],
                       cwd=work, stdout=subprocess.DEVNULL, stderr=subprocess.STDOUT)
    text = open(log).read()
    if p.returncode != 0:
        raise SystemExit("run %s failed, see %s" % (tag, log))
    loop = float(re.search(r"Loop time of (\S+)", text).group(1))
    rows, on = [], False
    for l in text.splitlines():
        if l.split()[:1] == ["Step"]:
            on = True
            continue
        if on:
            v = l.split()
            if l.startswith("Loop time") or len(v) != len(COLS):
                on = False
                continue
            rows.append([float(x) for x in v])
    return loop, rows


def plot(results):
    """Draws grid_two_spheres.png from the CSV and the summary in `results`."""
    import csv
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    data = {g: [] for g in GRIDS}
    for row in csv.DictReader(open(os.path.join(results, "grid_two_spheres.csv"))):
        data[row["grid"]].append([float(row[c]) for c in COLS])
    s = {row["grid"]: row for row in csv.DictReader(open(os.path.join(results, "grid_two_spheres_summary.csv")))}
    steps = int(max(r[0] for g in GRIDS for r in data[g]))
    repeats = len(s["regular"]["loop_s_runs"].split())
    fig, ax = plt.subplots(1, 3, figsize=(15, 4.2))
    colours = {"regular": "tab:blue", "adaptive": "tab:orange", "reluctant": "tab:green"}
    for g in GRIDS:
        t = [r[1] for r in data[g]]
        ax[0].plot(t, [r[2] for r in data[g]], drawstyle="steps-post", color=colours[g], label=g,
                   lw=1.5 if g != "regular" else 3, alpha=0.8)
        ax[1].semilogy(t, [r[6] for r in data[g]], color=colours[g], label=g)
    start, end = float(s["regular"]["contact_start_time"]), float(s["regular"]["contact_end_time"])
    if start == start:
        for k in (0, 1):
            ax[k].axvspan(start, end, color="grey", alpha=0.3, label="spheres touch" if k == 0 else None)
    ax[0].set_xlabel("simulated time (s)")
    ax[0].set_ylabel("pair comparisons per step")
    top = max(r[2] for g in GRIDS for r in data[g])
    ax[0].set_ylim(-0.05 * top, 1.6 * top)
    ax[0].set_title("comparisons in all: " + ", ".join("%s %d" % (g, float(s[g]["total_comparisons"])) for g in GRIDS),
                    fontsize=9)
    ax[0].legend(loc="upper left", ncol=2, fontsize=8)
    ax[1].set_xlabel("simulated time (s)")
    ax[1].set_ylabel("grid cells (all levels)")
    ax[1].set_title("mean cells: " + ", ".join("%s %.0f" % (g, float(s[g]["mean_cells"])) for g in GRIDS), fontsize=9)
    ax[1].legend()
    loops = [float(s[g]["loop_s"]) for g in GRIDS]
    ax[2].bar(GRIDS, loops, color=[colours[g] for g in GRIDS])
    for i, v in enumerate(loops):
        ax[2].text(i, v, "%.3f s" % v, ha="center", va="bottom", fontsize=9)
    ax[2].set_ylabel("wall time of %d steps (s, median of %d)" % (steps, repeats))
    ax[2].set_title("loop time, 1 rank", fontsize=9)
    fig.suptitle("paper §7.1: two spheres (d 0.02 / 0.2) collide, 1 rank")
    fig.tight_layout()
    fig.savefig(os.path.join(results, "grid_two_spheres.png"), dpi=120)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "liggghts-spacetree"))
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--steps", type=int, default=40000)
    ap.add_argument("--results", default=os.path.join(ROOT, "bench", "results"))
    ap.add_argument("--replot", action="store_true", help="only redraw the PNG from the stored CSVs")
    a = ap.parse_args()
    if a.replot:
        plot(a.results)
        return 0
    work = os.path.join(ROOT, "build", "bench_grid_two_spheres")
    os.makedirs(work, exist_ok=True)
    os.makedirs(a.results, exist_ok=True)
    loops = {g: [] for g in GRIDS}
    data = {}
    for g in GRIDS:  # statistics every step (their output costs time: timed separately)
        loop, data[g] = run(a.exe, work, g, "%s_stats" % g, a.steps)
    for rep in range(a.repeats):  # timing: thermo only at the start and the end
        for g in GRIDS:
            loop, _ = run(a.exe, work, g, "%s_%d" % (g, rep), a.steps, every=a.steps)
            loops[g].append(loop)
            print("%-9s rep %d: loop %.3f s" % (g, rep, loop), flush=True)

    with open(os.path.join(a.results, "grid_two_spheres.csv"), "w") as f:
        f.write("grid," + ",".join(COLS) + "\n")
        for g in GRIDS:
            for i, r in enumerate(data[g]):
                if i % 20 == 0 or r[2] > 0 or r[3] > 0 or r[4] > 0:
                    f.write(g + "," + ",".join("%.10g" % x for x in r) + "\n")
    summary = []
    for g in GRIDS:
        rows = data[g][1:]
        comp = [r[2] for r in rows]
        active = [r for r in rows if r[2] > 0]
        contact = [r for r in rows if r[9] <= 0.11]  # centre distance <= sum of radii
        s = dict(grid=g, loop_s=statistics.median(loops[g]), loop_s_runs=" ".join("%.3f" % x for x in loops[g]),
                 total_comparisons=sum(comp), max_comparisons=max(comp), steps_with_comparisons=len(active),
                 first_comparison_time=active[0][1] if active else float("nan"),
                 contact_start_time=contact[0][1] if contact else float("nan"),
                 contact_end_time=contact[-1][1] if contact else float("nan"),
                 mean_cells=statistics.mean(r[6] for r in rows), max_cells=max(r[6] for r in rows),
                 mean_leaf_cells=statistics.mean(r[7] for r in rows),
                 max_deepest_level=max(r[5] for r in rows),
                 refinements=sum(r[3] for r in rows), coarsenings=sum(r[4] for r in rows),
                 mean_update_us=1e6 * statistics.mean(r[8] for r in rows))
        summary.append(s)
    keys = list(summary[0].keys())
    with open(os.path.join(a.results, "grid_two_spheres_summary.csv"), "w") as f:
        f.write(",".join(keys) + "\n")
        for s in summary:
            f.write(",".join(str(s[k]) for k in keys) + "\n")
    for s in summary:
        print("%-9s loop %.3f s (runs %s), comparisons total %d max %d on %d steps (first at t=%.3f s), "
              "contact t=%.4f..%.4f s, cells mean %.4g max %.4g, leaves mean %.4g, deepest %d, "
              "refinements %d, coarsenings %d, grid update %.2f us/step"
              % (s["grid"], s["loop_s"], s["loop_s_runs"], s["total_comparisons"], s["max_comparisons"],
                 s["steps_with_comparisons"], s["first_comparison_time"], s["contact_start_time"],
                 s["contact_end_time"], s["mean_cells"], s["max_cells"], s["mean_leaf_cells"],
                 s["max_deepest_level"], s["refinements"], s["coarsenings"], s["mean_update_us"]))

    plot(a.results)
    print("wrote %s" % os.path.join(a.results, "grid_two_spheres.{csv,png}"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
