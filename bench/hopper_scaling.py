#!/usr/bin/env python3
"""Wall time per step of the hopper deck (inputs/hopper/in.hopper) for thread and rank counts of
pair_style trimesh ... threads N, side by side in one invocation: configurations interleaved in
every repetition, medians reported.

  hopper_scaling.py --exe build/liggghts-spacetree [--threads 1,2] [--ranks 1,2] [--nx 10]
                    [--steps 200] [--repeats 3] [--out bench/results/hopper_scaling]

--nx: grains per lattice side of the deck (nx^3 grains, 10 = the full 1000-grain deck; the deck's
box holds at most nx = 10 at its spacing 6 mm, so the grain count is limited by the deck, not by
this script). The deck is used unchanged except for `threads ${threads}` appended to its
pair_style line. No grid axis: this tree has no `fix spacetree grid` choice (regular / adaptive /
reluctant).

Writes OUT.csv (one row per run: nx, grains, ranks, threads, repeat, loop and pair seconds,
seconds per step, 1-minute load average before the run, wall and CPU seconds of the whole
process tree and their ratio = cores the run actually got) and OUT.png (median seconds per step per
configuration, one group per nx). Runs unchanged on a bigger machine (--threads 1,2,4,8
--ranks 1,2,4)."""
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
HOPPER = os.path.join(ROOT, "inputs", "hopper")


def ints(s):
    return [int(v) for v in s.split(",") if v]


def deck_with_threads(wd):
    text = open(os.path.join(HOPPER, "in.hopper")).read()
    lines = text.splitlines()
    hits = [i for i, l in enumerate(lines) if l.startswith("pair_style trimesh")]
    if len(hits) != 1:
        sys.exit("in.hopper: expected one 'pair_style trimesh' line, found %d" % len(hits))
    lines[hits[0]] += " threads ${threads}"
    path = os.path.join(wd, "in.hopper_threads")
    with open(path, "w") as f:
        f.write("variable threads index 1\n" + "\n".join(lines) + "\n")
    return path


def run(a, wd, deck, nx, ranks, threads, rep):
    log = os.path.join(wd, "log.nx%d.r%d.t%d.%d" % (nx, ranks, threads, rep))
    cmd = [os.path.abspath(a.exe), "-in", deck, "-echo", "none", "-log", log, "-var", "threads", str(threads),
           "-var", "n", str(a.steps), "-var", "nx", str(nx), "-var", "dumpevery", str(10 * a.steps),
           "-var", "th", str(a.steps), "-var", "method", a.method]
    for kv in a.var:
        name, _, value = kv.partition("=")
        cmd += ["-var", name, value]
    if ranks > 1 or a.always_mpi:
        cmd = [a.mpiexec] + a.mpiexec_flags.split() + ["-np", str(ranks)] + cmd
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    load = os.getloadavg()[0]
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.monotonic()
    subprocess.run(cmd, cwd=wd, check=True, stdout=subprocess.DEVNULL, env=env)
    wall = time.monotonic() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    text = open(log).read()
    loop = float(re.search(r"Loop time of ([0-9.eE+-]+)", text).group(1))
    pair = float(re.search(r"Pair\s+time \(%\) = ([0-9.eE+-]+)", text).group(1))
    grains = nx ** 3
    return dict(nx=nx, grains=grains, ranks=ranks, threads=threads, repeat=rep, loop_s=loop, pair_s=pair,
                s_per_step=loop / a.steps, load1=load, process_wall_s=wall, process_cpu_s=cpu,
                cores_used=cpu / wall)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", required=True)
    ap.add_argument("--threads", type=ints, default=[1, 2])
    ap.add_argument("--ranks", type=ints, default=[1, 2])
    ap.add_argument("--nx", type=ints, default=[10])
    ap.add_argument("--steps", type=int, default=200)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--method", default="hybrid")
    ap.add_argument("--mpiexec", default="mpirun")
    ap.add_argument("--mpiexec-flags", default="--oversubscribe")
    ap.add_argument("--always-mpi", action="store_true", help="start 1-rank runs through mpiexec too")
    ap.add_argument("--var", action="append", default=[], metavar="NAME=VALUE",
                    help="further deck variable, e.g. --var zlo=0.05 --var v0=2.0 (repeatable)")
    ap.add_argument("--out", default=os.path.join(ROOT, "bench", "results", "hopper_scaling"))
    a = ap.parse_args()

    wd = tempfile.mkdtemp(prefix="hopper_scaling_")
    subprocess.run([sys.executable, os.path.join(HOPPER, "make_hopper.py"), "hopper.stl", "floor.stl"], cwd=wd,
                   check=True, stdout=subprocess.DEVNULL)
    deck = deck_with_threads(wd)
    configs = [(nx, r, t) for nx in a.nx for r in a.ranks for t in a.threads]
    rows = []
    for rep in range(a.repeats):
        for nx, r, t in configs:
            row = run(a, wd, deck, nx, r, t, rep)
            rows.append(row)
            print("nx %d (%d grains) ranks %d threads %d run %d: %.4f s/step (pair %.3f s of %.3f s), "
                  "%.2f cores used, load %.2f" % (nx, row["grains"], r, t, rep, row["s_per_step"], row["pair_s"],
                                                  row["loop_s"], row["cores_used"], row["load1"]), flush=True)

    os.makedirs(os.path.dirname(os.path.abspath(a.out)), exist_ok=True)
    keys = ["nx", "grains", "ranks", "threads", "repeat", "loop_s", "pair_s", "s_per_step", "load1",
            "process_wall_s", "process_cpu_s", "cores_used"]
    with open(a.out + ".csv", "w") as f:
        f.write(",".join(keys) + "\n")
        for row in rows:
            f.write(",".join(("%.6g" % row[k]) if isinstance(row[k], float) else str(row[k]) for k in keys) + "\n")

    med = {c: statistics.median(row["s_per_step"] for row in rows if (row["nx"], row["ranks"], row["threads"]) == c)
           for c in configs}
    for nx, r, t in configs:
        base = med[(nx, a.ranks[0], a.threads[0])]
        cores = statistics.median(row["cores_used"] for row in rows if (row["nx"], row["ranks"], row["threads"]) == (nx, r, t))
        print("median nx %d ranks %d threads %d: %.4f s/step, speed-up vs ranks %d threads %d: %.2fx, %.2f cores used"
              % (nx, r, t, med[(nx, r, t)], a.ranks[0], a.threads[0], base / med[(nx, r, t)], cores))

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6, 3.8))
    labels = ["nx %d\n%dr x %dt" % c for c in configs]
    ax.bar(range(len(configs)), [med[c] for c in configs], color="tab:blue")
    ax.set_xticks(range(len(configs)))
    ax.set_xticklabels(labels, fontsize=8)
    ax.set_ylabel("wall s per step (median of %d)" % a.repeats)
    ax.set_title("hopper deck, pair_style trimesh threads / MPI ranks", fontsize=9)
    fig.tight_layout()
    fig.savefig(a.out + ".png", dpi=120)
    print("wrote %s.csv, %s.png" % (a.out, a.out))


if __name__ == "__main__":
    main()
