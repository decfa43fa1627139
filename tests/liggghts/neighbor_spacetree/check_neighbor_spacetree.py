#!/usr/bin/env python3
"""Regression driver: runs LIGGGHTS decks with `neighbor ... bin` and `neighbor ... spacetree`
and compares what they produce.  Pure Python (no numpy).

  check_neighbor_spacetree.py [options] TEST

TEST is one of (see `check_neighbor_spacetree.py list`):
  pairs:CASE:NP      the sorted pair sets (compute neigh/local, dumped every 10 steps over 40
                     steps of motion, list rebuilt every step) of spacetree on NP ranks equal
                     those of bin on 1 rank (as sets) and of bin on NP ranks (as multisets)
  thermo:settle:NP   thermo of a settling polydisperse pack (walls, gravity, hertz + history),
                     200 steps, full precision: spacetree vs bin on NP ranks within 1e-8 relative
  thermo:settle_wide_skin:NP
                     the same for 8000 grains, skin 2 mm, 600 steps: more than 1 MiB of contact
                     history in one page (zeroed with streaming stores by spacetree), pairs that
                     come into contact long after the build that listed them
  mesh:NP            the same for a pack falling onto an STL funnel (fix mesh/surface/stress +
                     fix wall/gran mesh)
  overflow:NP        crowded big particle (> 2000 neighbours): spacetree with the default
                     neigh_modify one (2000) runs and lists exactly bin's pairs (bin: one 20000)
  bad:NAME           bad input must stop with a non-zero exit code and the ERROR in EXPECTED_ERRORS

Decks: in.pairs, in.mesh, in.bad_* here, ../common/in.settle.  Runs, parsing and comparisons
come from ../common.  Exit status 0 = pass, 1 = fail, 2 = usage / setup problem.
"""

import os
import re
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
import common as C  # noqa: E402
from common import (PAIR_CASES, PAIR_VARS, SETTLE_GEN, SETTLE_WIDE_GEN, Fail, compare_pairsets,  # noqa: E402
                    cross_pairs, parse_atoms_dump, parse_local_dump, parse_stats, parse_thermo,
                    report_thermo, thermo_diff)

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

MESH_STL = ["stl-funnel", "--bottom", "0.015", "--top", "0.025", "--height", "0.02", "--z0", "0.0"]
MESH_GEN = ["continuous", "--rmin", "0.4e-3", "--rmax", "1.2e-3", "--fill", "0.3",
            "--box", "0.03", "0.03", "0.01", "--origin", "-0.015", "-0.015", "0.00005",
            "--domain", "-0.026", "0.026", "-0.026", "0.026", "-0.001", "0.025",
            "--boundary", "f", "--vel", "0.3", "--vz0", "-0.5", "--seed", "301"]
CROWDED_GEN = ["crowded", "--R", "40", "--gap", "0.05", "--vel", "0.2", "--bigs-first", "--seed", "401"]


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
    return thb, ss


# name -> (generator, in.settle variables, least contact history in bytes at the end (3 values
# of 8 bytes per listed pair))
SETTLE_CASES = {
    "settle": (SETTLE_GEN, {}, 0),
    "settle_wide_skin": (SETTLE_WIDE_GEN, {"skin": "2e-3", "nsteps": "600", "thermoevery": "20"}, 1 << 20),
}


def test_settle(R, name, np):
    gen, extra, least_history = SETTLE_CASES[name]
    data = R.gen(name + ".data", gen)
    thb, stats = test_thermo(R, os.path.join(C.COMMON, "in.settle"), dict(extra, data=data), np, name)
    history = 24 * stats.get("neighbors", 0) / np
    if history <= least_history:
        raise Fail("deck too weak: %.0f bytes of contact history per rank <= %d" % (history, least_history))
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
    thb, _ = test_thermo(R, "in.mesh", {"data": data, "stl": stl}, np, "mesh")
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
    t += ["thermo:settle:1", "thermo:settle:2", "thermo:settle_wide_skin:1", "mesh:1", "mesh:2",
          "overflow:1", "overflow:2"]
    t += ["bad:%s" % n for n in EXPECTED_ERRORS]
    return t


def dispatch(R, parts):
    if parts[0] == "pairs" and len(parts) == 3 and parts[1] in PAIR_CASES:
        test_pairs(R, parts[1], int(parts[2]))
    elif parts[0] == "thermo" and len(parts) == 3 and parts[1] in SETTLE_CASES:
        test_settle(R, parts[1], int(parts[2]))
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
    sys.exit(C.driver_main(__doc__, dispatch, list_tests))
