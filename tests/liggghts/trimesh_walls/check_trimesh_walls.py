#!/usr/bin/env python3
"""Triangulated grains against the walls of fix wall/gran, by their surfaces (pair_style trimesh):

  rest      a dented grain dropped onto a floor whose top face is z = 0 comes to rest at the same
            height (1e-6 m) on a fixed obstacle, a primitive zplane and an STL mesh wall; its
            lowest vertex lies within the two halos (0 < gap < 2 eps) and the penetration is
            what the spring needs to carry the weight; the stress mesh carries the grain's weight
  belt      the same floors moving at 0.05 m/s along x (fix move/trimesh, wall/gran shear, fix
            move/mesh): friction brings the grain to the floor's speed, the three agree
  cylinder  a grain inside a horizontal primitive cylinder (xcylinder) settles on it (viscous
            friction: it creeps towards the bottom), its surface 0 < gap < 2 eps from the cylinder
  ranks     primitive and mesh floors on 2 ranks give the 1-rank trajectory
  bad       fix move/trimesh on a grain type, a touching sphere pair under pair_style trimesh
            alone, a wall with grains but without pair_style trimesh: clear errors

  check_trimesh_walls.py CASE [--exe ...] [--workdir DIR]   (CASE list: the cases)
"""
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "trimesh"))
import common as C  # noqa: E402
from common import parse_thermo  # noqa: E402
from trimesh_check import box_triangles, read_vtk, write_stl  # noqa: E402

EPS = 1e-4
CASES = ["rest", "belt", "cylinder", "ranks", "bad"]
check = C.Checks()



def floors(work):
    write_stl(os.path.join(work, "floor.stl"), box_triangles((-0.03, -0.03, -0.01), (0.03, 0.03, 0.0)))
    # smaller than the box: the moving mesh wall must stay inside it
    write_stl(os.path.join(work, "belt.stl"), box_triangles((-0.02, -0.02, -0.01), (0.02, 0.02, 0.0)))


def final(R, floor, np_=1, **variables):
    tag = "%s_np%d%s" % (floor, np_, "_belt" if float(variables.get("belt", 0)) else "")
    _, text = R.run("in.walls", tag, np_, dict(floor=floor, here=R.deckdir, **variables))
    cols, rows = parse_thermo(text)
    return {c: rows[-1][k] for k, c in enumerate(cols)}, rows, cols


def lowest_point(R, floor, n):
    pts, _, _ = read_vtk(os.path.join(R.work, "walls_%s_%d.vtk" % (floor, n)))
    return pts


def case_rest(R):
    n = 90000   # the grain bounces on its dents for ~60 000 steps (restitution 0.67 per contact point)
    res = {}
    for floor in ("obstacle", "primitive", "mesh"):
        last, _, _ = final(R, floor, n=n)
        res[floor] = last
        pts = lowest_point(R, floor, n)
        gap = pts[:, 2].min()
        check(0 < gap < 2 * EPS, "rest %s: lowest vertex %.4g m above the floor, within the two halos (0, %g)"
              % (floor, gap, 2 * EPS))
        check(last["ke"] < 1e-10 and last["ncont"] >= 1,
              "rest %s: at rest (KE %.3g J, %d contacts)" % (floor, last["ke"], last["ncont"]))
        check(0 < last["pen"] < 0.01 * EPS, "rest %s: penetration %.3g m, a small part of eps" % (floor, last["pen"]))
    z = [res[f]["zg"] for f in res]
    check(max(z) - min(z) < 1e-6, "rest: same height on obstacle, primitive and mesh walls: %s (spread %.3g m)"
          % (", ".join("%.12g" % v for v in z), max(z) - min(z)))
    # the force on the mesh = -(contact force on the grain) = -(f_grain + m g), the same step
    mesh = res["mesh"]
    contact_z = mesh["fz"] + mesh["m"] * 9.81
    check(mesh["fwall"] < 0 and abs(mesh["fwall"] + contact_z) < 1e-9 * abs(contact_z),
          "rest: fix mesh/surface/stress gets the grain's contact force: %.9g N vs %.9g N"
          % (mesh["fwall"], -contact_z))


def case_belt(R):
    n, belt = 100000, 0.05
    res = {}
    for floor in ("obstacle", "primitive", "mesh"):
        last, rows, cols = final(R, floor, n=n, belt=belt, stl="belt.stl", every=10000)
        res[floor] = (last, rows)
        check(abs(last["vx"] / belt - 1) < 1e-3,
              "belt %s: friction brings the grain to the floor's speed: vx %.8g vs %g" % (floor, last["vx"], belt))
    # the bounces differ a little (the moving floors' triangles pass under the grain at other
    # places than the primitive's patch), the state on the belt does not
    ref = res["obstacle"][0]
    for floor in ("primitive", "mesh"):
        last = res[floor][0]
        dz, dv = abs(last["zg"] - ref["zg"]), abs(last["vx"] - ref["vx"])
        check(dz < 1e-6 and dv < 1e-6 * belt, "belt %s = obstacle on the belt: |dz| %.3g m, |dvx| %.3g m/s"
              % (floor, dz, dv))


def case_cylinder(R):
    n = 110000
    last, _, _ = final(R, "cylinder", n=n, z0=-0.003)
    pts = lowest_point(R, "cylinder", n)
    far = max(math.hypot(p[1], p[2] - 0.01) for p in pts)
    gap = 0.02 - far
    check(0 < gap < 2 * EPS, "cylinder: the grain's surface %.4g m from the cylinder, within the two halos"
          % gap)
    # viscous friction holds nothing on a slope: the grain creeps towards the bottom, slowly
    check(last["ke"] < 1e-8 and last["ncont"] >= 1, "cylinder: settled on the wall (KE %.3g J, %d contacts)"
          % (last["ke"], last["ncont"]))


def case_ranks(R):
    for floor in ("primitive", "mesh"):
        _, rows1, _ = final(R, floor, n=20000, every=2000)
        _, rows2, _ = final(R, floor, np_=2, n=20000, every=2000)
        dz = max(abs(a[1] - b[1]) for a, b in zip(rows1, rows2))
        check(len(rows1) == len(rows2) and dz < 1e-12, "ranks %s: 2 ranks = 1 rank (|dz| <= %.3g m)" % (floor, dz))


def case_bad(R):
    rc, text = R.run("in.bad", "bad_move", 1, dict(what="move", here=R.deckdir), expect_ok=False)
    check(rc != 0 and "Fix move/trimesh: atom type 1 is not an obstacle" in text,
          "bad: fix move/trimesh on a grain type is refused")
    rc, text = R.run("in.bad", "bad_spheres", 1, dict(what="spheres", here=R.deckdir), expect_ok=False)
    check(rc != 0 and "need pair_style gran" in text and "touch" in text,
          "bad: touching spheres under pair_style trimesh alone are refused")
    rc, text = R.run("in.bad", "bad_nopair", 1, dict(what="nopair", here=R.deckdir), expect_ok=False)
    check(rc != 0 and "would treat the grains as their bounding spheres" in text,
          "bad: a wall with grains but without pair_style trimesh is refused")




if __name__ == "__main__":
    dispatch = C.case_dispatch({c: globals()["case_" + c] for c in CASES}, check, before=lambda R: floors(R.work))
    sys.exit(C.driver_main(__doc__, dispatch, lambda: CASES, "trimesh_walls_"))
