"""Generated packs that the decks of several folders share (arguments of scripts/gen_pack.py)."""

import collections

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
# The same settling pack with 8000 grains: with a skin of 2 mm it lists ~47 000 pairs, so the
# contact history of one page (24 bytes per pair) passes the 1 MiB above which the spacetree
# list builder zeroes it with streaming stores.
SETTLE_WIDE_GEN = [("8000" if w == "3000" else w) for w in SETTLE_GEN]
