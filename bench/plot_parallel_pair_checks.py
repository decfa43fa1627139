#!/usr/bin/python3
"""Plots bench/results/parallel_pair_checks.csv (written by bench_parallel_pair_checks).

Left: wall time per task-parallel pair-check sweep versus threads, one line per pack size, the
serial (no-TBB) sweep as a cross at 1 thread, the process CPU time per sweep dotted. Right: speed-up over 1 thread, with the
ideal line.

Usage: /usr/bin/python3 bench/plot_parallel_pair_checks.py [CSV] [PNG] [--note TEXT]
"""
import csv
import sys
import textwrap
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    args = [a for a in sys.argv[1:]]
    note = ""
    if "--note" in args:
        k = args.index("--note")
        note = args[k + 1]
        del args[k:k + 2]
    source = args[0] if args else "bench/results/parallel_pair_checks.csv"
    target = args[1] if len(args) > 1 else source.rsplit(".", 1)[0] + ".png"
    series = defaultdict(list)
    with open(source, newline="") as f:
        for row in csv.DictReader(f):
            series[int(row["particles"])].append(row)

    fig, (time_ax, speed_ax) = plt.subplots(1, 2, figsize=(11, 4.5))
    max_threads = 1
    for n, rows in sorted(series.items()):
        rows.sort(key=lambda r: int(r["threads"]))
        threads = [int(r["threads"]) for r in rows]
        max_threads = max(max_threads, max(threads))
        t = [float(r["median_seconds_per_sweep"]) for r in rows]
        label = "%d particles, %s triangles each" % (n, rows[0]["triangles_per_particle"])
        line, = time_ax.plot(threads, t, "o-", label=label)
        time_ax.plot([1], [float(rows[0]["serial_seconds_per_sweep"])], "x", color=line.get_color(),
                     label="%d particles, serial sweep (no tasks)" % n)
        if "cpu_seconds_per_sweep" in rows[0]:
            time_ax.plot(threads, [float(r["cpu_seconds_per_sweep"]) for r in rows], ":",
                         color=line.get_color(), label="%d particles, CPU time (all threads)" % n)
        s = [float(r["speedup_vs_1_thread"]) for r in rows]
        speed_ax.plot(threads, s, "o-", color=line.get_color(), label=label)
        for x, y in zip(threads, s):
            speed_ax.annotate("%.2fx" % y, (x, y), textcoords="offset points", xytext=(4, -12))
    time_ax.set_xlabel("threads")
    time_ax.set_ylabel("wall time per sweep [s] (median)")
    time_ax.set_yscale("log")
    time_ax.set_title("Pair-check sweep: traversal as task producer")
    time_ax.legend(fontsize=7, loc="best")
    speed_ax.plot([1, max_threads], [1, max_threads], "k--", lw=0.8, label="ideal")
    speed_ax.set_xlabel("threads")
    speed_ax.set_ylabel("speed-up over 1 thread")
    speed_ax.set_title("Speed-up (same run, medians)")
    speed_ax.legend(fontsize=8)
    for ax in (time_ax, speed_ax):
        ax.set_xticks(range(1, max_threads + 1))
        ax.grid(alpha=0.3)
    if note:
        fig.text(0.01, 0.01, textwrap.fill(note, 170), fontsize=7, alpha=0.8)
    fig.tight_layout(rect=(0, 0.07 if note else 0, 1, 1))
    fig.savefig(target, dpi=120)
    print("wrote", target)


if __name__ == "__main__":
    main()
