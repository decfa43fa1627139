#!/usr/bin/env python3
"""Feature-cost benchmark: does a sphere-only `neighbor ... spacetree` scene pay for features
it does not name?

Configurations, all on the same deck (inputs/bench/in.feature_cost: the bidisperse demo pack of
scripts/gen_pack.py, about 23 000 spheres settling between six primitive walls, frictionless
Hertz, fix nve, lists rebuilt every 10 steps):

  full   the normal executable (build/liggghts-spacetree: every adapter compiled in:
         triangulated particles, adaptive time step, grid fix, ...), scene names none of them
  bare   the executable configured with -DSPACETREE_LIGGGHTS_FEATURES=neighbor-only
         (build-bare/liggghts-spacetree: only the neighbour search is compiled in)
  grid   the full executable, scene adds `fix spacetree grid regular` (what naming a feature
         costs; the lists are the same, so the trajectory is too)

The configurations alternate inside each repetition (the order rotates from one repetition to
the next), so slow drifts of the machine's load hit all of them alike. Per run: LIGGGHTS' loop
time, Pair and Neigh time, and the process CPU time (user + sys, from wait4). Reported: medians
per configuration and the ratio full/bare as the median of the per-repetition paired ratios with
its interquartile range and min..max. On a loaded machine wall times scatter by several per
cent, so the script also counts the instructions executed inside the time loop (Verlet::run)
under valgrind's callgrind for --callgrind-steps steps: a load-independent measure of the work
each configuration does. The final kinetic energy of every run is compared: full,
bare and grid must agree bit for bit (same physics; otherwise the timing comparison is void).

    bench/feature_cost.py [--reps 7] [--steps 1000] [--np 1] [--no-grid] [--callgrind-steps 100]
                          [--full build/liggghts-spacetree] [--bare build-bare/liggghts-spacetree]

Build the bare executable first (its LIGGGHTS objects come from ccache):
    cmake -S . -B build-bare -G Ninja -DSPACETREE_LIGGGHTS_FEATURES=neighbor-only \\
          -DSPACETREE_BUILD_TESTS=OFF && cmake --build build-bare --target liggghts-spacetree

Writes bench/results/feature_cost.csv (one row per run), feature_cost_summary.csv and
feature_cost.png.
"""

import argparse
import csv
import os
import re
import shutil
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
GEN = os.path.join(ROOT, "scripts", "gen_pack.py")
DECK = os.path.join(ROOT, "inputs", "bench", "in.feature_cost")
RESULTS = os.path.join(HERE, "results")

# Styles that must be absent from the bare executable (and present in the full one).
NON_NEIGHBOUR_STYLES = ["trimesh", "nve/trimesh", "trimesh/template", "trimesh/state",
                        "adapt/timestep", "spacetree", "trimesh/vtk"]

RUN_COLUMNS = ["rep", "slot", "config", "exe", "np", "steps", "loop_s", "pair_s", "neigh_s",
               "other_s", "cpu_s", "wall_s", "ke_final", "neigh_builds", "load1"]


def parse_log(text):
    def grab(pattern, cast=float):
        m = re.search(pattern, text, re.M)
        return cast(m.group(1)) if m else None
    out = {
        "loop_s": grab(r"^Loop time of ([0-9.eE+-]+)"),
        "pair_s": grab(r"^Pair\s+time \(%\) = ([0-9.eE+-]+)"),
        "neigh_s": grab(r"^Neigh\s+time \(%\) = ([0-9.eE+-]+)"),
        "other_s": grab(r"^Other\s+time \(%\) = ([0-9.eE+-]+)"),
        "neigh_builds": grab(r"^Neighbor list builds = (\d+)", int),
    }
    thermo = re.findall(r"^\s*(\d+)\s+(\d+)\s+([0-9.eE+-]+)\s*$", text, re.M)
    out["ke_final"] = thermo[-1][2] if thermo else None   # kept as printed: compared exactly
    return out


def styles_of(exe, workdir):
    """Style names an executable registers, from `liggghts -h` (Fix/Pair/Compute/Dump styles)."""
    p = subprocess.run([exe, "-h"], cwd=workdir, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       universal_newlines=True, timeout=60)
    names = set()
    section = False
    for line in p.stdout.splitlines():
        if line.startswith("*"):
            section = re.match(r"^\* (Fix|Pair|Compute|Dump) styles", line) is not None
            continue
        if section:
            names.update(line.split())
    return names


def run_once(exe, np_, workdir, steps, usegrid, grid):
    cmd = [exe, "-in", DECK, "-log", "none", "-echo", "none",
           "-var", "data", os.path.join(workdir, "pack.data"),
           "-var", "nsteps", str(steps), "-var", "usegrid", "1" if usegrid else "0",
           "-var", "grid", grid]
    if np_ > 1:
        mpirun = shutil.which("mpirun") or "mpirun"
        cmd = [mpirun, "--allow-run-as-root", "--oversubscribe", "-np", str(np_)] + cmd
    t0 = time.perf_counter()
    p = subprocess.Popen(cmd, cwd=workdir, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                         universal_newlines=True)
    text = p.stdout.read()
    _, status, ru = os.wait4(p.pid, 0)
    p.returncode = os.waitstatus_to_exitcode(status) if hasattr(os, "waitstatus_to_exitcode") else status
    wall = time.perf_counter() - t0
    if p.returncode != 0 or "ERROR" in text:
        sys.exit("feature_cost: run failed (%s):\n%s" % (" ".join(cmd), text[-3000:]))
    r = parse_log(text)
    if r["loop_s"] is None or r["ke_final"] is None:
        sys.exit("feature_cost: could not parse the log of %s:\n%s" % (" ".join(cmd), text[-3000:]))
    r["cpu_s"] = ru.ru_utime + ru.ru_stime   # of the child (and, with mpirun, its ranks)
    r["wall_s"] = wall
    return r


def instructions_once(exe, workdir, steps, usegrid, grid):
    """Instructions executed inside Verlet::run (the time loop, setup excluded) under callgrind:
    a count that the machine's load cannot disturb."""
    out = os.path.join(workdir, "callgrind.out")
    cmd = ["valgrind", "--tool=callgrind", "--callgrind-out-file=" + out, "--collect-atstart=no",
           "--toggle-collect=LAMMPS_NS::Verlet::run(int)",
           exe, "-in", DECK, "-log", "none", "-echo", "none",
           "-var", "data", os.path.join(workdir, "pack.data"), "-var", "nsteps", str(steps),
           "-var", "usegrid", "1" if usegrid else "0", "-var", "grid", grid]
    p = subprocess.run(cmd, cwd=workdir, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       universal_newlines=True)
    m = re.search(r"Collected : (\d+)", p.stdout)
    if p.returncode != 0 or not m:
        sys.exit("feature_cost: callgrind run failed (%s):\n%s" % (" ".join(cmd), p.stdout[-3000:]))
    return int(m.group(1))


def quartiles(values):
    v = sorted(values)
    if len(v) < 2:
        return v[0], v[0]
    q = statistics.quantiles(v, n=4, method="inclusive")
    return q[0], q[2]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--reps", type=int, default=7, help="repetitions of every configuration")
    ap.add_argument("--steps", type=int, default=1000, help="time steps per run")
    ap.add_argument("--np", type=int, default=1, help="MPI ranks per run")
    ap.add_argument("--grid", default="regular", help="grid type of the `grid` configuration")
    ap.add_argument("--no-grid", action="store_true", help="skip the `grid` configuration")
    ap.add_argument("--full", default=os.path.join(ROOT, "build", "liggghts-spacetree"))
    ap.add_argument("--bare", default=os.path.join(ROOT, "build-bare", "liggghts-spacetree"))
    ap.add_argument("--workdir", default=os.path.join(ROOT, "build", "feature_cost"))
    ap.add_argument("--python", default="/usr/bin/python3" if os.path.exists("/usr/bin/python3")
                    else sys.executable)
    ap.add_argument("--results", default=RESULTS)
    ap.add_argument("--callgrind-steps", type=int, default=100,
                    help="steps of the instruction count under valgrind (0: skip it)")
    ap.add_argument("--replot", action="store_true", help="only redraw feature_cost.png from the CSVs in --results")
    args = ap.parse_args()
    if args.replot:
        plot(args.results)
        return

    for name, exe in (("full", args.full), ("bare", args.bare)):
        if not os.access(exe, os.X_OK):
            sys.exit("feature_cost: %s executable %s not found (see the docstring to build it)"
                     % (name, exe))
    # The comparison is only meaningful if the bare executable really lacks the other features.
    os.makedirs(args.workdir, exist_ok=True)
    full_styles, bare_styles = styles_of(args.full, args.workdir), styles_of(args.bare, args.workdir)
    missing_in_full = [s for s in NON_NEIGHBOUR_STYLES if s not in full_styles]
    present_in_bare = [s for s in NON_NEIGHBOUR_STYLES if s in bare_styles]
    if missing_in_full or present_in_bare or "neigh/local" not in bare_styles:
        sys.exit("feature_cost: style check failed: missing in full %s, present in bare %s, "
                 "neigh/local in bare: %s" % (missing_in_full, present_in_bare,
                                              "neigh/local" in bare_styles))
    print("style check: full has %s; bare has none of them and has neigh/local"
          % ", ".join(NON_NEIGHBOUR_STYLES))

    os.makedirs(args.workdir, exist_ok=True)
    os.makedirs(args.results, exist_ok=True)
    data = os.path.join(args.workdir, "pack.data")
    subprocess.run([args.python, GEN, "bidisperse", "--d", "1e-3", "--R", "10", "--n", "30",
                    "--K", "8", "--boundary", "f", "--vel", "0.1", "--seed", "4242", "--out", data],
                   check=True, stdout=subprocess.DEVNULL)

    configs = [("full", args.full, False), ("bare", args.bare, False)]
    if not args.no_grid:
        configs.append(("grid", args.full, True))
    load_before = os.getloadavg()
    rows = []
    # one untimed warm-up run per executable (page cache, CPU frequency)
    for _, exe, _ in configs[:2]:
        run_once(exe, args.np, args.workdir, min(args.steps, 100), False, args.grid)
    for rep in range(args.reps):
        k = rep % len(configs)
        for slot, (name, exe, usegrid) in enumerate(configs[k:] + configs[:k]):
            r = run_once(exe, args.np, args.workdir, args.steps, usegrid, args.grid)
            r.update(rep=rep, slot=slot, config=name, exe=os.path.relpath(exe, ROOT), np=args.np,
                     steps=args.steps, load1=round(os.getloadavg()[0], 2))
            rows.append(r)
            print("rep %d %-4s loop %.3f s  pair %.3f  neigh %.3f  cpu %.3f  ke %s"
                  % (rep, name, r["loop_s"], r["pair_s"], r["neigh_s"], r["cpu_s"], r["ke_final"]),
                  flush=True)
    load_after = os.getloadavg()

    instructions = {}
    if args.callgrind_steps > 0 and shutil.which("valgrind"):
        for name, exe, usegrid in configs:
            instructions[name] = instructions_once(exe, args.workdir, args.callgrind_steps,
                                                   usegrid, args.grid)
            print("callgrind %-4s %d steps: %d instructions in Verlet::run"
                  % (name, args.callgrind_steps, instructions[name]), flush=True)
    elif args.callgrind_steps > 0:
        print("feature_cost: valgrind not found, no instruction counts")

    with open(os.path.join(args.results, "feature_cost.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=RUN_COLUMNS)
        w.writeheader()
        for r in rows:
            w.writerow({c: r[c] for c in RUN_COLUMNS})

    # same physics in every configuration (bit-identical final kinetic energy as printed)
    kes = sorted({r["ke_final"] for r in rows})
    if len(kes) != 1:
        sys.exit("feature_cost: final kinetic energies differ between runs: %s" % kes)

    by = {name: [r for r in rows if r["config"] == name] for name, _, _ in configs}
    summary = []
    for name, _, _ in configs:
        rs = by[name]
        entry = {"config": name}
        for key in ("loop_s", "pair_s", "neigh_s", "other_s", "cpu_s"):
            entry[key] = statistics.median(r[key] for r in rs)
        summary.append(entry)

    def paired(num, den, key):
        a = {r["rep"]: r[key] for r in by[num]}
        b = {r["rep"]: r[key] for r in by[den]}
        return [a[k] / b[k] for k in sorted(a)]

    ratio_rows = []
    for num in [n for n, _, _ in configs if n != "bare"]:
        for key in ("loop_s", "pair_s", "neigh_s", "cpu_s"):
            pr = paired(num, "bare", key)
            q1, q3 = quartiles(pr)
            ratio_rows.append({"ratio": "%s/bare" % num, "quantity": key,
                               "median": statistics.median(pr), "q1": q1, "q3": q3,
                               "min": min(pr), "max": max(pr), "n": len(pr)})

    with open(os.path.join(args.results, "feature_cost_summary.csv"), "w", newline="") as f:
        f.write("# steps %d, np %d, reps %d, atoms 23012, load average before %.2f %.2f %.2f, "
                "after %.2f %.2f %.2f, final ke %s (all runs)\n"
                % ((args.steps, args.np, args.reps) + tuple(load_before) + tuple(load_after)
                   + (kes[0],)))
        w = csv.writer(f)
        w.writerow(["config", "median_loop_s", "median_pair_s", "median_neigh_s",
                    "median_other_s", "median_cpu_s"])
        for e in summary:
            w.writerow([e["config"]] + ["%.5f" % e[k] for k in
                                        ("loop_s", "pair_s", "neigh_s", "other_s", "cpu_s")])
        w.writerow([])
        w.writerow(["config", "fastest_loop_s", "fastest_ratio_to_bare"])
        fastest = {n: min(r["loop_s"] for r in by[n]) for n in by}
        for n in by:
            w.writerow([n, "%.5f" % fastest[n], "%.4f" % (fastest[n] / fastest["bare"])])
        w.writerow([])
        w.writerow(["ratio", "quantity", "median_paired", "q1", "q3", "min", "max", "n"])
        for rr in ratio_rows:
            w.writerow([rr["ratio"], rr["quantity"]] +
                       ["%.4f" % rr[k] for k in ("median", "q1", "q3", "min", "max")] + [rr["n"]])
        if instructions:
            w.writerow([])
            w.writerow(["config", "callgrind_steps", "instructions_in_verlet_run", "ratio_to_bare"])
            for name in instructions:
                w.writerow([name, args.callgrind_steps, instructions[name],
                            "%.6f" % (instructions[name] / instructions["bare"])])

    print("\nmedians over %d repetitions (%d steps, %d rank(s)); load average before %.2f, after %.2f"
          % (args.reps, args.steps, args.np, load_before[0], load_after[0]))
    print("%-5s %9s %9s %9s %9s" % ("config", "loop s", "pair s", "neigh s", "cpu s"))
    for e in summary:
        print("%-5s %9.3f %9.3f %9.3f %9.3f" % (e["config"], e["loop_s"], e["pair_s"],
                                               e["neigh_s"], e["cpu_s"]))
    print("\npaired ratios (median [q1, q3] (min..max))")
    for rr in ratio_rows:
        print("%-10s %-8s %.4f [%.4f, %.4f] (%.4f..%.4f)" % (rr["ratio"], rr["quantity"],
              rr["median"], rr["q1"], rr["q3"], rr["min"], rr["max"]))
    main_ratio = next(rr for rr in ratio_rows if rr["ratio"] == "full/bare" and rr["quantity"] == "loop_s")
    fastest = {n: min(r["loop_s"] for r in by[n]) for n in by}
    print("ratio of the fastest runs (least disturbed by the load): " + ", ".join(
        "%s/bare %.4f" % (n, fastest[n] / fastest["bare"]) for n in by if n != "bare"))
    print("\nfull/bare loop time: %.4f (IQR %.4f..%.4f); target within 2 %%: %s"
          % (main_ratio["median"], main_ratio["q1"], main_ratio["q3"],
             "yes" if abs(main_ratio["median"] - 1.0) <= 0.02 else "NO"))
    print("final kinetic energy identical in all %d runs: %s" % (len(rows), kes[0]))
    for name in instructions:
        if name != "bare":
            print("%s/bare instructions in the time loop (%d steps, callgrind): %.6f (%+d)"
                  % (name, args.callgrind_steps, instructions[name] / instructions["bare"],
                     instructions[name] - instructions["bare"]))

    plot(args.results)


def plot(results):
    """Draws feature_cost.png from the CSVs in `results`: the paired ratios to `bare` of every
    repetition (loop and CPU time) against the 2 % band, and the instruction ratio when the
    summary has one (callgrind: the load-independent measure)."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("feature_cost: matplotlib missing, no PNG")
        return
    runs = list(csv.DictReader(open(os.path.join(results, "feature_cost.csv"))))
    lines = open(os.path.join(results, "feature_cost_summary.csv")).read().splitlines()
    header = lines[0].lstrip("# ")
    instructions = {}
    for k, line in enumerate(lines):
        if line.startswith("config,callgrind_steps"):
            for row in csv.reader(lines[k + 1:]):
                if len(row) == 4:
                    instructions[row[0]] = float(row[3])
    names = [n for n in dict.fromkeys(r["config"] for r in runs) if n != "bare"]
    bare = {r["rep"]: r for r in runs if r["config"] == "bare"}
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.4), gridspec_kw={"width_ratios": (2, 1)})
    ax = axes[0]
    positions, data, labels = [], [], []
    for i, name in enumerate(names):
        for j, key in enumerate(("loop_s", "cpu_s")):
            ratios = [float(r[key]) / float(bare[r["rep"]][key]) for r in runs
                      if r["config"] == name and r["rep"] in bare]
            positions.append(3 * i + j)
            data.append(ratios)
            labels.append("%s / bare\n%s" % (name, "loop time" if key == "loop_s" else "CPU time"))
            ax.plot([3 * i + j] * len(ratios), ratios, "k.", ms=3, alpha=0.5)
            ax.text(3 * i + j + 0.3, statistics.median(ratios), "%.3f" % statistics.median(ratios),
                    va="center", fontsize=8)
    ax.boxplot(data, positions=positions, widths=0.5, showfliers=False)
    ax.set_xticks(positions)
    ax.set_xticklabels(labels, fontsize=8)
    ax.axhspan(0.98, 1.02, color="0.85", label="within 2 %")
    ax.axhline(1.0, color="k", lw=0.8)
    ax.set_ylabel("paired ratio (same repetition)")
    ax.set_title("wall-clock ratios, every repetition (box: quartiles, number: median)", fontsize=9)
    ax.legend(fontsize=8, loc="upper right")
    ax = axes[1]
    if instructions:
        inst = [n for n in names if n in instructions]
        bars = ax.bar(range(len(inst)), [instructions[n] for n in inst], color="tab:blue")
        for bar, n in zip(bars, inst):
            ax.text(bar.get_x() + bar.get_width() / 2, instructions[n], "%.6f" % instructions[n],
                    ha="center", va="bottom", fontsize=8)
        ax.set_xticks(range(len(inst)))
        ax.set_xticklabels(["%s / bare" % n for n in inst], fontsize=8)
        ax.set_ylim(0.9, max(1.15, 1.03 * max(instructions[n] for n in inst)))
        ax.axhline(1.0, color="k", lw=0.8)
        ax.axhspan(0.98, 1.02, color="0.85", zorder=0, label="within 2 %")
        ax.legend(fontsize=8, loc="upper left")
        ax.set_ylabel("instructions in the time loop / bare")
        ax.set_title("work (callgrind instruction count)", fontsize=9)
    else:
        ax.axis("off")
        ax.text(0.5, 0.5, "no instruction count in this run\n(--callgrind-steps 0)", ha="center",
                va="center")
    fig.suptitle("Feature cost, sphere deck: " + header, fontsize=8)
    fig.tight_layout()
    out = os.path.join(results, "feature_cost.png")
    fig.savefig(out, dpi=120)
    print("wrote %s" % out)

if __name__ == "__main__":
    main()
