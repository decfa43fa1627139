#!/usr/bin/env python3
"""Pair cost of the hopper deck per triangle-distance method, side by side in one invocation,
alternating, median of REPEATS runs. Configuration of the short regression case (64 grains
started inside the hopper at 2 m/s, STEPS steps, one rank), so grains hit the hopper walls.

  bench_hopper.py --exe build/liggghts-spacetree [--repeats 3] [--steps 2500] [--ntri 40,12]
                  [--methods exact,penalty,hybrid,hybrid1] [--threads 1]
                  [--out bench/results/hopper_trimesh]

Methods (the pair_style trimesh `method ...` words each stands for):
  exact    method exact
  penalty  method penalty                                (8 Newton steps, not certified)
  hybrid   method hybrid                                 (default: two-stage, 5 + 4 steps)
  hybrid1  method hybrid iterations 8 continuation 0     (single stage, the former default)
--ntri: triangles per grain (in.hopper's `dented ntri 40`, replaced in a copy of the deck;
12 is the coarsest dented sphere). Every (ntri, method) runs once per repeat, alternating.

--threads: pair_style trimesh threads (default 1: the serial path, one core per run, so that
the methods are compared on one core; 0 = TBB default).

Timings: LIGGGHTS' pair time (wall clock) and the CPU seconds (user + system) of the whole
LIGGGHTS process, which a loaded machine inflates much less than the wall clock (pair is
97-99 % of the loop; the set-up, the same for every method, is in the CPU seconds too).
Ratios exact / method are given of the medians and as the median of the per-repeat ratios
(each repeat runs every method back to back, so the load is about the same for them).

Writes OUT.csv (ntri, method, repeat, pair seconds, loop seconds, CPU seconds, max contacts at
the thermo outputs), OUT_summary.csv (medians and ratios) and OUT.png (median pair time and
median CPU seconds per method and ntri). --plot-only: summary and plot again from OUT.csv."""
import argparse
import os
import re
import resource
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


def measure(a, methods, ntris):
    wd = tempfile.mkdtemp(prefix="hopper_bench_")
    subprocess.run(["python3", os.path.join(HERE, "make_hopper.py"), "hopper.stl", "floor.stl"], cwd=wd, check=True)
    decks = {t: deck_with_ntri(wd, t) for t in ntris}
    rows = []
    for r in range(a.repeats):
        for t in ntris:
            for m in methods:
                log = os.path.join(wd, "log.%d.%s.%d" % (t, m, r))
                before = resource.getrusage(resource.RUSAGE_CHILDREN)
                p = subprocess.run([os.path.abspath(a.exe), "-in", decks[t], "-echo", "none",
                                    "-log", log, "-var", "n", str(a.steps), "-var", "nx", "4", "-var", "a", "0.007",
                                    "-var", "zlo", "0.05", "-var", "v0", "2.0", "-var", "dumpevery", str(a.steps),
                                    "-var", "th", "10", "-var", "method", METHODS[m],
                                    "-var", "threads", str(a.threads)], cwd=wd, check=True,
                                   stdout=subprocess.PIPE, text=True, errors="replace")
                after = resource.getrusage(resource.RUSAGE_CHILDREN)
                cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
                schedule = re.search(r"pair_style trimesh: method (\w+), (.*)", p.stdout)
                text = open(log).read()
                pair = float(re.search(r"Pair\s+time \(%\) = ([0-9.eE+-]+)", text).group(1))
                loop = float(re.search(r"Loop time of ([0-9.eE+-]+)", text).group(1))
                contacts = [int(float(l.split()[2])) for l in text.splitlines()
                            if re.match(r"^\s+\d+\s+\d+\s", l)]
                rows.append((t, m, r, pair, loop, cpu, max(contacts)))
                print("ntri %3d %-8s run %d: pair %.3f s, loop %.3f s, cpu %.3f s, max contacts %d" % rows[-1],
                      ("(%s)" % schedule.group(2)) if schedule and r == 0 else "", flush=True)
    os.makedirs(os.path.dirname(os.path.abspath(a.out)), exist_ok=True)
    with open(a.out + ".csv", "w") as f:
        f.write("ntri,method,repeat,pair_s,loop_s,cpu_s,max_contacts\n")
        for row in rows:
            f.write("%d,%s,%d,%.6f,%.6f,%.6f,%d\n" % row)
    return rows


def read_rows(path):
    rows = []
    with open(path) as f:
        next(f)
        for line in f:
            t, m, r, pair, loop, cpu, cont = line.strip().split(",")
            rows.append((int(t), m, int(r), float(pair), float(loop), float(cpu), int(cont)))
    return rows


def summarise(a, rows):
    ntris = list(dict.fromkeys(row[0] for row in rows))
    methods = list(dict.fromkeys(row[1] for row in rows))
    repeats = sorted(set(row[2] for row in rows))
    threads = a.threads
    value = {(row[0], row[1], row[2], col): row[3 + col] for row in rows for col in range(3)}
    PAIR, CPU = 0, 2

    def median(t, m, col):
        return statistics.median([value[(t, m, r, col)] for r in repeats])

    def ratio(t, m, col):   # of the medians
        return median(t, "exact", col) / median(t, m, col) if "exact" in methods else float("nan")

    def paired(t, m, col):  # median over repeats of exact / method in the same repeat
        if "exact" not in methods:
            return float("nan")
        return statistics.median([value[(t, "exact", r, col)] / value[(t, m, r, col)] for r in repeats])

    with open(a.out + "_summary.csv", "w") as f:
        f.write("ntri,method,pair_command,threads,repeats,median_pair_s,median_cpu_s,"
                "exact_over_method_pair,exact_over_method_cpu,paired_exact_over_method_pair,"
                "paired_exact_over_method_cpu\n")
        for t in ntris:
            for m in methods:
                f.write("%d,%s,method %s,%d,%d,%.6f,%.6f,%.3f,%.3f,%.3f,%.3f\n"
                        % (t, m, METHODS[m], threads, len(repeats), median(t, m, PAIR), median(t, m, CPU),
                           ratio(t, m, PAIR), ratio(t, m, CPU), paired(t, m, PAIR), paired(t, m, CPU)))
                print("ntri %3d %-8s median pair %.3f s, cpu %.3f s; exact / %s: pair %.2f, cpu %.2f "
                      "(paired: %.2f, %.2f)" % (t, m, median(t, m, PAIR), median(t, m, CPU), m, ratio(t, m, PAIR),
                                                ratio(t, m, CPU), paired(t, m, PAIR), paired(t, m, CPU)))
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(4.0 + 1.1 * len(methods) * len(ntris), 3.8))
    width = 0.8 / len(ntris)
    colours = ["tab:gray", "tab:orange", "tab:blue", "tab:cyan", "tab:green"]
    for ax, col, label in ((axes[0], PAIR, "pair time (wall clock)"), (axes[1], CPU, "CPU seconds of the run")):
        for k, t in enumerate(ntris):
            xs = [i + (k - (len(ntris) - 1) / 2) * width for i in range(len(methods))]
            ax.bar(xs, [median(t, m, col) for m in methods], width, label="%d triangles per grain" % t,
                   color=colours[k % len(colours)])
            if "exact" in methods:
                for x, m in zip(xs, methods):
                    ax.text(x, median(t, m, col), "%.1fx" % ratio(t, m, col), ha="center", va="bottom", fontsize=8)
        ax.set_xticks(range(len(methods)))
        ax.set_xticklabels(methods)
        ax.set_ylabel("%s, median of %d [s]" % (label, len(repeats)))
        ax.legend(fontsize=8)
    fig.suptitle("hopper deck, 64 grains, %d steps, 1 rank, threads %d (x: exact / method)" % (a.steps, threads))
    fig.tight_layout()
    fig.savefig(a.out + ".png", dpi=120)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--exe")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--steps", type=int, default=2500)
    ap.add_argument("--ntri", default="40", help="comma-separated triangles per grain")
    ap.add_argument("--methods", default="exact,penalty,hybrid")
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--out", default=os.path.join(HERE, "..", "..", "bench", "results", "hopper_trimesh"))
    ap.add_argument("--plot-only", action="store_true")
    a = ap.parse_args()
    if a.plot_only:
        summarise(a, read_rows(a.out + ".csv"))
        return
    if not a.exe:
        ap.error("--exe is required (except with --plot-only)")
    methods = a.methods.split(",")
    for m in methods:
        if m not in METHODS:
            raise SystemExit("bench_hopper.py: unknown method '%s' (%s)" % (m, ", ".join(METHODS)))
    summarise(a, measure(a, methods, [int(t) for t in a.ntri.split(",")]))


if __name__ == "__main__":
    main()
