#!/usr/bin/python3
"""Plots bench/results/triangle_distance.csv (written by bench_triangle_distance).

Left: triangle-pair checks per second on one core versus triangles per particle, for the
exact, penalty and hybrid methods. Right: the hybrid's speed-up over the exact method and the
fraction of pairs it hands to the exact method.

Usage: /usr/bin/python3 bench/plot_triangle_distance.py [CSV] [PNG] [PIPELINE_CSV]
       /usr/bin/python3 bench/plot_triangle_distance.py --median OUT.csv RUN1.csv RUN2.csv ...

If bench/results/mesh_contact.csv (the contact-pipeline part of the benchmark) exists, it is
plotted too, into mesh_contact.png next to it: microseconds per particle pair per method; so is
triangle_distance_replay.csv (--replay-out: the same scenes repeated in a row vs interleaved),
into triangle_distance_replay.png.

--median merges runs of the benchmark (any of its three CSVs) row by row: the median of the
timings and of the per-run speed-ups (side-by-side ratios within a run), "yes" in
decisions_equal_exact only if every run says yes, and a column "runs".
"""
import os
import csv
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


# Columns that vary between runs (timings and the ratios computed from them).
TIMED = ("ns_per_pair", "pairs_per_second", "speedup_vs_exact", "us_per_particle_pair",
         "time_over_repeated")


def median(values):
    values = sorted(values)
    n = len(values)
    return values[n // 2] if n % 2 else 0.5 * (values[n // 2 - 1] + values[n // 2])


def merge_runs(out, sources):
    runs = []
    for source in sources:
        with open(source, newline="") as f:
            reader = csv.DictReader(f)
            fields = reader.fieldnames
            runs.append(list(reader))
    if any(len(r) != len(runs[0]) for r in runs):
        sys.exit("runs have different row counts")
    merged = []
    for rows in zip(*runs):
        row = dict(rows[0])
        for name in fields:
            if name in TIMED:
                row[name] = f"{median([float(r[name]) for r in rows]):.6g}"
            elif name == "decisions_equal_exact":
                row[name] = "yes" if all(r[name] == "yes" for r in rows) else "no"
            elif any(r[name] != row[name] for r in rows):
                sys.exit(f"column {name} differs between runs: {[r[name] for r in rows]}")
        if "pairs_per_second" in row:  # consistent with the median time
            row["pairs_per_second"] = f"{1e9 / float(row['ns_per_pair']):.6g}"
        row["runs"] = str(len(rows))
        merged.append(row)
    with open(out, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=[n for n in fields if n != "runs"] + ["runs"])
        writer.writeheader()
        writer.writerows(merged)
    print(f"wrote {out} (median of {len(runs)} runs)")


def series_style(method, iterations, styles):
    """Colour, marker, line style, step schedule ("5" or "5+4") and legend label of a series
    (method, Newton steps); "hybrid2+C" is the two-stage hybrid with C stage-2 steps."""
    color, marker = styles.get(method, ("gray", "x"))
    dashes = {0: "-", 8: "-", 6: ":", 4: "--"}.get(iterations, "-.")
    if method.startswith("hybrid2+"):
        steps = f"{iterations}+{method[len('hybrid2+'):]}"
        label = f"two-stage hybrid, {steps} Newton steps"
    else:
        steps = str(iterations)
        label = method if method == "exact" else f"{method}, {iterations} Newton steps"
    return color, marker, dashes, steps, label


def main():
    if len(sys.argv) > 2 and sys.argv[1] == "--median":
        merge_runs(sys.argv[2], sys.argv[3:])
        return
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

    # Three panels sharing one legend below them (a series has the same colour, marker and
    # line style in every panel), so no legend covers a curve.
    fig, (speed, hybrid, fallback) = plt.subplots(1, 3, figsize=(15, 5.6))
    styles = {"exact": ("k", "o"), "penalty": ("tab:blue", "s"), "hybrid": ("tab:red", "^")}
    # Two-stage hybrids ("hybrid2+C": C stage-2 steps after the row's stage-1 steps).
    for method, _ in series:
        if method.startswith("hybrid2"):
            styles[method] = ("tab:purple", "v")
    for (method, iterations), rows in sorted(series.items()):
        rows.sort(key=lambda r: int(r["triangles_per_particle"]))
        color, marker, dashes, steps, label = series_style(method, iterations, styles)
        x = column(rows, "triangles_per_particle")
        speed.plot(x, column(rows, "pairs_per_second"), dashes, color=color, marker=marker,
                   label=label)
        if method.startswith("hybrid"):
            hybrid.plot(x, column(rows, "speedup_vs_exact"), dashes, color=color, marker=marker)
            fallback.plot(x, [100 * v for v in column(rows, "fallback_fraction")], dashes,
                          color=color, marker=marker)

    for ax in (speed, hybrid, fallback):
        ax.set_xscale("log")
        ax.set_xlabel("triangles per particle")
        ax.grid(True, which="both", alpha=0.3)
    speed.set_yscale("log")
    speed.set_ylabel("triangle-pair checks per second (one core)")
    speed.set_title("Throughput: two spheres at contact distance,\nall triangle pairs "
                    "(>= 16384 distinct pairs per pass, median of 5 rounds)", fontsize=9)
    hybrid.axhline(4.0, color="gray", lw=0.8, ls=":")
    hybrid.set_ylabel("hybrid speed-up over exact (same run)")
    hybrid.set_title(f"Hybrid speed-up over exact (ISA: {', '.join(sorted(isa))});\n"
                     "dotted line: 4x", fontsize=9)
    fallback.set_yscale("log")
    fallback.set_ylabel("pairs falling back to exact [%]")
    fallback.set_title("Hybrid: pairs left uncertified (exact fallback)", fontsize=9)
    lines, labels = speed.get_legend_handles_labels()
    fig.legend(lines, labels, loc="lower center", ncol=4, fontsize=8, frameon=False)
    fig.tight_layout(rect=(0, 0.14, 1, 1))
    fig.savefig(target, dpi=120)
    print(f"wrote {target}")

    pipeline = sys.argv[3] if len(sys.argv) > 3 else os.path.join(os.path.dirname(source), "mesh_contact.csv")
    if os.path.exists(pipeline):
        plot_pipeline(pipeline, styles)
    replay = os.path.join(os.path.dirname(source), "triangle_distance_replay.csv")
    if os.path.exists(replay):
        plot_replay(replay, styles)


def plot_replay(source, styles):
    """ns per pair versus the distinct pairs one pass replays: "repeated" (one scene in a row)
    is the leftmost point of each line, then 4, 16, ... scenes interleaved."""
    series = defaultdict(list)
    with open(source, newline="") as f:
        for row in csv.DictReader(f):
            series[(int(row["triangles_per_particle"]), row["method"], int(row["newton_iterations"]))].append(row)
    counts = sorted({k[0] for k in series})
    fig, axes = plt.subplots(1, len(counts), figsize=(4.5 * len(counts), 4.5), squeeze=False)
    for ax, count in zip(axes[0], counts):
        for (tri, method, iterations), rows in sorted(series.items()):
            if tri != count:
                continue
            rows.sort(key=lambda r: int(r["distinct_pairs_per_pass"]))
            color, marker, _, _, label = series_style(method, iterations, styles)
            ax.plot([int(r["distinct_pairs_per_pass"]) for r in rows],
                    [float(r["ns_per_pair"]) for r in rows], "-", color=color, marker=marker,
                    label=label)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("distinct triangle pairs per pass")
        ax.set_ylabel("ns per triangle pair (one core)")
        ax.set_title(f"{count} triangles per particle")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle("Same scenes: leftmost point one scene repeated in a row, then 4, 16, ... "
                 "scenes interleaved", fontsize=10)
    fig.tight_layout()
    target = source.rsplit(".", 1)[0] + ".png"
    fig.savefig(target, dpi=120)
    print(f"wrote {target}")


def plot_pipeline(source, styles):
    series = defaultdict(list)
    with open(source, newline="") as f:
        for row in csv.DictReader(f):
            series[(row["method"], int(row["newton_iterations"]))].append(row)
    fig, (cost, ratio) = plt.subplots(1, 2, figsize=(12, 5.6))
    for (method, iterations), rows in sorted(series.items()):
        rows.sort(key=lambda r: int(r["triangles_per_particle"]))
        color, marker, dashes, steps, label = series_style(method, iterations, styles)
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
    cost.set_yscale("log")
    cost.set_ylabel("microseconds per particle pair (one core)")
    cost.set_title("Contact search (prechecks, pruning, method, merging)")
    ratio.axhline(4.0, color="gray", lw=0.8, ls=":")
    ratio.set_ylabel("speed-up over exact")
    ratio.set_title("Whole contact search: speed-up over the exact method")
    # one legend below both panels (same style per series in each), so none covers a curve
    lines, labels = cost.get_legend_handles_labels()
    fig.legend(lines, labels, loc="lower center", ncol=3, fontsize=8, frameon=False)
    fig.tight_layout(rect=(0, 0.15, 1, 1))
    target = source.rsplit(".", 1)[0] + ".png"
    fig.savefig(target, dpi=120)
    print(f"wrote {target}")


if __name__ == "__main__":
    main()
