#!/usr/bin/env python3
"""fix move/trimesh: prescribed motion of obstacles (pose from the elapsed time).

  pose       an obstacle cube turning about an inclined axis whose point translates, 10 turns:
             orientation = R(axis, omega t) q0 within 1e-9 rad and position = o + v t +
             R (x0 - o) within 1e-12 m at every dump, velocity = v + w x (x - o(t)), angular
             velocity = omega axis, f_ID[2] = omega t; 1 and 2 ranks (the obstacle migrates)
  restart    write_restart after 5 turns, read_restart and 5 more: the straight run's pose
  turntable  a grain on a slab turning about z, an obstacle (fix move/trimesh) or an STL mesh
             wall (fix move/mesh): friction carries it round at omega x r (the table's surface
             velocity enters the contact law); both tables carry it along the same path
  drum       a small closed drum (inputs/drum/in.drum) with 20 spheres and 20 grains turning a
             quarter turn: every particle stays inside, the drum's angle is omega t; 1 and 2 ranks
  bad        malformed or conflicting commands stop with a clear error

  check_move_trimesh.py CASE [--exe ...] [--workdir DIR]   (CASE list: the cases)
"""
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "trimesh"))
import common as C  # noqa: E402
from common import parse_thermo  # noqa: E402
from trimesh_check import box_triangles, write_stl  # noqa: E402
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(HERE)))
DRUM = os.path.join(ROOT, "inputs", "drum")
sys.path.insert(0, DRUM)
from drum_analysis import Cavity, angle_error_about_y  # noqa: E402

CASES = ["pose", "restart", "turntable", "drum", "bad"]
check = C.Checks()
P, VX, DT = 0.01, -0.05, 1e-5                      # in.pose: period, axis velocity, time step
ORIGIN = (0.004, -0.002, 0.001)
AXIS = (0.3, 1.0, 0.2)




def qmul(a, b):
    w1, x1, y1, z1 = a
    w2, x2, y2, z2 = b
    return (w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2, w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
            w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2, w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2)


def rotate(q, v):
    w, x, y, z = qmul(qmul(q, (0.0,) + tuple(v)), (q[0], -q[1], -q[2], -q[3]))
    return (x, y, z)


def axis_rotation(angle):
    n = math.sqrt(sum(a * a for a in AXIS))
    s = math.sin(angle / 2) / n
    return (math.cos(angle / 2), AXIS[0] * s, AXIS[1] * s, AXIS[2] * s)


def check_pose(frames, label):
    omega = 2 * math.pi / P
    n = math.sqrt(sum(a * a for a in AXIS))
    w = tuple(omega * a / n for a in AXIS)
    x0 = frames[0][1][2][2:5]
    q0 = tuple(frames[0][1][2][5:9])
    worst_angle = worst_pos = worst_v = 0.0
    for step, rows in frames:
        r = rows[2]
        t = step * DT
        qe = qmul(axis_rotation(omega * t), q0)
        d = qmul((qe[0], -qe[1], -qe[2], -qe[3]), tuple(r[5:9]))
        worst_angle = max(worst_angle, 2 * math.atan2(math.sqrt(d[1] ** 2 + d[2] ** 2 + d[3] ** 2), abs(d[0])))
        o = (ORIGIN[0] + VX * t, ORIGIN[1], ORIGIN[2])
        rel = rotate(axis_rotation(omega * t), [x0[k] - ORIGIN[k] for k in range(3)])
        xe = [o[k] + rel[k] for k in range(3)]
        worst_pos = max(worst_pos, max(abs(r[2 + k] - xe[k]) for k in range(3)))
        arm = [r[2 + k] - o[k] for k in range(3)]
        ve = (VX + w[1] * arm[2] - w[2] * arm[1], w[2] * arm[0] - w[0] * arm[2], w[0] * arm[1] - w[1] * arm[0])
        worst_v = max(worst_v, max(abs(r[9 + k] - ve[k]) for k in range(3)),
                      max(abs(r[12 + k] - w[k]) for k in range(3)))
    turns = frames[-1][0] * DT / P
    check(turns > 9.99, "%s: %.2f turns simulated" % (label, turns))
    check(worst_angle < 1e-9, "%s: orientation = R(omega t) q0 within %.3g rad over %d dumps"
          % (label, worst_angle, len(frames)))
    check(worst_pos < 1e-12, "%s: position = o + v t + R (x0 - o) within %.3g m" % (label, worst_pos))
    check(worst_v < 1e-9, "%s: velocity and angular velocity as prescribed (within %.3g)" % (label, worst_v))


def case_pose(R):
    write_stl(os.path.join(R.work, "cube.stl"), box_triangles((-0.005,) * 3, (0.005,) * 3))
    for np_ in (1, 2):
        dump = "pose_np%d.dump" % np_
        _, text = R.run("in.pose", "pose_np%d" % np_, np_, dict(here=R.deckdir, vx=VX, dumpfile=dump))
        check_pose(C.parse_dump_rows(os.path.join(R.work, dump)), "pose %d rank(s)" % np_)
        cols, rows = parse_thermo(text)
        t, a = rows[-1][cols.index("t")], rows[-1][cols.index("a")]
        check(abs(t - 10 * P) < 1e-15 and abs(a - 20 * math.pi) < 1e-12,
              "pose %d rank(s): f_spin = (%.17g s, %.17g rad) = (10 P, 10 turns)" % (np_, t, a))


def case_restart(R):
    write_stl(os.path.join(R.work, "cube.stl"), box_triangles((-0.005,) * 3, (0.005,) * 3))
    R.run("in.pose", "straight", 1, dict(here=R.deckdir, vx=VX, dumpfile="straight.dump"))
    R.run("in.pose", "first", 1, dict(here=R.deckdir, vx=VX, n=5000, restart=1, dumpfile="first.dump"))
    R.run("in.pose", "second", 1, dict(here=R.deckdir, vx=VX, n=5000, start="restart", dumpfile="second.dump"))
    a = C.parse_dump_rows(os.path.join(R.work, "straight.dump"))[-1]
    b = C.parse_dump_rows(os.path.join(R.work, "second.dump"))[-1]
    check(a[0] == b[0] == 10000, "restart: both end at step 10000")
    d = max(abs(x - y) for x, y in zip(a[1][2], b[1][2]))
    check(d < 1e-15, "restart: the restarted obstacle's pose and velocities equal the straight run's "
          "(largest difference %.3g)" % d)


def case_turntable(R):
    write_stl(os.path.join(R.work, "slab.stl"), box_triangles((-0.025, -0.025, -0.005), (0.025, 0.025, 0.0)))
    omega = 2 * math.pi / 2.0
    final = {}
    for table in ("obstacle", "mesh"):
        _, text = R.run("in.turntable", "turntable_" + table, 1, dict(here=R.deckdir, table=table))
        cols, rows = parse_thermo(text)
        last = final[table] = {c: rows[-1][k] for k, c in enumerate(cols)}
        r = math.hypot(last["x"], last["y"])
        expected = (-omega * last["y"], omega * last["x"])   # omega x r about +z
        err = math.hypot(last["vx"] - expected[0], last["vy"] - expected[1]) / (omega * r)
        angle = math.atan2(last["y"], last["x"])
        check(err < 0.05, "turntable %s: the grain is carried round at omega x r (|v - w x r| = %.2g of "
              "w r, w r = %.4g m/s)" % (table, err, omega * r))
        check(angle > 0.5, "turntable %s: it went round with the table (%.2f rad)" % (table, angle))
    # the same surface turned by fix move/mesh (followed by its nodes' rigid motion) and by fix
    # move/trimesh (pose from t): the same grain path. The two compute the same contacts in
    # different frames; the tumbling landing of the dented grain amplifies that round-off from
    # 1e-11 m to ~1e-5 m (the path then stays that far apart): 1e-4 m of a 7 mm path
    a, b = final["obstacle"], final["mesh"]
    dx = math.hypot(a["x"] - b["x"], a["y"] - b["y"])
    dz = abs(a["z"] - b["z"])
    check(dx < 1e-4 and dz < 1e-6, "turntable mesh wall = obstacle: |dxy| %.3g m, |dz| %.3g m" % (dx, dz))


def case_drum(R):
    """A small drum (radius 15 mm, 20 spheres and 20 grains of 1.5 mm) settled, then a quarter
    turn at period 0.5 s (1 rank; 2 ranks: 500 steps of settling, 0.05 turn): every particle
    stays inside, the drum turns by omega t."""
    import subprocess
    subprocess.run([sys.executable, os.path.join(DRUM, "make_drum.py"), os.path.join(R.work, "drum.stl"),
                    os.path.join(R.work, "positions.in"), "--radius", "0.015", "--length", "0.012",
                    "--wall", "0.002", "--segments", "36", "--particles", "40",
                    "--particle-radius", "0.0015", "--spacing", "0.0034"], check=True)
    cavity = Cavity(R=0.015, L=0.012, eps=5e-5, sphere_radius=0.0015, grain_radius=0.0015)
    period, dt = 0.5, 4e-5
    # 2 ranks: a shorter run (falling and the first turning steps; MPI is slow on a busy box)
    for np_, settle, turns, frames in ((1, 3000, 0.25, 7), (2, 500, 0.05, 2)):
        out = "drum_np%d" % np_
        R.run(os.path.join(DRUM, "in.drum"), out, np_,
              dict(diameter=0.003, grain=0.0015, half=0.02, halfy=0.01, period=period, turns=turns,
                   settle=settle, dt=dt, every=500, out=out))
        parts = C.parse_dump_rows(os.path.join(R.work, out + ".particles"))
        drum = C.parse_dump_rows(os.path.join(R.work, out + ".drum"))
        q0 = tuple(drum[0][1][41][2:6])
        worst = min(cavity.worst_margin(list(rows.values())) for _, rows in parts)
        count = {len(rows) for _, rows in parts}
        err = max(abs(angle_error_about_y(tuple(rows[41][2:6]), q0, 2 * math.pi / period * (step - settle) * dt))
                  for step, rows in drum)
        check(count == {40} and len(parts) == frames, "drum %d rank(s): all 40 particles in every one of %d dumps"
              % (np_, len(parts)))
        check(worst > -cavity.eps, "drum %d rank(s): every particle inside the cavity (worst margin %.3g m)"
              % (np_, worst))
        check(err < 1e-9, "drum %d rank(s): the drum turned by omega t (within %.3g rad)" % (np_, err))


def case_bad(R):
    write_stl(os.path.join(R.work, "cube.stl"), box_triangles((-0.005,) * 3, (0.005,) * 3))
    expected = {
        "syntax": "rotate origin Px Py Pz axis Ax Ay Az (period P | omega W)",
        "axis": "the axis must not be zero",
        "twice": "atom type 2 is moved by two fixes",
        "period": "period must not be 0",
    }
    for what, message in expected.items():
        rc, text = R.run("in.bad", "bad_" + what, 1, dict(here=R.deckdir, what=what), expect_ok=False)
        check(rc != 0 and message in text, "bad %s: refused with '%s'" % (what, message))




if __name__ == "__main__":
    dispatch = C.case_dispatch({c: globals()["case_" + c] for c in CASES}, check)
    sys.exit(C.driver_main(__doc__, dispatch, lambda: CASES, "move_trimesh_"))
