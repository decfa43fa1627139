#!/usr/bin/env python3
"""Regression driver for `fix spacetree grid regular|adaptive|reluctant` and `compute treestats`.

  check_adaptive_grid.py [options] TEST

TEST is one of (see `check_adaptive_grid.py list`):
  pairs:CASE:NP    a polydisperse deck of the foundation (common.PAIR_CASES): for each grid
                   type, the pair sets (compute neigh/local, dumped every 10 of 40 steps, lists
                   rebuilt every step) of spacetree + fix spacetree on NP ranks equal bin's on NP
                   ranks (multisets) and on 1 rank (sets); the adaptive grids must refine
  moving:NP        randomised: a dilute 1:20 continuous gas with fast random velocities
                   (seed from $SPACETREE_TEST_SEED, default 701), lists rebuilt every step, pairs
                   dumped every 3 of 180 steps, for all three grid types; the adaptive and
                   reluctant grids must refine and coarsen on many steps while staying exact
  paper71          the §7.1 deck (inputs/paper71/in.two_spheres_grid, 40 000 steps) for the three
                   grids: the spheres touch on the same steps; regular and adaptive compare the
                   pair only shortly before impact (<= 8 comparisons per step); reluctant compares
                   it over more steps but uses fewer cells than adaptive, which uses far fewer
                   than regular
  empty:NP         compute treestats in thermo output of a box that is empty at setup and filled
                   by fix insert/pack during the run (in.treestats_empty), every grid type, NP
                   ranks: the run completes, step 0 reports zeros, after the insertion the real
                   particles equal the atom count and the sweep compares pairs
  bad:NAME         bad input stops with a non-zero exit code and a clear ERROR (BAD_INPUT)

Exit status 0 = pass, 1 = fail, 2 = usage / setup problem.  Reuses ../common's runner, dump
parsers and comparisons.
"""

import os
import re
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
import common as cr  # noqa: E402

GRIDS = ["regular", "adaptive", "reluctant"]
DECK = "in.grid_pairs"
PAIR_CASE_NAMES = ["r10_cont_periodic", "r100_bi_periodic", "r100_cont_walled"]

MOVING_STEPS = 180
MOVING_DUMP = 3

# name: (fixargs, extra -var settings, regex the ERROR line must match)
BAD_INPUT = {
    "gridtype": ("grid bogus", {}, r"ERROR.*fix spacetree.*unknown grid type 'bogus'"),
    "gridmissing": ("adaptive", {}, r"ERROR.*fix spacetree.*expected 'grid"),
    "keyword": ("grid reluctant heat 3", {}, r"ERROR.*fix spacetree.*unknown keyword 'heat'"),
    "novalue": ("grid reluctant shock", {}, r"ERROR.*fix spacetree.*keyword 'shock' needs"),
    "threshold": ("grid reluctant shock 4 threshold 4", {},
                  r"ERROR.*fix spacetree.*threshold 4 must be below shock 4"),
    "maxlevel": ("grid adaptive maxlevel 13", {}, r"ERROR.*fix spacetree.*maxlevel 13"),
    "noneighbor": ("grid adaptive", {"nstyle": "bin"},
                   r"ERROR.*[Ff]ix spacetree requires 'neighbor <skin> spacetree'"),
    "treestats": ("grid adaptive", {"usefix": "0", "usecompute": "1"},
                  r"ERROR.*[Cc]ompute treestats requires fix spacetree"),
}
BAD_DATA = ["bidisperse", "--R", "1", "--n", "4", "--boundary", "p"]


def thermo_columns(text):
    cols, rows = cr.parse_thermo(text)
    return {c: [r[j] for r in rows] for j, c in enumerate(cols)}


def check_grid_runs(R, base, np, periodic, skin, label, min_refining_steps=0):
    """bin np1 (and npN) reference, then the three grid types; returns per-grid thermo columns."""
    R.run(DECK, "bin_np1", 1, dict(base, nstyle="bin"))
    ref = cr.parse_local_dump(os.path.join(R.work, "bin_np1.pairs"))
    atoms, boxes = cr.parse_atoms_dump(os.path.join(R.work, "bin_np1.atoms"))
    steps = list(ref.keys())
    first = ref[steps[0]]
    changed = len(set(ref[steps[0]]) ^ set(ref[steps[-1]]))
    print("  bin np1: %d dumped steps, %d distinct pairs at step %d, %d cross-size, %d pair changes"
          % (len(steps), len(first), steps[0], cr.cross_pairs(first, atoms[steps[0]]), changed))
    binn = ref
    if np > 1:
        R.run(DECK, "bin_np%d" % np, np, dict(base, nstyle="bin"))
        binn = cr.parse_local_dump(os.path.join(R.work, "bin_np%d.pairs" % np))
        cr.compare_pairsets("bin np%d vs bin np1 (harness sanity)" % np, ref, binn, False, atoms, boxes,
                            periodic, skin)
    stats = {}
    for grid in GRIDS:
        tag = "%s_np%d" % (grid, np)
        rc, text = R.run(DECK, tag, np, dict(base, nstyle="spacetree", usegrid="1", grid=grid))
        st = cr.parse_local_dump(os.path.join(R.work, tag + ".pairs"))
        cr.compare_pairsets("%s grid np%d vs bin np%d" % (grid, np, np), binn, st, True, atoms, boxes,
                            periodic, skin)
        if np > 1:
            cr.compare_pairsets("%s grid np%d vs bin np1" % (grid, np), ref, st, False, atoms, boxes,
                                periodic, skin)
        th = thermo_columns(text)
        stats[grid] = th
        refining = sum(1 for v in th["ts[2]"][1:] if v > 0)
        coarsening = sum(1 for v in th["ts[3]"][1:] if v > 0)
        print("  %-9s == bin on %d dumped steps; thermo rows %d: comparisons %d..%d, cells %d..%d, "
              "deepest level %d..%d, steps refining %d, coarsening %d, refinements %d, coarsenings %d"
              % (grid, len(steps), len(th["Step"]), min(th["ts[1]"]), max(th["ts[1]"]), min(th["ts[5]"]),
                 max(th["ts[5]"]), min(th["ts[4]"]), max(th["ts[4]"]), refining, coarsening,
                 sum(th["ts[2]"]), sum(th["ts[3]"])))
        if any(int(a) != int(n) for a, n in zip(th["Atoms"], th["ts[8]"])):
            raise cr.Fail("%s: treestats real particles (sum over ranks) differ from the atom count" % grid)
        if grid == "regular" and (sum(th["ts[2]"]) or sum(th["ts[3]"])):
            raise cr.Fail("regular grid reports refinements or coarsenings")
        if grid != "regular":
            if th["ts[2]"][0] <= 0:
                raise cr.Fail("%s grid did not refine at the first build" % grid)
            if refining < min_refining_steps or coarsening < min_refining_steps:
                raise cr.Fail("%s grid refined on %d and coarsened on %d steps after the first, "
                              "expected >= %d each (deck too weak)" % (grid, refining, coarsening,
                                                                       min_refining_steps))
    print("  PASS %s: all grid types list bin's pairs on %d rank(s)" % (label, np))
    return stats


def test_pairs(R, case, np):
    c = cr.PAIR_CASES[case]
    data = R.gen(case + ".data", c["gen"])
    base = dict(cr.PAIR_VARS, data=data, bnd=c["bnd"], thermoevery="1")
    base.update(c.get("vars", {}))
    check_grid_runs(R, base, np, c["bnd"] == "p", float(base["skin"]), "pairs:%s" % case)


def test_moving(R, np):
    seed = os.environ.get("SPACETREE_TEST_SEED", "701")
    print("  seed %s (set SPACETREE_TEST_SEED to vary)" % seed)
    # dilute 1:20 gas, periodic, fast: particles cross many fine cells, pairs form and break
    gen = ["continuous", "--rmin", "0.5e-3", "--rmax", "1e-2", "--n", "3000", "--fill", "0.25",
           "--boundary", "p", "--vel", "6.0", "--seed", seed]
    data = R.gen("moving.data", gen)
    base = dict(data=data, bnd="p", skin="1e-3", nsteps=str(MOVING_STEPS), dumpevery=str(MOVING_DUMP),
                thermoevery="1", dt="5e-6")
    stats = check_grid_runs(R, base, np, True, 1e-3, "moving", min_refining_steps=MOVING_STEPS // 3)
    cells = {g: sum(stats[g]["ts[5]"]) / len(stats[g]["ts[5]"]) for g in GRIDS}
    print("  mean cells per step: %s" % ", ".join("%s %.0f" % (g, cells[g]) for g in GRIDS))


def test_paper71(R):
    deck = os.path.join(cr.ROOT, "inputs", "paper71", "in.two_spheres_grid")
    res = {}
    for grid in GRIDS:
        rc, text = R.run(deck, grid, 1, {"grid": grid, "every": "1"})
        th = thermo_columns(text)
        touching = [int(s) for s, d in zip(th["Step"], th["dist"]) if d <= 0.11]
        compared = [t for t, c in zip(th["Time"], th["ts[1]"]) if c > 0]
        res[grid] = dict(touching=touching, compared=compared, max_comp=max(th["ts[1]"]),
                         total=sum(th["ts[1]"]), cells=sum(th["ts[5]"]) / len(th["ts[5]"]),
                         deepest=max(th["ts[4]"]))
        r = res[grid]
        print("  %-9s touching steps %s..%s (%d), comparisons on %d steps (first at t=%.3f s), max %d, "
              "total %d, mean cells %.1f, deepest level %d"
              % (grid, touching[0] if touching else None, touching[-1] if touching else None, len(touching),
                 len(compared), compared[0] if compared else -1, r["max_comp"], r["total"], r["cells"],
                 r["deepest"]))
    if not res["regular"]["touching"]:
        raise cr.Fail("the spheres never touched (expected at t ~ 2.68 s)")
    for grid in GRIDS:
        r = res[grid]
        if r["touching"] != res["regular"]["touching"]:
            raise cr.Fail("%s: the spheres touch on other steps than with the regular grid" % grid)
        if not 1 <= r["max_comp"] <= 8:
            raise cr.Fail("%s: %d comparisons in one step (expected 1..8)" % (grid, r["max_comp"]))
    for grid in ("regular", "adaptive"):
        if res[grid]["compared"][0] < 2.0:
            raise cr.Fail("%s compares the far-apart spheres already at t = %.3f s" % (grid, res[grid]["compared"][0]))
    if not res["reluctant"]["total"] > res["adaptive"]["total"]:
        raise cr.Fail("reluctant should make more comparisons than adaptive")
    if not res["reluctant"]["cells"] < res["adaptive"]["cells"] < 0.01 * res["regular"]["cells"]:
        raise cr.Fail("expected cells: reluctant < adaptive < 1%% of regular")
    # the leaf-cell VTK output of the fix: one file per output step, as many voxels as leaves
    rc, text = R.run(deck, "adaptive_vtk", 1, {"grid": "adaptive", "every": "13000", "nsteps": "26000",
                                               "vtk": "13000"})
    th = thermo_columns(text)
    for step, leaves in zip(th["Step"][1:], th["ts[6]"][1:]):
        path = os.path.join(R.work, "grid_adaptive_%d.vtk" % int(step))
        if not os.path.exists(path):
            raise cr.Fail("fix spacetree vtk wrote no %s" % path)
        with open(path, "rb") as f:
            head = f.read(4096)
        m = re.search(rb"CELLS (\d+) (\d+)", open(path, "rb").read())
        if not head.startswith(b"# vtk DataFile Version 3.0") or not m or int(m.group(1)) != int(leaves):
            raise cr.Fail("%s: expected a legacy VTK file with %d cells (the leaf count of compute "
                          "treestats)" % (path, leaves))
        print("  %s: %d leaf cells, as compute treestats reports" % (os.path.basename(path), leaves))
    print("  PASS")


def test_empty(R, np):
    for grid in GRIDS:
        rc, text = R.run("in.treestats_empty", "empty_%s_np%d" % (grid, np), np,
                         {"grid": grid, "np": str(np)})
        th = thermo_columns(text)
        first = {c: th[c][0] for c in ("Atoms", "ts[1]", "ts[5]", "ts[8]")}
        last = {c: th[c][-1] for c in ("Atoms", "ts[1]", "ts[5]", "ts[8]")}
        print("  %-9s step 0: %s; step %d: %s" % (grid, first, int(th["Step"][-1]), last))
        if any(v != 0 for v in first.values()):
            raise cr.Fail("%s: the empty box should report zeros at step 0, got %s" % (grid, first))
        if last["Atoms"] != 50 or last["ts[8]"] != last["Atoms"]:
            raise cr.Fail("%s: after insertion treestats counts %s real particles for %s atoms"
                          % (grid, last["ts[8]"], last["Atoms"]))
        if not (last["ts[1]"] > 0 and last["ts[5]"] > 0):
            raise cr.Fail("%s: no comparisons or cells after the insertion" % grid)
    print("  PASS")


def test_bad(R, name):
    fixargs, extra, regex = BAD_INPUT[name]
    v = dict(extra, data=R.gen("bad.data", BAD_DATA), fixargs=fixargs)
    if name == "noneighbor":  # control: the same fix with spacetree runs
        R.run("in.bad_grid", "control", 1, dict(v, nstyle="spacetree"))
        print("  control run with neighbor spacetree succeeded")
    rc, text = R.run("in.bad_grid", "bad_" + name, 1, v, expect_ok=False)
    errs = [l for l in text.splitlines() if "ERROR" in l]
    print("  rc=%d, ERROR lines: %s" % (rc, errs[:2]))
    if rc == 0:
        raise cr.Fail("bad input '%s' did not fail (rc 0)" % name)
    if not any(re.search(regex, l) for l in errs):
        raise cr.Fail("bad input '%s': no ERROR line matches /%s/" % (name, regex))
    print("  PASS (non-zero exit, message matches /%s/)" % regex)


def list_tests():
    t = ["pairs:%s:%d" % (c, n) for c in PAIR_CASE_NAMES for n in (1, 2)]
    t += ["moving:1", "moving:2", "paper71", "empty:1", "empty:2"] + ["bad:%s" % n for n in BAD_INPUT]
    return t


def dispatch(R, parts):
    if parts[0] == "pairs" and len(parts) == 3 and parts[1] in cr.PAIR_CASES:
        test_pairs(R, parts[1], int(parts[2]))
    elif parts[0] == "moving" and len(parts) == 2:
        test_moving(R, int(parts[1]))
    elif parts == ["paper71"]:
        test_paper71(R)
    elif parts[0] == "empty" and len(parts) == 2 and parts[1] in ("1", "2"):
        test_empty(R, int(parts[1]))
    elif parts[0] == "bad" and len(parts) == 2 and parts[1] in BAD_INPUT:
        test_bad(R, parts[1])
    else:
        return False
    return True

if __name__ == "__main__":
    sys.exit(cr.driver_main(__doc__, dispatch, list_tests, workdir_prefix="grid_"))
