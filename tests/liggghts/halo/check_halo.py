#!/usr/bin/env python3
"""Regression driver for neighbor spacetree's per-size ghost rule (`halo levels`, the default):
ghost atoms exchanged per size class, coarse first, each only as far as its partners need.

  check_halo.py [options] TEST

TEST is one of (`check_halo.py list`):
  pairs:CASE:NP     pair sets (compute neigh/local every 10 of 40 steps, lists rebuilt every
                    step) of spacetree on NP ranks (1, 2, 4, 8, oversubscribed) equal those of bin
                    on 1 rank (as sets) and of bin on NP ranks (as multisets: a pair across ranks
                    is listed on both); and the ghost atoms per owned atom (compute halo) are
                    below GHOST_FRACTION of bin's (0 ghosts for both is fine)
  settle:NP         a bidisperse pack (a big sphere touched by hundreds of small ones) settling
                    for 200 steps with Hertz + tangential history: NP ranks vs 1 rank, thermo
                    within SETTLE_RTOL, final positions, velocities, angular velocities within
                    FINAL_RTOL
  restart:NP:NR     the settle deck written with write_restart at step 100 on NP ranks, continued
                    on NR ranks: equals the uninterrupted run on NP ranks (SETTLE_RTOL, FINAL_RTOL)
  single:NP         `halo single` (the stock shell): the same ghost count as bin, the same pairs
  switch:NP         spacetree, then bin, then spacetree in one deck: per-size ghosts, the stock
                    shell (bin's count), per-size ghosts again (compute halo)
  hopper:NP         inputs/hopper, 125 triangulated grains dropped on the floor obstacle under the
                    hopper obstacle (inside its bounding sphere, away from its surface), the box cut
                    through the axis: NP ranks vs 1 rank, atoms exactly, thermo within HOPPER_RTOL,
                    fewer ghosts than the stock shell
  bad:NAME          bad input stops with the ERROR in BAD (keyword, ratio, newton, triclinic)
Exit status 0 = pass, 1 = fail, 2 = usage / setup problem.
"""

import collections
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
import common as C  # noqa: E402

ROOT = C.ROOT
DECK_PAIRS = os.path.join(HERE, "in.halo_pairs")
DECK_SETTLE = os.path.join(HERE, "in.halo_settle")

GHOST_FRACTION = 0.5       # ghosts at most this fraction of the stock shell's (bidisperse, hopper)
SETTLE_RTOL = 1e-12        # thermo (global sums) of N ranks vs 1 rank
# Per atom, roundoff of a different summation order grows through 200 steps of dense collisions:
# bin on 1 rank and spacetree on 1 rank already differ by ~1e-12 (x / box) and ~6e-10 (v / v_max)
# on this deck; a lost contact would differ by O(1).
FINAL_RTOL = {"x": 1e-10, "v": 1e-8, "omega": 1e-8}
HOPPER_RTOL = 1e-8

# gen_pack.py arguments, boundary, minimum pairs at the first dump, minimum cross-size pairs,
# ghosts at most this fraction of bin's
PAIR_CASES = {
    # 8 spheres of 10 mm among 1 mm ones, periodic: images of big and small ones
    "r10_bi_periodic": (["bidisperse", "--R", "10", "--n", "20", "--K", "8", "--big-type", "2",
                         "--boundary", "p", "--vel", "1.0", "--bigs-first", "--seed", "1601"],
                        "p", 5000, 400, GHOST_FRACTION),
    # one 50 mm sphere at the box centre (the corner of all 8 subdomains on 8 ranks), a patch of
    # small ones on its surface across subdomain faces, walls
    "r50_bi_walled": (["bidisperse", "--R", "50", "--n", "62", "--K", "1", "--big-type", "2",
                       "--boundary", "f", "--vel", "1.0", "--big-at", "0.5", "0.5", "0.5",
                       "--lattice-region", "0.15", "0.85", "0.15", "0.85", "0.05", "0.3",
                       "--shell", "2", "--seed", "1602"],
                      "f", 1000, 300, GHOST_FRACTION),
    # radii 0.5 - 5 mm log-uniform (two size classes of halo_ratio 4), periodic: each class's
    # shell is as thick as its largest radius, so the saving is smaller than for two sizes
    "r10_cont_periodic": (["continuous", "--rmin", "0.5e-3", "--rmax", "5e-3", "--n", "4000",
                           "--fill", "0.4", "--boundary", "p", "--vel", "1.0", "--seed", "1603"],
                          "p", 1000, 300, 0.85),
}
SETTLE_GEN = ["bidisperse", "--R", "20", "--n", "28", "--K", "1", "--big-type", "2", "--gap", "0.05",
              "--big-at", "0.5", "0.5", "0.45", "--boundary", "f", "--vel", "1.0", "--seed", "1604"]
MIN_BIG_CONTACTS = 100   # largest contact count of a big sphere during the settle run

BAD = {
    "keyword": ({"nopts": "halo bogus"}, None, r"ERROR.*halo 'bogus'"),
    "ratio": ({"nopts": "halo_ratio 1"}, None, r"ERROR.*halo_ratio '1'"),
    "newton": ({}, "newton on", r"ERROR.*[Ss]pacetree.*newton"),
    "triclinic": ({}, "triclinic", r"ERROR.*[Ss]pacetree.*triclinic"),
}


def gen_two_types(R, name, args):
    """gen_pack.py data with 2 atom types declared (the decks' materials are per type pair)."""
    path = R.gen(name, args)
    with open(path) as f:
        text = f.read()
    with open(path, "w") as f:
        f.write(re.sub(r"^1 atom types$", "2 atom types", text, flags=re.M))
    return path


def thermo_columns(thermo, keep):
    cols, rows = thermo
    idx = [cols.index(c) for c in keep]
    return [cols[i] for i in idx], [[r[i] for i in idx] for r in rows]


def column(thermo, name):
    cols, rows = thermo
    j = cols.index(name)
    return [r[j] for r in rows]


def ghosts_per_owned(text):
    """(owned, ghosts) from the last thermo row's compute halo columns (gh[1], gh[2])."""
    th = C.parse_thermo(text)
    return column(th, "gh[1]")[-1], column(th, "gh[2]")[-1]


def test_pairs(R, case, np):
    gen, bnd, min_pairs, min_cross, fraction = PAIR_CASES[case]
    data = gen_two_types(R, case + ".data", gen)
    base = {"data": data, "bnd": bnd, "walls": "1" if bnd == "f" else "0"}
    _, tb1 = R.run(DECK_PAIRS, "bin_np1", 1, dict(base, nstyle="bin"))
    ref = C.parse_local_dump(os.path.join(R.work, "bin_np1.pairs"))
    atoms, boxes = C.parse_atoms_dump(os.path.join(R.work, "bin_np1.atoms"))
    steps = list(ref.keys())
    first = ref[steps[0]]
    ncross = C.cross_pairs(first, atoms[steps[0]])
    print("  bin np1: %d distinct pairs at step %d (%d cross-size)" % (len(first), steps[0], ncross))
    if len(first) < min_pairs or ncross < min_cross:
        raise C.Fail("deck too weak: %d pairs (>= %d), %d cross-size (>= %d)"
                     % (len(first), min_pairs, ncross, min_cross))
    periodic, skin = bnd == "p", 3e-4
    _, tbn = R.run(DECK_PAIRS, "bin_np%d" % np, np, dict(base, nstyle="bin"))
    binn = C.parse_local_dump(os.path.join(R.work, "bin_np%d.pairs" % np))
    _, tsn = R.run(DECK_PAIRS, "spacetree_np%d" % np, np, dict(base, nstyle="spacetree"))
    st = C.parse_local_dump(os.path.join(R.work, "spacetree_np%d.pairs" % np))
    C.compare_pairsets("spacetree np%d vs bin np1" % np, ref, st, False, atoms, boxes, periodic, skin)
    C.compare_pairsets("spacetree np%d vs bin np%d" % (np, np), binn, st, True, atoms, boxes, periodic, skin)
    print("  PASS spacetree np%d == bin np1 (sets) == bin np%d (multisets) at steps %s" % (np, np, steps))
    ob, gb = ghosts_per_owned(tbn)
    os_, gs = ghosts_per_owned(tsn)
    rule = column(C.parse_thermo(tsn), "gh[6]")[-1]
    print("  ghosts per owned atom: spacetree %.4f (%d), bin %.4f (%d); halo rule %d"
          % (gs / os_, gs, gb / ob, gb, rule))
    if rule != 1 or column(C.parse_thermo(tbn), "gh[6]")[-1] != 0:
        raise C.Fail("compute halo: spacetree must report halo levels (1), bin the stock shell (0)")
    if gb > 0 and gs > fraction * gb:
        raise C.Fail("ghosts: spacetree %d > %.2f x bin's %d" % (gs, fraction, gb))
    print("  PASS ghosts")


def settle_run(R, tag, np, extra):
    data = R.gen("settle.data", SETTLE_GEN)
    v = dict({"data": data, "out": tag}, **extra)
    R.run(DECK_SETTLE, tag, np, v)
    with open(os.path.join(R.work, tag + ".log")) as f:   # the log alone (no screen copy)
        return f.read()


def read_final(path):
    """write_dump custom (id x y z vx vy vz wx wy wz) -> dict id -> 9 floats."""
    out, on = {}, False
    with open(path) as f:
        for line in f:
            if line.startswith("ITEM: ATOMS"):
                on = True
                continue
            if line.startswith("ITEM:"):
                on = False
                continue
            if on:
                v = line.split()
                out[int(v[0])] = [float(x) for x in v[1:10]]
    return out


def compare_final(name, a, b, box):
    """Positions relative to the box length, velocities and angular velocities relative to the
    largest magnitude of each quantity."""
    if sorted(a) != sorted(b):
        raise C.Fail("%s: different atom ids in the final dumps" % name)
    worst = {}
    for label, cols, scale in (("x", range(0, 3), box), ("v", range(3, 6), None), ("omega", range(6, 9), None)):
        s = scale or max(max(abs(a[i][k]) for k in cols) for i in a)
        worst[label] = max(abs(a[i][k] - b[i][k]) for i in a for k in cols) / s
    print("  %s: final state, max difference relative to scale: %s"
          % (name, ", ".join("%s %.3e" % kv for kv in worst.items())))
    bad = [k for k, w in worst.items() if w > FINAL_RTOL[k]]
    if bad:
        raise C.Fail("%s: final %s differ by more than %s" % (name, bad, FINAL_RTOL))


SETTLE_COLS = ["Step", "Atoms", "KinEng", "rke", "nc", "bigc", "ps[1]", "ps[2]", "ps[3]", "ps[4]",
               "ps[5]", "ps[6]", "fn"]
FORCE_SUMS = ["fs[1]", "fs[2]", "fs[3]"]   # nearly cancelling sums: relative to fn = sum |f_i|


def force_sum_diff(t1, tn):
    """Largest difference of the total force components relative to sum_i |f_i| of the row."""
    a, b = thermo_columns(t1, FORCE_SUMS + ["fn"]), thermo_columns(tn, FORCE_SUMS + ["fn"])
    worst = 0.0
    for ra, rb in zip(a[1], b[1]):
        if ra[3] > 0.0:
            worst = max(worst, max(abs(x - y) for x, y in zip(ra[:3], rb[:3])) / ra[3])
    return worst


def parse_all_thermo(text):
    """The thermo rows of every run in a log (the settle deck runs twice), as one table."""
    chunks = re.split(r"(?m)^(?=\s*Step\s)", text)[1:]
    tables = [C.parse_thermo(c) for c in chunks]
    rows = [r for t in tables for r in t[1]]
    return tables[0][0], rows


def compare_settle(name, t1, tn):
    full1, fulln = parse_all_thermo(t1), parse_all_thermo(tn)
    th1 = thermo_columns(full1, SETTLE_COLS)
    thn = thermo_columns(fulln, SETTLE_COLS)
    if column(th1, "Atoms") != column(thn, "Atoms"):
        raise C.Fail("%s: particle counts differ" % name)
    worst = C.thermo_diff(th1, thn, name)
    print("  %s: %d thermo rows; max relative difference per column:" % (name, len(th1[1])))
    for col, (rel, step) in worst.items():
        print("    %-8s %.3e  (step %s)" % (col, rel, step))
    fsum = force_sum_diff(full1, fulln)
    print("    %-8s %.3e  (relative to sum |f_i|)" % ("fs[1-3]", fsum))
    overall = max(max(w[0] for w in worst.values()), fsum)
    if overall > SETTLE_RTOL:
        raise C.Fail("%s: thermo differs by %.3e > %g" % (name, overall, SETTLE_RTOL))
    return th1


def settle_box():
    return 28 * 1.05e-3


def test_settle(R, np):
    t1 = settle_run(R, "np1", 1, {})
    tn = settle_run(R, "np%d" % np, np, {})
    th1 = compare_settle("settle np%d vs np1" % np, t1, tn)
    big = max(column(th1, "bigc"))
    print("  largest contact count of a big sphere: %d; contacts (c_nc) at the end: %d"
          % (big, column(th1, "nc")[-1]))
    if big < MIN_BIG_CONTACTS:
        raise C.Fail("deck too weak: a big sphere has at most %d contacts (< %d)" % (big, MIN_BIG_CONTACTS))
    compare_final("settle np%d vs np1" % np, read_final(os.path.join(R.work, "np1.final")),
                  read_final(os.path.join(R.work, "np%d.final" % np)), settle_box())
    print("  ghosts per owned atom on %d ranks (compute halo): %.4f"
          % (np, column(parse_all_thermo(tn), "gh[3]")[-1]))
    print("  PASS")


def test_restart(R, np, nr):
    rf = os.path.join(R.work, "halo.restart")
    t0 = settle_run(R, "full_np%d" % np, np, {"phase": "0"})
    settle_run(R, "write_np%d" % np, np, {"phase": "1", "restartfile": rf})
    if not os.path.isfile(rf):
        raise C.Fail("write_restart wrote no %s" % rf)
    t2 = settle_run(R, "read_np%d" % nr, nr, {"phase": "2", "restartfile": rf})
    ref = thermo_columns(C.parse_thermo(t0), SETTLE_COLS)
    cont = thermo_columns(C.parse_thermo(t2), SETTLE_COLS)
    first = cont[1][0][0]
    ref = (ref[0], [r for r in ref[1] if r[0] >= first])
    if column(ref, "Atoms") != column(cont, "Atoms"):
        raise C.Fail("restart: particle counts differ")
    worst = C.thermo_diff(ref, cont, "restart")
    overall = max(w[0] for w in worst.values())
    print("  restart written on %d ranks, read on %d: steps %d..%d, max relative thermo difference %.3e"
          % (np, nr, first, ref[1][-1][0], overall))
    if overall > SETTLE_RTOL:
        raise C.Fail("restart: thermo differs by %.3e > %g" % (overall, SETTLE_RTOL))
    compare_final("restart %d -> %d vs uninterrupted" % (np, nr),
                  read_final(os.path.join(R.work, "full_np%d.final" % np)),
                  read_final(os.path.join(R.work, "read_np%d.final" % nr)), settle_box())
    print("  PASS")


def test_switch(R, np):
    gen, bnd = PAIR_CASES["r10_bi_periodic"][:2]
    data = gen_two_types(R, "switch.data", gen)
    _, text = R.run(os.path.join(HERE, "in.halo_switch"), "switch", np, {"data": data})
    _, tb = R.run(DECK_PAIRS, "bin", np, {"data": data, "bnd": bnd, "walls": "0", "nstyle": "bin",
                                         "nsteps": "0"})
    with open(os.path.join(R.work, "switch.log")) as f:
        runs = [C.parse_thermo(c) for c in re.split(r"(?m)^(?=\s*Step\s)", f.read())[1:]]
    got = [(column(t, "gh[6]")[-1], column(t, "gh[2]")[-1]) for t in runs]
    bin_ghosts = ghosts_per_owned(tb)[1]
    print("  runs (rule, ghosts): %s; bin alone: %d ghosts" % (got, bin_ghosts))
    if len(got) != 3 or [g[0] for g in got] != [1, 0, 1]:
        raise C.Fail("switch: expected halo levels, the stock shell, halo levels; got %s" % got)
    if got[1][1] != bin_ghosts or got[0][1] != got[2][1] or not got[0][1] < bin_ghosts:
        raise C.Fail("switch: ghosts %s, bin alone %d" % (got, bin_ghosts))
    print("  PASS")


def test_single(R, np):
    gen, bnd = PAIR_CASES["r10_bi_periodic"][:2]
    data = gen_two_types(R, "single.data", gen)
    base = {"data": data, "bnd": bnd, "walls": "0"}
    _, tb = R.run(DECK_PAIRS, "bin", np, dict(base, nstyle="bin"))
    _, ts = R.run(DECK_PAIRS, "single", np, dict(base, nstyle="spacetree", nopts="halo single"))
    _, tl = R.run(DECK_PAIRS, "levels", np, dict(base, nstyle="spacetree"))
    ref = C.parse_local_dump(os.path.join(R.work, "bin.pairs"))
    for tag in ("single", "levels"):
        C.compare_pairsets("spacetree %s vs bin np%d" % (tag, np), ref,
                           C.parse_local_dump(os.path.join(R.work, tag + ".pairs")), True)
    (ob, gb), (os_, gs), (ol, gl) = ghosts_per_owned(tb), ghosts_per_owned(ts), ghosts_per_owned(tl)
    print("  ghosts on %d rank(s): bin %d, halo single %d, halo levels %d" % (np, gb, gs, gl))
    if gs != gb:
        raise C.Fail("halo single must give the stock shell: %d ghosts vs bin's %d" % (gs, gb))
    if not gl < gb:
        raise C.Fail("halo levels gave no fewer ghosts (%d) than the stock shell (%d)" % (gl, gb))
    print("  PASS")


def log_ghosts(text):
    """(owned, ghost) atoms summed over ranks from the run's last Nlocal / Nghost statistics."""
    nprocs = int(re.findall(r"Loop time of \S+ on (\d+) procs", text)[-1])
    nlocal = float(re.findall(r"Nlocal:\s+(\S+) ave", text)[-1])
    nghost = float(re.findall(r"Nghost:\s+(\S+) ave", text)[-1])
    return nlocal * nprocs, nghost * nprocs


def test_hopper(R, np):
    gen = os.path.join(ROOT, "inputs", "hopper", "make_hopper.py")
    subprocess.run([sys.executable, gen, os.path.join(R.work, "hopper.stl"),
                    os.path.join(R.work, "floor.stl")], check=True, stdout=subprocess.DEVNULL)
    # the deck, cut through the hopper's axis (x, y) as bench/hopper_scaling.py does: LIGGGHTS'
    # own choice cuts it in z, where one rank would hold every grain
    with open(os.path.join(ROOT, "inputs", "hopper", "in.hopper")) as f:
        text = f.read()
    # create_atoms numbers the grains rank by rank and `orientation random` follows the IDs:
    # identity orientations give the same grains on any rank count
    deck = os.path.join(R.work, "in.hopper_xy")
    # plus the pairs of the neighbour list every 100 steps (compute neigh/local)
    # (and the atoms, to name the pairs by position: create_atoms numbers atoms rank by rank)
    pairs = ('compute nl all neigh/local\ndump dp all local 100 ${out}.pairs c_nl[1] c_nl[2]\n'
             'dump_modify dp format "%.0f %.0f"\n'
             'dump dx all custom 100 ${out}.atoms id radius x y z\n'
             'dump_modify dx format "%d %.17g %.17g %.17g %.17g" sort id\nrun ${n}')
    with open(deck, "w") as f:
        f.write(text.replace("region box block", "processors * * 1\nregion box block", 1)
                    .replace("orientation random 99", "orientation identity")
                    .replace("\nrun ${n}", "\n" + pairs, 1))
    # 125 grains dropped onto the floor obstacle, under the hopper obstacle (inside its bounding
    # sphere, away from its surface): grain-grain and grain-floor contacts across the cut
    n = 1500
    v = {"n": n, "nx": 5, "a": 0.0062, "zlo": 0.0035, "v0": 1.0, "dumpevery": n, "th": 50,
         "meshdir": R.work, "nstyle": "spacetree", "threads": 1, "penevery": 1}
    _, t1 = R.run(deck, "hopper_np1", 1, v)
    with open(os.path.join(R.work, "hopper_pen.txt")) as f:   # step, penetration, contacts
        contacts = [int(float(l.split()[2])) for l in f if l.strip() and not l.startswith("#")]
    _, tn = R.run(deck, "hopper_np%d" % np, np, v)
    _, ts = R.run(deck, "hopper_single_np%d" % np, np, dict(v, nstyle="spacetree halo single"))
    th1, thn = C.parse_thermo(t1), C.parse_thermo(tn)
    if column(th1, "Atoms") != column(thn, "Atoms"):
        raise C.Fail("hopper: atom counts differ between 1 and %d ranks" % np)
    print("  1 rank: %d contacts summed over the %d steps, at most %d at once"
          % (sum(contacts), n, max(contacts)))
    if sum(contacts) < 1000:
        raise C.Fail("hopper: deck too weak, %d contacts summed over the steps" % sum(contacts))
    # compute trimesh/contacts counts a contact across the cut on both ranks: not compared
    keep = [c for c in th1[0] if c != "ncont"]
    worst = C.thermo_diff(thermo_columns(th1, keep), thermo_columns(thn, keep), "hopper")
    overall = max(w[0] for w in worst.values())
    print("  hopper np%d vs np1: %d thermo rows (%s), max relative difference %.3e"
          % (np, len(th1[1]), " ".join(keep), overall))
    if overall > HOPPER_RTOL:
        raise C.Fail("hopper: thermo differs by %.3e > %g" % (overall, HOPPER_RTOL))
    # the pair sets: every pair of the 1-rank list on some rank; an obstacle's pairs with grains
    # away from its surface are listed on the grain's rank only (the stock shell: on both)
    def pairs_by_position(tag):
        steps = C.parse_local_dump(os.path.join(R.work, tag + ".pairs"))
        atoms, _ = C.parse_atoms_dump(os.path.join(R.work, tag + ".atoms"))
        out = {}
        for step, counter in steps.items():
            where = {i: "%.12e %.12e %.12e" % a[1:] for i, a in atoms[step].items()}
            out[step] = collections.Counter(tuple(sorted((where[a], where[b]))) for a, b in counter.elements())
        return out
    ref = pairs_by_position("hopper_np1")
    for tag in ("hopper_np%d" % np, "hopper_single_np%d" % np):
        C.compare_pairsets("%s vs hopper np1" % tag, ref, pairs_by_position(tag), False)
    steps = list(ref.keys())
    print("  pair sets equal at steps %s (%d pairs at step %d, obstacles included)"
          % (steps, len(ref[steps[-1]]), steps[-1]))
    (ol, gl), (os_, gs) = log_ghosts(tn), log_ghosts(ts)
    print("  ghosts on %d ranks: halo levels %d, stock shell (halo single) %d" % (np, gl, gs))
    # the stock shell (twice the obstacles' radius) sends every grain across the cut; the grains'
    # own reach (6.5 mm) still takes the three middle of the five columns across
    if not gl < 0.75 * gs:
        raise C.Fail("hopper: halo levels %d ghosts, not below 0.75 x the stock shell's %d" % (gl, gs))
    print("  PASS")


def test_bad(R, name):
    extra_vars, edit, regex = BAD[name]
    data = R.gen("bad.data", ["bidisperse", "--R", "4", "--n", "6", "--K", "1", "--big-type", "2",
                              "--boundary", "p", "--seed", "1605"])
    deck = DECK_PAIRS
    if edit:
        text = open(DECK_PAIRS).read()
        if edit == "newton on":   # without history, so that pair gran accepts newton on
            text = text.replace("newton          off", "newton          on")
            text = text.replace("tangential history", "tangential no_history")
        elif edit == "triclinic":
            text = text.replace("read_data       ${data}",
                                "read_data       ${data}\nchange_box all triclinic")
        deck = os.path.join(R.work, "in.bad_" + name)
        with open(deck, "w") as f:
            f.write(text)
    rc, text = R.run(deck, "bad_" + name, 1, dict({"data": data, "bnd": "p", "nstyle": "spacetree"},
                                                  **extra_vars), expect_ok=False)
    errs = [l for l in text.splitlines() if "ERROR" in l]
    print("  rc=%d, ERROR lines: %s" % (rc, errs[:2]))
    if rc == 0 or not any(re.search(regex, l) for l in errs):
        raise C.Fail("bad input '%s': expected a non-zero exit and an ERROR matching /%s/" % (name, regex))
    print("  PASS")


def list_tests():
    t = ["pairs:%s:%d" % (c, n) for c in PAIR_CASES for n in (1, 2, 4, 8)]
    t += ["settle:%d" % n for n in (2, 4, 8)] + ["restart:2:4", "restart:4:1", "single:1", "single:2",
                                                  "switch:2", "hopper:2"]
    return t + ["bad:%s" % b for b in BAD]


def dispatch(R, parts):
    if parts[0] == "pairs" and len(parts) == 3 and parts[1] in PAIR_CASES:
        test_pairs(R, parts[1], int(parts[2]))
    elif parts[0] == "settle" and len(parts) == 2:
        test_settle(R, int(parts[1]))
    elif parts[0] == "restart" and len(parts) == 3:
        test_restart(R, int(parts[1]), int(parts[2]))
    elif parts[0] == "single" and len(parts) == 2:
        test_single(R, int(parts[1]))
    elif parts[0] == "switch" and len(parts) == 2:
        test_switch(R, int(parts[1]))
    elif parts[0] == "hopper" and len(parts) == 2:
        test_hopper(R, int(parts[1]))
    elif parts[0] == "bad" and len(parts) == 2 and parts[1] in BAD:
        test_bad(R, parts[1])
    else:
        return False
    return True


if __name__ == "__main__":
    sys.exit(C.driver_main(__doc__, dispatch, list_tests, workdir_prefix="halo_"))
