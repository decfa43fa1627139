#!/usr/bin/env python3
"""Restart regression driver for `fix spacetree` (options and grid state; issue 6).

  check_restart_tree.py [options] TEST

TEST is one of:
  restart:NP      deck in.restart_tree on NP ranks, for grid adaptive and reluctant (non-default
                  shock / threshold / padding): 60 steps + write_restart, then (new process)
                  read_restart + 60 steps, against the same 120 steps in one process (same run
                  boundary).  The restarted run restates the fix
                    - with its options: the grid counters in thermo (comparisons, refinements,
                      coarsenings, cells, leaves, vertices, cube resets) must equal the
                      uninterrupted run's exactly, the particle thermo to THERMO_RTOL, and the
                      log must say the stored grids are reused;
                    - bare (`fix tree all spacetree`): the same, and the log must list the
                      options as taken from the restart file with their stored values;
                    - reluctant only, with a conflicting shock and with another grid type: the
                      warning must name the keyword and both values (other type: the stored
                      grids are dropped); the particle thermo must still equal the reference
                      (the lists never depend on the grid)
  restart:NP:NR   written on NP ranks, read on NR != NP: the warning about the rank count, the
                  run starts from the start-off grid, the particle thermo equals the reference

Runs, parsing and the thermo comparison come from ../common.
Exit status 0 = pass, 1 = fail, 2 = usage / setup problem.
"""

import os
import re
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
import common as C  # noqa: E402

# dilute and fast: the adaptive grid, too, refines and coarsens on most steps
PACK_GEN = ["continuous", "--rmin", "0.4e-3", "--rmax", "4e-3", "--n", "1500", "--fill", "0.1",
            "--boundary", "f", "--vel", "4.0", "--seed", "601"]
DECK = "in.restart_tree"
NFIRST = 60
# thermo columns of in.restart_tree: grid counters (exact) and particle sums (THERMO_RTOL)
GRID_COLS = ["ts[1]", "ts[2]", "ts[3]", "ts[5]", "ts[6]", "ts[7]", "ts[10]"]
PARTICLE_COLS = ["Atoms", "KinEng", "ps[1]", "ps[3]", "ps[4]", "ps[6]"]
OPTIONS = {"adaptive": "grid adaptive padding 0.3",
           "reluctant": "grid reluctant shock 6 threshold 3 padding 0.3"}
STORED_LINE = {"adaptive": "grid adaptive shock 8 threshold 4 maxlevel 12 padding 0.3",
               "reluctant": "grid reluctant shock 6 threshold 3 maxlevel 12 padding 0.3"}


def columns(thermo, names):
    cols, rows = thermo
    missing = [n for n in names if n not in cols]
    if missing:
        raise C.Fail("thermo lacks columns %s (has %s)" % (missing, cols))
    return {n: [r[cols.index(n)] for r in rows] for n in names}


def tail_from(thermo, first):
    return (thermo[0], [r for r in thermo[1] if r[0] >= first])


def expect_in_log(text, pattern, what):
    if not re.search(pattern, text):
        raise C.Fail("%s: the log lacks /%s/" % (what, pattern))


def compare(name, ref, cont, grid_exact):
    """Particle columns to THERMO_RTOL; grid columns exactly (grid_exact)."""
    if not cont[1] or cont[1][0][0] != float(NFIRST):
        raise C.Fail("%s: the restarted run starts at step %s, not %d"
                     % (name, cont[1][0][0] if cont[1] else None, NFIRST))
    ref = tail_from(ref, NFIRST)
    if [r[0] for r in ref[1]] != [r[0] for r in cont[1]]:
        raise C.Fail("%s: thermo steps differ" % name)
    cols = ["Step"] + PARTICLE_COLS
    pick = lambda th: (cols, [[r[th[0].index(c)] for c in cols] for r in th[1]])  # noqa: E731
    worst = C.thermo_diff(pick(ref), pick(cont), name)
    C.report_thermo(name + ": particle thermo", worst, len(ref[1]))
    a, b = columns(ref, GRID_COLS), columns(cont, GRID_COLS)
    diffs = [(c, int(ref[1][i][0]), a[c][i], b[c][i])
             for c in GRID_COLS for i in range(len(a[c])) if a[c][i] != b[c][i]]
    if grid_exact:
        if diffs:
            raise C.Fail("%s: grid counters differ from the uninterrupted run (%d entries), first: "
                         "%s at step %d: %s vs %s" % ((name, len(diffs)) + diffs[0]))
        nrows = len(a["ts[1]"])
        refining = sum(1 for x in a["ts[2]"] if x > 0)
        coarsening = sum(1 for x in a["ts[3]"] if x > 0)
        print("  %s: grid counters equal on all %d rows (refinements %d on %d rows, coarsenings "
              "%d on %d rows)" % (name, nrows, sum(a["ts[2]"]), refining, sum(a["ts[3]"]), coarsening))
        if min(refining, coarsening) < nrows // 3:
            raise C.Fail("%s: deck too weak: the grid refines on %d and coarsens on %d of %d rows"
                         % (name, refining, coarsening, nrows))
    else:
        print("  %s: grid counters differ in %d entries (as they may)" % (name, len(diffs)))


def test_restart(R, np, np_read):
    data = R.gen("pack.data", PACK_GEN)
    grids = ["adaptive", "reluctant"] if np == np_read else ["reluctant"]
    for grid in grids:
        args = OPTIONS[grid]
        rfile = os.path.join(R.work, "%s_np%d.restart" % (grid, np))
        v = {"data": data, "restartfile": rfile, "fixargs": args, "fixargs2": args,
             "nfirst": str(NFIRST), "nsteps": str(2 * NFIRST), "thermoevery": "1"}
        _, t0 = R.run(DECK, "%s_reference_np%d" % (grid, np), np, dict(v, phase="0"))
        ref = C.parse_thermo(t0)
        R.run(DECK, "%s_write_np%d" % (grid, np), np, dict(v, phase="1"))
        if not os.path.isfile(rfile):
            raise C.Fail("write_restart wrote no %s" % rfile)
        tag = "%s_read_np%d" % (grid, np_read)
        if np_read != np:
            _, t = R.run(DECK, tag, np_read, dict(v, phase="2"))
            expect_in_log(t, r"WARNING: Fix spacetree: the restart file holds the grids of %d ranks "
                             r"\(.*\), this run has %d .*start-off grid" % (np, np_read), tag)
            if "reusing the grids" in t:
                raise C.Fail("%s: grids of %d ranks reused on %d" % (tag, np, np_read))
            compare(tag, ref, C.parse_thermo(t), grid_exact=False)
            continue
        # restated with the same options
        _, t = R.run(DECK, tag, np_read, dict(v, phase="2"))
        expect_in_log(t, r"Fix spacetree tree: reusing the grids of %d ranks? from the restart file"
                      % np, tag)
        expect_in_log(t, re.escape("Fix spacetree tree: %s (from the restart file:" % STORED_LINE[grid]), tag)
        compare(tag, ref, C.parse_thermo(t), grid_exact=True)
        # restated bare: every option from the file
        tag = "%s_read_bare_np%d" % (grid, np)
        _, t = R.run(DECK, tag, np, dict(v, phase="2", bare="1"))
        expect_in_log(t, re.escape("Fix spacetree tree: %s (from the restart file: grid shock "
                                   "threshold maxlevel padding)" % STORED_LINE[grid]), tag)
        if "WARNING: Fix spacetree" in t:
            raise C.Fail("%s: unexpected fix spacetree warning" % tag)
        compare(tag, ref, C.parse_thermo(t), grid_exact=True)
        if grid != "reluctant":
            continue
        # conflicting option: the command wins, with a warning; the grids are still reused
        tag = "reluctant_read_shock10_np%d" % np
        _, t = R.run(DECK, tag, np, dict(v, phase="2", fixargs2="grid reluctant shock 10"))
        expect_in_log(t, re.escape("WARNING: Fix spacetree: keyword 'shock' is 10 in this command "
                                   "but 6 in the restart file: using 10"), tag)
        expect_in_log(t, re.escape("Fix spacetree tree: grid reluctant shock 10 threshold 3 "
                                   "maxlevel 12 padding 0.3 (from the restart file: threshold "
                                   "maxlevel padding)"), tag)
        expect_in_log(t, r"reusing the grids", tag)
        compare(tag, ref, C.parse_thermo(t), grid_exact=False)
        # another grid type: the stored grids are dropped
        tag = "reluctant_read_adaptive_np%d" % np
        _, t = R.run(DECK, tag, np, dict(v, phase="2", fixargs2="grid adaptive"))
        expect_in_log(t, re.escape("WARNING: Fix spacetree: keyword 'grid' is adaptive in this "
                                   "command but reluctant in the restart file: using adaptive; the "
                                   "stored grids are dropped (start-off grid)"), tag)
        if "reusing the grids" in t:
            raise C.Fail("%s: reluctant grids reused by an adaptive grid" % tag)
        compare(tag, ref, C.parse_thermo(t), grid_exact=False)
    print("  PASS")


def dispatch(R, parts):
    if parts[0] == "restart" and len(parts) in (2, 3):
        test_restart(R, int(parts[1]), int(parts[-1]))
    else:
        return False
    return True

if __name__ == "__main__":
    sys.exit(C.driver_main(__doc__, dispatch))
