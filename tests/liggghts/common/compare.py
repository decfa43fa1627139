"""Comparisons of two runs: pair sets per dumped step (sets or multisets, with the distance to
the cutoff of each differing pair) and thermo columns (worst relative difference per column)."""

import math

from .runner import Fail

THERMO_RTOL = 1e-8


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
