#!/usr/bin/env python3
"""Regression driver: runs LIGGGHTS decks with `neighbor ... bin` and `neighbor ... spacetree`
and compares what they produce.  Pure Python (no numpy).

  compare_runs.py [options] TEST

TEST is one of (see `compare_runs.py list`):
  pairs:CASE:NP      the sorted pair sets (compute neigh/local, dumped every 10 steps over 40
                     steps of motion, list rebuilt every step) of spacetree on NP ranks equal
                     those of bin on 1 rank (as sets) and of bin on NP ranks (as multisets)
  thermo:settle:NP   thermo of a settling polydisperse pack (walls, gravity, hertz + history),
                     200 steps, full precision: spacetree vs bin on NP ranks within 1e-8 relative
  mesh:NP            the same for a pack falling onto an STL funnel (fix mesh/surface/stress +
                     fix wall/gran mesh)
  overflow:NP        crowded big particle (> 2000 neighbours): spacetree with the default
                     neigh_modify one (2000) runs and lists exactly bin's pairs (bin: one 20000)
  bad:NAME           bad input must stop with a non-zero exit code and the ERROR in EXPECTED_ERRORS

Exit status 0 = pass, 1 = fail, 2 = usage / setup problem.
"""

import argparse
import collections
import math
import os
import re
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
GEN = os.path.join(ROOT, "scripts", "gen_pack.py")

# ------------------------------------------------------------------------------------------------
# Expected error messages of the bad-input tests: the ONE place to adjust them.
# Each: (deck, generator args or None, extra -var settings, regex that the ERROR line must match)
EXPECTED_ERRORS = {
    "atomic": ("in.bad_atomic", None, {},
               r"ERROR.*[Ss]pacetree.*radius"),
    "keyword": ("in.bad_keyword",
                ["bidisperse", "--R", "1", "--n", "4", "--boundary", "p"], {},
                r"ERROR.*spacetree.*'?bogus'?"),
    "smallbox": ("in.bad_smallbox",
                 # one sphere of d = 9.95 mm in a periodic 10 mm box, skin 0.1 mm
                 ["continuous", "--rmin", "4.975e-3", "--rmax", "4.975e-3", "--n", "1",
                  "--box", "0.01", "--boundary", "p"], {"skin": "1e-4"},
                 r"ERROR.*(domain|box).*too small.*largest particle"),
}
# For these, the same deck with `bin` must run (proves the error is specific to spacetree).
BIN_MUST_RUN = {"atomic": {"nstyle": "bin"}}

# ------------------------------------------------------------------------------------------------
# Pair-set cases.  gen: gen_pack.py arguments; min_pairs / min_cross: lower bounds (at step 0)
# that keep the comparison meaningful; cross pairs = pairs whose diameters differ by >= 2x.
PAIR_CASES = collections.OrderedDict([
    ("r1_bi_periodic", dict(
        gen=["bidisperse", "--R", "1", "--n", "15", "--boundary", "p", "--vel", "1.0", "--seed", "101"],
        bnd="p", min_pairs=8000, min_cross=0)),
    ("r10_bi_walled", dict(
        gen=["bidisperse", "--R", "10", "--n", "20", "--K", "8", "--boundary", "f", "--vel", "1.0",
             "--bigs-first", "--seed", "102"],
        bnd="f", min_pairs=8000, min_cross=400)),
    ("r10_cont_periodic", dict(
        gen=["continuous", "--rmin", "0.5e-3", "--rmax", "5e-3", "--n", "4000", "--fill", "0.4",
             "--boundary", "p", "--vel", "1.0", "--seed", "103"],
        bnd="p", min_pairs=1000, min_cross=300)),
    ("r100_bi_periodic", dict(
        # one 100 mm sphere in a 143 mm periodic box; small lattice only in a patch at its +x side
        gen=["bidisperse", "--R", "100", "--n", "130", "--K", "1", "--boundary", "p", "--vel", "1.0",
             "--big-at", "0.5", "0.5", "0.5", "--lattice-region", "0.78", "0.95", "0.35", "0.65",
             "0.35", "0.65", "--shell", "3", "--seed", "104"],
        bnd="p", min_pairs=4000, min_cross=250)),
    ("r100_cont_walled", dict(
        # the small spheres are a dilute gas between the big ones: a wider skin (2 rmin) gives
        # enough pairs
        gen=["continuous", "--rmin", "0.5e-3", "--rmax", "0.05", "--n", "6000", "--fill", "0.4",
             "--boundary", "f", "--vel", "1.0", "--seed", "105"],
        bnd="f", vars={"skin": "1e-3"}, min_pairs=600, min_cross=400)),
    ("r10_bi_periodic_bigsfirst", dict(
        gen=["bidisperse", "--R", "10", "--n", "22", "--K", "8", "--boundary", "p", "--vel", "1.0",
             "--bigs-first", "--seed", "106"],
        bnd="p", min_pairs=8000, min_cross=400)),
    ("r100_bi_periodic_maxlevel2", dict(
        # as r100_bi_periodic, with a shallow tree (`neighbor ... spacetree maxlevel 2`): the list
        # must stay exact for any maxlevel
        gen=["bidisperse", "--R", "100", "--n", "130", "--K", "1", "--boundary", "p", "--vel", "1.0",
             "--big-at", "0.5", "0.5", "0.5", "--lattice-region", "0.78", "0.95", "0.35", "0.65",
             "0.35", "0.65", "--shell", "3", "--seed", "107"],
        bnd="p", st_vars={"nopts": "maxlevel 2"}, min_pairs=4000, min_cross=250)),
])
PAIR_VARS = {"skin": "3e-4", "nsteps": "40", "dumpevery": "10", "dt": "4e-6"}

SETTLE_GEN = ["continuous", "--rmin", "0.5e-3", "--rmax", "2.5e-3", "--n", "3000", "--fill", "0.4",
              "--boundary", "f", "--vel", "1.0", "--seed", "201"]
MESH_STL = ["stl-funnel", "--bottom", "0.015", "--top", "0.025", "--height", "0.02", "--z0", "0.0"]
MESH_GEN = ["continuous", "--rmin", "0.4e-3", "--rmax", "1.2e-3", "--fill", "0.3",
            "--box", "0.03", "0.03", "0.01", "--origin", "-0.015", "-0.015", "0.00005",
            "--domain", "-0.026", "0.026", "-0.026", "0.026", "-0.001", "0.025",
            "--boundary", "f", "--vel", "0.3", "--vz0", "-0.5", "--seed", "301"]
CROWDED_GEN = ["crowded", "--R", "40", "--gap", "0.05", "--vel", "0.2", "--bigs-first", "--seed", "401"]
THERMO_RTOL = 1e-8


# ------------------------------------------------------------------------------------------------


class Fail(Exception):
    pass


def read_text(path):
    with open(path, encoding="utf-8", errors="replace") as f:
        return f.read()


class Runner:
    def __init__(self, args):
        self.exe = args.exe
        self.mpiexec = args.mpiexec
        self.mpiflags = [f for f in re.split(r"[;\s]+", args.mpiexec_flags or "") if f]
        self.python = args.python or sys.executable
        self.work = os.path.abspath(args.workdir)
        self.timeout = args.timeout
        if os.path.isdir(self.work) and not args.keep:
            shutil.rmtree(self.work)
        os.makedirs(self.work, exist_ok=True)
        if not (os.path.isfile(self.exe) and os.access(self.exe, os.X_OK)):
            raise Fail("LIGGGHTS executable not found: %s" % self.exe)

    def gen(self, name, gen_args):
        out = os.path.join(self.work, name)
        cmd = [self.python, GEN] + gen_args + ["--out", out]
        r = subprocess.run(cmd, cwd=self.work, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                           universal_newlines=True)
        if r.returncode != 0:
            raise Fail("generator failed: %s\n%s" % (" ".join(cmd), r.stdout))
        print("  gen: " + r.stdout.strip())
        return out

    def run(self, deck, tag, np, variables, expect_ok=True):
        """Runs deck in the work dir; returns (rc, log text, tag)."""
        log = os.path.join(self.work, tag + ".log")
        cmd = []
        if np != 1:  # one rank: run the executable directly (mpirun start-up costs ~2 s)
            if not self.mpiexec:
                raise Fail("no mpiexec given, cannot run on %d ranks" % np)
            cmd += [self.mpiexec] + self.mpiflags + ["-np", str(np)]
        # Screen output goes to our pipe, line-buffered (stdbuf): errors raised on one rank
        # (error->one, e.g. "Neighbor list overflow") reach only the screen, then MPI_Abort
        # discards whatever stdio still buffers, the log file included.
        if shutil.which("stdbuf"):
            cmd += ["stdbuf", "-oL", "-eL"]
        cmd += [self.exe, "-in", os.path.join(HERE, deck), "-log", log, "-echo", "none"]
        variables = dict(variables)
        variables.setdefault("deckdir", HERE)
        variables.setdefault("out", tag)
        for k, v in variables.items():
            cmd += ["-var", k, str(v)]
        env = dict(os.environ)
        # Open MPI: allow root, allow more ranks than cores (harmless for other MPIs)
        env.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
        env.setdefault("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
        env.setdefault("OMPI_MCA_rmaps_base_oversubscribe", "1")
        env.setdefault("OMPI_MCA_btl_vader_single_copy_mechanism", "none")
        t0 = time.time()
        try:
            r = subprocess.run(cmd, cwd=self.work, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                               universal_newlines=True, errors="replace", env=env, timeout=self.timeout)
            rc, out = r.returncode, r.stdout
        except subprocess.TimeoutExpired as e:
            rc, out = 124, (e.stdout or "") if isinstance(e.stdout, str) else ""
        dt = time.time() - t0
        text = read_text(log) if os.path.exists(log) else ""
        print("  run: %-34s np=%d rc=%d %.1fs" % (tag, np, rc, dt))
        if expect_ok and rc != 0:
            err = [l for l in (text + "\n" + out).splitlines() if "ERROR" in l]
            raise Fail("%s failed (rc=%d): %s\n  command: %s\n  log: %s"
                       % (tag, rc, "; ".join(err[:3]) or out[-2000:], " ".join(cmd), log))
        return rc, text + "\n" + out


# ------------------------------------------------------------------------------------------------
# parsing


def parse_local_dump(path):
    """dump local file -> OrderedDict step -> Counter of (min tag, max tag)."""
    steps = collections.OrderedDict()
    with open(path) as f:
        lines = f.read().split("\n")
    i = 0
    n = len(lines)
    while i < n:
        if lines[i].startswith("ITEM: TIMESTEP"):
            step = int(lines[i + 1])
            i += 2
            continue
        if lines[i].startswith("ITEM: NUMBER OF ENTRIES"):
            count = int(lines[i + 1])
            i += 2
            continue
        if lines[i].startswith("ITEM: ENTRIES"):
            c = collections.Counter()
            for k in range(i + 1, i + 1 + count):
                a, b = lines[k].split()[:2]
                a, b = int(float(a)), int(float(b))
                c[(a, b) if a < b else (b, a)] += 1
            steps[step] = c
            i += 1 + count
            continue
        i += 1
    return steps


def parse_atoms_dump(path):
    """dump custom (id radius x y z) -> dict step -> dict id -> (r, x, y, z), and box per step."""
    steps, boxes = {}, {}
    with open(path) as f:
        lines = f.read().split("\n")
    i, n = 0, len(lines)
    while i < n:
        if lines[i].startswith("ITEM: TIMESTEP"):
            step = int(lines[i + 1])
            i += 2
        elif lines[i].startswith("ITEM: NUMBER OF ATOMS"):
            count = int(lines[i + 1])
            i += 2
        elif lines[i].startswith("ITEM: BOX BOUNDS"):
            boxes[step] = [tuple(float(v) for v in lines[i + 1 + k].split()[:2]) for k in range(3)]
            i += 4
        elif lines[i].startswith("ITEM: ATOMS"):
            d = {}
            for k in range(i + 1, i + 1 + count):
                v = lines[k].split()
                d[int(v[0])] = tuple(float(x) for x in v[1:5])
            steps[step] = d
            i += 1 + count
        else:
            i += 1
    return steps, boxes


def parse_thermo(text):
    """-> (column names, list of rows (floats)) of the last thermo block in a log.
    Column names as LIGGGHTS prints them: c_/f_/v_ prefixes stripped (c_rke -> rke)."""
    lines = text.splitlines()
    blocks = []
    i = 0
    while i < len(lines):
        t = lines[i].split()
        if t and t[0] == "Step":
            cols = [re.sub(r"^[cfv]_", "", c) for c in t]
            rows = []
            i += 1
            while i < len(lines) and not lines[i].startswith("Loop time"):
                v = lines[i].split()
                if len(v) == len(cols):
                    try:
                        rows.append([float(x) for x in v])
                    except ValueError:
                        pass
                i += 1
            blocks.append((cols, rows))
        i += 1
    if not blocks:
        raise Fail("no thermo output found in log")
    return blocks[-1]


def parse_stats(text):
    s = {}
    m = re.search(r"Total # of neighbors = (\S+)", text)
    if m:
        s["neighbors"] = float(m.group(1))
    m = re.search(r"Neighbor list builds = (\d+)", text)
    if m:
        s["builds"] = int(m.group(1))
    m = re.search(r"Dangerous builds = (\d+)", text)
    if m:
        s["dangerous"] = int(m.group(1))
    return s


# ------------------------------------------------------------------------------------------------
# checks


def cutoff_info(atoms, box, periodic, pair, skin):
    """(distance - cutoff) / cutoff of a pair from the dumped positions (minimum image if periodic)."""
    a, b = atoms[pair[0]], atoms[pair[1]]
    d = [b[k + 1] - a[k + 1] for k in range(3)]
    if periodic:
        for k in range(3):
            L = box[k][1] - box[k][0]
            d[k] -= L * round(d[k] / L)
    dist = math.sqrt(sum(x * x for x in d))
    cut = a[0] + b[0] + skin
    return (dist - cut) / cut


def compare_pairsets(name, ref, test, as_multiset, atoms=None, boxes=None, periodic=False, skin=0.0):
    """ref/test: step -> Counter.  Raises Fail with details on the first difference."""
    if list(ref.keys()) != list(test.keys()):
        raise Fail("%s: dumped steps differ: %s vs %s" % (name, list(ref.keys()), list(test.keys())))
    for step in ref:
        r, t = ref[step], test[step]
        if as_multiset:
            same = (r == t)
        else:
            same = (set(r) == set(t))
        if same:
            continue
        missing = sorted(set(r) - set(t))
        extra = sorted(set(t) - set(r))
        mult = [] if not as_multiset else sorted(p for p in set(r) & set(t) if r[p] != t[p])
        msg = ["%s: step %d: %d pairs missing, %d extra, %d with different multiplicity "
               "(reference %d distinct pairs)" % (name, step, len(missing), len(extra), len(mult), len(r))]
        if atoms and step in atoms:
            for lab, lst in (("missing", missing), ("extra", extra)):
                for p in lst[:8]:
                    msg.append("   %s %s: (dist - cutoff)/cutoff = %.3e" %
                               (lab, p, cutoff_info(atoms[step], boxes.get(step), periodic, p, skin)))
        for p in mult[:8]:
            msg.append("   multiplicity %s: reference %d, test %d" % (p, r[p], t[p]))
        raise Fail("\n".join(msg))


def cross_pairs(pairs, atoms, ratio=2.0):
    n = 0
    for (a, b) in pairs:
        ra, rb = atoms[a][0], atoms[b][0]
        if max(ra, rb) >= ratio * min(ra, rb):
            n += 1
    return n


def test_pairs(R, case, np):
    c = PAIR_CASES[case]
    data = R.gen(case + ".data", c["gen"])
    base = dict(PAIR_VARS, data=data, bnd=c["bnd"])
    base.update(c.get("vars", {}))
    periodic = c["bnd"] == "p"
    skin = float(base["skin"])
    R.run("in.pairs", "bin_np1", 1, dict(base, nstyle="bin"))
    ref = parse_local_dump(os.path.join(R.work, "bin_np1.pairs"))
    atoms, boxes = parse_atoms_dump(os.path.join(R.work, "bin_np1.atoms"))
    steps = list(ref.keys())
    if len(steps) < 3:
        raise Fail("expected >= 3 dumped steps, got %s" % steps)
    first = ref[steps[0]]
    ncross = cross_pairs(first, atoms[steps[0]])
    changed = len(set(ref[steps[0]]) ^ set(ref[steps[-1]]))
    print("  bin np1: steps %s, %d distinct pairs at step %d (%d cross-size, %d pair changes over the run)"
          % (steps, len(first), steps[0], ncross, changed))
    if len(first) < c["min_pairs"]:
        raise Fail("deck too weak: %d pairs < %d" % (len(first), c["min_pairs"]))
    if ncross < c["min_cross"]:
        raise Fail("deck too weak: %d cross-size pairs < %d" % (ncross, c["min_cross"]))
    if np == 1:
        # bin lists each owned/owned pair once: tags may repeat only via periodic images
        if not periodic:
            dup = [p for p, k in first.items() if k > 1]
            if dup:
                raise Fail("bin np1 lists %d pairs twice in a non-periodic box" % len(dup))
        R.run("in.pairs", "spacetree_np1", 1, dict(base, nstyle="spacetree", **c.get("st_vars", {})))
        st = parse_local_dump(os.path.join(R.work, "spacetree_np1.pairs"))
        compare_pairsets("spacetree np1 vs bin np1", ref, st, True, atoms, boxes, periodic, skin)
        print("  PASS spacetree np1 == bin np1 (multisets of pairs at steps %s)" % steps)
    else:
        R.run("in.pairs", "bin_np%d" % np, np, dict(base, nstyle="bin"))
        binn = parse_local_dump(os.path.join(R.work, "bin_np%d.pairs" % np))
        compare_pairsets("bin np%d vs bin np1 (harness sanity)" % np, ref, binn, False, atoms, boxes,
                         periodic, skin)
        R.run("in.pairs", "spacetree_np%d" % np, np, dict(base, nstyle="spacetree", **c.get("st_vars", {})))
        st = parse_local_dump(os.path.join(R.work, "spacetree_np%d.pairs" % np))
        compare_pairsets("spacetree np%d vs bin np%d" % (np, np), binn, st, True, atoms, boxes, periodic, skin)
        compare_pairsets("spacetree np%d vs bin np1" % np, ref, st, False, atoms, boxes, periodic, skin)
        print("  PASS spacetree np%d == bin np%d (multisets) == bin np1 (sets) at steps %s" % (np, np, steps))


def thermo_diff(ta, tb, name):
    ca, ra = ta
    cb, rb = tb
    if ca != cb:
        raise Fail("%s: thermo columns differ: %s vs %s" % (name, ca, cb))
    if len(ra) != len(rb) or not ra:
        raise Fail("%s: thermo rows differ: %d vs %d" % (name, len(ra), len(rb)))
    worst = {}
    for j, col in enumerate(ca):
        colmax = max(max(abs(r[j]) for r in ra), max(abs(r[j]) for r in rb))
        w = (0.0, None)
        for ia, (x, y) in enumerate(zip((r[j] for r in ra), (r[j] for r in rb))):
            m = max(abs(x), abs(y))
            if m == 0.0:
                rel = 0.0
            elif m < 1e-12 * colmax:  # an entry near zero by cancellation: compare to the column scale
                rel = abs(x - y) / colmax
            else:
                rel = abs(x - y) / m
            if rel > w[0] or w[1] is None:
                w = (rel, int(ra[ia][0]))
        worst[col] = w
    return worst


def report_thermo(name, worst, nrows):
    print("  %s: %d thermo rows; max relative difference per column:" % (name, nrows))
    for col, (rel, step) in worst.items():
        print("    %-10s %.3e  (step %s)" % (col, rel, step))
    overall = max(w[0] for w in worst.values())
    print("  max relative difference over all columns: %.3e (tolerance %.0e)" % (overall, THERMO_RTOL))
    if overall > THERMO_RTOL:
        bad = [c for c, (r, s) in worst.items() if r > THERMO_RTOL]
        raise Fail("%s: thermo differs by more than %g in %s" % (name, THERMO_RTOL, bad))


def test_thermo(R, deck, data_vars, np, label):
    rc, tb = R.run(deck, "bin_np%d" % np, np, dict(data_vars, nstyle="bin"))
    rc, ts = R.run(deck, "spacetree_np%d" % np, np, dict(data_vars, nstyle="spacetree"))
    thb, ths = parse_thermo(tb), parse_thermo(ts)
    sb, ss = parse_stats(tb), parse_stats(ts)
    print("  bin:       %s" % sb)
    print("  spacetree: %s" % ss)
    if len(thb[1]) < 2:
        raise Fail("too few thermo rows")
    worst = thermo_diff(thb, ths, label)
    report_thermo("%s spacetree vs bin np%d" % (label, np), worst, len(thb[1]))
    for k in ("neighbors", "builds"):
        if sb.get(k) != ss.get(k):
            raise Fail("%s differs: bin %s, spacetree %s" % (k, sb.get(k), ss.get(k)))
    return thb


def test_settle(R, np):
    data = R.gen("settle.data", SETTLE_GEN)
    thb = test_thermo(R, "in.settle", {"data": data}, np, "settle")
    cols, rows = thb
    j = cols.index("nc") if "nc" in cols else None
    if j is not None:
        print("  contacts (c_nc = 2 x particle contacts) along the run: %s" % [int(r[j]) for r in rows[::4]])
        if max(r[j] for r in rows) < 100:
            raise Fail("deck too weak: fewer than 100 contacts")
    jr = cols.index("rke")
    if max(r[jr] for r in rows) <= 0:
        raise Fail("deck too weak: no rotational energy (tangential forces never acted)")
    print("  PASS")


def test_mesh(R, np):
    stl = R.gen("funnel.stl", MESH_STL)
    data = R.gen("mesh.data", MESH_GEN)
    thb = test_thermo(R, "in.mesh", {"data": data, "stl": stl}, np, "mesh")
    cols, rows = thb
    jz = cols.index("cad[3]")
    fz = [r[jz] for r in rows]
    print("  vertical force on the mesh along the run: %s" % ["%.3g" % v for v in fz[::4]])
    if max(abs(v) for v in fz) <= 0:
        raise Fail("deck too weak: no particle touched the mesh")
    print("  PASS")


def test_overflow(R, np):
    data = R.gen("crowded.data", CROWDED_GEN)
    # no atom sorting: the big particle keeps the lowest local index, so a half list stores all
    # its pairs under it (with sorting they spread over the small particles' lists)
    base = dict(PAIR_VARS, data=data, bnd="f", skin="1e-4", sortevery="0")
    # informational: does stock bin overflow with the default neigh_modify one?
    rc, text = R.run("in.pairs", "bin_default_one", np, dict(base, nstyle="bin", one="2000", page="100000"),
                     expect_ok=False)
    over = rc != 0 and "overflow" in text.lower()
    print("  bin with the default 'neigh_modify one 2000': %s"
          % ("stops: neighbour list overflow (expected)" if over else "rc=%d" % rc))
    if not over:
        raise Fail("deck too weak: stock bin did not overflow with the default neigh_modify one")
    R.run("in.pairs", "bin", np, dict(base, nstyle="bin", one="20000", page="200000"))
    R.run("in.pairs", "spacetree", np, dict(base, nstyle="spacetree", one="2000", page="100000"))
    ref = parse_local_dump(os.path.join(R.work, "bin.pairs"))
    st = parse_local_dump(os.path.join(R.work, "spacetree.pairs"))
    atoms, boxes = parse_atoms_dump(os.path.join(R.work, "bin.atoms"))
    s0 = list(ref.keys())[0]
    nbig = sum(k for p, k in ref[s0].items() if 1 in p)
    print("  the big particle (id 1) has %d neighbours at step %d" % (nbig, s0))
    if nbig <= 2000:
        raise Fail("deck too weak: the big particle has only %d <= 2000 neighbours" % nbig)
    compare_pairsets("spacetree (one 2000) vs bin (one 20000) np%d" % np, ref, st, True, atoms, boxes,
                     False, 1e-4)
    print("  PASS spacetree with the default page size lists exactly bin's pairs at steps %s" % list(ref.keys()))


def test_bad(R, name):
    deck, gen, extra, regex = EXPECTED_ERRORS[name]
    v = dict(extra)
    if gen:
        v["data"] = R.gen(name + ".data", gen)
    if name in BIN_MUST_RUN:
        R.run(deck, "bin_control", 1, dict(v, **BIN_MUST_RUN[name]))
        print("  control run with bin succeeded")
    rc, text = R.run(deck, "bad_" + name, 1, v, expect_ok=False)
    errs = [l for l in text.splitlines() if "ERROR" in l]
    print("  rc=%d, ERROR lines: %s" % (rc, errs[:2]))
    if rc == 0:
        raise Fail("bad input '%s' did not fail (rc 0)" % name)
    if not any(re.search(regex, l) for l in errs):
        raise Fail("bad input '%s': no ERROR line matches /%s/" % (name, regex))
    print("  PASS (non-zero exit, message matches /%s/)" % regex)


def list_tests():
    t = []
    for c in PAIR_CASES:
        t += ["pairs:%s:1" % c, "pairs:%s:2" % c]
    t += ["thermo:settle:1", "thermo:settle:2", "mesh:1", "mesh:2", "overflow:1", "overflow:2"]
    t += ["bad:%s" % n for n in EXPECTED_ERRORS]
    return t


def driver_main(doc, dispatch, list_tests=None, workdir_prefix=""):
    """The command line every regression driver shares (compare_runs.py, check_ranks.py,
    check_adaptive_grid.py, check_restart_tree.py): `TEST [--exe ...]`; dispatch(R, parts) runs
    the test named by the ':'-separated parts and returns False for an unknown name. Exit status
    0 = pass, 1 = fail, 2 = unknown test."""
    ap = argparse.ArgumentParser(description=doc, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("test", help="test name" + (", or 'list'" if list_tests else ""))
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "liggghts-spacetree"))
    ap.add_argument("--mpiexec", default=shutil.which("mpirun") or shutil.which("mpiexec"))
    ap.add_argument("--mpiexec-flags", default="",
                    help="flags before -np (';' or blank separated), e.g. --allow-run-as-root;--oversubscribe")
    ap.add_argument("--python", default=None, help="interpreter for gen_pack.py (default: this one)")
    ap.add_argument("--workdir", default=None)
    ap.add_argument("--keep", action="store_true", help="do not wipe the work directory first")
    ap.add_argument("--timeout", type=float, default=300.0, help="per LIGGGHTS run (s)")
    a = ap.parse_args()
    if list_tests and a.test == "list":
        print("\n".join(list_tests()))
        return 0
    if a.workdir is None:
        a.workdir = os.path.join(ROOT, "build", "tests-liggghts", workdir_prefix + a.test.replace(":", "_"))
    print("test %s (exe %s)" % (a.test, a.exe))
    t0 = time.time()
    try:
        if not dispatch(Runner(a), a.test.split(":")):
            known = ("; known:\n  " + "\n  ".join(list_tests())) if list_tests else ""
            print("unknown test '%s'%s" % (a.test, known))
            return 2
    except Fail as e:
        print("FAIL %s (%.1fs)\n%s" % (a.test, time.time() - t0, e))
        return 1
    print("ok %s (%.1fs)" % (a.test, time.time() - t0))
    return 0


def dispatch(R, parts):
    if parts[0] == "pairs" and len(parts) == 3 and parts[1] in PAIR_CASES:
        test_pairs(R, parts[1], int(parts[2]))
    elif parts[0] == "thermo" and parts[1:2] == ["settle"] and len(parts) == 3:
        test_settle(R, int(parts[2]))
    elif parts[0] == "mesh" and len(parts) == 2:
        test_mesh(R, int(parts[1]))
    elif parts[0] == "overflow" and len(parts) == 2:
        test_overflow(R, int(parts[1]))
    elif parts[0] == "bad" and len(parts) == 2 and parts[1] in EXPECTED_ERRORS:
        test_bad(R, parts[1])
    else:
        return False
    return True


if __name__ == "__main__":
    sys.exit(driver_main(__doc__, dispatch, list_tests))
