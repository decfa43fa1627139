#!/usr/bin/env python3
"""Clustered and sparse polydisperse scenes: time per step and cell count of `neighbor spacetree`
on the regular / adaptive / reluctant grids of `fix spacetree`, and of stock `neighbor bin`.

  /usr/bin/python3 bench/grid_scenes.py [--exe build/liggghts-spacetree] [--steps 40] [--repeats 3]

Scenes (generated here, seeded, between walls, random velocities, lists rebuilt every step):
  clustered  NSMALL small spheres (d log-uniform 0.5..2 mm) packed loosely into one corner
             (a cube of ~3 cm) of a 0.3 m box, plus 3 big spheres (d 20 mm) elsewhere
  sparse     8 big spheres (d 40 mm) in a dilute cloud of NSMALL small ones (d 0.5..2 mm)
             filling a 0.25 m box (solid fraction ~ 1e-3)
Each configuration runs `--repeats` times, alternating; the CSV keeps every run, the summary
and the plot use medians (ratio_to_regular: median over repeats of the ratio within a repeat).
ms_per_step excludes LIGGGHTS' thermo output time (compute treestats counts vertices on
request, a diagnostic); loop_ms_per_step keeps it. Writes bench/results/<name>.csv,
<name>_summary.csv and <name>.png (--name, default grid_scenes).
"""
import argparse
import math
import os
import random
import re
import statistics
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DECK = os.path.join(ROOT, "inputs", "bench", "in.grid_bench")
CONFIGS = [("bin", None), ("spacetree", "regular"), ("spacetree", "adaptive"), ("spacetree", "reluctant")]


def place(rng, n, dmin, dmax, lo, hi, fixed, maxtry=200):
    """Random sequential placement without overlap (log-uniform diameters) in the box [lo, hi]^3;
    `fixed` spheres (d, x, y, z) are avoided too. Cell grid of the largest small diameter."""
    cell = dmax * 1.01
    grid = {}
    out = []

    def key(p):
        return tuple(int(math.floor(c / cell)) for c in p)

    def free(p, d):
        for (D, x, y, z) in fixed:
            if (p[0] - x) ** 2 + (p[1] - y) ** 2 + (p[2] - z) ** 2 < (0.5 * (D + d)) ** 2:
                return False
        k = key(p)
        for a in (-1, 0, 1):
            for b in (-1, 0, 1):
                for c in (-1, 0, 1):
                    for (q, e) in grid.get((k[0] + a, k[1] + b, k[2] + c), ()):
                        if sum((p[m] - q[m]) ** 2 for m in range(3)) < (0.5 * (d + e)) ** 2:
                            return False
        return True

    for _ in range(n):
        d = math.exp(rng.uniform(math.log(dmin), math.log(dmax)))
        for _t in range(maxtry):
            p = [rng.uniform(lo[m] + 0.5 * d, hi[m] - 0.5 * d) for m in range(3)]
            if free(p, d):
                grid.setdefault(key(p), []).append((p, d))
                out.append((d, p[0], p[1], p[2]))
                break
    return out


def scene(name, nsmall, seed):
    rng = random.Random(seed)
    if name == "clustered":
        L = 0.3
        bigs = [(0.02, 0.2, 0.15, 0.25), (0.02, 0.25, 0.25, 0.1), (0.02, 0.1, 0.25, 0.2)]
        # cube side for a solid fraction ~0.25 of the small ones (mean volume of log-uniform d)
        mean_v = math.pi / 6 * (2e-3 ** 3 - 0.5e-3 ** 3) / (3 * math.log(4.0))
        side = (nsmall * mean_v / 0.25) ** (1.0 / 3.0)
        small = place(rng, nsmall, 0.5e-3, 2e-3, [0.002] * 3, [0.002 + side] * 3, bigs)
    else:
        L = 0.25
        bigs = []
        for i in range(8):
            c = [0.0625 + 0.125 * ((i >> k) & 1) + rng.uniform(-0.02, 0.02) for k in range(3)]
            bigs.append((0.04, c[0], c[1], c[2]))
        small = place(rng, nsmall, 0.5e-3, 2e-3, [0.0] * 3, [L] * 3, bigs)
    spheres = bigs + small
    vel = [[rng.uniform(-0.5, 0.5) for _ in range(3)] for _ in spheres]
    return L, spheres, vel


def write_data(path, L, spheres, vel):
    with open(path, "w") as f:
        f.write("LIGGGHTS data file written by bench/grid_scenes.py\n\n%d atoms\n1 atom types\n\n" % len(spheres))
        for a in ("x", "y", "z"):
            f.write("0 %r %slo %shi\n" % (L, a, a))
        f.write("\nAtoms\n\n")
        for i, (d, x, y, z) in enumerate(spheres):
            f.write("%d 1 %r 2500 %r %r %r\n" % (i + 1, d, x, y, z))
        f.write("\nVelocities\n\n")
        for i, v in enumerate(vel):
            f.write("%d %r %r %r 0 0 0\n" % (i + 1, v[0], v[1], v[2]))


def run(exe, work, data, nstyle, grid, steps, tag):
    log = os.path.join(work, "log." + tag)
    cmd = [exe, "-in", DECK, "-log", log, "-echo", "none", "-var", "data", data, "-var", "nstyle", nstyle,
           "-var", "nsteps", str(steps)]
    if grid:
        cmd += ["-var", "usegrid", "1", "-var", "grid", grid]
    p = subprocess.run(cmd, cwd=work, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, errors="replace")
    text = open(log).read() if os.path.exists(log) else p.stdout
    if p.returncode != 0:
        raise SystemExit("run %s failed:\n%s" % (tag, p.stdout[-3000:]))
    loop = float(re.search(r"Loop time of (\S+)", text).group(1))
    neigh = re.search(r"Neigh\s+time \(%\) = (\S+)", text)
    neigh = float(neigh.group(1)) if neigh else float("nan")
    outpt = re.search(r"Outpt\s+time \(%\) = (\S+)", text)
    outpt = float(outpt.group(1)) if outpt else 0.0
    nb = re.search(r"Total # of neighbors = (\S+)", text)
    # ms_per_step excludes the thermo output: compute treestats counts the grid's vertices on
    # request (up to 64 look-ups per refined cell), a diagnostic, not a cost of the grid.
    res = dict(ms_per_step=1e3 * (loop - outpt) / steps, loop_ms_per_step=1e3 * loop / steps,
               output_ms_per_step=1e3 * outpt / steps, neigh_ms_per_step=1e3 * neigh / steps,
               neighbors=int(float(nb.group(1))) if nb else -1, cells=float("nan"), leaf_cells=float("nan"),
               comparisons=float("nan"), update_ms=float("nan"))
    if grid:
        rows = []
        lines = text.splitlines()
        for i, l in enumerate(lines):
            if l.split()[:1] == ["Step"]:
                for m in lines[i + 1:]:
                    v = m.split()
                    if m.startswith("Loop time") or len(v) != 8:
                        break
                    rows.append([float(x) for x in v])
        rows = rows[1:] or rows  # skip the setup row when there are others
        res["comparisons"] = statistics.median(r[3] for r in rows)
        res["cells"] = statistics.median(r[4] for r in rows)
        res["leaf_cells"] = statistics.median(r[5] for r in rows)
        res["update_ms"] = 1e3 * statistics.median(r[7] for r in rows)
    return res


def plot(results, name):
    """Draws <name>.png from <name>.csv and <name>_summary.csv: time per step, the ratio to the
    regular grid per repeat (the figure the docs quote) and the grid cells."""
    import csv
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    rows = list(csv.DictReader(open(os.path.join(results, name + ".csv"))))
    summary = list(csv.DictReader(open(os.path.join(results, name + "_summary.csv"))))
    scenes = list(dict.fromkeys(r["scene"] for r in rows))
    labels = [g or "bin" for _, g in CONFIGS]
    value = lambda sc, lab, k: float(next(m for m in summary if m["scene"] == sc and m["config"] == lab)[k])
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.6))
    width = 0.8 / len(scenes)
    colours = ["tab:blue", "tab:orange", "tab:green", "tab:red"]
    for k, sc in enumerate(scenes):
        shift = (k - 0.5 * (len(scenes) - 1)) * width
        xs = [i + shift for i in range(len(labels))]
        axes[0].bar(xs, [value(sc, lab, "ms_per_step") for lab in labels], width, label=sc,
                    color=colours[k])
        axes[2].bar(xs[1:], [value(sc, lab, "cells") for lab in labels[1:]], width, label=sc,
                    color=colours[k])
        # ratio to regular within each repeat (side by side in one round), every repeat drawn
        for i, lab in enumerate(labels[2:], start=2):
            ratios = []
            for r in rows:
                if r["scene"] != sc or r["config"] != lab:
                    continue
                reg = next(q for q in rows if q["scene"] == sc and q["config"] == "regular"
                           and q["repeat"] == r["repeat"])
                ratios.append(float(r["ms_per_step"]) / float(reg["ms_per_step"]))
            axes[1].scatter([i - 2 + shift] * len(ratios), ratios, s=14, color=colours[k], alpha=0.6,
                            label=sc if i == 2 else None)
            axes[1].plot([i - 2 + shift - 0.35 * width, i - 2 + shift + 0.35 * width],
                         [value(sc, lab, "ratio_to_regular")] * 2, color="k", lw=2)
    axes[0].set_xticks(range(len(labels)))
    axes[0].set_xticklabels(labels)
    axes[0].set_yscale("log")
    axes[0].set_ylabel("ms per step (median over repeats, no thermo)")
    axes[0].set_title("time per step")
    axes[1].axhline(1.0, color="gray", lw=0.8, ls=":")
    axes[1].set_xticks(range(len(labels) - 2))
    axes[1].set_xticklabels(labels[2:])
    axes[1].set_ylabel("time per step / regular grid's (same repeat)")
    axes[1].set_title("ratio to the regular grid (dots: repeats, bar: median)")
    axes[2].set_xticks(range(1, len(labels)))
    axes[2].set_xticklabels(labels[1:])
    axes[2].set_yscale("log")
    axes[2].set_ylabel("grid cells (all levels, median per step)")
    axes[2].set_title("grid cells")
    for ax in axes:
        ax.legend(fontsize=8)
        ax.grid(True, axis="y", which="both", alpha=0.3)
    nsmall = max(int(r["atoms"]) for r in rows)
    fig.suptitle("clustered and sparse polydisperse scenes (up to %d spheres), 1 rank, lists rebuilt "
                 "every step" % nsmall)
    fig.tight_layout()
    fig.savefig(os.path.join(results, name + ".png"), dpi=120)
    print("wrote %s" % os.path.join(results, name + ".{csv,png}"))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "liggghts-spacetree"))
    ap.add_argument("--steps", type=int, default=40)
    ap.add_argument("--bin-steps", type=int, default=10, help="bin is slow on these scenes")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--nsmall", type=int, default=20000)
    ap.add_argument("--scenes", nargs="+", default=["clustered", "sparse"])
    ap.add_argument("--results", default=os.path.join(ROOT, "bench", "results"))
    ap.add_argument("--name", default="grid_scenes", help="file name stem of the results")
    ap.add_argument("--replot", action="store_true", help="only redraw <name>.png from the stored CSVs")
    a = ap.parse_args()
    if a.replot:
        plot(a.results, a.name)
        return 0
    work = os.path.join(ROOT, "build", "bench_" + a.name)
    os.makedirs(work, exist_ok=True)
    os.makedirs(a.results, exist_ok=True)
    rows = []
    for sc in a.scenes:
        L, spheres, vel = scene(sc, a.nsmall, 1234)
        data = os.path.join(work, sc + ".data")
        write_data(data, L, spheres, vel)
        print("scene %s: %d spheres in a %.2f m box" % (sc, len(spheres), L), flush=True)
        for rep in range(a.repeats):
            for nstyle, grid in CONFIGS:
                label = grid or nstyle
                steps = a.bin_steps if nstyle == "bin" else a.steps
                r = run(a.exe, work, data, nstyle, grid, steps, "%s_%s_%d" % (sc, label, rep))
                r.update(scene=sc, config=label, repeat=rep, atoms=len(spheres), steps=steps)
                rows.append(r)
                print("  %-9s rep %d: %8.2f ms/step (neigh %8.2f), cells %.4g, comparisons %.4g, grid update %.3g ms"
                      % (label, rep, r["ms_per_step"], r["neigh_ms_per_step"], r["cells"], r["comparisons"],
                         r["update_ms"]), flush=True)
    keys = ["scene", "config", "repeat", "atoms", "steps", "ms_per_step", "neigh_ms_per_step", "loop_ms_per_step",
            "output_ms_per_step", "cells", "leaf_cells", "comparisons", "update_ms", "neighbors"]
    with open(os.path.join(a.results, a.name + ".csv"), "w") as f:
        f.write(",".join(keys) + "\n")
        for r in rows:
            f.write(",".join(str(r[k]) for k in keys) + "\n")
    summary = []
    for sc in a.scenes:
        for _, grid in CONFIGS:
            label = grid or "bin"
            rs = [r for r in rows if r["scene"] == sc and r["config"] == label]
            med = {k: statistics.median(r[k] for r in rs) for k in ("ms_per_step", "neigh_ms_per_step",
                                                                     "loop_ms_per_step", "output_ms_per_step", "cells",
                                                                     "leaf_cells", "comparisons", "update_ms")}
            med.update(scene=sc, config=label, atoms=rs[0]["atoms"], neighbors=rs[0]["neighbors"])
            summary.append(med)
        # Ratios to the regular grid, per repeat (side by side in one round), then the median.
        for m in summary[-len(CONFIGS):]:
            ratios = []
            for rep in range(a.repeats):
                mine = [r for r in rows if r["scene"] == sc and r["config"] == m["config"] and r["repeat"] == rep]
                reg = [r for r in rows if r["scene"] == sc and r["config"] == "regular" and r["repeat"] == rep]
                if mine and reg:
                    ratios.append(mine[0]["ms_per_step"] / reg[0]["ms_per_step"])
            m["ratio_to_regular"] = statistics.median(ratios) if ratios else float("nan")
    skeys = ["scene", "config", "atoms", "ms_per_step", "ratio_to_regular", "neigh_ms_per_step", "loop_ms_per_step",
             "output_ms_per_step", "cells", "leaf_cells", "comparisons", "update_ms", "neighbors"]
    with open(os.path.join(a.results, a.name + "_summary.csv"), "w") as f:
        f.write(",".join(skeys) + "\n")
        for m in summary:
            f.write(",".join(str(m[k]) for k in skeys) + "\n")
    print("\nmedians over %d repeats:" % a.repeats)
    for m in summary:
        print("  %-9s %-9s %8.2f ms/step (x%.3f of regular)  neigh %8.2f ms/step  cells %10.4g  comparisons %10.4g"
              "  update %7.3g ms" % (m["scene"], m["config"], m["ms_per_step"], m["ratio_to_regular"],
                                     m["neigh_ms_per_step"], m["cells"], m["comparisons"], m["update_ms"]))

    plot(a.results, a.name)
    return 0


if __name__ == "__main__":
    sys.exit(main())
