#!/usr/bin/env python3
"""Neighbour-search scaling benchmark: `neighbor ... spacetree` vs stock `neighbor ... bin`.

Dense bidisperse packs (scripts/gen_pack.py bidisperse): small spheres d = 1 mm on a jittered
cubic lattice (spacing 1.1 mm, jitter +-0.04 mm, so no overlaps), big spheres of d = R mm on a
coarse lattice, lattice sites overlapping a big one removed; six primitive walls at the box
bounds; Hertz + tangential history; skin 0.1 mm; `neigh_modify every 10 check no`; 1 rank by
default.  Deck: inputs/bench/in.neighbor_bench.

Pack per R (chosen to keep the atom counts near those of shared/notes/anchors.md and within
<= 200k atoms for R = 50, <= 800k for R = 100):

    R     lattice     box      bigs   atoms (about)
    1     30^3        33 mm    0      27 000
    10    30^3        33 mm    8      22 800   (2x2x2 bigs)
    20    40^3        44 mm    1      60 400
    50    60^3        66 mm    1      164 000
    100   100^3       110 mm   1      595 000

Timing: LIGGGHTS' `Neigh time` (run phase only: the setup build before step 0 is not in it, and
verlet.cpp resets the build counter after setup) divided by `Neighbor list builds` (builds during
the run: steps / every).  `Neigh time` includes the pre_neighbor fixes and the list build.
Peak RSS from `/usr/bin/time -v` (maximum resident set size of the largest process).

bin is skipped when its estimated run time exceeds --skip-bin-above seconds, except that R values
in --bin-single-R are measured with a single rebuild (steps = every) as long as that is estimated
below --max-bin-seconds.  Estimate per rebuild: N * 0.3 us + C * t_c with C = N * min(N, n V) the
candidate pairs a bin build examines (V: the +-2-bin stencil of bins of half the largest cutoff,
about 0.6 (2.5 cutoff)^3, clipped to the box) and t_c = 2.5 ns, recalibrated from every measured bin
run whose candidate work dominates.  Setup builds one more list before step 0 (not in Neigh time).

Writes bench/results/neighbor_scaling.csv (+ .png) and prints a table with the speed-up.
"""

import argparse
import csv
import math
import os
import re
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
GEN = os.path.join(ROOT, "scripts", "gen_pack.py")
DECK = os.path.join(ROOT, "inputs", "bench", "in.neighbor_bench")

D_SMALL = 1e-3
GAP = 0.1            # lattice spacing = d (1 + GAP)
SKIN = 1e-4
PACKS = {            # R -> (lattice sites per dimension, number of bigs)
    1: (30, 0),
    10: (30, 8),
    20: (40, 1),
    50: (60, 1),
    100: (100, 1),
}
NS_PER_CANDIDATE = 2.5   # bin cost model: t = N * US_PER_ATOM + candidates * NS_PER_CANDIDATE
US_PER_ATOM = 0.3        # (priors; the candidate cost is recalibrated from each measured bin run)

COLUMNS = ["R", "atoms", "style", "rebuilds", "ms_per_rebuild", "us_per_atom_per_rebuild", "neighbours",
           "peak_rss_mb", "total_s", "steps", "note"]


def pack_for(R):
    if R in PACKS:
        return PACKS[R]
    # other R: a box of at least 1.3 R lattice spacings holding one big sphere
    n = max(30, int(math.ceil(1.3 * R / (1 + GAP))) + 2)
    return (n, 1 if R > 1 else 0)


def generate(R, workdir, python):
    n, K = pack_for(R)
    out = os.path.join(workdir, "bidisperse_R%g.data" % R)
    args = ["bidisperse", "--d", repr(D_SMALL), "--R", repr(float(R)), "--n", str(n), "--K", str(K),
            "--gap", repr(GAP), "--boundary", "f", "--vel", "0.05", "--seed", "2024", "--out", out]
    if K == 1:
        args += ["--big-at", "0.5", "0.5", "0.5"]
    if os.path.exists(out):
        with open(out) as f:
            f.readline()
            m = re.match(r"# atoms: (\d+)", f.readline())
            cmdline = f.readline()
        if m and " ".join(args[:-2]) in cmdline:
            return out, int(m.group(1))
    r = subprocess.run([python, GEN] + args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       universal_newlines=True)
    if r.returncode != 0:
        sys.exit("generator failed:\n" + r.stdout)
    print("  " + r.stdout.strip())
    m = re.search(r": (\d+) atoms", r.stdout)
    return out, int(m.group(1))


def run_liggghts(exe, mpiexec, mpiflags, np, data, style, steps, every, logpath, timeout, extra_vars):
    cmd = ["/usr/bin/time", "-v"]
    if np > 1:
        cmd += [mpiexec] + mpiflags + ["-np", str(np)]
    if shutil.which("stdbuf"):  # errors raised on one rank reach only the screen before MPI_Abort
        cmd += ["stdbuf", "-oL", "-eL"]
    cmd += [exe, "-in", DECK, "-log", logpath, "-echo", "none",
            "-var", "nstyle", style, "-var", "data", data, "-var", "nsteps", str(steps),
            "-var", "every", str(every), "-var", "skin", repr(SKIN)]
    for k, v in extra_vars.items():
        cmd += ["-var", k, str(v)]
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               OMPI_MCA_rmaps_base_oversubscribe="1")
    t0 = time.time()
    try:
        r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True,
                           errors="replace", env=env, timeout=timeout)
        out, rc = r.stdout, r.returncode
    except subprocess.TimeoutExpired as e:
        return {"error": "timeout after %.0f s" % timeout}
    wall = time.time() - t0
    log = open(logpath, errors="replace").read() if os.path.exists(logpath) else ""
    res = {"total_s": wall, "cmd": " ".join(cmd)}
    if rc != 0:
        errs = [l for l in (log + out).splitlines() if "ERROR" in l]
        res["error"] = "rc=%d %s" % (rc, "; ".join(errs[:2]))
        return res
    m = re.search(r"Maximum resident set size \(kbytes\): (\d+)", out)
    res["peak_rss_mb"] = int(m.group(1)) / 1024.0 if m else float("nan")
    m = re.search(r"Neigh time \(%\) = (\S+)", log)
    res["neigh_s"] = float(m.group(1)) if m else float("nan")
    m = re.search(r"Neighbor list builds = (\d+)", log)
    res["builds"] = int(m.group(1)) if m else 0
    m = re.search(r"Total # of neighbors = (\S+)", log)
    res["neighbours"] = int(float(m.group(1))) if m else -1
    m = re.search(r"Loop time of (\S+) on (\d+) procs for (\d+) steps with (\d+) atoms", log)
    if m:
        res["loop_s"] = float(m.group(1))
        res["atoms"] = int(m.group(4))
    return res


def bin_work(R, atoms):
    """Candidate pairs a stock bin build examines: every atom scans the stencil (bins of half the
    largest cutoff, +-2 bins, culled to a sphere-ish volume) clipped to the box."""
    n, K = pack_for(R)
    L = n * D_SMALL * (1 + GAP)
    cut = (R if K else 1) * D_SMALL + SKIN
    stencil = min(1.0, 0.6 * (2.5 * cut) ** 3 / L ** 3)
    return atoms * atoms * stencil


def plot(rows, results, np_, every):
    """Draws neighbor_scaling.png from the rows of neighbor_scaling.csv: ms per rebuild of both
    styles against the size ratio, with the atom counts and bin's time over spacetree's."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("(matplotlib not available: no plot; run with /usr/bin/python3)")
        return
    timed = {style: {float(r["R"]): r for r in rows if r["style"] == style and r["ms_per_rebuild"] != ""}
             for style in ("spacetree", "bin")}
    fig, ax = plt.subplots(figsize=(7, 4.6))
    for style, mk in (("spacetree", "o-"), ("bin", "s--")):
        pts = sorted(timed[style].items())
        if not pts:
            continue
        ax.plot([R for R, _ in pts], [float(r["ms_per_rebuild"]) for _, r in pts], mk, label="neighbor %s" % style)
        if style == "spacetree":
            for R, r in pts:
                ax.annotate("%d atoms" % int(r["atoms"]), (R, float(r["ms_per_rebuild"])), textcoords="offset points",
                            xytext=(4, -12), fontsize=7)
    for R, r in sorted(timed["bin"].items()):  # the claim: bin / spacetree per rebuild
        if R in timed["spacetree"]:
            ratio = float(r["ms_per_rebuild"]) / float(timed["spacetree"][R]["ms_per_rebuild"])
            ax.annotate("%.0fx" % ratio if ratio >= 10 else "%.1fx" % ratio, (R, float(r["ms_per_rebuild"])),
                        textcoords="offset points", xytext=(-8, 8), fontsize=8, color="tab:orange")
    ax.set_xscale("log")
    ax.set_yscale("log")
    top = max(float(r["ms_per_rebuild"]) for style in timed for r in timed[style].values())
    ax.set_ylim(top=4 * top)  # room for the labels above the highest point
    ax.set_xlabel("size ratio R (big / small diameter)")
    ax.set_ylabel("ms per neighbour-list rebuild")
    ax.set_title("Bidisperse packs, %d rank(s), lists rebuilt every %d steps;\n"
                 "orange labels: bin's time over spacetree's" % (np_, every), fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(loc="upper left")
    fig.tight_layout()
    png = os.path.join(results, "neighbor_scaling.png")
    fig.savefig(png, dpi=120)
    print("wrote %s" % png)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--R", type=float, nargs="+", default=[1, 10, 20, 50, 100])
    ap.add_argument("--steps", type=int, default=50, help="run length (steps)")
    ap.add_argument("--every", type=int, default=10, help="neigh_modify every")
    ap.add_argument("--np", type=int, default=1, help="MPI ranks")
    ap.add_argument("--skip-bin-above", type=float, default=60.0,
                    help="skip bin when its estimated run time exceeds this (s)")
    ap.add_argument("--bin-single-R", type=float, nargs="*", default=[20],
                    help="R values where bin is measured with one rebuild even above --skip-bin-above")
    ap.add_argument("--max-bin-seconds", type=float, default=400.0,
                    help="never start a bin run estimated longer than this (s)")
    ap.add_argument("--styles", nargs="+", default=["spacetree", "bin"])
    ap.add_argument("--spacetree-opts", default="", help="e.g. 'maxlevel 8'")
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "liggghts-spacetree"))
    ap.add_argument("--mpiexec", default=shutil.which("mpirun") or shutil.which("mpiexec"))
    ap.add_argument("--mpiexec-flags", default="--allow-run-as-root --oversubscribe")
    ap.add_argument("--python", default=sys.executable, help="interpreter for gen_pack.py")
    ap.add_argument("--workdir", default=os.path.join(HERE, "work"))
    ap.add_argument("--results", default=os.path.join(HERE, "results"))
    ap.add_argument("--timeout", type=float, default=1800.0, help="per LIGGGHTS run (s)")
    ap.add_argument("--replot", action="store_true",
                    help="only redraw the PNG from the stored CSV (give --np and --every as measured)")
    a = ap.parse_args()
    if a.replot:
        with open(os.path.join(a.results, "neighbor_scaling.csv"), newline="") as f:
            plot(list(csv.DictReader(f)), a.results, a.np, a.every)
        return 0

    if not os.path.isfile(a.exe):
        sys.exit("executable not found: %s (build first: scripts/build.sh)" % a.exe)
    os.makedirs(a.workdir, exist_ok=True)
    os.makedirs(a.results, exist_ok=True)
    mpiflags = a.mpiexec_flags.split()
    rows = []
    bin_ref = None  # seconds per candidate pair, calibrated on the measured bin runs
    check_nb = {}   # R -> (spacetree neighbours, steps) when bin ran fewer steps

    for R in a.R:
        Rn = int(R) if float(R).is_integer() else R
        print("R = %g" % R)
        data, atoms = generate(R, a.workdir, a.python)
        for style in a.styles:
            steps = a.steps
            note = ""
            if style == "bin":
                w = bin_work(R, atoms)
                t_build = US_PER_ATOM * 1e-6 * atoms + (bin_ref if bin_ref else NS_PER_CANDIDATE * 1e-9) * w
                builds = a.steps // a.every
                est_full = (builds + 1) * t_build
                est_single = 2 * t_build
                if est_full <= a.skip_bin_above:
                    pass
                elif est_single <= a.max_bin_seconds and any(abs(R - x) < 1e-9 for x in a.bin_single_R):
                    steps = a.every
                    note = "single rebuild (estimated full run %.0f s)" % est_full
                else:
                    note = "skipped: estimated %.1f s per rebuild, %.0f s for the run" % (t_build, est_full)
                    print("  bin: %s" % note)
                    rows.append(dict(R=Rn, atoms=atoms, style=style, rebuilds=0, ms_per_rebuild="",
                                     us_per_atom_per_rebuild="", neighbours="", peak_rss_mb="", total_s="",
                                     steps=0, note=note + " (%.2g ns per candidate pair%s)"
                                     % (1e9 * (bin_ref or NS_PER_CANDIDATE * 1e-9),
                                        ", calibrated on the measured bin runs" if bin_ref else ", prior")))
                    continue
                print("  bin: estimated %.2f s per rebuild%s" % (t_build, (", " + note) if note else ""))
            extra_st = {"nopts": a.spacetree_opts} if a.spacetree_opts else {}
            extra = extra_st if style == "spacetree" else {}
            log = os.path.join(a.workdir, "R%g_%s_np%d.log" % (R, style, a.np))
            res = run_liggghts(a.exe, a.mpiexec, mpiflags, a.np, data, style, steps, a.every, log,
                               a.timeout, extra)
            if "error" in res:
                print("  %s: FAILED %s (log %s)" % (style, res["error"], log))
                rows.append(dict(R=Rn, atoms=atoms, style=style, rebuilds=0, ms_per_rebuild="",
                                 us_per_atom_per_rebuild="", neighbours="", peak_rss_mb="",
                                 total_s="%.2f" % res.get("total_s", 0), steps=steps, note="failed: " + res["error"]))
                continue
            b = res["builds"]
            per = res["neigh_s"] / b if b else float("nan")
            if style == "bin" and b:
                rest = per - US_PER_ATOM * 1e-6 * atoms
                if rest > 0.5 * per:  # candidate work dominates: recalibrate the cost per candidate
                    bin_ref = rest / bin_work(R, atoms)
            row = dict(R=Rn, atoms=res.get("atoms", atoms), style=style, rebuilds=b,
                       ms_per_rebuild="%.4g" % (1e3 * per),
                       us_per_atom_per_rebuild="%.4g" % (1e6 * per / atoms),
                       neighbours=res["neighbours"], peak_rss_mb="%.1f" % res["peak_rss_mb"],
                       total_s="%.2f" % res["total_s"], steps=steps, note=note)
            rows.append(row)
            if style == "bin" and steps != a.steps and "spacetree" in a.styles:
                # bin ran fewer steps: list the same configuration with spacetree for the check
                chk = run_liggghts(a.exe, a.mpiexec, mpiflags, a.np, data, "spacetree", steps, a.every,
                                   log.replace("_bin_", "_spacetree_check_"), a.timeout, extra_st)
                check_nb[Rn] = (chk.get("neighbours", -1), steps)
            print("  %-9s %7d atoms  %3d rebuilds  %10.3f ms/rebuild  %8.3f us/atom/rebuild  %10d neighbours  "
                  "%8.1f MB  %7.1f s" % (style, row["atoms"], b, 1e3 * per, 1e6 * per / atoms, res["neighbours"],
                                          res["peak_rss_mb"], res["total_s"]))

    csv_path = os.path.join(a.results, "neighbor_scaling.csv")
    with open(csv_path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=COLUMNS)
        w.writeheader()
        for r in rows:
            w.writerow(r)
    print("\nwrote %s" % csv_path)

    # table with the speed-up
    print("\n%6s %8s %16s %16s %10s  %s" % ("R", "atoms", "spacetree ms/rb", "bin ms/rb", "speed-up",
                                              "neighbour count spacetree vs bin"))
    for R in a.R:
        Rn = int(R) if float(R).is_integer() else R
        st = [r for r in rows if r["R"] == Rn and r["style"] == "spacetree" and r["ms_per_rebuild"] != ""]
        bn = [r for r in rows if r["R"] == Rn and r["style"] == "bin" and r["ms_per_rebuild"] != ""]
        s = float(st[0]["ms_per_rebuild"]) if st else None
        bb = float(bn[0]["ms_per_rebuild"]) if bn else None
        sp = "%.1fx" % (bb / s) if (s and bb) else "-"
        nb = ""
        if st and bn:
            ref, label = st[0]["neighbours"], ""
            if Rn in check_nb:
                ref, label = check_nb[Rn][0], " (at step %d)" % check_nb[Rn][1]
            nb = ("equal" if ref == bn[0]["neighbours"] else "DIFFER %s/%s" % (ref, bn[0]["neighbours"])) + label
        atoms = (st or bn or [{"atoms": "?"}])[0]["atoms"]
        print("%6s %8s %16s %16s %10s  %s" % (Rn, atoms, "%.3f" % s if s else "-", "%.3f" % bb if bb else "-",
                                               sp, nb))

    plot(rows, a.results, a.np, a.every)
    return 0


if __name__ == "__main__":
    sys.exit(main())
