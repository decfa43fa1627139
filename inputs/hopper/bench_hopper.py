#!/usr/bin/env python3
"""Pair cost of the hopper deck per triangle-distance method (exact / penalty / hybrid), side by
side in one invocation, alternating, median of REPEATS runs. Configuration of the short
regression case (64 grains started inside the hopper at 2 m/s, 2500 steps, one rank), so
grains hit the hopper walls.

  bench_hopper.py --exe build/liggghts-spacetree [--repeats 3] [--out bench/results/hopper_trimesh]

Writes OUT.csv (method, repeat, pair seconds, triangle pairs checked per step at the last thermo
output, loop seconds) and OUT.png (median pair time per method)."""
import argparse
import os
import re
import statistics
import subprocess
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--exe", required=True)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--steps", type=int, default=2500)
    ap.add_argument("--out", default=os.path.join(HERE, "..", "..", "bench", "results", "hopper_trimesh"))
    a = ap.parse_args()
    wd = tempfile.mkdtemp(prefix="hopper_bench_")
    subprocess.run(["python3", os.path.join(HERE, "make_hopper.py"), "hopper.stl", "floor.stl"], cwd=wd, check=True)
    rows = []
    methods = ["exact", "penalty", "hybrid"]
    for r in range(a.repeats):
        for m in methods:
            log = os.path.join(wd, "log.%s.%d" % (m, r))
            subprocess.run([os.path.abspath(a.exe), "-in", os.path.join(HERE, "in.hopper"), "-echo", "none",
                            "-log", log, "-var", "n", str(a.steps), "-var", "nx", "4", "-var", "a", "0.007",
                            "-var", "zlo", "0.05", "-var", "v0", "2.0", "-var", "dumpevery", str(a.steps),
                            "-var", "th", "10", "-var", "method", m], cwd=wd, check=True,
                           stdout=subprocess.DEVNULL)
            text = open(log).read()
            pair = float(re.search(r"Pair\s+time \(%\) = ([0-9.eE+-]+)", text).group(1))
            loop = float(re.search(r"Loop time of ([0-9.eE+-]+)", text).group(1))
            contacts = [int(float(l.split()[2])) for l in text.splitlines()
                        if re.match(r"^\s+\d+\s+\d+\s", l)]
            rows.append((m, r, pair, loop, max(contacts)))
            print("%-8s run %d: pair %.3f s, loop %.3f s, max contacts %d" % rows[-1], flush=True)
    os.makedirs(os.path.dirname(os.path.abspath(a.out)), exist_ok=True)
    with open(a.out + ".csv", "w") as f:
        f.write("method,repeat,pair_s,loop_s,max_contacts\n")
        for row in rows:
            f.write("%s,%d,%.6f,%.6f,%d\n" % row)
    med = {m: statistics.median([p for mm, _, p, _, _ in rows if mm == m]) for m in methods}
    for m in methods:
        print("median pair time %-8s %.3f s  (exact / %s = %.2f)" % (m, med[m], m, med["exact"] / med[m]))
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(5, 3.5))
    ax.bar(methods, [med[m] for m in methods], color=["tab:gray", "tab:orange", "tab:blue"])
    ax.set_ylabel("pair time, median of %d runs [s]" % a.repeats)
    ax.set_title("hopper deck, 64 grains, %d steps, 1 rank" % a.steps)
    for i, m in enumerate(methods):
        ax.text(i, med[m], "%.2fx" % (med["exact"] / med[m]), ha="center", va="bottom")
    fig.tight_layout()
    fig.savefig(a.out + ".png", dpi=120)


if __name__ == "__main__":
    main()
