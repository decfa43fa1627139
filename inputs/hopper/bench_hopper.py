#!/usr/bin/env python3
"""Pair cost of the hopper deck per triangle-distance method, side by side in one invocation,
alternating, median of REPEATS runs. Configuration of the short regression case (64 grains
started inside the hopper at 2 m/s, STEPS steps, one rank), so grains hit the hopper walls.

  bench_hopper.py --exe build/liggghts-spacetree [--repeats 3] [--steps 2500] [--ntri 40,12]
                  [--methods exact,penalty,hybrid,hybrid1] [--out bench/results/hopper_trimesh]

Methods (the pair_style trimesh `method ...` words each stands for):
  exact    method exact
  penalty  method penalty                                (8 Newton steps, not certified)
  hybrid   method hybrid                                 (default: two-stage, 5 + 4 steps)
  hybrid1  method hybrid iterations 8 continuation 0     (single stage, the former default)
--ntri: triangles per grain (in.hopper's `dented ntri 40`, replaced in a copy of the deck;
12 is the coarsest dented sphere). Every (ntri, method) runs once per repeat, alternating.

Writes OUT.csv (ntri, method, repeat, pair seconds, loop seconds, max contacts at the thermo
outputs), OUT_summary.csv (medians, exact / method) and OUT.png (median pair time per method
and ntri)."""
import argparse
import os
import re
import statistics
import subprocess
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
METHODS = {
    "exact": "exact",
    "penalty": "penalty",
    "hybrid": "hybrid",
    "hybrid1": "hybrid iterations 8 continuation 0",
}


def deck_with_ntri(wd, ntri):
    """in.hopper with its grains at `ntri` triangles (a copy in the work directory)."""
    text = open(os.path.join(HERE, "in.hopper")).read()
    pattern = r"\bdented ntri 40\b"
    if len(re.findall(pattern, text)) != 1:
        raise SystemExit("bench_hopper.py: in.hopper no longer has exactly one 'dented ntri 40'")
    path = os.path.join(wd, "in.hopper_ntri%d" % ntri)
    with open(path, "w") as f:
        f.write(re.sub(pattern, "dented ntri %d" % ntri, text))
    return path


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--exe", required=True)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--steps", type=int, default=2500)
    ap.add_argument("--ntri", default="40", help="comma-separated triangles per grain")
    ap.add_argument("--methods", default="exact,penalty,hybrid")
    ap.add_argument("--out", default=os.path.join(HERE, "..", "..", "bench", "results", "hopper_trimesh"))
    a = ap.parse_args()
    methods = a.methods.split(",")
    for m in methods:
        if m not in METHODS:
            raise SystemExit("bench_hopper.py: unknown method '%s' (%s)" % (m, ", ".join(METHODS)))
    ntris = [int(t) for t in a.ntri.split(",")]
    wd = tempfile.mkdtemp(prefix="hopper_bench_")
    subprocess.run(["python3", os.path.join(HERE, "make_hopper.py"), "hopper.stl", "floor.stl"], cwd=wd, check=True)
    decks = {t: deck_with_ntri(wd, t) for t in ntris}
    rows = []
    for r in range(a.repeats):
        for t in ntris:
            for m in methods:
                log = os.path.join(wd, "log.%d.%s.%d" % (t, m, r))
                p = subprocess.run([os.path.abspath(a.exe), "-in", decks[t], "-echo", "none",
                                    "-log", log, "-var", "n", str(a.steps), "-var", "nx", "4", "-var", "a", "0.007",
                                    "-var", "zlo", "0.05", "-var", "v0", "2.0", "-var", "dumpevery", str(a.steps),
                                    "-var", "th", "10", "-var", "method", METHODS[m]], cwd=wd, check=True,
                                   stdout=subprocess.PIPE, text=True, errors="replace")
                schedule = re.search(r"pair_style trimesh: method (\w+), (.*)", p.stdout)
                text = open(log).read()
                pair = float(re.search(r"Pair\s+time \(%\) = ([0-9.eE+-]+)", text).group(1))
                loop = float(re.search(r"Loop time of ([0-9.eE+-]+)", text).group(1))
                contacts = [int(float(l.split()[2])) for l in text.splitlines()
                            if re.match(r"^\s+\d+\s+\d+\s", l)]
                rows.append((t, m, r, pair, loop, max(contacts)))
                print("ntri %3d %-8s run %d: pair %.3f s, loop %.3f s, max contacts %d" % rows[-1],
                      ("(%s)" % schedule.group(2)) if schedule and r == 0 else "", flush=True)
    os.makedirs(os.path.dirname(os.path.abspath(a.out)), exist_ok=True)
    with open(a.out + ".csv", "w") as f:
        f.write("ntri,method,repeat,pair_s,loop_s,max_contacts\n")
        for row in rows:
            f.write("%d,%s,%d,%.6f,%.6f,%d\n" % row)
    med = {(t, m): statistics.median([p for tt, mm, _, p, _, _ in rows if (tt, mm) == (t, m)])
           for t in ntris for m in methods}
    with open(a.out + "_summary.csv", "w") as f:
        f.write("ntri,method,pair_command,repeats,median_pair_s,exact_over_method\n")
        for t in ntris:
            for m in methods:
                ratio = med[(t, "exact")] / med[(t, m)] if "exact" in methods else float("nan")
                f.write("%d,%s,method %s,%d,%.6f,%.3f\n" % (t, m, METHODS[m], a.repeats, med[(t, m)], ratio))
                print("ntri %3d median pair time %-8s %.3f s  (exact / %s = %.2f)" % (t, m, med[(t, m)], m, ratio))
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(1.6 + 1.4 * len(methods) * len(ntris) / 2, 3.6))
    width = 0.8 / len(ntris)
    colours = ["tab:gray", "tab:orange", "tab:blue", "tab:cyan", "tab:green"]
    for k, t in enumerate(ntris):
        xs = [i + (k - (len(ntris) - 1) / 2) * width for i in range(len(methods))]
        ys = [med[(t, m)] for m in methods]
        ax.bar(xs, ys, width, label="%d triangles per grain" % t, color=colours[k % len(colours)],
               alpha=1.0 - 0.35 * k)
        if "exact" in methods:
            for x, m in zip(xs, methods):
                ax.text(x, med[(t, m)], "%.1fx" % (med[(t, "exact")] / med[(t, m)]), ha="center", va="bottom",
                        fontsize=8)
    ax.set_xticks(range(len(methods)))
    ax.set_xticklabels(methods)
    ax.set_ylabel("pair time, median of %d runs [s]" % a.repeats)
    ax.set_title("hopper deck, 64 grains, %d steps, 1 rank" % a.steps)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(a.out + ".png", dpi=120)


if __name__ == "__main__":
    main()
