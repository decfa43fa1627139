#!/usr/bin/env python3
"""Neighbour build per rebuild: `neighbor ... spacetree` (LIGGGHTS 3.8 + spacetree-dem) against
LAMMPS `neighbor multi` (Debian's `lammps`, the best of a few `collection/interval` settings),
on every kind of size distribution, the runs interleaved, the neighbour counts asserted equal.

Scenes (generated here with scripts/gen_pack.py, or ported; all lengths in m, small d = 1 mm):

    bidisperse_R{1,10,20,50,100}  small spheres on a jittered lattice (spacing 1.1 d) plus big ones
                                  of diameter R d (as bench/neighbor_scaling.py), skin 0.1 d
    big_sphere_R60                one sphere of 60 d in such a lattice (62^3 sites), skin 0.5 d:
                                  thousands of small ones within the skin of its surface
    powerlaw_100_f{50,30,10}      number of spheres ~ d^-3, d in [1, 100] mm, random sequential
                                  placement, solid fraction 0.5 / 0.3 / 0.1, 40 000 spheres,
                                  skin 0.1 d
    powerlaw_1000_f{20,10}        the same for d in [1, 1000] mm (150 000 spheres; the biggest
                                  one, 1 m, is always included and holds most of the solid
                                  volume: 0.2 is the densest random placement reaches), solid
                                  fraction 0.2 / 0.1
    lammps_examples_powerlaw      LAMMPS' examples/multi/data.powerlaw (10 000 disks of diameter
                                  1..164 in a sheared 2-d packing) ported: lengths in mm, every
                                  centre at z = 0 of a 3-d box, fixed walls instead of the
                                  periodic triclinic cell, skin 1 mm as the deck's `neighbor 1`

Every scene runs `neigh_modify every 10 check no` with the particles held in place (no
integrator: both codes rebuild their lists from scratch at every rebuild, and the two codes
see bit-identical positions, so their neighbour counts must agree exactly): LIGGGHTS (inputs/bench/in.neighbor_bench)
with `spacetree` and, at R = 1, stock `bin`; LAMMPS (inputs/bench/in.neighbor_lammps) with
`neighbor multi` under each collection setting (collections by size: the two sizes of a
bidisperse pack, or geometric size intervals from the smallest to the biggest diameter, one
collection per factor 3, 5, 10 or 30 in size), newton on (LAMMPS' faster mode; without ghosts
the half lists are the same).
The variants of one scene run interleaved, --repeats times; medians are reported. Time per
rebuild: the code's `Neigh` time of the run (LIGGGHTS: pre_neighbor fixes + list build, with
the contact history copied into the list; LAMMPS: the list build only, its history copy is
`fix NEIGH_HISTORY` in `Modify`) over `Neighbor list builds`. Memory: peak RSS of the run
minus peak RSS of the same deck stopped before `run` (data read, styles set up).

Writes bench/results/neighbor_vs_lammps_runs.csv (every run), neighbor_vs_lammps.csv (medians
and ratios per scene) and neighbor_vs_lammps.png; prints the table. `uptime` is recorded with
every run.
"""

import argparse
import csv
import math
import os
import re
import shutil
import statistics
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
GEN = os.path.join(ROOT, "scripts", "gen_pack.py")
DECK_LIGGGHTS = os.path.join(ROOT, "inputs", "bench", "in.neighbor_bench")
DECK_LAMMPS = os.path.join(ROOT, "inputs", "bench", "in.neighbor_lammps")
LAMMPS_POWERLAW = "/usr/share/lammps/examples/multi/data.powerlaw"

D = 1e-3

# name -> how to make it. gen: gen_pack.py arguments (without --out); skin in m; steps of the
# run (10 steps per rebuild); one/page: neigh_modify one/page for both codes.
SCENES = {
    "bidisperse_R1": dict(gen=["bidisperse", "--R", "1", "--n", "30", "--K", "0"], skin=1e-4, steps=100, bin=True),
    "bidisperse_R10": dict(gen=["bidisperse", "--R", "10", "--n", "30", "--K", "8"], skin=1e-4, steps=100),
    "bidisperse_R20": dict(gen=["bidisperse", "--R", "20", "--n", "40", "--K", "1", "--big-at", "0.5", "0.5", "0.5"],
                           skin=1e-4, steps=50),
    "bidisperse_R50": dict(gen=["bidisperse", "--R", "50", "--n", "60", "--K", "1", "--big-at", "0.5", "0.5", "0.5"],
                           skin=1e-4, steps=50),
    "bidisperse_R100": dict(gen=["bidisperse", "--R", "100", "--n", "100", "--K", "1", "--big-at", "0.5", "0.5",
                                 "0.5"], skin=1e-4, steps=30),
    "big_sphere_R60": dict(gen=["bidisperse", "--R", "60", "--n", "62", "--K", "1", "--big-at", "0.5", "0.5", "0.5"],
                           skin=5e-4, steps=50, one=20000, page=200000),
    "powerlaw_100_f50": dict(gen=["continuous", "--law", "power", "--exponent", "3", "--rmin", "0.5e-3",
                                    "--rmax", "50e-3", "--n", "40000", "--fill", "0.5"], skin=1e-4, steps=100),
    "powerlaw_100_f30": dict(gen=["continuous", "--law", "power", "--exponent", "3", "--rmin", "0.5e-3",
                                  "--rmax", "50e-3", "--n", "40000", "--fill", "0.3"], skin=1e-4, steps=100),
    "powerlaw_100_f10": dict(gen=["continuous", "--law", "power", "--exponent", "3", "--rmin", "0.5e-3",
                                     "--rmax", "50e-3", "--n", "40000", "--fill", "0.1"], skin=1e-4, steps=100),
    "powerlaw_1000_f20": dict(gen=["continuous", "--law", "power", "--exponent", "3", "--rmin", "0.5e-3",
                                   "--rmax", "0.5", "--n", "150000", "--fill", "0.2"], skin=1e-4, steps=50),
    "powerlaw_1000_f10": dict(gen=["continuous", "--law", "power", "--exponent", "3", "--rmin", "0.5e-3",
                                      "--rmax", "0.5", "--n", "150000", "--fill", "0.1"], skin=1e-4, steps=50),
    "lammps_examples_powerlaw": dict(port=LAMMPS_POWERLAW, skin=1e-3, steps=100),
}
GEOMETRIC_FACTORS = (3.0, 5.0, 10.0, 30.0)


def sh(cmd, timeout=None):
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True,
                       errors="replace", timeout=timeout)
    return r.returncode, r.stdout


def load_average():
    try:
        return float(open("/proc/loadavg").read().split()[0])
    except (OSError, ValueError, IndexError):
        return float("nan")


def read_diameters(path):
    """Diameters of the Atoms section of a LIGGGHTS/LAMMPS data file (id type d density x y z)."""
    ds, section = [], None
    with open(path) as f:
        for line in f:
            s = line.strip()
            if not s or s.startswith("#"):
                continue
            if s[0].isalpha():
                section = s.split()[0]
                continue
            if section == "Atoms":
                ds.append(float(s.split()[2]))
    return ds


def port_lammps_powerlaw(src, out):
    """examples/multi/data.powerlaw as a 3-d LIGGGHTS/LAMMPS data file in m (lj length 1 -> 1 mm)."""
    atoms, box, section = [], {}, None
    with open(src) as f:
        for line in f:
            s = line.split("#")[0].strip()
            if not s:
                continue
            w = s.split()
            if len(w) == 4 and w[2].endswith("lo"):
                box[w[2][0]] = (float(w[0]), float(w[1]))
                continue
            if s[0].isalpha():
                section = w[0]
                continue
            if section == "Atoms" and len(w) >= 7:
                atoms.append((int(w[0]), float(w[2]), float(w[4]), float(w[5])))
    s = 1e-3
    dmax = max(a[1] for a in atoms) * s
    half = 0.5 * dmax * 1.01
    with open(out, "w") as f:
        f.write("LIGGGHTS data file: %s ported to 3-d (lj length 1 = 1 mm, z = 0, fixed walls)\n" % src)
        f.write("# atoms: %d\n\n%d atoms\n1 atom types\n\n" % (len(atoms), len(atoms)))
        f.write("%r %r xlo xhi\n%r %r ylo yhi\n%r %r zlo zhi\n\nAtoms\n\n"
                % (box["x"][0] * s, box["x"][1] * s, box["y"][0] * s, box["y"][1] * s, -half, half))
        for k, (i, d, x, y) in enumerate(atoms):
            f.write("%d 1 %r 2500.0 %r %r 0.0\n" % (k + 1, d * s, x * s, y * s))
    return len(atoms)


def make_scene(name, spec, workdir, python):
    out = os.path.join(workdir, name + ".data")
    if not os.path.exists(out):
        if "port" in spec:
            if not os.path.exists(spec["port"]):
                return None, "missing %s (apt-get install lammps-data)" % spec["port"]
            port_lammps_powerlaw(spec["port"], out + ".tmp")
        else:
            args = spec["gen"] + ["--d", repr(D)] if spec["gen"][0] == "bidisperse" else list(spec["gen"])
            args += ["--boundary", "f", "--vel", "0.05", "--seed", "2024", "--out", out + ".tmp"]
            rc, text = sh([python, GEN] + args)
            if rc != 0:
                return None, "generator failed: " + text[-500:]
            print("  " + text.strip().splitlines()[-1])
        os.replace(out + ".tmp", out)
    return out, ""


def lammps_settings(diameters):
    """`neigh_modify collection/interval ...` settings to try for these sizes."""
    sizes = sorted(set(diameters))
    dmin, dmax = sizes[0], sizes[-1]
    top = dmax * 1.001
    if len(sizes) <= 2:  # one or two sizes: one collection per size
        bounds = [dmin * 1.001] + ([top] if len(sizes) == 2 else [])
        return ["collection/interval %d %s" % (len(bounds), " ".join("%.9g" % b for b in bounds))]
    out = []
    for k in GEOMETRIC_FACTORS:
        bounds, c = [], dmin * k
        while c < dmax:
            bounds.append(c)
            c *= k
        bounds.append(top)
        out.append("collection/interval %d %s" % (len(bounds), " ".join("%.9g" % b for b in bounds)))
    return out


def parse_log(text):
    res = {}
    m = re.search(r"Neigh time \(%\) = (\S+)", text)  # LIGGGHTS
    if m:
        res["neigh_s"] = float(m.group(1))
    m = re.search(r"^Neigh\s+\|\s*(\S+)\s*\|\s*(\S+)", text, re.M)  # LAMMPS: min | avg | ...
    if m:
        res["neigh_s"] = float(m.group(2))
    m = re.search(r"Neighbor list builds = (\d+)", text)
    res["builds"] = int(m.group(1)) if m else 0
    m = re.search(r"Total # of neighbors = (\S+)", text)
    res["neighbours"] = int(float(m.group(1))) if m else -1
    m = re.search(r"Loop time of \S+ on \d+ procs for \d+ steps with (\d+) atoms", text)
    res["atoms"] = int(m.group(1)) if m else 0
    m = re.search(r"Maximum resident set size \(kbytes\): (\d+)", text)
    res["peak_rss_mb"] = int(m.group(1)) / 1024.0 if m else float("nan")
    return res


def run(variant, data, spec, workdir, a, baseline=False):
    code, style, setting = variant
    logpath = os.path.join(workdir, "run.log")
    common = ["-var", "data", data, "-var", "skin", repr(spec["skin"]), "-var", "nsteps", str(spec["steps"]),
              "-var", "every", "10", "-var", "one", str(spec.get("one", 2000)), "-var", "page",
              str(spec.get("page", 100000)), "-var", "integrate", "0",
              "-var", "baseline", "1" if baseline else "0"]
    if code == "liggghts":
        cmd = [a.exe, "-in", DECK_LIGGGHTS, "-var", "nstyle", style] + common
    else:
        cmd = [a.lmp, "-in", DECK_LAMMPS, "-var", "nstyle", style, "-var", "coll", setting] + common
    cmd = ["/usr/bin/time", "-v"] + cmd + ["-log", logpath, "-echo", "none", "-screen", "none"]
    if os.path.exists(logpath):
        os.remove(logpath)
    load = load_average()
    rc, out = sh(cmd, timeout=a.timeout)
    log = open(logpath, errors="replace").read() if os.path.exists(logpath) else ""
    res = parse_log(log + "\n" + out)
    res["load1"] = load
    if rc != 0 or (not baseline and not res.get("builds")):
        errs = [l for l in (log + out).splitlines() if "ERROR" in l]
        res["error"] = "rc=%d %s" % (rc, "; ".join(errs[:2]))
    return res


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scenes", nargs="+", default=list(SCENES), choices=list(SCENES))
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "liggghts-spacetree"))
    ap.add_argument("--lmp", default=shutil.which("lmp") or "lmp", help="LAMMPS executable")
    ap.add_argument("--python", default="/usr/bin/python3" if os.path.exists("/usr/bin/python3") else sys.executable,
                    help="interpreter for gen_pack.py")
    ap.add_argument("--workdir", default=os.path.join(HERE, "work"))
    ap.add_argument("--results", default=os.path.join(HERE, "results"))
    ap.add_argument("--tag", default="", help="suffix of the output files")
    ap.add_argument("--timeout", type=float, default=900.0, help="per run (s)")
    a = ap.parse_args()
    for exe in (a.exe, a.lmp):
        if not shutil.which(exe):
            sys.exit("not found: %s (build first: scripts/build.sh; LAMMPS: apt-get install lammps)" % exe)
    os.makedirs(a.workdir, exist_ok=True)
    os.makedirs(a.results, exist_ok=True)
    rc, uptime = sh(["uptime"])
    print("machine: %s" % uptime.strip())

    runs, summary = [], []
    for name in a.scenes:
        spec = SCENES[name]
        print("%s" % name)
        data, why = make_scene(name, spec, a.workdir, a.python)
        if not data:
            print("  skipped: " + why)
            continue
        diameters = read_diameters(data)
        variants = [("liggghts", "spacetree", "")]
        if spec.get("bin"):
            variants.append(("liggghts", "bin", ""))
        variants += [("lammps", "multi", s) for s in lammps_settings(diameters)]
        times = {v: [] for v in variants}
        counts, rss = {}, {}
        for rep in range(a.repeats):
            for v in variants:
                res = run(v, data, spec, a.workdir, a)
                row = dict(scene=name, atoms=res.get("atoms", len(diameters)), code=v[0], style=v[1], setting=v[2],
                           repeat=rep, builds=res.get("builds", 0), neighbours=res.get("neighbours", -1),
                           peak_rss_mb="%.1f" % res.get("peak_rss_mb", float("nan")), load1=res["load1"],
                           ms_per_rebuild="", error=res.get("error", ""))
                if "error" not in res:
                    per = res["neigh_s"] / res["builds"]
                    times[v].append(per)
                    counts.setdefault(v, res["neighbours"])
                    rss.setdefault(v, []).append(res["peak_rss_mb"])
                    row["ms_per_rebuild"] = "%.4g" % (1e3 * per)
                    print("  %-8s %-9s %-60s %9.3f ms/rebuild %10d neighbours  load %.2f"
                          % (v[0], v[1], v[2][:60], 1e3 * per, res["neighbours"], res["load1"]))
                else:
                    print("  %-8s %-9s %-60s FAILED %s" % (v[0], v[1], v[2][:60], res["error"]))
                runs.append(row)
        # memory the run adds over the set-up alone, per code
        base = {}
        for code in ("liggghts", "lammps"):
            res = run((code, "spacetree" if code == "liggghts" else "multi", ""), data, spec, a.workdir, a,
                      baseline=True)
            base[code] = res.get("peak_rss_mb", float("nan"))
        med = {v: statistics.median(t) for v, t in times.items() if t}
        st = variants[0]
        lammps = [v for v in med if v[0] == "lammps"]
        if st not in med or not lammps:
            print("  no comparison (failed runs)")
            continue
        best = min(lammps, key=lambda v: med[v])
        equal = all(counts[v] == counts[st] for v in counts)
        atoms = len(diameters)
        srow = dict(scene=name, atoms=atoms, neighbours=counts[st], counts_equal="yes" if equal else "NO",
                    spacetree_ms="%.4g" % (1e3 * med[st]), lammps_best_ms="%.4g" % (1e3 * med[best]),
                    lammps_best_setting=best[2], ratio="%.3f" % (med[st] / med[best]),
                    spacetree_us_per_atom="%.4g" % (1e6 * med[st] / atoms),
                    lammps_us_per_atom="%.4g" % (1e6 * med[best] / atoms),
                    spacetree_run_mb="%.1f" % (statistics.median(rss[st]) - base["liggghts"]),
                    lammps_run_mb="%.1f" % (statistics.median(rss[best]) - base["lammps"]),
                    bin_ms="", bin_run_mb="", repeats=a.repeats,
                    load1_median="%.2f" % statistics.median([r["load1"] for r in runs if r["scene"] == name]))
        binv = ("liggghts", "bin", "")
        if binv in med:
            srow["bin_ms"] = "%.4g" % (1e3 * med[binv])
            srow["bin_run_mb"] = "%.1f" % (statistics.median(rss[binv]) - base["liggghts"])
        summary.append(srow)
        print("  => spacetree %s ms, LAMMPS multi best %s ms (%s): ratio %s, %s us/atom; counts %s; run memory "
              "%s MB vs %s MB" % (srow["spacetree_ms"], srow["lammps_best_ms"], best[2], srow["ratio"],
                                  srow["spacetree_us_per_atom"], "equal" if equal else "DIFFER " + str(counts),
                                  srow["spacetree_run_mb"], srow["lammps_run_mb"]))
        if not equal:
            print("  ERROR: neighbour counts differ")

    tag = ("_" + a.tag) if a.tag else ""
    path = os.path.join(a.results, "neighbor_vs_lammps_runs%s.csv" % tag)
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(runs[0].keys()) if runs else ["scene"])
        w.writeheader()
        w.writerows(runs)
    path = os.path.join(a.results, "neighbor_vs_lammps%s.csv" % tag)
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(summary[0].keys()) if summary else ["scene"])
        w.writeheader()
        w.writerows(summary)
    print("\nwrote %s" % path)
    print("\n%-26s %8s %10s %10s %7s %9s %9s %6s" % ("scene", "atoms", "st ms", "lmp ms", "ratio", "st us/at",
                                                     "lmp us/at", "equal"))
    for r in summary:
        print("%-26s %8d %10s %10s %7s %9s %9s %6s" % (r["scene"], r["atoms"], r["spacetree_ms"], r["lammps_best_ms"],
                                                       r["ratio"], r["spacetree_us_per_atom"],
                                                       r["lammps_us_per_atom"], r["counts_equal"]))
    rc, uptime = sh(["uptime"])
    print("machine: %s" % uptime.strip())
    plot(summary, os.path.join(a.results, "neighbor_vs_lammps%s.png" % tag))
    return 0 if all(r["counts_equal"] == "yes" for r in summary) else 1


def plot(summary, png):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("(matplotlib not available: no plot; run with /usr/bin/python3)")
        return
    if not summary:
        return
    names = [r["scene"] for r in summary]
    y = list(range(len(names)))
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 0.45 * len(names) + 1.6), sharey=True)
    ax1.barh(y, [float(r["ratio"]) for r in summary], color="tab:blue")
    ax1.axvline(0.5, color="k", ls="--", lw=1, label="target 0.5")
    ax1.axvline(1.0, color="grey", ls=":", lw=1)
    ax1.set_xlabel("spacetree / LAMMPS multi (best setting), time per rebuild")
    ax1.set_yticks(y)
    ax1.set_yticklabels(names, fontsize=8)
    ax1.invert_yaxis()
    ax1.legend(loc="lower right", fontsize=8)
    h = 0.38
    ax2.barh([v - h / 2 for v in y], [float(r["spacetree_us_per_atom"]) for r in summary], h,
             label="spacetree", color="tab:blue")
    ax2.barh([v + h / 2 for v in y], [float(r["lammps_us_per_atom"]) for r in summary], h,
             label="LAMMPS multi (best)", color="tab:orange")
    ax2.axvline(0.3, color="k", ls="--", lw=1, label="target 0.3 us")
    ax2.set_xlabel("us per atom per rebuild (1 rank)")
    ax2.legend(loc="lower right", fontsize=8)
    fig.tight_layout()
    fig.savefig(png, dpi=120)
    print("wrote %s" % png)


if __name__ == "__main__":
    sys.exit(main())
