#!/usr/bin/env python3
"""pair_style trimesh as a granular material: contact sub-models, static friction (tangential
history), LIGGGHTS materials, cohesion, against closed forms (tests/liggghts/pair_trimesh).

  check_pair_trimesh.py TEST --exe EXE --workdir DIR [--mpiexec M --mpiexec-flags F]

Tests (`:2` = on 2 ranks, the bodies on both sides of the rank boundary):
  incline[:2]      a 1 cm cube on a plane tilted by theta (materials, mu 0.5): with tangential
                   history it stays put (moves < 1e-3 of its edge in 1 s) for tan theta = 0.9 mu
                   and slides with g (sin theta - mu cos theta) within 2 % for tan theta = 1.1 mu;
                   the viscous model creeps at 0.9 mu (moves > 1e-3 edge: the test can fail)
  spring[:2]       the cube pushed sideways (rotation no) by F = mu N / 2 rests at the offset
                   F / (n k_t) within 2 % (n contact points); by 1.5 mu N it slides with
                   (F - mu N) / m; the stiffnesses printed at run are 4 E* R* and Mindlin's k_t
  restitution[:2]  three head-on collisions, one per type pair (two materials): each pair's
                   restitution = its coefficientRestitution within 2 %
  cohesion[:2]     two cubes held corner to corner by `cohesion sjkr`, pulled apart by a growing
                   force: they come off at 2 pi R* eps k_c within 2 %
  history_ranks    a pile of 32 dented grains with tangential history and rolling_friction epsd
                   on 1, 2 and 4 ranks: same
                   positions (1e-12 m) and history (number of points; sum of |xi| to 1e-9)
  history_restart[:2]  the pile (with rolling_friction epsd) written to a restart file half way
                   and continued = the same run split in one process (both set up at the
                   half-way step), bit for bit: dumps and the history's thermo columns
  rollback[:2]     two cubes meeting corner to corner with a sideways speed (tangential history,
                   rolling_friction epsd), fix adapt/timestep
                   rollback yes: the step entering the halo too deep is redone with half the step;
                   the redone step's spring (and positions, velocities) = those of a replay of the
                   same step sizes without rollback, bit for bit (the rejected attempt's spring
                   restored away), later steps to 1e-12 (relative)
  shuffle          the incline (hold and slide) with the cube's triangles in another order: the
                   same trajectory and history to 1e-12
  bad              unknown sub-model or keyword, a missing material for a type pair, negative
                   or NaN coefficients, history with newton on, rolling friction missing,
                   negative, with rotation no or newton on: each a clear ERROR
"""
import math
import os
import random
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "trimesh"))
import common as C  # noqa: E402
from trimesh_check import box_triangles, cube_diag_stl  # noqa: E402
from make_hopper import write_stl  # noqa: E402  (trimesh_check puts inputs/hopper on the path)

EDGE, EPS, DENSITY, G, MU = 0.01, 1e-4, 2500.0, 9.81, 0.5
YOUNGS, POISSON = 5e6, 0.3   # in.incline's materials (both types)


def check(cond, what):
    print(("PASS " if cond else "FAIL ") + what, flush=True)
    if not cond:
        raise C.Fail(what)


def thermo(text):
    cols, rows = C.parse_thermo(text)
    return {c: [r[k] for r in rows] for k, c in enumerate(cols)}


def radius(volume):
    return (3.0 * volume / (4.0 * math.pi)) ** (1.0 / 3.0)


def zeta_of_restitution(e):
    """The damping ratio of the approach-only dashpot with restitution e (DampingApproach.h), by
    bisection on its closed form."""
    def restitution(z):
        if z < 1:
            s = math.sqrt(1 - z * z)
            return math.exp(-z / s * math.atan(s / z))
        s = math.sqrt(z * z - 1)
        return math.exp(-z / s * math.atanh(s / z))
    lo, hi = 1e-12, 50.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if restitution(mid) > e else (lo, mid)
    return 0.5 * (lo + hi)


def halo_stiffness(e1, nu1, r1, e2, nu2, r2):
    """S = 4 E* R* (contact_model/MaterialMapping.h), r = inf for a fixed obstacle."""
    estar = 1.0 / ((1 - nu1 ** 2) / e1 + (1 - nu2 ** 2) / e2)
    rstar = r2 if r1 == math.inf else r1 if r2 == math.inf else r1 * r2 / (r1 + r2)
    return 4 * estar * rstar


def mindlin(nu):
    return 2 * (1 - nu) / (2 - nu)


def cube_on_floor_stiffness():
    return halo_stiffness(YOUNGS, POISSON, radius(EDGE ** 3), YOUNGS, POISSON, math.inf)


def write_incline_meshes(wd):
    h = EDGE / 2
    write_stl(os.path.join(wd, "cube.stl"), box_triangles((-h, -h, -h), (h, h, h)))
    # the floor's top face is split along its diagonal, which passes 2.5 cm beside the cube (an
    # edge crossing under a face would add a contact point of its own)
    write_stl(os.path.join(wd, "floor.stl"), box_triangles((-0.055, -0.065, -0.01), (0.055, 0.015, 0.0)))


def incline(R, tag, tantheta, seconds, np, tangential="history", extra="rotation yes", push=0.0,
            ramp=0.0, cube="cube.stl", floor="obstacle"):
    """Runs in.incline (the push grows over `ramp` s); returns the thermo columns and the log."""
    mass = DENSITY * EDGE ** 3
    rest = mass * G * math.cos(math.atan(tantheta)) / (4 * cube_on_floor_stiffness())
    dt = 2e-5
    cols = "v_ncont v_hn v_hsum" if tangential == "history" else "v_ncont"
    _, text = R.run("in.incline", tag, np, dict(
        tangential=tangential, tantheta=tantheta, mu=MU, n=int(round(seconds / dt)), dt=dt,
        z0=EDGE / 2 + 2 * (EPS - rest), push=push, ramp=max(1, int(round(ramp / dt))), extra=extra,
        cube=cube, cols=cols, floor=floor, here=R.deckdir,
        every=1000, procs="2 1 1" if np == 2 else "1 1 1"))
    return thermo(text), text


def slope(t, v, start):
    """Least-squares slope of v(t) over t >= start."""
    pts = [(a, b) for a, b in zip(t, v) if a >= start]
    n = len(pts)
    mt = sum(a for a, _ in pts) / n
    mv = sum(b for _, b in pts) / n
    return sum((a - mt) * (b - mv) for a, b in pts) / sum((a - mt) ** 2 for a, _ in pts)


def case_incline(R, np):
    write_incline_meshes(R.work)
    hold, _ = incline(R, "hold", 0.9 * MU, 1.0, np)
    moved = abs(hold["xg"][-1] - hold["xg"][0])
    check(moved < 1e-3 * EDGE, "incline: tan theta = 0.9 mu, tangential history: moves %.3g m = %.3g "
          "edge in 1 s (< 1e-3)" % (moved, moved / EDGE))
    check(min(hold["hn"][1:]) >= 3,
          "incline: the cube rests on >= 3 contact points with history (%d..%d)"
          % (min(hold["hn"][1:]), max(hold["hn"])))
    theta = math.atan(1.1 * MU)
    slide, _ = incline(R, "slide", 1.1 * MU, 0.3, np)
    a = slope(slide["Time"], slide["vx"], 0.1)
    expected = G * (math.sin(theta) - MU * math.cos(theta))
    check(abs(a / expected - 1) < 0.02, "incline: tan theta = 1.1 mu slides with a = %.5f m/s^2, "
          "g (sin - mu cos) = %.5f (%.2f %%)" % (a, expected, 100 * (a / expected - 1)))
    creep, _ = incline(R, "viscous", 0.9 * MU, 1.0, np, tangential="viscous", extra="friction %g 0.5" % MU)
    moved_v = abs(creep["xg"][-1] - creep["xg"][0])
    check(moved_v > 1e-3 * EDGE, "incline: the viscous model (no static friction) creeps %.3g edge in 1 s "
          "(> 1e-3: the hold test can fail)" % (moved_v / EDGE))


def case_incline_walls(R, np):
    """The hold and slide of case_incline on fix wall/gran floors: an STL mesh wall and a
    primitive zplane (grain-wall contacts keep their tangential history like grain pairs)."""
    write_incline_meshes(R.work)
    theta = math.atan(1.1 * MU)
    expected = G * (math.sin(theta) - MU * math.cos(theta))
    for floor in ("mesh", "primitive"):
        hold, _ = incline(R, "hold_" + floor, 0.9 * MU, 1.0, np, floor=floor)
        moved = abs(hold["xg"][-1] - hold["xg"][0])
        check(moved < 1e-3 * EDGE, "incline on a %s wall: tan theta = 0.9 mu, tangential history: moves "
              "%.3g m = %.3g edge in 1 s (< 1e-3)" % (floor, moved, moved / EDGE))
        check(min(hold["hn"][1:]) >= 3, "incline on a %s wall: >= 3 contact points with history (%d..%d)"
              % (floor, min(hold["hn"][1:]), max(hold["hn"])))
        slide, _ = incline(R, "slide_" + floor, 1.1 * MU, 0.3, np, floor=floor)
        a = slope(slide["Time"], slide["vx"], 0.1)
        check(abs(a / expected - 1) < 0.02, "incline on a %s wall: tan theta = 1.1 mu slides with a = %.5f "
              "m/s^2, g (sin - mu cos) = %.5f (%.2f %%)" % (floor, a, expected, 100 * (a / expected - 1)))


def case_spring(R, np):
    write_incline_meshes(R.work)
    mass = DENSITY * EDGE ** 3
    S = cube_on_floor_stiffness()
    kt = S * mindlin(POISSON)
    for fraction in (0.5, 1.5):
        push = fraction * MU * mass * G
        t, text = incline(R, "push%g" % fraction, 0.0, 0.3, np, extra="rotation no", push=push, ramp=0.1)
        if fraction == 0.5:
            import re
            m = re.search(r"type pair 1 2: stiffness ([0-9.e+-]+) N/m.*tangential stiffness ([0-9.e+-]+) N/m", text)
            check(m is not None and abs(float(m.group(1)) / S - 1) < 1e-3 and abs(float(m.group(2)) / kt - 1) < 1e-3,
                  "spring: printed stiffness %s / tangential %s N/m = 4 E* R* %.4g / Mindlin %.4g"
                  % (m.group(1) if m else "?", m.group(2) if m else "?", S, kt))
            # the stable step with the dashpots (leapfrog: 2 (sqrt(1 + zeta^2) - zeta) / omega) of
            # the normal (zeta of e = 0.5, approach only) and tangential (two-way zeta_t of e)
            # oscillation; rotation no: the contact point's mass is the cube's
            e = 0.5
            zeta = zeta_of_restitution(e)
            zeta_t = -math.log(e) / math.sqrt(math.pi ** 2 + math.log(e) ** 2)
            limit = lambda omega, z: 2 * (math.sqrt(1 + z * z) - z) / omega  # noqa: E731
            stable = min(limit(math.sqrt(S / (2 * mass)), zeta), limit(math.sqrt(kt / mass), zeta_t))
            m = re.search(r"type pair 1 2: .*largest stable time step ([0-9.e+-]+) s", text)
            check(m is not None and abs(float(m.group(1)) / stable - 1) < 1e-3,
                  "spring: printed stable step %s s = %.4g s of the dashpots on the cube's mass"
                  % (m.group(1) if m else "?", stable))
            n = t["ncont"][-1]
            offset = t["xg"][-1] - t["xg"][0]
            expected = push / (n * kt)
            check(abs(offset / expected - 1) < 0.02, "spring: F = mu N / 2 rests at offset %.5g m, "
                  "F / (%d k_t) = %.5g m (%.2f %%)" % (offset, n, expected, 100 * (offset / expected - 1)))
            check(abs(t["vx"][-1]) < 1e-6, "spring: at rest (v %.2g m/s)" % t["vx"][-1])
        else:
            a = slope(t["Time"], t["vx"], 0.15)
            expected = (push - MU * mass * G) / mass
            check(abs(a / expected - 1) < 0.02, "spring: F = 1.5 mu N slides with a = %.5f m/s^2, "
                  "(F - mu N) / m = %.5f" % (a, expected))


def case_restitution(R, np):
    cube_diag_stl(os.path.join(R.work, "cube_diag.stl"), EDGE)
    e = {"11": 0.9, "22": 0.5, "12": 0.7}
    _, text = R.run("in.restitution", "restitution", np, dict(
        e11=e["11"], e22=e["22"], e12=e["12"], v0=0.2, n=5000, dt=1e-6,
        procs="2 1 1" if np == 2 else "1 1 1"))
    t = thermo(text)
    for p in ("11", "22", "12"):
        before, after = t["v" + p][0], t["v" + p][-1]
        measured = -after / before
        check(abs(measured / e[p] - 1) < 0.02, "restitution of type pair %s %s: %.4f vs "
              "coefficientRestitution %.4f (%.2f %%)" % (p[0], p[1], measured, e[p], 100 * (measured / e[p] - 1)))
    check(t["c[1]"][-1] == 0, "restitution: all pairs separated")


def case_cohesion(R, np):
    cube_diag_stl(os.path.join(R.work, "cube_diag.stl"), EDGE)
    ced = 1e5
    r = radius(EDGE ** 3)
    pulloff = 2 * math.pi * (r / 2) * EPS * ced          # R* of two equal cubes: r / 2
    S = halo_stiffness(YOUNGS, POISSON, r, YOUNGS, POISSON, r)
    rest = pulloff / S                                    # one contact point at rest
    x0 = 0.5 * (EDGE * math.sqrt(3) + 2 * (EPS - rest))   # corners 2 (eps - rest) apart
    rate = pulloff / 0.02                                 # N/s: comes off after ~0.02 s
    _, text = R.run("in.cohesion", "cohesion", np, dict(
        x0=x0, ced=ced, rate=rate, n=40000, dt=1e-6, procs="2 1 1" if np == 2 else "1 1 1"))
    t = thermo(text)
    touching = [k for k, c in enumerate(t["c[1]"]) if c > 0]
    check(touching and touching[0] == 0, "cohesion: in contact from the start")
    off = next((k for k in range(len(t["c[1]"])) if t["c[1]"][k] == 0), None)
    check(off is not None, "cohesion: the cubes come apart")
    force = t["F"][off]
    check(abs(force / pulloff - 1) < 0.02, "cohesion: pulled apart at %.5f N, 2 pi R* eps k_c = %.5f N "
          "(%.2f %%)" % (force, pulloff, 100 * (force / pulloff - 1)))


def pile_floor(wd):
    write_stl(os.path.join(wd, "floor.stl"), box_triangles((-0.012, -0.012, -0.004), (0.012, 0.012, 0.0)))


def pile(R, tag, np, n, every, deck="in.pile", **extra):
    procs = {1: "1 1 1", 2: "2 1 1", 4: "2 2 1"}[np]
    variables = dict(n=n, every=every, out=tag, procs=procs, deckdir=HERE)
    variables.update(extra)
    _, text = R.run(deck, tag, np, variables)
    return thermo(text)


def dump(wd, name):
    with open(os.path.join(wd, name)) as f:
        lines = f.read().split("ITEM: ATOMS")[1].splitlines()[1:]
    return {int(l.split()[0]): [float(x) for x in l.split()[1:]] for l in lines if l.strip()}


def case_history_ranks(R):
    pile_floor(R.work)
    n = 2400
    # with rolling resistance: its torques ride in the same records (hsum adds them up)
    runs = {np: pile(R, "np%d" % np, np, n, n, rolling="epsd") for np in (1, 2, 4)}
    ref = dump(R.work, "np1_%d.dump" % n)
    h = runs[1]["hn"][-1]
    # not a vacuous comparison: the grains still bounce at step n (4 points with history there)
    check(h >= 3, "history_ranks: %d contact points with history at step %d" % (h, n))
    for np in (2, 4):
        d = dump(R.work, "np%d_%d.dump" % (np, n))
        dx = max(abs(ref[k][i] - d[k][i]) for k in ref for i in range(3))
        check(dx < 1e-12, "history_ranks: %d ranks: positions = 1 rank's to %.3g m" % (np, dx))
        same_n = runs[np]["hn"] == runs[1]["hn"]
        check(same_n, "history_ranks: %d ranks: the same number of points with history at every output" % np)
        rel = max(abs(a - b) / max(abs(a), 1e-300) for a, b in zip(runs[1]["hsum"],
                                                                 runs[np]["hsum"]) if a)
        check(rel < 1e-9, "history_ranks: %d ranks: sum of |xi| = 1 rank's to %.3g (relative)" % (np, rel))


def case_history_restart(R, np):
    pile_floor(R.work)
    n = 1200
    # with rolling resistance: its torques ride in the same records (hsum adds them up)
    split = pile(R, "split", np, n, 2 * n, after="run %d" % n, rolling="epsd")
    pile(R, "first", np, n, 2 * n, after="write_restart half.restart", rolling="epsd")
    cont = pile(R, "restarted", np, n, 2 * n, deck="in.pile_restart", file="half.restart", rolling="epsd")
    a = open(os.path.join(R.work, "split_%d.dump" % (2 * n))).read()
    b = open(os.path.join(R.work, "restarted_%d.dump" % (2 * n))).read()
    check(a == b, "history_restart: restarted run = the split run, dump at step %d byte for byte" % (2 * n))
    for col in ("hn", "hsum"):
        check(split[col][-len(cont[col]):] == cont[col],
              "history_restart: %s bit-identical at every output after the restart (%d rows, last %r)"
              % (col, len(cont[col]), cont[col][-1]))
    check(cont["hn"][0] > 0, "history_restart: the restart carries %d points with "
          "history" % cont["hn"][0])


ROLLBACK_COLS = ("hn", "hsum", "x1", "x2", "y2", "vy1", "vy2")


def rollback_rows(text):
    """{step: {column: thermo string}} of every thermo row of every run in a log (last one wins)."""
    rows, cols = {}, None
    for line in text.splitlines():
        w = line.split()
        if w and w[0] == "Step":
            cols = w
        elif line.startswith("Loop time"):
            cols = None
        elif cols and len(w) == len(cols) and w[0].isdigit():
            rows[int(w[0])] = dict(zip(cols, w))
    return rows


def case_rollback(R, np):
    from trimesh_check import cube_diag_stl  # noqa: E402
    cube_diag_stl(os.path.join(R.work, "cube_diag.stl"), EDGE)
    vt, dt, n = 0.02, 1e-4, 12
    with open(os.path.join(R.work, "adaptive.in"), "w") as f:
        # the rollback alone (no contact ceiling: dtcontact none)
        f.write("fix dtv all adapt/timestep creep 1.1 dtcontact none veto no rollback yes penetration 0.8\n"
                "thermo_style custom step time dt v_ncont v_hn v_hsum v_x1 v_x2 v_y2 v_vy1 v_vy2 f_dtv[5]\n"
                "thermo_modify format float %%.17g\nrun %d\n" % n)
    procs = "2 1 1" if np == 2 else "1 1 1"
    # with rolling resistance: its torque is restored with the tangential spring
    _, text = R.run("in.rollback", "adaptive", np, dict(vt=vt, dt=dt, steps="adaptive.in", procs=procs,
                                                        rolling="epsd"))
    a = rollback_rows(text)
    redone = [k for k in range(1, n + 1) if float(a[k]["dtv[5]"]) > float(a[k - 1]["dtv[5]"])]
    check(len(redone) == 1 and a[redone[0]]["hn"] == "1",
          "rollback: one step redone (%s), the one that first touches (%s contact point with history)"
          % (redone, a[redone[0]]["hn"] if redone else "-"))
    k0 = redone[0]
    # the step sizes: dt up to the redone step, which fix adapt/timestep redoes with half of it
    # (RollbackPolicy::shrink), then those printed at each row (dt is the next step's size)
    sizes = [dt] * (k0 - 1) + [0.5 * dt] + [float(a[k]["Dt"]) for k in range(k0, n)]
    with open(os.path.join(R.work, "replay.in"), "w") as f:
        f.write("thermo_modify format float %.17g\n")
        for size in sizes:
            f.write("timestep %r\nrun 1\n" % size)
    _, text = R.run("in.rollback", "replay", 1, dict(vt=vt, dt=dt, steps="replay.in", procs="1 1 1",
                                                     rolling="epsd"))
    b = rollback_rows(text)
    same = [c for c in ROLLBACK_COLS if a[k0][c] == b[k0][c]]
    check(len(same) == len(ROLLBACK_COLS), "rollback: the redone step %d = the replay with dt %r without "
          "rollback, bit for bit in %s (spring sum %s)" % (k0, 0.5 * dt, same, a[k0]["hsum"]))
    worst = max(abs(float(a[k][c]) - float(b[k][c])) / max(abs(float(b[k][c])), 1e-300)
                for k in range(k0, n + 1) for c in ROLLBACK_COLS if float(b[k][c]) != 0.0)
    check(worst < 1e-12 and all(a[k]["hn"] == b[k]["hn"] for k in range(k0, n + 1)),
          "rollback: steps %d..%d = the replay to %.3g (relative), the same points with history"
          % (k0, n, worst))


def case_shuffle(R):
    write_incline_meshes(R.work)
    h = EDGE / 2
    tris = box_triangles((-h, -h, -h), (h, h, h)).tolist()
    random.Random(5).shuffle(tris)
    write_stl(os.path.join(R.work, "cube_shuffled.stl"), tris)
    for tantheta, seconds, name in ((0.9 * MU, 0.3, "hold"), (1.1 * MU, 0.2, "slide")):
        a, _ = incline(R, name + "_ordered", tantheta, seconds, 1)
        b, _ = incline(R, name + "_shuffled", tantheta, seconds, 1, cube="cube_shuffled.stl")
        for col, scale in (("xg", EDGE), ("vx", 1e-3), ("hsum", 1e-6)):
            d = max(abs(x - y) for x, y in zip(a[col], b[col])) / scale
            check(d < 1e-12, "shuffle: %s: %s with the triangles reordered = ordered to %.3g (of %g)"
                  % (name, col, d, scale))
        check(a["hn"] == b["hn"],
              "shuffle: %s: the same contact points with history" % name)


BAD_PRELUDE = """atom_style granular
atom_modify map array
boundary f f f
newton {newton}
communicate single vel yes
units si
region box block -0.06 0.06 -0.07 0.03 -0.02 0.03 units box
create_box 2 box
create_atoms 1 single 0.0 0.0 0.0052 units box
create_atoms 2 single 0.001 0.001 -0.002 units box
fix shapes all trimesh/template type 1 file cube.stl density 2500 type 2 file floor.stl fixed
"""
MATERIALS = """fix m1 all property/global youngsModulus peratomtype 5e6 5e6
fix m2 all property/global poissonsRatio peratomtype 0.3 {nu}
fix m3 all property/global coefficientRestitution peratomtypepair 2 0.5 {e} {e} 0.5
fix m4 all property/global coefficientFriction peratomtypepair 2 0.5 0.5 0.5 0.5
"""
RUN = "pair_coeff * *\ntimestep 1e-5\nfix integr all nve/trimesh\nrun 1\n"
BAD = {
    "unknown_sub_model": ("pair_style trimesh eps 1e-4 tangential sticky\n",
                          r"unknown tangential sub-model 'sticky' \(one of: none, viscous, history\)"),
    "unknown_cohesion": ("pair_style trimesh eps 1e-4 cohesion glue\n",
                         r"unknown cohesion sub-model 'glue' \(one of: none, sjkr\)"),
    "unknown_keyword": ("pair_style trimesh eps 1e-4 tangential history wobble 2\n",
                        r"unknown keyword 'wobble'"),
    "missing_material": ("fix m1 all property/global youngsModulus peratomtype 5e6 5e6\n"
                         "fix m2 all property/global poissonsRatio peratomtype 0.3 0.3\n"
                         "pair_style trimesh eps 1e-4\n" + RUN,
                         r"damping .*needs fix property/global coefficientRestitution peratomtypepair"),
    "material_short": ("fix m1 all property/global youngsModulus peratomtype 5e6\n"
                       "fix m2 all property/global poissonsRatio peratomtype 0.3 0.3\n"
                       "pair_style trimesh eps 1e-4 damping 10\n" + RUN,
                       r"youngsModulus has no value for every type pair of the 2 atom types"),
    "missing_friction": ("fix m1 all property/global youngsModulus peratomtype 5e6 5e6\n"
                         "fix m2 all property/global poissonsRatio peratomtype 0.3 0.3\n"
                         "fix m3 all property/global coefficientRestitution peratomtypepair 2 0.5 0.5 0.5 0.5\n"
                         "pair_style trimesh eps 1e-4 tangential history\n" + RUN,
                         r"friction .*needs fix property/global coefficientFriction"),
    "negative_keyword": ("pair_style trimesh eps 1e-4 stiffness -5 damping 1\n",
                         r"stiffness '-5' must be a finite number > 0"),
    "nan_keyword": ("pair_style trimesh eps 1e-4 stiffness 1e5 damping nan\n",
                    r"ERROR.*damping 'nan' must be a finite number"),
    "negative_friction": ("pair_style trimesh eps 1e-4 stiffness 1e5 damping 1 tangential history friction -0.5\n",
                          r"friction MU '-0.5' must be a finite number >= 0"),
    "bad_restitution": (MATERIALS.format(nu=0.3, e=1.5) + "pair_style trimesh eps 1e-4 tangential history\n" + RUN,
                        r"coefficientRestitution = 1.5 for type pair 1 2 must be in \(0, 1\]"),
    "bad_poisson": (MATERIALS.format(nu=0.7, e=0.5) + "pair_style trimesh eps 1e-4\n" + RUN,
                    r"poissonsRatio = 0.7 for type pair 1 2 must be in \[0, 0.5\)"),
    "viscous_gamma": ("pair_style trimesh eps 1e-4 stiffness 1e5 damping 1 tangential viscous friction 0.5\n",
                      r"tangential viscous needs friction MU GAMMA"),
    "gamma_with_history": ("pair_style trimesh eps 1e-4 stiffness 1e5 damping 1 tangential history friction 0.5 2\n",
                           r"GAMMA is the sliding damping of tangential viscous"),
    "kt_without_history": ("pair_style trimesh eps 1e-4 stiffness 1e5 damping 1 tangential_stiffness 1e5\n",
                           r"tangential_stiffness needs tangential history"),
    "unknown_rolling": ("pair_style trimesh eps 1e-4 rolling_friction cdt\n",
                        r"unknown rolling sub-model 'cdt' \(one of: none, epsd\)"),
    "missing_rolling_friction": (MATERIALS.format(nu=0.3, e=0.5) +
                                 "pair_style trimesh eps 1e-4 tangential history rolling_friction epsd\n" + RUN,
                                 r"rolling_friction epsd needs fix property/global coefficientRollingFriction "
                                 r"peratomtypepair"),
    "negative_rolling_friction": (MATERIALS.format(nu=0.3, e=0.5) +
                                  "fix m5 all property/global coefficientRollingFriction peratomtypepair 2 "
                                  "0.2 -0.1 -0.1 0.2\n"
                                  "pair_style trimesh eps 1e-4 tangential history rolling_friction epsd\n" + RUN,
                                  r"coefficientRollingFriction = -0.1 for type pair 1 2 must be >= 0"),
    "rolling_rotation_no": ("pair_style trimesh eps 1e-4 stiffness 1e5 damping 1 rolling_friction epsd rotation no\n",
                            r"rolling_friction needs rotation yes"),
    "rolling_newton_on": ("fix m5 all property/global coefficientRollingFriction peratomtypepair 2 0.2 0.2 0.2 0.2\n"
                          "pair_style trimesh eps 1e-4 stiffness 1e5 damping 1 rolling_friction epsd\n" + RUN,
                          r"requires newton off.*rolling_friction epsd"),
    "history_newton_on": ("pair_style trimesh eps 1e-4 stiffness 1e5 damping 1 tangential history friction 0.5\n" + RUN,
                          r"requires newton off.*tangential history"),
}


def case_bad(R):
    import re
    write_incline_meshes(R.work)
    for name, (body, pattern) in sorted(BAD.items()):
        deck = os.path.join(R.work, "bad_%s.in" % name)
        with open(deck, "w") as f:
            f.write(BAD_PRELUDE.format(newton="on" if name.endswith("newton_on") else "off") + body)
        rc, text = R.run(deck, "bad_" + name, 1, {}, expect_ok=False)
        err = [l for l in text.splitlines() if "ERROR" in l]
        check(rc != 0 and any(re.search(pattern, l) for l in err),
              "bad %s: %s" % (name, err[0].strip() if err else "no ERROR (rc %d)" % rc))


def dispatch(R, parts):
    name = parts[0]
    np = int(parts[1]) if len(parts) > 1 else 1
    cases = {"incline": lambda: case_incline(R, np), "spring": lambda: case_spring(R, np),
             "incline_walls": lambda: case_incline_walls(R, np),
             "restitution": lambda: case_restitution(R, np), "cohesion": lambda: case_cohesion(R, np),
             "history_ranks": lambda: case_history_ranks(R),
             "history_restart": lambda: case_history_restart(R, np),
             "rollback": lambda: case_rollback(R, np),
             "shuffle": lambda: case_shuffle(R), "bad": lambda: case_bad(R)}
    if name not in cases:
        return False
    cases[name]()
    return True


if __name__ == "__main__":
    sys.exit(C.driver_main(__doc__, dispatch))
