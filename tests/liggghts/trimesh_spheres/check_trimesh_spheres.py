#!/usr/bin/env python3
"""Spheres beside triangulated grains (pair_style hybrid gran ... trimesh ...): spheres meet
grains and obstacles as exact spheres against triangles, through pair_style trimesh's contact
law; sphere pairs stay with pair gran.

  restitution  a sphere moving onto a cube grain's face (no gravity): the normal restitution is
               the halo spring-dashpot's e(zeta), zeta = D sqrt(2/S), within 2 %, against a fixed
               obstacle (the sphere's own velocity) and a free cube hit head-on (relative
               velocity); one contact, penetration below eps, the cube does not spin
  hybrid       27 spheres settling with Hertz + tangential history between primitive walls: the
               same trajectories bit for bit under pair_style gran and under pair_style hybrid
               gran ... trimesh ... (pair gran's history survives the skip list)
  mixed        24 spheres and 24 grains poured together onto an obstacle floor between primitive
               walls: none lost, penetrations below eps, a bed several particles high comes to
               rest; 2 ranks = 1 rank (first 3000 steps)

  check_trimesh_spheres.py CASE [--exe ...] [--workdir DIR]   (CASE list: the cases)
"""
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "trimesh"))
import common as C  # noqa: E402
from common import parse_thermo  # noqa: E402
from trimesh_check import box_triangles, restitution_analytic, write_stl  # noqa: E402

EPS = 1e-4
CASES = ["restitution", "hybrid", "mixed"]
check = C.Checks()



def table(text):
    cols, rows = parse_thermo(text)
    return {c: [r[k] for r in rows] for k, c in enumerate(cols)}


def case_restitution(R):
    write_stl(os.path.join(R.work, "cube.stl"), box_triangles((-0.005,) * 3, (0.005,) * 3))
    S, D, v0 = 1e4, 10.0, 0.5
    e_ref, zeta = restitution_analytic(S, D)
    print("analytic restitution e = %.6f (zeta = %.4f)" % (e_ref, zeta))
    for fixed in ("fixed", "free"):
        _, text = R.run("in.sphere_impact", "impact_" + fixed, 1,
                        dict(here=R.deckdir, fixed=fixed, S=S, D=D, v0=v0))
        t = table(text)
        vrel = [a - b for a, b in zip(t["vz1"], t["vz2"])]
        e = vrel[-1] / -vrel[0]
        check(abs(e / e_ref - 1) < 0.02, "restitution %s cube: e %.5f vs %.5f (%.2f %%)"
              % (fixed, e, e_ref, 100 * (e / e_ref - 1)))
        check(max(t["ncont"]) == 1 and t["ncont"][-1] == 0,
              "restitution %s cube: one contact point, separated at the end" % fixed)
        check(0 < max(t["pen"]) < EPS, "restitution %s cube: largest penetration %.3g m below eps"
              % (fixed, max(t["pen"])))
        check(max(abs(w) for w in t["wx2"]) < 1e-9, "restitution %s cube: a head-on impact does not spin it"
              % fixed)


def case_hybrid(R):
    res = {}
    for style in ("gran", "hybrid"):
        _, text = R.run("in.spheres_only", "spheres_" + style, 1, dict(here=R.deckdir, style=style))
        res[style] = parse_thermo(text)[1]
    a, b = res["gran"], res["hybrid"]
    check(len(a) == len(b) and a == b,
          "hybrid: pair gran under pair_style hybrid gives the trajectory of plain pair_style gran "
          "(%d thermo rows, KE %.15g vs %.15g, rotational KE %.15g vs %.15g)"
          % (len(a), a[-1][2], b[-1][2], a[-1][3], b[-1][3]))
    check(a[-1][3] > 0, "hybrid: the spheres roll (tangential forces acted)")


def case_mixed(R):
    write_stl(os.path.join(R.work, "floor.stl"), box_triangles((-0.012, -0.012, -0.005), (0.012, 0.012, 0.0)))
    res = {}
    for np_, n in ((1, 10000), (2, 3000)):   # 2 ranks: the first impacts (MPI is slow on a busy box)
        _, text = R.run("in.mixed", "mixed_np%d" % np_, np_, dict(here=R.deckdir, n=n))
        res[np_] = table(text)
    t = res[1]
    check(min(t["Atoms"]) == max(t["Atoms"]) == 49, "mixed: no particle lost (49 atoms)")
    check(0 < max(t["pen"]) < EPS, "mixed: largest penetration %.3g m below eps" % max(t["pen"]))
    # 48 particles of 3 mm on a 24 mm square floor (about 64 sites): a second layer, its
    # centres above 1.5 diameters
    check(min(t["zmin"]) > 0 and t["zmax"][-1] > 0.0045,
          "mixed: every particle stays above the floor (lowest centre %.3g m), the bed has a second "
          "layer (highest centre %.3g m)" % (min(t["zmin"]), t["zmax"][-1]))
    check(t["ke"][-1] < 0.01 * max(t["ke"]), "mixed: the pour comes to rest (KE %.3g J of peak %.3g J)"
          % (t["ke"][-1], max(t["ke"])))
    d = max(abs(x - y) / max(abs(x), 1e-30) for x, y in zip(res[1]["ke"], res[2]["ke"]))
    check(len(res[2]["ke"]) == 7 and d < 1e-9,
          "mixed: 2 ranks = 1 rank over the first 3000 steps (kinetic energy within %.3g relative)" % d)




if __name__ == "__main__":
    dispatch = C.case_dispatch({c: globals()["case_" + c] for c in CASES}, check)
    sys.exit(C.driver_main(__doc__, dispatch, lambda: CASES, "trimesh_spheres_"))
