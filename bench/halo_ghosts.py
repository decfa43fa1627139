#!/usr/bin/env python3
"""Ghost atoms per owned atom of `neighbor ... spacetree halo levels` (ghosts per size class,
coarse first), beside LIGGGHTS' stock shell and LAMMPS `neighbor multi` + `comm_modify mode multi`.

  halo_ghosts.py --exe build/liggghts-spacetree [--lmp lmp] [--R 1,10,20,50] [--ranks 1,2,4,8]
                 [--project 64,512] [--timing-repeats 5] [--out bench/results/halo_ghosts]

Packs: periodic bidisperse (scripts/gen_pack.py bidisperse), small spheres d = 1 mm on a jittered
lattice (spacing 1.1 mm), big spheres of d = R mm (type 2) - the packs of bench/neighbor_scaling.py
with periodic boundaries:

    R     lattice   box     bigs   atoms (about)
    1     30^3      33 mm   0      27 000
    10    30^3      33 mm   8      22 800
    20    40^3      44 mm   1      60 400
    50    60^3      66 mm   1      164 000

Ghost counts (deck inputs/bench/in.halo_bench, `run 0`: the setup's exchange, ranks
oversubscribed, counts do not depend on cores) for every R and rank count:
  levels          neighbor 1e-4 spacetree (halo levels, the default)
  single          neighbor 1e-4 spacetree halo single: LIGGGHTS' stock shell r + r_max + skin
                  (the same ghosts as neighbor bin, liggghts.halo.single tests it; bin itself is
                  O(N^2) at R = 50)
  lammps_multi    LAMMPS (Debian lmp) neighbor multi, collection/interval by the two diameters,
                  comm_modify mode multi, newton off (what granular history needs in LIGGGHTS)
  lammps_reduce   the same with comm_modify ... reduce/multi, which LAMMPS allows only with
                  newton on (not possible with LIGGGHTS' granular history)
Totals from each log's Nlocal / Nghost statistics (average x ranks), per size class from
compute halo.

Projection (--project): a geometric model of the Cartesian ghost exchange, evaluated on the very
same pack. An atom with reach c lands in every subdomain (and periodic image) whose box lies
within L-infinity distance c of it; with uniform boxes of width w_d that is, per dimension, the
number of integers j with j w_d - c <= x_d <= (j+1) w_d + c, and the ghosts of an atom are the
product over the dimensions minus 1 (its own box). Reaches: stock r + r_max + skin; levels
(r + R_class) + skin, or, for a small atom that can touch a big one (|x - x_b| <= r + r_b + skin,
any periodic image), the L-infinity distance to that big one's owner box if larger. The model is
checked against the measured counts of every rank count (the `model` column next to `measured`)
and then evaluated for cubic grids of 64 (4x4x4) and 512 (8x8x8) subdomains of the same pack
(strong scaling). LAMMPS multi's shell per atom is that of the stock rule (its measured counts
equal single's), so its projection is single's.

Timing (--timing-repeats N > 0): the 1-rank periodic R = 50 pack, 200 steps, lists every 10
steps, levels and single alternating N times: LIGGGHTS' Comm time and its share of the loop
(medians), with the 1-minute load average before each run.

Writes OUT.csv (measured + model), OUT_projection.csv, OUT_timing.csv, OUT.png; --replot redraws
OUT.png from the CSVs; --remodel recomputes the model columns and the projection of OUT.csv.
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
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
GEN = os.path.join(ROOT, "scripts", "gen_pack.py")
DECK = os.path.join(ROOT, "inputs", "bench", "in.halo_bench")
LMP_DECK = os.path.join(ROOT, "inputs", "bench", "in.halo_lammps")
PACKS = {1: (30, 0), 10: (30, 8), 20: (40, 1), 50: (60, 1)}
D_SMALL, GAP, SKIN = 1e-3, 0.1, 1e-4
METHODS = ("levels", "single", "lammps_multi", "lammps_reduce")
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1", OMPI_MCA_btl_vader_single_copy_mechanism="none")


def ints(s):
    return [int(v) for v in s.split(",") if v]


def generate(R, work, python):
    n, K = PACKS[R]
    out = os.path.join(work, "halo_R%g.data" % R)
    args = ["bidisperse", "--d", repr(D_SMALL), "--R", repr(float(R)), "--n", str(n), "--K", str(K),
            "--gap", repr(GAP), "--big-type", "2", "--boundary", "p", "--vel", "0.05",
            "--seed", "2024", "--out", out]
    if K == 1:
        args += ["--big-at", "0.5", "0.5", "0.5"]
    if not os.path.exists(out):
        subprocess.run([python, GEN] + args, check=True, stdout=subprocess.DEVNULL)
        with open(out) as f:   # the decks' materials are per type pair: always 2 types
            text = f.read()
        with open(out, "w") as f:
            f.write(re.sub(r"^1 atom types$", "2 atom types", text, flags=re.M))
    return out


def read_pack(path):
    """-> box (lo, hi) per dim, list of (x, y, z, r)."""
    box, atoms, section = [None] * 3, [], None
    with open(path) as f:
        for line in f:
            s = line.split()
            if not s or s[0].startswith("#"):
                continue
            if len(s) == 4 and s[2].endswith("lo") and s[3].endswith("hi"):
                box["xyz".index(s[2][0])] = (float(s[0]), float(s[1]))
            elif s[0] in ("Atoms", "Velocities"):
                section = s[0]
            elif section == "Atoms" and len(s) >= 7:
                atoms.append((float(s[4]), float(s[5]), float(s[6]), 0.5 * float(s[2])))
    return box, atoms


def mpirun(np_, mpiexec):
    return [] if np_ == 1 else [mpiexec, "-np", str(np_)]


def run(cmd, log, timeout):
    t0 = time.time()
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True,
                       errors="replace", env=ENV, timeout=timeout)
    text = open(log, errors="replace").read() if os.path.exists(log) else ""
    if r.returncode != 0:
        sys.exit("run failed (rc %d): %s\n%s" % (r.returncode, " ".join(cmd), (text + r.stdout)[-3000:]))
    return text, time.time() - t0


def stats(text):
    procs = int(re.findall(r"on (\d+) procs", text)[-1])
    nlocal = float(re.findall(r"Nlocal:\s+(\S+) ave", text)[-1])
    nghost = float(re.findall(r"Nghost:\s+(\S+) ave", text)[-1])
    m = re.findall(r"(\d+) by (\d+) by (\d+) MPI processor grid", text)
    grid = tuple(int(g) for g in m[-1]) if m else (1, 1, 1)
    return round(nlocal * procs), round(nghost * procs), grid


def class_ghosts(text):
    """Ghosts per size class 0..11 from the last thermo row of in.halo_bench."""
    rows = [l.split() for l in text.splitlines()]
    heads = [i for i, r in enumerate(rows) if r and r[0] == "Step"]
    if not heads:
        return []
    cols = rows[heads[-1]]
    if "gh[9]" not in cols:
        return []
    last = None
    for r in rows[heads[-1] + 1:]:
        if len(r) == len(cols) and r[0].isdigit():
            last = r
    if not last:
        return []
    return [float(last[cols.index("gh[%d]" % (9 + 5 * k))]) for k in range(12)]


def measure(a, R, data, np_, method):
    log = os.path.join(a.work, "R%g_np%d_%s.log" % (R, np_, method))
    if method in ("levels", "single"):
        cmd = mpirun(np_, a.mpiexec) + [a.exe, "-in", DECK, "-log", log, "-echo", "none", "-screen", "none",
                                        "-var", "data", data, "-var", "nopts", "halo " + method]
    else:
        if not a.lmp:
            return None
        dbig = max(R, 1.1) * D_SMALL
        cmd = mpirun(np_, a.mpiexec) + [a.lmp, "-in", LMP_DECK, "-log", log, "-echo", "none", "-screen", "none",
                                        "-var", "data", data, "-var", "dsmall", repr(D_SMALL), "-var", "dbig",
                                        repr(dbig)]
        if method == "lammps_reduce":
            cmd += ["-var", "newton", "on", "-var", "reduce", "reduce/multi"]
    text, wall = run(cmd, log, a.timeout)
    owned, ghosts, grid = stats(text)
    return {"owned": owned, "ghosts": ghosts, "grid": grid, "classes": class_ghosts(text), "wall": wall}


# ---------------------------------------------------------------------------------------------
# the geometric model (numpy)

def model_ghosts(np, box, atoms, grid, rule):
    lo = np.array([b[0] for b in box])
    L = np.array([b[1] - b[0] for b in box])
    X = np.array([[a[0], a[1], a[2]] for a in atoms]) - lo
    r = np.array([a[3] for a in atoms])
    rmax = r.max()
    w = L / np.array(grid, dtype=float)
    if rule == "single":
        c = r + rmax + SKIN
    else:
        # classes of ratio 4 (halo_ratio's default) from r_max; own reach (r + R_class) + skin
        k = np.zeros(len(r), dtype=int)
        bound = rmax
        for _ in range(15):
            bound /= 4.0
            k += (r <= bound)
        R_class = np.zeros(len(r))
        for kk in np.unique(k):
            R_class[k == kk] = r[k == kk].max()
        c = r + R_class + SKIN
        # serve: a small atom touching a big one (an image of it) reaches the big one's owner box
        big = np.where(k == k.min())[0] if len(np.unique(k)) > 1 else []
        for b in big:
            xb = X[b]
            for sx in (-1, 0, 1):
                for sy in (-1, 0, 1):
                    for sz in (-1, 0, 1):
                        s = np.array([sx, sy, sz])
                        xi = xb + s * L
                        d = np.sqrt(((X - xi) ** 2).sum(axis=1))
                        touch = (d <= r + r[b] + SKIN) & (k != k[b])
                        if not s.any():   # b itself: not a ghost for the atoms of its own box
                            own = np.floor(xb / w)
                            touch &= ~(np.floor(X / w) == own).all(axis=1)
                        if not touch.any():
                            continue
                        # owner box of b, shifted to image s; b on a cut (within rounding):
                        # both boxes, the larger distance (as parallel::SubdomainGrid does)
                        cell = np.floor(xb / w)
                        near_cut = np.abs(xb / w - np.round(xb / w)) < 1e-10
                        dist = np.zeros(len(r))
                        for dim in range(3):
                            cands = [cell[dim]]
                            if near_cut[dim]:
                                cands = [np.round(xb[dim] / w[dim]) - 1, np.round(xb[dim] / w[dim])]
                            for cd in cands:
                                blo = cd * w[dim] + s[dim] * L[dim]
                                d1 = np.maximum(np.maximum(blo - X[:, dim], X[:, dim] - blo - w[dim]), 0.0)
                                dist = np.maximum(dist, d1)
                        c = np.where(touch, np.maximum(c, dist), c)
    copies = np.ones(len(r))
    for dim in range(3):
        x, cc = X[:, dim], c
        n = np.floor((x + cc) / w[dim]) - np.ceil((x - cc) / w[dim] - 1.0) + 1.0
        copies *= n
    return float((copies - 1.0).sum())


# ---------------------------------------------------------------------------------------------

def project(np, a, R, box, atoms):
    out = []
    for p in a.project:
        side = round(p ** (1.0 / 3.0))
        for method in ("levels", "single"):
            g = model_ghosts(np, box, atoms, (side, side, side), method) / len(atoms)
            out.append({"R": R, "atoms": len(atoms), "ranks": p, "grid": "%dx%dx%d" % (side, side, side),
                        "method": method, "model_ghosts_per_owned": g})
            print("  projection %d ranks %-7s ghosts/owned %.3f" % (p, method, g))
    return out


def timing(a, data):
    rows = []
    for rep in range(a.timing_repeats):
        for method in ("levels", "single"):
            load = os.getloadavg()[0]
            log = os.path.join(a.work, "timing_%s_%d.log" % (method, rep))
            cmd = [a.exe, "-in", DECK, "-log", log, "-echo", "none", "-screen", "none", "-var", "data", data,
                   "-var", "nopts", "halo " + method, "-var", "nsteps", "200", "-var", "every", "10"]
            text, wall = run(cmd, log, a.timeout)
            loop = float(re.findall(r"Loop time of (\S+)", text)[-1])
            comm = float(re.findall(r"Comm\s+time \(%\) = (\S+)", text)[-1])
            rows.append({"method": method, "repeat": rep, "loop_s": loop, "comm_s": comm,
                         "comm_share": comm / loop, "load1": load})
            print("  timing %-7s repeat %d: loop %.3f s, comm %.3f s (%.1f %%), load %.2f"
                  % (method, rep, loop, comm, 100 * comm / loop, load))
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "liggghts-spacetree"))
    ap.add_argument("--lmp", default=shutil.which("lmp"))
    ap.add_argument("--mpiexec", default=shutil.which("mpirun") or shutil.which("mpiexec"))
    ap.add_argument("--R", type=ints, default=[1, 10, 20, 50])
    ap.add_argument("--ranks", type=ints, default=[1, 2, 4, 8])
    ap.add_argument("--project", type=ints, default=[64, 512])
    ap.add_argument("--timing-repeats", type=int, default=0)
    ap.add_argument("--work", default=os.path.join(ROOT, "build", "bench-halo"))
    ap.add_argument("--out", default=os.path.join(ROOT, "bench", "results", "halo_ghosts"))
    ap.add_argument("--timeout", type=float, default=1800.0)
    ap.add_argument("--replot", action="store_true", help="only redraw OUT.png from OUT.csv and OUT_projection.csv")
    ap.add_argument("--remodel", action="store_true",
                    help="keep the measured counts of OUT.csv, recompute the model columns and the projection")
    a = ap.parse_args()
    if a.replot:
        def load(path):
            if not os.path.exists(path):
                return []
            rows = list(csv.DictReader(open(path)))
            for r in rows:
                for k in ("R", "ranks"):
                    r[k] = float(r[k]) if k == "R" else int(r[k])
                for k in ("ghosts_per_owned", "model_ghosts_per_owned"):
                    if r.get(k) not in (None, ""):
                        r[k] = float(r[k])
            return rows
        plot(a, load(a.out + ".csv"), load(a.out + "_projection.csv"))
        return
    os.makedirs(a.work, exist_ok=True)
    import numpy as np

    rows, proj = [], []
    if a.remodel:
        rows = list(csv.DictReader(open(a.out + ".csv")))
        for R in a.R:
            box, atoms = read_pack(generate(R, a.work, sys.executable))
            for row in rows:
                if float(row["R"]) == R and row["method"] in ("levels", "single"):
                    grid = tuple(int(g) for g in row["grid"].split("x"))
                    row["model_ghosts_per_owned"] = model_ghosts(np, box, atoms, grid, row["method"]) / len(atoms)
                    print("  R %g, %s, %s: measured %s, model %.4f" % (R, row["grid"], row["method"],
                                                                      row["ghosts_per_owned"],
                                                                      row["model_ghosts_per_owned"]))
            proj += project(np, a, R, box, atoms)
        for row in rows:
            for k in ("ranks", "owned", "ghosts", "atoms"):
                row[k] = int(row[k])
            row["R"] = float(row["R"])
            row["ghosts_per_owned"] = float(row["ghosts_per_owned"])
        a.R = []
    for R in a.R:
        data = generate(R, a.work, sys.executable)
        box, atoms = read_pack(data)
        print("R = %g: %d atoms, box %.4g m" % (R, len(atoms), box[0][1] - box[0][0]))
        for np_ in a.ranks:
            for method in METHODS:
                m = measure(a, R, data, np_, method)
                if m is None:
                    continue
                model = ""
                if method in ("levels", "single"):
                    model = model_ghosts(np, box, atoms, m["grid"], method) / len(atoms)
                row = {"R": R, "atoms": len(atoms), "ranks": np_, "grid": "x".join(map(str, m["grid"])),
                       "method": method, "owned": m["owned"], "ghosts": m["ghosts"],
                       "ghosts_per_owned": m["ghosts"] / m["owned"],
                       "model_ghosts_per_owned": model,
                       "class_ghosts": " ".join("%d" % g for g in m["classes"] if g) if m["classes"] else ""}
                rows.append(row)
                print("  %d ranks (%s) %-13s ghosts/owned %.3f%s" % (
                    np_, row["grid"], method, row["ghosts_per_owned"],
                    "  (model %.3f)" % model if model != "" else ""))
        proj += project(np, a, R, box, atoms)

    os.makedirs(os.path.dirname(a.out), exist_ok=True)
    with open(a.out + ".csv", "w", newline="") as f:
        wr = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        wr.writeheader()
        wr.writerows(rows)
    if proj:
        with open(a.out + "_projection.csv", "w", newline="") as f:
            wr = csv.DictWriter(f, fieldnames=list(proj[0].keys()))
            wr.writeheader()
            wr.writerows(proj)
    if a.timing_repeats > 0 and 50 in PACKS:
        trows = timing(a, generate(50, a.work, sys.executable))
        with open(a.out + "_timing.csv", "w", newline="") as f:
            wr = csv.DictWriter(f, fieldnames=list(trows[0].keys()))
            wr.writeheader()
            wr.writerows(trows)
        for method in ("levels", "single"):
            t = [r for r in trows if r["method"] == method]
            print("timing %-7s median comm %.3f s of loop %.3f s (share %.1f %%)" % (
                method, statistics.median(r["comm_s"] for r in t), statistics.median(r["loop_s"] for r in t),
                100 * statistics.median(r["comm_share"] for r in t)))
    plot(a, rows, proj)


def plot(a, rows, proj):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib missing: no PNG")
        return
    Rs = sorted(set(r["R"] for r in rows))
    fig, axes = plt.subplots(1, len(Rs), figsize=(4 * len(Rs), 3.8), squeeze=False)
    style = {"levels": ("C0", "o-", "spacetree halo levels"), "single": ("C1", "s-", "stock shell (bin, halo single)"),
             "lammps_multi": ("C2", "^--", "LAMMPS multi, comm multi"),
             "lammps_reduce": ("C3", "v:", "LAMMPS reduce/multi (newton on)")}
    for ax, R in zip(axes[0], Rs):
        for method in METHODS:
            pts = sorted((r["ranks"], r["ghosts_per_owned"]) for r in rows if r["R"] == R and r["method"] == method)
            if pts:
                col, mk, lab = style[method]
                ax.plot([p[0] for p in pts], [max(p[1], 1e-3) for p in pts], mk, color=col, label=lab)
        for method in ("levels", "single"):
            pts = sorted((p["ranks"], p["model_ghosts_per_owned"]) for p in proj if p["R"] == R and p["method"] == method)
            if pts:
                ax.plot([p[0] for p in pts], [p[1] for p in pts], "x", color=style[method][0], ms=9,
                        label="model, %s" % method)
        ax.set_xscale("log", base=2)
        ax.set_yscale("log")
        ax.set_title("R = %g" % R)
        ax.set_xlabel("MPI ranks")
        ax.grid(True, which="both", alpha=0.3)
    axes[0][0].set_ylabel("ghost atoms per owned atom")
    axes[0][-1].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(a.out + ".png", dpi=120)
    print("wrote %s.csv, %s.png" % (a.out, a.out))


if __name__ == "__main__":
    main()
