#!/usr/bin/python3
"""Plots bench/results/triangle_distance.csv (written by bench_triangle_distance).

Left: triangle-pair checks per second on one core versus triangles per particle, for the
exact, penalty and hybrid methods. Right: the hybrid's speed-up over the exact method and the
fraction of pairs it hands to the exact method.

Usage: /usr/bin/python3 bench/plot_triangle_distance.py [CSV] [PNG] [PIPELINE_CSV]

If bench/results/mesh_contact.csv (the contact-pipeline part of the benchmark) exists, it is
plotted too, into mesh_contact.png next to it: microseconds per particle pair per method.
"""
import os
import csv
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    source = sys.argv[1] if len(sys.argv) > 1 else "bench/results/triangle_distance.csv"
    target = sys.argv[2] if len(sys.argv) > 2 else source.rsplit(".", 1)[0] + ".png"
    series = defaultdict(list)  # (method, iterations) -> rows
    isa = set()
    with open(source, newline="") as f:
        for row in csv.DictReader(f):
            series[(row["method"], int(row["newton_iterations"]))].append(row)
            isa.add(row["isa"])

    def column(rows, name):
        return [float(r[name]) for r in rows]

    fig, (speed, hybrid) = plt.subplots(1, 2, figsize=(12, 4.8))
    fallback = hybrid.twinx()
    styles = {"exact": ("k", "o"), "penalty": ("tab:blue", "s"), "hybrid": ("tab:red", "^")}
    # Two-stage hybrids ("hybrid2+C": C stage-2 steps after the row's stage-1 steps).
    for method, _ in series:
        if method.startswith("hybrid2"):
            styles[method] = ("tab:purple", "v")
    for (method, iterations), rows in sorted(series.items()):
        rows.sort(key=lambda r: int(r["triangles_per_particle"]))
        color, marker = styles.get(method, ("gray", "x"))
        if method.startswith("hybrid2+"):
            steps = f"{iterations}+{method[len('hybrid2+'):]}"
            label = f"two-stage hybrid, {steps} Newton steps"
        else:
            steps = str(iterations)
            label = method if method == "exact" else f"{method}, {iterations} Newton steps"
        dashes = {0: "-", 8: "-", 6: ":", 4: "--"}.get(iterations, "-.")
        speed.plot(column(rows, "triangles_per_particle"), column(rows, "pairs_per_second"),
                   dashes, color=color, marker=marker, label=label)
        if method.startswith("hybrid"):
            hybrid.plot(column(rows, "triangles_per_particle"), column(rows, "speedup_vs_exact"),
                        dashes, color=color, marker=marker,
                        label=f"speed-up over exact, {steps} steps")
            fallback.plot(column(rows, "triangles_per_particle"),
                          [100 * v for v in column(rows, "fallback_fraction")], dashes,
                          color="tab:green", marker=marker, alpha=0.8,
                          label=f"fallback, {steps} steps")

    speed.set_xscale("log")
    speed.set_yscale("log")
    speed.set_xlabel("triangles per particle")
    speed.set_ylabel("triangle-pair checks per second (one core)")
    speed.set_title("Two spheres at contact distance, all triangle pairs (median of 5 rounds)")
    speed.grid(True, which="both", alpha=0.3)
    speed.legend(fontsize=8)

    hybrid.set_xscale("log")
    hybrid.axhline(4.0, color="gray", lw=0.8, ls=":")
    hybrid.set_xlabel("triangles per particle")
    hybrid.set_ylabel("hybrid speed-up over exact")
    hybrid.set_title(f"Hybrid (ISA: {', '.join(sorted(isa))})")
    hybrid.grid(True, which="both", alpha=0.3)
    fallback.set_ylabel("pairs falling back to exact [%]", color="tab:green")
    fallback.set_yscale("log")
    lines, labels = hybrid.get_legend_handles_labels()
    more_lines, more_labels = fallback.get_legend_handles_labels()
    hybrid.legend(lines + more_lines, labels + more_labels, fontsize=8, loc="center right")

    fig.tight_layout()
    fig.savefig(target, dpi=120)
    print(f"wrote {target}")

    pipeline = sys.argv[3] if len(sys.argv) > 3 else os.path.join(os.path.dirname(source), "mesh_contact.csv")
    if os.path.exists(pipeline):
        plot_pipeline(pipeline, styles)


def plot_pipeline(source, styles):
    series = defaultdict(list)
    with open(source, newline="") as f:
        for row in csv.DictReader(f):
            series[(row["method"], int(row["newton_iterations"]))].append(row)
    fig, (cost, ratio) = plt.subplots(1, 2, figsize=(12, 4.8))
    for (method, iterations), rows in sorted(series.items()):
        rows.sort(key=lambda r: int(r["triangles_per_particle"]))
        color, marker = styles.get(method, ("gray", "x"))
        dashes = {0: "-", 8: "-", 6: ":", 4: "--"}.get(iterations, "-.")
        if method.startswith("hybrid2+"):
            steps = f"{iterations}+{method[len('hybrid2+'):]}"
            label = f"two-stage hybrid, {steps} Newton steps"
        else:
            steps = str(iterations)
            label = method if method == "exact" else f"{method}, {iterations} Newton steps"
        x = [int(r["triangles_per_particle"]) for r in rows]
        cost.plot(x, [float(r["us_per_particle_pair"]) for r in rows], dashes, color=color,
                  marker=marker, label=label)
        if method != "exact":
            ratio.plot(x, [float(r["speedup_vs_exact"]) for r in rows], dashes, color=color,
                       marker=marker, label=label)
    for ax in (cost, ratio):
        ax.set_xscale("log")
        ax.set_xlabel("triangles per particle")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    cost.set_yscale("log")
    cost.set_ylabel("microseconds per particle pair (one core)")
    cost.set_title("Contact search (prechecks, pruning, method, merging)")
    ratio.axhline(4.0, color="gray", lw=0.8, ls=":")
    ratio.set_ylabel("speed-up over exact")
    ratio.set_title("Whole contact search: speed-up over the exact method")
    fig.tight_layout()
    target = source.rsplit(".", 1)[0] + ".png"
    fig.savefig(target, dpi=120)
    print(f"wrote {target}")


if __name__ == "__main__":
    main()
