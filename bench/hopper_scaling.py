#!/usr/bin/env python3
"""Wall time per step of the hopper deck (inputs/hopper/in.hopper) for grain counts, MPI ranks,
threads of pair_style trimesh and spacetree grids, side by side in one invocation: all
configurations interleaved in every repetition, medians reported.

  hopper_scaling.py --exe build/liggghts-spacetree [--sizes 1000,10000] [--threads 1,2] [--ranks 1,2]
                    [--grids none,regular,adaptive,reluctant] [--neigh-every 0] [--steps 200]
                    [--repeats 3] [--out bench/results/hopper_scaling]

--sizes: grain counts; each becomes a cubic lattice of nx = round(N^(1/3)) grains per side
(1000 -> nx 10, 10000 -> nx 22 = 10 648 grains); --nx gives the lattice sides directly instead.
The deck's hopper (top radius 50 mm) takes the lattice up to nx = 11; a larger lattice gets the
deck's meshes scaled by S, the smallest multiple of 0.5 whose hopper top holds the lattice's
diagonal (nx 22: S = 2): this script writes them with make_hopper.py
--segments 32S --layers 5S --cell 0.01/S (triangles of the default size once scaled) and
multiplies their vertices by S, and scales the deck's box variables with it (box 0.09 S,
boxzlo -0.02 S, boxzhi above the lattice, zlo 5 mm above the hopper top: hopper outlet radius
30 mm at z = 80 mm, top radius 100 mm at z = 200 mm, floor 0.24 m wide for S = 2). nx <= 11 runs
the deck's defaults.

--grids: `none` = the deck's plain `neighbor ... spacetree`; `regular|adaptive|reluctant` add
`fix tree all spacetree grid TYPE` and `compute treestats` (docs/fix_spacetree.md) after the
deck's neighbor line. --neigh-every N > 0 adds `neigh_modify delay 0 every N check no` (the
deck as is rebuilds its lists only when a grain moved half the 0.5 mm skin: never in the first
few hundred steps of a grain at rest, so a grid comparison without it measures only the setup).
--processors (default `* * 1`): a `processors` line before the box. The grains start as a
column on the hopper's axis; LIGGGHTS' own choice for the deck's box (`--processors deck`) cuts
it in z (1 by 1 by 2 on 2 ranks) where the grains are all above the cut: one rank holds every
grain and the other waits. `* * 1` cuts through the axis (2 by 1 by 1: half the grains each).
Otherwise the deck is used unchanged, except `threads ${threads}` appended to its pair_style
line (unless it has a threads keyword already) and two thermo columns (lowest and highest grain
centre) for where the grains are.

Writes OUT.csv (one row per run: nx, grains, scale, grid, ranks, threads, repeat, loop / pair /
neigh / comm seconds, neighbour-list builds, seconds per step, the last thermo row's contacts,
grain heights and treestats values, 1-minute load average before the run, wall and CPU seconds
of the whole process tree and their ratio = cores the run actually got, and the cores that other
processes used meanwhile, from /proc/stat: on a shared machine a speed-up is only read from runs
with others_cores near 0; --wait-busy C waits before each run until the others use at most C
cores), OUT_summary.csv (medians per configuration, speed-ups) and OUT.png (median seconds per step per configuration,
split into pair / neigh / rest, one panel per grain count). Runs unchanged on a bigger machine
(--threads 1,2,4,8 --ranks 1,2,4)."""
import argparse
import math
import os
import re
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
HOPPER = os.path.join(ROOT, "inputs", "hopper")
GRIDS = ("none", "regular", "adaptive", "reluctant")
# treestats columns appended to thermo for grid != none (docs/compute_treestats.md)
TREESTATS = (("comparisons", 1), ("cells", 5), ("leaves", 6), ("virtual_links", 9), ("update_s", 11))


def ints(s):
    return [int(v) for v in s.split(",") if v]


def names(s):
    out = [v for v in s.split(",") if v]
    bad = [v for v in out if v not in GRIDS]
    if bad:
        raise argparse.ArgumentTypeError("unknown grid %s (choose from %s)" % (",".join(bad), ",".join(GRIDS)))
    return out


def lattice(nx, spacing=0.006):
    """Mesh scale and deck variables for an nx^3 lattice (None: the deck's defaults fit)."""
    if nx <= 11:
        return 1.0, {}
    # inner top radius 0.05 S must hold the lattice's half diagonal plus a grain (3 mm)
    need = (0.5 * spacing * (nx - 1) * math.sqrt(2.0) + 0.003) / 0.05
    s = math.ceil(2.0 * need) / 2.0
    zlo = 0.10 * s + 0.005
    return s, dict(zlo="%.6g" % zlo, box="%.6g" % (0.09 * s), boxzlo="%.6g" % (-0.02 * s),
                   boxzhi="%.6g" % max(0.17 * s, zlo + spacing * (nx - 1) + 0.01))


def scale_stl(path, s):
    """Multiply every vertex of the ASCII STL file `path` by s, in place (17 digits, as written)."""
    def vertex(m):
        return m.group(1) + " ".join("%.17g" % (s * float(c)) for c in m.group(2).split())
    text = open(path).read()
    with open(path, "w") as f:
        f.write(re.sub(r"^(\s*vertex\s+)(\S+\s+\S+\s+\S+)", vertex, text, flags=re.M))


def meshes(wd, s):
    """The deck's meshes (make_hopper.py) with every length times s: segments, layers and floor
    cells multiplied by s first, so that the triangles keep the default size."""
    d = os.path.join(wd, "meshes_s%g" % s)
    if not os.path.isdir(d):
        os.makedirs(d)
        extra = [] if s == 1.0 else ["--segments", str(int(round(32 * s))), "--layers", str(int(round(5 * s))),
                                     "--cell", "%.17g" % (0.01 / s)]
        subprocess.run([sys.executable, os.path.join(HOPPER, "make_hopper.py"), "hopper.stl", "floor.stl"] + extra,
                       cwd=d, check=True, stdout=subprocess.DEVNULL)
        if s != 1.0:
            for name in ("hopper.stl", "floor.stl"):
                scale_stl(os.path.join(d, name), s)
    return d


def deck_for(wd, grid, neigh_every, processors):
    lines = open(os.path.join(HOPPER, "in.hopper")).read().splitlines()

    def one(prefix):
        hits = [i for i, l in enumerate(lines) if l.startswith(prefix)]
        if len(hits) != 1:
            sys.exit("in.hopper: expected one '%s' line, found %d" % (prefix, len(hits)))
        return hits[0]

    pair = one("pair_style trimesh")
    if " threads " not in lines[pair] + " ":
        lines[pair] += " threads ${threads}"
    if processors != "deck":
        box = one("region box")
        lines[box:box] = ["processors " + processors]
    thermo = one("thermo_style custom")
    lines[thermo] += " v_zmin v_zmax"
    if grid != "none":
        lines[thermo] += "".join(" c_ts[%d]" % k for _, k in TREESTATS)
    extra = []
    if neigh_every > 0:
        extra.append("neigh_modify delay 0 every %d check no" % neigh_every)
    if grid != "none":
        extra += ["fix tree all spacetree grid %s" % grid, "compute ts all treestats"]
    at = one("neigh_modify")
    lines[at + 1:at + 1] = extra
    lines[thermo + len(extra):thermo + len(extra)] = ["variable zmin equal bound(grains,zmin)",
                                                       "variable zmax equal bound(grains,zmax)"]
    path = os.path.join(wd, "in.hopper_%s_every%d" % (grid, neigh_every))
    with open(path, "w") as f:
        f.write("variable threads index 1\n" + "\n".join(lines) + "\n")
    return path, lines[thermo + len(extra) + 2].split()[2:]  # thermo keywords, in column order


def timing(text, name):
    m = re.search(r"%s\s+time \(%%\) = ([0-9.eE+-]+)" % name, text)
    return float(m.group(1)) if m else float("nan")


def last_thermo(text, columns):
    """The last row of the last thermo table, by thermo keyword (the header drops v_/c_ prefixes)."""
    row = None
    for block in re.findall(r"^\s*Step\s.*?(?=^Loop time)", text, re.S | re.M):
        row = block.strip().splitlines()[-1].split()
    if row is None or len(row) != len(columns):
        sys.exit("no thermo row with the %d columns %s in the log" % (len(columns), " ".join(columns)))
    return dict(zip(columns, row))


def cpu_jiffies():
    """(busy, total) CPU seconds of the whole machine since boot, from /proc/stat (None elsewhere)."""
    try:
        with open("/proc/stat") as f:
            v = [int(x) for x in f.readline().split()[1:]]
    except OSError:
        return None
    hz = os.sysconf("SC_CLK_TCK")
    idle = v[3] + (v[4] if len(v) > 4 else 0)  # idle + iowait
    return (sum(v[:8]) - idle) / hz, sum(v[:8]) / hz


def wait_idle(a):
    """Wait (at most --wait-max s) until the machine's other load is below --wait-busy cores over 1 s;
    returns the busy cores of the last sample (nan without /proc/stat)."""
    deadline = time.monotonic() + a.wait_max
    while True:
        j0 = cpu_jiffies()
        time.sleep(1.0)
        j1 = cpu_jiffies()
        if j0 is None or j1 is None:
            return float("nan")
        busy = (j1[0] - j0[0]) / max(1e-9, (j1[1] - j0[1]) / os.cpu_count())
        if busy <= a.wait_busy or time.monotonic() > deadline:
            return busy


def run(a, wd, cfg, rep):
    nx, s, deckvars, grid, ranks, threads = cfg
    deck, columns = deck_for(wd, grid, a.neigh_every, a.processors)
    log = os.path.join(wd, "log.nx%d.%s.r%d.t%d.%d" % (nx, grid, ranks, threads, rep))
    cmd = [os.path.abspath(a.exe), "-in", deck, "-echo", "none", "-log", log, "-var", "threads", str(threads),
           "-var", "n", str(a.steps), "-var", "nx", str(nx), "-var", "dumpevery", str(10 * a.steps),
           "-var", "th", str(a.steps), "-var", "method", a.method, "-var", "meshdir", meshes(wd, s)]
    for name, value in deckvars.items():
        cmd += ["-var", name, value]
    for kv in a.var:
        name, _, value = kv.partition("=")
        cmd += ["-var", name, value]
    if ranks > 1 or a.always_mpi:
        cmd = [a.mpiexec] + a.mpiexec_flags.split() + ["-np", str(ranks)] + cmd
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    if a.keep:
        print("(in %s) %s" % (wd, " ".join(cmd)), flush=True)
    busy_before = wait_idle(a) if a.wait_busy < os.cpu_count() else float("nan")
    load = os.getloadavg()[0]
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    j0 = cpu_jiffies()
    start = time.monotonic()
    subprocess.run(cmd, cwd=wd, check=True, stdout=subprocess.DEVNULL, env=env)
    wall = time.monotonic() - start
    j1 = cpu_jiffies()
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    # cores that other processes used during the run (machine busy time minus this run's CPU time)
    others = (j1[0] - j0[0] - cpu) / wall if j0 and j1 else float("nan")
    text = open(log).read()
    loop = float(re.search(r"Loop time of ([0-9.eE+-]+)", text).group(1))
    builds = int(re.search(r"Neighbor list builds = (\d+)", text).group(1))
    th = last_thermo(text, columns)
    row = dict(nx=nx, grains=nx ** 3, scale=s, grid=grid, ranks=ranks, threads=threads, repeat=rep, loop_s=loop,
               pair_s=timing(text, "Pair"), neigh_s=timing(text, "Neigh"), comm_s=timing(text, "Comm"),
               builds=builds, s_per_step=loop / a.steps, contacts=int(float(th["v_ncont"])),
               zmin=float(th["v_zmin"]), zmean=float(th["v_zm"]), zmax=float(th["v_zmax"]), load1=load,
               busy_before=busy_before, process_wall_s=wall, process_cpu_s=cpu, cores_used=cpu / wall,
               others_cores=max(0.0, others))
    for name, k in TREESTATS:
        row[name] = float(th["c_ts[%d]" % k]) if grid != "none" else float("nan")
    return row


KEYS = ["nx", "grains", "scale", "grid", "ranks", "threads", "repeat", "loop_s", "pair_s", "neigh_s", "comm_s",
        "builds", "s_per_step", "contacts", "zmin", "zmean", "zmax"] + [n for n, _ in TREESTATS] + \
       ["load1", "busy_before", "process_wall_s", "process_cpu_s", "cores_used", "others_cores"]


def fmt(v):
    return ("%.6g" % v) if isinstance(v, float) else str(v)


def plot(out, steps, repeats, neigh_every):
    """Draws OUT.png from OUT_summary.csv: per configuration the wall time per step split into
    pair, neighbour and the rest, with the speed-up over the first configuration."""
    import csv
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    if os.path.exists(out + "_summary.csv"):
        summary = [{k: (v if k == "grid" else float(v)) for k, v in row.items()}
                   for row in csv.DictReader(open(out + "_summary.csv"))]
    else:  # only the per-run CSV (e.g. written before the summary existed): its medians
        runs = list(csv.DictReader(open(out + ".csv")))
        keys = list(dict.fromkeys((int(r["nx"]), r.get("grid", "none"), int(r["ranks"]), int(r["threads"]))
                                  for r in runs))
        summary = []
        for nx, grid, ranks, threads in keys:
            mine = [r for r in runs if (int(r["nx"]), r.get("grid", "none"), int(r["ranks"]),
                                        int(r["threads"])) == (nx, grid, ranks, threads)]
            med = {k: statistics.median(float(r.get(k, 0.0)) for r in mine) for k in ("s_per_step", "pair_s", "neigh_s")}
            summary.append(dict(med, nx=nx, grid=grid, ranks=ranks, threads=threads))
        for m in summary:
            base = next(b for b in summary if b["nx"] == m["nx"])
            m["speedup"] = base["s_per_step"] / m["s_per_step"]
    nxs = list(dict.fromkeys(int(m["nx"]) for m in summary))
    per = max(len([m for m in summary if m["nx"] == nx]) for nx in nxs)
    fig, axes = plt.subplots(1, len(nxs), figsize=(max(4.5, 1.1 * per + 2.0) * len(nxs), 4.4), squeeze=False)
    for ax, nx in zip(axes[0], nxs):
        ms = [m for m in summary if m["nx"] == nx]
        x = range(len(ms))
        pair = [m["pair_s"] / steps for m in ms]
        neigh = [m["neigh_s"] / steps for m in ms]
        rest = [m["s_per_step"] - p - n for m, p, n in zip(ms, pair, neigh)]
        ax.bar(x, pair, color="tab:blue", label="pair (triangle checks, forces)")
        ax.bar(x, neigh, bottom=pair, color="tab:orange", label="neighbour lists")
        ax.bar(x, rest, bottom=[p + n for p, n in zip(pair, neigh)], color="tab:gray",
               label="rest (communication, integration)")
        for i, m in enumerate(ms):
            ax.text(i, m["s_per_step"], "%.2fx" % m["speedup"], ha="center", va="bottom", fontsize=8)
        ax.set_xticks(list(x))
        grids = any(m["grid"] != "none" for m in summary)
        ax.set_xticklabels(["%d rank%s\n%d thread%s%s" % (m["ranks"], "s" * (m["ranks"] > 1), m["threads"],
                                                          "s" * (m["threads"] > 1),
                                                          ("\nno grid fix" if m["grid"] == "none" else "\ngrid " + m["grid"])
                                                          if grids else "")
                            for m in ms], fontsize=8)
        ax.set_xlabel("MPI ranks, pair_style trimesh threads per rank" + (", fix spacetree grid" if grids else ""))
        ax.set_title("%d grains (nx %d); label: speed-up over the first bar" % (nx ** 3, nx), fontsize=9)
        ax.set_ylabel("wall s per step (median of %d)" % repeats)
        ax.set_ylim(0, 1.45 * max(m["s_per_step"] for m in ms))  # room for the legend above the bars
        ax.legend(fontsize=7, loc="upper left", framealpha=0.9)
    fig.suptitle("hopper deck, %d steps%s" % (steps, ", lists rebuilt every %d" % neigh_every if neigh_every else ""),
                 fontsize=9)
    fig.tight_layout()
    fig.savefig(out + ".png", dpi=120)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe")
    ap.add_argument("--replot", action="store_true",
                    help="only redraw OUT.png from OUT_summary.csv, or from the medians of OUT.csv without it "
                         "(give --out, --steps, --repeats as measured)")
    ap.add_argument("--sizes", type=ints, default=[1000], help="grain counts (nx = round(N^(1/3)))")
    ap.add_argument("--nx", type=ints, default=None, help="lattice sides instead of --sizes")
    ap.add_argument("--threads", type=ints, default=[1, 2])
    ap.add_argument("--ranks", type=ints, default=[1, 2])
    ap.add_argument("--grids", type=names, default=["none"], help="none,regular,adaptive,reluctant")
    ap.add_argument("--neigh-every", type=int, default=0,
                    help="N > 0: rebuild the neighbour lists every N steps (neigh_modify every N check no)")
    ap.add_argument("--processors", default="* * 1",
                    help="rank grid of a `processors` line before the box ('deck': none, LIGGGHTS' own choice)")
    ap.add_argument("--wait-busy", type=float, default=1e9, metavar="CORES",
                    help="before each run wait until the machine's busy cores (1 s sample) are at most CORES")
    ap.add_argument("--wait-max", type=float, default=120.0, help="longest wait of --wait-busy, seconds")
    ap.add_argument("--steps", type=int, default=200)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--method", default="hybrid")
    ap.add_argument("--mpiexec", default="mpirun")
    ap.add_argument("--mpiexec-flags", default="--oversubscribe")
    ap.add_argument("--always-mpi", action="store_true", help="start 1-rank runs through mpiexec too")
    ap.add_argument("--var", action="append", default=[], metavar="NAME=VALUE",
                    help="further deck variable, e.g. --var zlo=0.05 --var v0=2.0 (repeatable, wins over presets)")
    ap.add_argument("--keep", action="store_true", help="keep the working directory (decks, logs, meshes) and print every run's command line")
    ap.add_argument("--out", default=os.path.join(ROOT, "bench", "results", "hopper_scaling"))
    a = ap.parse_args()
    if a.replot:
        plot(a.out, a.steps, a.repeats, a.neigh_every)
        return
    if not a.exe:
        ap.error("--exe is required (unless --replot)")

    nxs = a.nx if a.nx else [int(round(n ** (1.0 / 3.0))) for n in a.sizes]
    wd = tempfile.mkdtemp(prefix="hopper_scaling_")
    configs = []
    for nx in nxs:
        s, deckvars = lattice(nx)
        configs += [(nx, s, deckvars, g, r, t) for g in a.grids for r in a.ranks for t in a.threads]
    rows = []
    os.makedirs(os.path.dirname(os.path.abspath(a.out)), exist_ok=True)
    for rep in range(a.repeats):
        for cfg in configs:
            row = run(a, wd, cfg, rep)
            rows.append(row)
            with open(a.out + ".csv", "w") as f:  # after every run: an interrupted sweep keeps its rows
                f.write(",".join(KEYS) + "\n")
                for r in rows:
                    f.write(",".join(fmt(r[k]) for k in KEYS) + "\n")
            print("nx %d (%d grains) grid %s ranks %d threads %d run %d: %.4f s/step (pair %.3f, neigh %.3f of "
                  "%.3f s, %d builds), %.2f cores used, others %.2f cores, load %.2f" %
                  (cfg[0], row["grains"], cfg[3], cfg[4], cfg[5], rep, row["s_per_step"], row["pair_s"],
                   row["neigh_s"], row["loop_s"], row["builds"], row["cores_used"], row["others_cores"],
                   row["load1"]), flush=True)

    def median(c, k):
        """Median of column k over the repetitions of configuration c (nx, grid, ranks, threads)."""
        return statistics.median(row[k] for row in rows
                                 if (row["nx"], row["grid"], row["ranks"], row["threads"]) == (c[0], c[3], c[4], c[5]))

    summary = []
    for c in configs:
        nx, _, _, g, r, t = c
        base = next(b for b in configs if b[0] == nx and b[3] == a.grids[0] and b[4] == a.ranks[0]
                    and b[5] == a.threads[0])
        m = {k: median(c, k) for k in ("s_per_step", "pair_s", "neigh_s", "loop_s", "builds", "cores_used", "others_cores",
                                       "load1", "contacts", "zmin", "zmean", "zmax") + tuple(n for n, _ in TREESTATS)}
        m.update(nx=nx, grains=nx ** 3, grid=g, ranks=r, threads=t, speedup=median(base, "s_per_step") / m["s_per_step"])
        summary.append(m)
        print("median nx %d grid %s ranks %d threads %d: %.4f s/step (pair %.3f, neigh %.3f s), speed-up vs %s "
              "%dr x %dt: %.2fx, %.2f cores used, contacts %d, grain z %.3f..%.3f" %
              (nx, g, r, t, m["s_per_step"], m["pair_s"], m["neigh_s"], a.grids[0], a.ranks[0], a.threads[0],
               m["speedup"], m["cores_used"], m["contacts"], m["zmin"], m["zmax"]))
    skeys = ["nx", "grains", "grid", "ranks", "threads", "s_per_step", "speedup", "pair_s", "neigh_s", "loop_s",
             "builds", "contacts", "zmin", "zmean", "zmax"] + [n for n, _ in TREESTATS] + ["cores_used", "others_cores", "load1"]
    with open(a.out + "_summary.csv", "w") as f:
        f.write(",".join(skeys) + "\n")
        for m in summary:
            f.write(",".join(fmt(m[k]) for k in skeys) + "\n")

    plot(a.out, a.steps, a.repeats, a.neigh_every)
    print("wrote %s.csv, %s_summary.csv, %s.png" % (a.out, a.out, a.out))
    if a.keep:
        print("runs in", wd)
    else:
        shutil.rmtree(wd)


if __name__ == "__main__":
    main()
