#!/usr/bin/env python3
"""MPI regression driver for `neighbor ... spacetree` sphere runs (issue 6).

  check_ranks.py [options] TEST

TEST is one of:
  ranks:CASE:NP   the same deck with spacetree on 1 rank and on NP ranks: the same particle count
                  in every thermo row (exactly) and the same thermo to THERMO_RTOL (1e-8
                  relative).  CASE settle: the in.settle pack (radii 0.5-2.5 mm); wide: radii
                  0.4-4 mm (ratio 10, several tree levels, so virtual links and coarse ghosts
                  cross the subdomain boundaries)
  restart:NP[:NR] in.restart: 100 steps + write_restart on NP ranks, then read_restart + 100
                  steps on NR ranks (default NP), against the same 200 steps in one process on
                  NP ranks (same run boundary); the particle count exactly, the thermo to
                  THERMO_RTOL

Runs, parsing and the thermo comparison come from ../common (deck in.settle there).
Exit status 0 = pass, 1 = fail, 2 = usage / setup problem.
"""

import os
import re
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
import common as C  # noqa: E402

RANK_CASES = {
    "settle": C.SETTLE_GEN,
    "wide": ["continuous", "--rmin", "0.4e-3", "--rmax", "4e-3", "--n", "3000", "--fill", "0.4",
             "--boundary", "f", "--vel", "1.0", "--seed", "601"],
}
MIN_CONTACTS = 100  # c_nc at some row: the pack must really collide


def processor_grid(text):
    m = re.search(r"(\d+) by (\d+) by (\d+) MPI processor grid", text)
    return tuple(int(g) for g in m.groups()) if m else None


def check_atoms(name, ref, test):
    ja, jb = ref[0].index("Atoms"), test[0].index("Atoms")
    a = [int(r[ja]) for r in ref[1]]
    b = [int(r[jb]) for r in test[1]]
    if a != b:
        raise C.Fail("%s: particle counts differ: %s vs %s" % (name, a, b))
    return a[-1]


def check_contacts(name, thermo):
    cols, rows = thermo
    nc = max(r[cols.index("nc")] for r in rows)
    if nc < MIN_CONTACTS:
        raise C.Fail("%s: deck too weak: at most %d contacts" % (name, nc))
    return nc


def test_ranks(R, case, np):
    data = R.gen(case + ".data", RANK_CASES[case])
    v = {"data": data, "nstyle": "spacetree"}
    deck = os.path.join(C.COMMON, "in.settle")
    _, t1 = R.run(deck, "spacetree_np1", 1, v)
    _, tn = R.run(deck, "spacetree_np%d" % np, np, v)
    grid = processor_grid(tn)
    if grid is None or grid[0] * grid[1] * grid[2] != np:
        raise C.Fail("run on %d ranks reports processor grid %s" % (np, grid))
    th1, thn = C.parse_thermo(t1), C.parse_thermo(tn)
    atoms = check_atoms("%s np1 vs np%d" % (case, np), th1, thn)
    nc = check_contacts(case, th1)
    print("  %d particles on a %s processor grid, up to %d contacts (c_nc)" % (atoms, grid, nc))
    worst = C.thermo_diff(th1, thn, case)
    C.report_thermo("%s spacetree np%d vs np1" % (case, np), worst, len(th1[1]))
    print("  PASS")


def test_restart(R, np, np_read):
    data = R.gen("settle.data", C.SETTLE_GEN)
    v = {"data": data, "restartfile": os.path.join(R.work, "settle.restart")}
    _, t0 = R.run("in.restart", "reference_np%d" % np, np, dict(v, phase="0"))
    R.run("in.restart", "write_np%d" % np, np, dict(v, phase="1"))
    if not os.path.isfile(v["restartfile"]):
        raise C.Fail("write_restart wrote no %s" % v["restartfile"])
    _, t2 = R.run("in.restart", "read_np%d" % np_read, np_read, dict(v, phase="2"))
    ref = C.parse_thermo(t0)
    cont = C.parse_thermo(t2)
    first = cont[1][0][0] if cont[1] else None
    if first != 100.0:
        raise C.Fail("the restarted run starts at step %s, not 100" % first)
    ref = (ref[0], [r for r in ref[1] if r[0] >= first])
    atoms = check_atoms("restart np%d -> np%d" % (np, np_read), ref, cont)
    nc = check_contacts("restart", ref)
    print("  %d particles, up to %d contacts; comparing steps %d..%d"
          % (atoms, nc, ref[1][0][0], ref[1][-1][0]))
    worst = C.thermo_diff(ref, cont, "restart")
    C.report_thermo("restart written on %d, read on %d ranks vs uninterrupted" % (np, np_read),
                    worst, len(ref[1]))
    print("  PASS")


def dispatch(R, parts):
    if parts[0] == "ranks" and len(parts) == 3 and parts[1] in RANK_CASES:
        test_ranks(R, parts[1], int(parts[2]))
    elif parts[0] == "restart" and len(parts) in (2, 3):
        test_restart(R, int(parts[1]), int(parts[-1]))
    else:
        return False
    return True

if __name__ == "__main__":
    sys.exit(C.driver_main(__doc__, dispatch))
