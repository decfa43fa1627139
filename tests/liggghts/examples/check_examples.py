#!/usr/bin/env python3
"""Smoke tests of the example decks in inputs/examples/ (run as a user would, from a copy of the
folder).

  check_examples.py [options] TEST

TEST is one of:
  trimesh_drop   in.trimesh_drop (fix trimesh/template, pair_style trimesh, fix nve/trimesh,
                 compute trimesh/contacts, dump trimesh/vtk), full length (20 000 steps): the run
                 completes with all 28 atoms; every 2000 steps one VTK file with the 28 surfaces
                 (27 grains x 40 triangles + the 12-triangle floor, cell data id 1..28); the
                 grains touch the floor (contacts, halo penetration below eps at every thermo
                 row), end on it (lowest centre above the floor's top and within a grain
                 diameter of it) and lose kinetic energy to the contact damping.
  first_deck     in.first_deck (docs/first_triangulated_deck.md: STL and dented templates,
                 materials from fix property/global, tangential history, fix wall/gran floor
                 and cylinder by surface, insertion by particletemplate/trimesh, fix
                 adapt/timestep, dump trimesh/vtk and dump custom quat1..4), 40 000 steps: 40
                 grains inserted and none lost, halo penetration below eps at every row, the
                 step above dtcontact during the fall, at the end every grain inside the
                 container (centre above the floor, within the cylinder), at rest (kinetic
                 energy below 1e-3 of its peak) with unit quaternions.

Runs come from ../common.  Exit status 0 = pass, 1 = fail, 2 = usage / setup problem.
"""

import glob
import math
import os
import re
import shutil
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
import common as C  # noqa: E402

EXAMPLES = os.path.join(C.ROOT, "inputs", "examples")


def vtk_surfaces(path):
    """(polygon count, sorted set of cell-data atom ids) of a dump trimesh/vtk file."""
    text = C.read_text(path)
    polygons = int(re.search(r"^POLYGONS (\d+) ", text, re.M).group(1))
    lines = text.split("\n")
    k = next(i for i, line in enumerate(lines) if line.startswith("SCALARS id"))
    ids = [int(v) for v in lines[k + 2:k + 2 + polygons]]  # after LOOKUP_TABLE
    return polygons, sorted(set(ids))


def test_trimesh_drop(R):
    for f in os.listdir(EXAMPLES):
        shutil.copy(os.path.join(EXAMPLES, f), R.work)
    _, text = R.run(os.path.join(R.work, "in.trimesh_drop"), "drop", 1, {})
    cols, rows = C.parse_thermo(text)
    col = {c: [r[j] for r in rows] for j, c in enumerate(cols)}
    steps = [int(s) for s in col["Step"]]
    print("  %d thermo rows, steps %d..%d" % (len(rows), steps[0], steps[-1]))
    if steps[-1] != 20000:
        raise C.Fail("the run stopped at step %d, not 20000" % steps[-1])
    m = re.search(r"Nlocal:\s+(\d+)", text)
    if not m or int(m.group(1)) != 28:
        raise C.Fail("expected 28 atoms at the end, log says %s" % (m.group(1) if m else None))

    files = sorted(glob.glob(os.path.join(R.work, "drop_*.vtk")),
                   key=lambda p: int(re.search(r"drop_(\d+)\.vtk$", p).group(1)))
    written = [int(re.search(r"drop_(\d+)\.vtk$", p).group(1)) for p in files]
    if written != list(range(0, 20001, 2000)):
        raise C.Fail("dump trimesh/vtk wrote steps %s, expected every 2000 of 0..20000" % written)
    for path in files:
        polygons, ids = vtk_surfaces(path)
        if polygons != 27 * 40 + 12 or ids != list(range(1, 29)):
            raise C.Fail("%s: %d polygons for atoms %s, expected 1092 for atoms 1..28"
                         % (os.path.basename(path), polygons, ids[:5]))
    print("  %d VTK files, each 1092 triangles of atoms 1..28" % len(files))

    # thermo headers are cut to 8 characters (v_ncontacts -> ncontact)
    contacts, penetration = col["ncontact"], col["penetrat"]
    ke, zlow = col["integr"], col["zlow"]
    print("  contacts up to %d, largest penetration %.3f eps, kinetic energy %.3g J (peak %.3g J), "
          "lowest grain centre %.4f m at the end" % (max(contacts), max(penetration), ke[-1], max(ke), zlow[-1]))
    if max(contacts) < 1:
        raise C.Fail("the grains never touched the floor (compute trimesh/contacts reports 0)")
    if not max(penetration) < 1.0:
        raise C.Fail("halo penetration %.3f eps: the rigid surfaces touched" % max(penetration))
    # floor.stl: the floor's top face is z = 0; grains: radius 4 mm, dented by +-25 %
    if not 0.003 - 1e-9 < zlow[-1] < 0.008:
        raise C.Fail("lowest grain centre %.4f m at the end: not resting on the floor (top z = 0)" % zlow[-1])
    if not ke[-1] < 0.5 * max(ke):
        raise C.Fail("kinetic energy %.3g J at the end, peak %.3g J: the contacts dissipated too little"
                     % (ke[-1], max(ke)))
    print("  PASS")


# columns of in.first_deck's dump custom poses_*.txt
POSE_COLUMNS = ("id", "type", "x", "y", "z", "vx", "vy", "vz", "quat1", "quat2", "quat3", "quat4")


def test_first_deck(R):
    for f in os.listdir(EXAMPLES):
        shutil.copy(os.path.join(EXAMPLES, f), R.work)
    n, dtcontact, eps, radius = 40000, 6e-6, 5e-5, 0.03
    _, text = R.run(os.path.join(R.work, "in.first_deck"), "first", 1, {"n": n})
    cols, rows = C.parse_thermo(text)
    col = {c: [r[j] for r in rows] for j, c in enumerate(cols)}
    steps = [int(s) for s in col["Step"]]
    if steps[-1] != n:
        raise C.Fail("the run stopped at step %d, not %d" % (steps[-1], n))
    atoms = [int(a) for s, a in zip(steps, col["Atoms"]) if s > 0]
    if set(atoms) != {40}:
        raise C.Fail("atoms after the insertion step: %s, expected 40 throughout" % sorted(set(atoms)))
    pen, ke, time = col["penetrat"], col["integr"], col["Time"]
    print("  largest penetration %.3f eps, kinetic energy %.3g J at the end (peak %.3g J), "
          "simulated time %.4f s (%.4f s at step %d)" % (max(pen), ke[-1], max(ke), time[-1], time[1], steps[1]))
    if not max(pen) < 1.0:
        raise C.Fail("halo penetration %.3f eps: the rigid surfaces touched" % max(pen))
    if not time[1] > 1.5 * steps[1] * dtcontact:
        raise C.Fail("%.4f s in the first %d steps: the adaptive step never rose above dtcontact %g"
                     % (time[1], steps[1], dtcontact))
    if not ke[-1] < 1e-3 * max(ke):
        raise C.Fail("kinetic energy %.3g J at the end, peak %.3g J: the grains are not at rest" % (ke[-1], max(ke)))
    (_, rows), = C.parse_dump_rows(os.path.join(R.work, "poses_%d.txt" % n))
    poses = [dict(zip(POSE_COLUMNS, row)) for row in rows.values()]
    if len(poses) != 40:
        raise C.Fail("poses_%d.txt has %d grains, expected 40" % (n, len(poses)))
    zmin = min(p["z"] for p in poses)
    rmax = max(math.hypot(p["x"], p["y"]) for p in poses)
    qerr = max(abs(sum(p["quat%d" % i] ** 2 for i in range(1, 5)) - 1.0) for p in poses)
    print("  at the end: lowest centre %.5f m, largest distance from the axis %.5f m, |q|^2 - 1 up to %.1e"
          % (zmin, rmax, qerr))
    if not zmin > 0.0 or not rmax < radius:
        raise C.Fail("a grain centre left the container (floor z = 0, cylinder radius %g m)" % radius)
    # an L prism lying on a face rests with its centre half its 3 mm depth (+ the halo) above the
    # floor; a wall pushing bounding spheres would hold every centre >= 4 mm up
    if not zmin < 0.0017:
        raise C.Fail("lowest grain centre %.5f m: no grain rests on the floor by its surface" % zmin)
    if not qerr < 1e-4:   # the dump prints 6 digits
        raise C.Fail("dump custom quat1..4 are not unit quaternions (|q|^2 - 1 = %.1e)" % qerr)
    if not glob.glob(os.path.join(R.work, "first_%d.vtk" % n)):
        raise C.Fail("dump trimesh/vtk wrote no first_%d.vtk" % n)
    print("  PASS")


def dispatch(R, parts):
    if parts == ["trimesh_drop"]:
        test_trimesh_drop(R)
    elif parts == ["first_deck"]:
        test_first_deck(R)
    else:
        return False
    return True


if __name__ == "__main__":
    sys.exit(C.driver_main(__doc__, dispatch, lambda: ["trimesh_drop", "first_deck"]))
