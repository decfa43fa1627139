#!/usr/bin/env python3
"""Regression tests of the triangulated rigid particles (pair_style trimesh, fix trimesh/template,
fix nve/trimesh, dump trimesh/vtk, compute trimesh/contacts).

  trimesh_check.py CASE --exe EXE --workdir DIR [--mpiexec M --mpiexec-flags=F]

Cases (each prints PASS/FAIL lines; exit status 0 = all passed):
  collide   two cubes corner to corner: restitution = the spring-dashpot value (damping only
            while approaching) within 2 %, for exact/penalty/hybrid, rotation yes/no, and under
            fix adapt/timestep (reset_dt of fix nve/trimesh)
  floor     dented sphere on a fixed floor: comes to rest (kinetic energy < 1e-12 J), the surface
            never sinks more than eps below the floor, contacts stay
  edge      a tilted cube dropped on its edge turns the right way and ends flat on a face
  insert    grains from fix insert/pack get their templates (1 and 2 ranks) and land on a floor;
            particletemplate/trimesh inserts the grain's bounding sphere with its mass (INFO
            line), a too small particletemplate/sphere is refused
  pose      dump custom quat1..quat4 and f_ID_state[1..7] of freely spinning box grains: the known
            rotation and angular momentum (1 and 2 ranks)
  big_obstacle  grains on a fixed floor 17 times wider than the box: neighbor spacetree runs it as
            bin does, same trajectories (1 and 2 ranks)
  ranks     six spinning particles crossing the rank boundary: 1 and 2 ranks give the same surfaces
  restart   write_restart / read_restart half way = one uninterrupted run
  bad       bad input stops with a clear ERROR; the printed Newton-step schedule (defaults,
            iterations/continuation, a repeated pair_style line starts from the defaults)
  hopper    short version of inputs/hopper: no particle lost, no penetration beyond eps
"""
import argparse
import glob
import math
import os
import re
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(HERE)))
sys.path.insert(0, os.path.join(ROOT, "inputs", "hopper"))
from make_hopper import write_stl  # noqa: E402  (one ASCII STL writer for decks and tests)
OK = True


def check(cond, what):
    global OK
    print(("PASS " if cond else "FAIL ") + what, flush=True)
    OK = OK and bool(cond)


def box_triangles(lo, hi):
    """Closed, outward-oriented box."""
    x0, y0, z0 = lo
    x1, y1, z1 = hi
    v = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
         (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    quads = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (2, 3, 7, 6), (1, 2, 6, 5), (3, 0, 4, 7)]
    tris = []
    for a, b, c, d in quads:
        tris.append((v[a], v[b], v[c]))
        tris.append((v[a], v[c], v[d]))
    return np.array(tris, dtype=float)


def rotation_onto(a, b):
    a = a / np.linalg.norm(a)
    b = b / np.linalg.norm(b)
    v = np.cross(a, b)
    c = float(np.dot(a, b))
    k = np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])
    return np.eye(3) + k + k @ k / (1.0 + c)


def cube_diag_stl(path, edge):
    h = edge / 2
    tris = box_triangles((-h, -h, -h), (h, h, h))
    r = rotation_onto(np.array([1.0, 1.0, 1.0]), np.array([1.0, 0.0, 0.0]))
    write_stl(path, tris @ r.T)


def write_obj(path, tris, scale=1.0):
    """Indexed Wavefront OBJ (shared vertices, 1-based faces) of a triangle soup."""
    index, verts, faces = {}, [], []
    for t in tris:
        f = []
        for v in t:
            key = tuple(float(c) for c in v)
            if key not in index:
                index[key] = len(verts) + 1
                verts.append(key)
            f.append(index[key])
        faces.append(f)
    with open(path, "w") as out:
        out.write("# cube\n")
        for v in verts:
            out.write("v %.17g %.17g %.17g\n" % tuple(c * scale for c in v))
        for f in faces:
            out.write("f %d %d %d\n" % tuple(f))


def run(a, deck, workdir, name, vars_, np_=1, expect_fail=False, timeout=600):
    log = os.path.join(workdir, "log." + name)
    cmd = [a.exe, "-in", os.path.join(HERE, deck), "-log", log, "-echo", "none"]
    for k, v in vars_.items():
        cmd += ["-var", k, str(v)]
    if np_ > 1:
        cmd = [a.mpiexec] + [f for f in a.mpiexec_flags.split(";") if f] + ["-np", str(np_)] + cmd
    p = subprocess.run(cmd, cwd=workdir, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       errors="replace", text=True, timeout=timeout)
    if p.returncode != 0 and not expect_fail:
        print(p.stdout[-3000:])
    return p.returncode, p.stdout, log


def thermo(log):
    rows, on = [], False
    for line in open(log, errors="replace"):
        s = line.strip()
        if s.startswith("Step"):
            on = True
            continue
        if on:
            if s.startswith("Loop time"):
                on = False
                continue
            try:
                rows.append([float(t) for t in s.split()])
            except ValueError:
                pass
    return np.array(rows)


def read_vtk(path):
    """Points (n x 3) and per-cell ids of a dump trimesh/vtk file."""
    lines = open(path).read().split("\n")
    i = next(k for k, l in enumerate(lines) if l.startswith("POINTS"))
    n = int(lines[i].split()[1])
    pts = np.array([[float(t) for t in l.split()] for l in lines[i + 1:i + 1 + n]])
    j = next(k for k, l in enumerate(lines) if l.startswith("POLYGONS"))
    m = int(lines[j].split()[1])
    cells = np.array([[int(t) for t in l.split()[1:]] for l in lines[j + 1:j + 1 + m]])
    k = next(k for k, l in enumerate(lines) if l.startswith("SCALARS id"))
    ids = np.array([int(l) for l in lines[k + 2:k + 2 + m]])
    return pts, cells, ids


def restitution_analytic(S, D):
    """Eq. (1): F = S (eps - d/2) + 2 D sqrt(m_eff) v_n while approaching. In the relative
    approach delta = 2 eps - d the spring is S/2, so omega0^2 = S / (2 m_eff) and the damping
    ratio zeta = D / sqrt(S/2), independent of the mass. Compression damped, restitution
    undamped: e = exp(-zeta / sqrt(1 - zeta^2) * atan(sqrt(1 - zeta^2) / zeta))."""
    zeta = D / math.sqrt(S / 2.0)
    w = math.sqrt(1.0 - zeta * zeta)
    return math.exp(-zeta / w * math.atan2(w, zeta)), zeta


def case_collide(a):
    wd = a.workdir
    cube_diag_stl(os.path.join(wd, "cube_diag.stl"), 0.01)
    # the same cube as an OBJ in millimetres, read with `scale 1e-3` by the penalty run
    h = 0.005
    r = rotation_onto(np.array([1.0, 1.0, 1.0]), np.array([1.0, 0.0, 0.0]))
    write_obj(os.path.join(wd, "cube_diag_mm.obj"), box_triangles((-h, -h, -h), (h, h, h)) @ r.T, 1000.0)
    S, D, v0 = 5e5, 150.0, 0.5
    e_ref, zeta = restitution_analytic(S, D)
    print("analytic restitution e = %.6f (zeta = %.4f)" % (e_ref, zeta))
    adapt = "fix ad all adapt/timestep creep 1.1 dtmax 2e-6 dtcontact 5e-7"
    for method, rot, extra in (("exact", "no", None), ("hybrid", "yes", None), ("penalty", "yes", None),
                               ("hybrid", "yes", adapt)):
        vars_ = dict(method=method, rot=rot, S=S, D=D, v0=v0, n=2500)
        if method == "penalty":
            vars_["shape"] = "cube_diag_mm.obj scale 1e-3"
            rot += " (OBJ in mm, scale 1e-3)"
        if extra:
            vars_["adapt"] = extra
            rot += " + fix adapt/timestep"
        rc, out, log = run(a, "trimesh_collide.in", wd, "collide_%s_%s" % (method, "adapt" if extra else rot), vars_)
        check(rc == 0, "collide %s rotation %s runs" % (method, rot))
        if rc != 0:
            continue
        t = thermo(log)
        vrel, ncont, pen = t[:, 1], t[:, 2], t[:, 3]
        e = vrel[-1] / (-vrel[0])
        check(abs(e / e_ref - 1) < 0.02,
              "collide %s rotation %s: restitution %.5f vs analytic %.5f (%.2f %%)"
              % (method, rot, e, e_ref, 100 * (e / e_ref - 1)))
        check(ncont.max() == 1, "collide %s: corner-corner contact is one de-duplicated point (max %d)"
              % (method, ncont.max()))
        check(0 < pen.max() < 1e-4, "collide %s: largest penetration %.3g in (0, eps): surfaces never touch" % (method, pen.max()))
        check(ncont[-1] == 0, "collide %s: cubes separated at the end" % method)
        if extra:
            dt = t[:, 5]
            check(dt.min() <= 5e-7 * (1 + 1e-12) and dt[-1] == 2e-6,
                  "collide with fix adapt/timestep: dt cut to dtcontact at impact (min %.3g s), back to 2e-6 s"
                  % dt.min())
            # the integrator follows the changing step: separation speed = d(sep)/d(time)
            time_, sep = t[:, 6], t[:, 7]
            speed = (sep[-1] - sep[-10]) / (time_[-1] - time_[-10])
            check(abs(speed / vrel[-1] - 1) < 1e-6,
                  "collide with fix adapt/timestep: d(separation)/d(time) %.8g = v_rel %.8g" % (speed, vrel[-1]))


def case_floor(a):
    wd = a.workdir
    write_stl(os.path.join(wd, "floor.stl"), box_triangles((-0.025, -0.025, -0.01), (0.025, 0.025, 0.0)))
    n = 60000
    rc, out, log = run(a, "trimesh_floor.in", wd, "floor",
                       dict(n=n, method="hybrid", S=2e4, D=100, gamma=5))
    check(rc == 0, "floor runs")
    if rc != 0:
        return
    t = thermo(log)
    ke = t[:, 4]
    print("kinetic energy every 6000 steps:", " ".join("%.3g" % k for k in ke[::6]))
    check(ke[-1] < 1e-12, "floor: kinetic energy at the end %.3g J < 1e-12 J" % ke[-1])
    check(ke[-1] < 1e-6 * ke.max(), "floor: kinetic energy decayed by > 1e6 (max %.3g J)" % ke.max())
    check(t[-1, 2] >= 2, "floor: grain rests on >= 2 contact points at the end (%d)" % t[-1, 2])
    eps = 1e-4
    check(t[:, 3].max() < eps, "floor: penetration below eps, surfaces never touch (max %.3g)" % t[:, 3].max())
    pts, cells, ids = read_vtk(os.path.join(wd, "floor_%d.vtk" % n))
    grain = np.unique(cells[ids == 1])
    zmin = pts[grain, 2].min()
    check(-eps <= zmin <= 2 * eps, "floor: lowest grain vertex z = %.3g in [-eps, 2 eps] above the floor top 0" % zmin)
    floor = np.unique(cells[ids == 2])
    check(abs(pts[floor, 2].max()) < 1e-12 and abs(pts[floor, 0].min() + 0.025) < 1e-12,
          "floor: obstacle stays where the file puts it")


def case_edge(a):
    """A cube tilted by 30 degrees about y, dropped onto its lowest edge (at x > 0 of its centre):
    the floor's push at that edge must turn it with omega_y < 0 (towards lying flat), and it
    must come to rest on a face (its vertices at two heights, 0 + halo and the edge length)."""
    wd = a.workdir
    write_stl(os.path.join(wd, "floor.stl"), box_triangles((-0.025, -0.025, -0.01), (0.025, 0.025, 0.0)))
    h, th = 0.005, math.radians(30)
    c, s_ = math.cos(th), math.sin(th)
    ry = np.array([[c, 0, s_], [0, 1, 0], [-s_, 0, c]])
    write_stl(os.path.join(wd, "cube_tilt.stl"), box_triangles((-h, -h, -h), (h, h, h)) @ ry.T)
    z0 = h * (s_ + c) + 0.0003
    n = 60000
    rc, out, log = run(a, "trimesh_floor.in", wd, "edge",
                       dict(n=n, method="hybrid", S=2e4, D=100, gamma=5, grain="file cube_tilt.stl",
                            z0=z0, th=100))
    check(rc == 0, "edge: cube dropped on its edge runs")
    if rc != 0:
        return
    t = thermo(log)
    ncont, wy = t[:, 2], t[:, 5]
    first = int(np.argmax(ncont > 0))
    check(ncont.max() > 0, "edge: the edge hits the floor at step %d" % t[first, 0])
    after = wy[first + 1:first + 20]
    check(after.size > 0 and after[np.argmax(np.abs(after))] < 0,
          "edge: it starts rotating with omega_y < 0 (largest |omega_y| after impact %.4g rad/s)"
          % after[np.argmax(np.abs(after))])
    pts, cells, ids = read_vtk(os.path.join(wd, "floor_%d.vtk" % n))
    z = np.sort(pts[np.unique(cells[ids == 1]), 2])
    check(abs(z[:4].max() - z[:4].min()) < 1e-5 and abs(z[4:].min() - z[:4].max() - 2 * h) < 1e-5 and
          0 < z[0] < 2e-4,
          "edge: the cube ends flat on a face (vertex heights %.3g..%.3g and %.5g..%.5g m)"
          % (z[0], z[3], z[4], z[7]))


GRAIN_MASS = 1.2269e-4     # the deck's dented sphere, 2500 kg/m^3
GRAIN_REACH = 0.0030098    # its bounding radius + eps


def case_insert(a):
    """Grains inserted by fix insert/pack get their template (radius = bounding radius + eps,
    template mass, orientation) before the next list build, on 1 and 2 ranks, and land on the
    floor; the insertion template is the grain's (particletemplate/trimesh: its bounding sphere,
    the INFO line counts the grains' mass) or a sphere large enough (a warning names the mass it
    counts); a sphere smaller than the grain is refused."""
    wd = a.workdir
    n = 4000
    for np_, rsphere in ((1, 0), (2, 0), (1, 0.0031)):
        what = "insert: %d rank(s), %s" % (np_, "particletemplate/sphere" if rsphere else "particletemplate/trimesh")
        sub = os.path.join(wd, "np%d_%s" % (np_, "sphere" if rsphere else "trimesh"))
        os.makedirs(sub, exist_ok=True)
        write_stl(os.path.join(sub, "floor.stl"), box_triangles((-0.025, -0.025, -0.01), (0.025, 0.025, 0.0)))
        rc, out, log = run(a, "trimesh_insert.in", sub, "insert", dict(n=n, np=np_, rsphere=rsphere), np_=np_)
        m = re.search(r"inserted (\d+) particle templates \(mass ([0-9.eE+-]+)\)", out)
        check(rc == 0 and m and int(m.group(1)) == 20, "%s: 20 grains inserted" % what)
        if rc != 0 or not m:
            return
        t = thermo(log)
        t = t[1:]   # step 0: before the insertion
        check((t[:, 1] == 21).all(), "%s: no grain lost (21 atoms with the floor)" % what)
        rmax, mmin = t[:, 4].max(), t[:, 5].min()
        check(abs(rmax - GRAIN_REACH) < 1e-7 and abs(mmin - GRAIN_MASS) < 1e-7,
              "%s: radius = template bounding radius + eps (%.6g), mass = template mass %.6g kg"
              % (what, rmax, mmin))
        info = float(m.group(2))
        if rsphere:
            sphere_mass = 2500 * 4 / 3 * math.pi * rsphere ** 3
            check(abs(info - 20 * sphere_mass) < 1e-3 * info and
                  re.search(r"WARNING: Fix particletemplate/sphere pts1 inserts grains of type 1 as spheres", out),
                  "%s: the INFO line counts the spheres' mass (%.6g kg), and a warning says so" % (what, info))
        else:
            check(abs(info - 20 * mmin) < 1e-6 * info,
                  "%s: the INFO line reports the grains' mass %.7g kg = 20 x %.7g kg" % (what, info, mmin))
        check(t[:, 2].max() >= 1 and t[:, 3].max() < 5e-5,
              "insert: %d rank(s): grains reach the floor (max contacts %d), penetration %.3g < eps"
              % (np_, t[:, 2].max(), t[:, 3].max()))
        pts, cells, ids = read_vtk(os.path.join(sub, "insert_%d.vtk" % n))
        check(np.isfinite(pts).all() and len(np.unique(ids)) == 21 and pts[:, 2].min() > -0.0101,
              "%s: 21 finite surfaces in the last frame" % what)
    # A sphere template smaller than the grain's bounding sphere: refused, naming the fix and
    # the radius needed (it would insert overlapping grains).
    sub = os.path.join(wd, "small")
    os.makedirs(sub, exist_ok=True)
    write_stl(os.path.join(sub, "floor.stl"), box_triangles((-0.025, -0.025, -0.01), (0.025, 0.025, 0.0)))
    rc, out, log = run(a, "trimesh_insert.in", sub, "insert", dict(n=n, np=1, rsphere=0.0025), expect_fail=True)
    m = re.search(r"ERROR: Fix particletemplate/sphere pts1 inserts atom type 1 .* radius 0.0025 m, below the "
                  r"grain's bounding radius \+ eps 0.00300\d* m", out)
    check(rc != 0 and m and "inserted" not in out,
          "insert: a sphere template smaller than the grain is an error before any insertion (%s)"
          % (m.group(0)[:90] if m else out[-300:]))


def read_custom_dump(path):
    """dump custom file -> list of (step, {column: array}) (rows sorted by id)."""
    frames, lines = [], open(path).read().split("\n")
    i = 0
    while i < len(lines):
        if lines[i].startswith("ITEM: TIMESTEP"):
            step = int(lines[i + 1])
            n = int(lines[i + 3])
            cols = lines[i + 8].split()[2:]
            rows = np.array([[float(v) for v in l.split()] for l in lines[i + 9:i + 9 + n]])
            rows = rows[np.argsort(rows[:, 0])]
            frames.append((step, {c: rows[:, k] for k, c in enumerate(cols)}))
            i += 9 + n
        else:
            i += 1
    return frames


def case_pose(a):
    """dump custom quat1..quat4 and f_<template>_state[1..7] of two box grains spinning freely
    about principal axes (1 and 2 ranks): the quaternion is the known rotation, exp(w t / 2 e),
    over several turns, and the angular momentum is I w with the box's closed-form moments."""
    wd = a.workdir
    write_stl(os.path.join(wd, "box.stl"), box_triangles((-0.003, -0.002, -0.001), (0.003, 0.002, 0.001)))
    n, every, dt, w1, w2 = 20000, 1000, 1e-5, 50.0, -30.0
    mass = 2000 * 6e-3 * 4e-3 * 2e-3
    i_long = mass * (4e-3 ** 2 + 2e-3 ** 2) / 12     # about x, the 6 mm side (smallest moment)
    i_short = mass * (6e-3 ** 2 + 4e-3 ** 2) / 12    # about z, the 2 mm side (largest moment)
    for np_ in (1, 2):
        sub = os.path.join(wd, "np%d" % np_)
        os.makedirs(sub, exist_ok=True)
        write_stl(os.path.join(sub, "box.stl"), box_triangles((-0.003, -0.002, -0.001), (0.003, 0.002, 0.001)))
        rc, out, log = run(a, "trimesh_pose.in", sub, "pose", dict(n=n, every=every, w1=w1, w2=w2), np_=np_)
        check(rc == 0, "pose: %d rank(s): dump custom quat1..4 and f_shapes_state[1..7] run" % np_)
        if rc != 0:
            return
        frames = read_custom_dump(os.path.join(sub, "pose.dump"))
        quat_err = state_err = angmom_err = 0.0
        for step, c in frames:
            t = step * dt
            q = np.array([c["quat%d" % k] for k in (1, 2, 3, 4)]).T
            want = np.array([[math.cos(w1 * t / 2), 0, 0, math.sin(w1 * t / 2)],
                             [math.cos(w2 * t / 2), math.sin(w2 * t / 2), 0, 0]])
            quat_err = max(quat_err, np.abs(q - want).max())
            f = np.array([c["f_shapes_state[%d]" % k] for k in range(1, 8)]).T
            state_err = max(state_err, np.abs(f[:, :4] - q).max())
            L = np.array([[0, 0, i_short * w1], [i_long * w2, 0, 0]])
            angmom_err = max(angmom_err, np.abs(f[:, 4:] - L).max() / np.abs(L).max())
        turns = abs(w1) * n * dt / (2 * math.pi)
        check(len(frames) == n // every + 1 and quat_err < 1e-10,
              "pose: %d rank(s): dumped quaternions = exp(w t/2 e) over %.1f turns (max error %.2g)"
              % (np_, turns, quat_err))
        check(state_err == 0.0, "pose: %d rank(s): f_shapes_state[1..4] = quat1..quat4" % np_)
        check(angmom_err < 1e-12, "pose: %d rank(s): f_shapes_state[5..7] = I w (box moments; max rel. "
              "error %.2g)" % (np_, angmom_err))


def case_big_obstacle(a):
    """A fixed floor slab 0.4 x 0.3 m in a box 24 mm wide (its bounding sphere spans 20 boxes):
    neighbor spacetree runs the deck as bin does (1 and 2 ranks), with the same trajectories,
    and the grains land on the floor (none falls through or is lost)."""
    wd = a.workdir
    n = 10000
    res = {}
    for np_, nstyle in ((1, "bin"), (1, "spacetree"), (2, "spacetree")):
        tag = "%s_np%d" % (nstyle, np_)
        sub = os.path.join(wd, tag)
        os.makedirs(sub, exist_ok=True)
        write_stl(os.path.join(sub, "floor.stl"), box_triangles((-0.2, -0.15, -0.01), (0.2, 0.15, 0.0)))
        rc, out, log = run(a, "trimesh_big_obstacle.in", sub, "big", dict(n=n, np=np_, nstyle=nstyle), np_=np_)
        check(rc == 0, "big obstacle: neighbor %s, %d rank(s) runs (the obstacle is 17 boxes wide)" % (nstyle, np_))
        if rc != 0:
            return
        frames = read_custom_dump(os.path.join(sub, "big_obstacle.dump"))
        res[tag] = (thermo(log), frames[-1][1])
    t, last = res["bin_np1"]
    check((t[:, 1] == 6).all() and t[:, 2].max() >= 1 and t[-1, 4] > 0.0019 and t[-1, 4] < 0.003,
          "big obstacle: grains land on the floor (contacts up to %d, lowest centre %.4g m, none lost)"
          % (t[:, 2].max(), t[-1, 4]))
    cols = ["x", "y", "z", "quat1", "quat2", "quat3", "quat4"]
    for tag in ("spacetree_np1", "spacetree_np2"):
        other = res[tag][1]
        d = max(np.abs(other[c] - last[c]).max() for c in cols)
        check(d < 1e-9, "big obstacle: %s = bin on 1 rank (positions and quaternions, max difference %.3g)"
              % (tag, d))


def case_ranks(a):
    wd = a.workdir
    n = 6000
    res = {}
    for np_, nstyle in ((1, "bin"), (2, "bin"), (2, "spacetree")):
        sub = os.path.join(wd, "np%d_%s" % (np_, nstyle))
        os.makedirs(sub, exist_ok=True)
        rc, out, log = run(a, "trimesh_ranks.in", sub, "ranks",
                           dict(n=n, np=np_, nstyle=nstyle, after="print done"), np_=np_)
        check(rc == 0, "ranks: %d rank(s), neighbor %s runs" % (np_, nstyle))
        if rc != 0:
            return
        res[np_ if nstyle == "bin" else nstyle] = (read_vtk(os.path.join(sub, "ranks_%d.vtk" % n)), thermo(log))
    (ps, _, _), ts = res["spacetree"]
    ds = np.abs(ps - res[1][0][0]).max() if ps.shape == res[1][0][0].shape else float("inf")
    check(ds < 1e-9, "ranks: neighbor spacetree on 2 ranks = bin on 1 rank (max vertex difference %.3g m)" % ds)
    (p1, c1, i1), t1 = res[1]
    (p2, c2, i2), t2 = res[2]
    check(p1.shape == p2.shape and (c1 == c2).all() and (i1 == i2).all(), "ranks: same surfaces (triangles, ids)")
    d = np.abs(p1 - p2).max()
    check(d < 1e-9, "ranks: max vertex difference 1 vs 2 ranks %.3g m < 1e-9 m" % d)
    check(t1[:, 1].max() >= 1, "ranks: particles collided (max contacts %d)" % t1[:, 1].max())
    check(t1[-1, 2] < 0.9 * t1[0, 2], "ranks: collisions dissipated energy (%.4g -> %.4g J)" % (t1[0, 2], t1[-1, 2]))
    dke = np.abs(t1[:, 2] - t2[:, 2]).max() / t1[0, 2]
    check(t1.shape == t2.shape and dke < 1e-9, "ranks: same kinetic energy history (max rel. diff %.3g)" % dke)
    p0, _, _ = read_vtk(os.path.join(wd, "np1_bin", "ranks_0.vtk"))
    moved = np.abs(p1 - p0).max()
    check(moved > 0.005, "ranks: particles moved (max vertex displacement %.3g m)" % moved)


def case_restart(a):
    wd = a.workdir
    n = 4000
    rc, _, log = run(a, "trimesh_ranks.in", wd, "full", dict(n=n, np=1, after="print done"))
    check(rc == 0, "restart: uninterrupted run")
    rc2, _, _ = run(a, "trimesh_ranks.in", wd, "first", dict(n=n // 2, np=1, after="write_restart half.restart"))
    check(rc2 == 0 and os.path.exists(os.path.join(wd, "half.restart")), "restart: first half + write_restart")
    rc3, _, _ = run(a, "trimesh_restart.in", wd, "second", dict(n=n // 2, file="half.restart"), np_=2)
    check(rc3 == 0, "restart: read_restart + second half on 2 ranks")
    if rc or rc2 or rc3:
        return
    pa, ca, _ = read_vtk(os.path.join(wd, "ranks_%d.vtk" % n))
    pb, cb, _ = read_vtk(os.path.join(wd, "restarted_%d.vtk" % n))
    d = np.abs(pa - pb).max() if pa.shape == pb.shape else float("inf")
    check(d < 1e-9, "restart: surfaces after restart = uninterrupted run (max diff %.3g m)" % d)


BAD = {
    "missing_file": ("fix shapes all trimesh/template type 1 file no_such_mesh.stl",
                     r"ERROR.*no_such_mesh\.stl"),
    "template_keyword": ("fix shapes all trimesh/template type 1 dented ntri 40 radius 0.002 amplitude 0.2 seed 7 bogus 3",
                         r"ERROR.*unknown keyword 'bogus'"),
    "pair_keyword": ("fix shapes all trimesh/template type 1 dented ntri 40 radius 0.002 amplitude 0.2 seed 7\n"
                     "pair_style trimesh eps 1e-4 stiffness 1e5 damping 10 wobble 2",
                     r"ERROR.*unknown keyword 'wobble'"),
    "method": ("fix shapes all trimesh/template type 1 dented ntri 40 radius 0.002 amplitude 0.2 seed 7\n"
               "pair_style trimesh eps 1e-4 stiffness 1e5 damping 10 method fast",
               r"ERROR.*method 'fast'"),
    "continuation": ("fix shapes all trimesh/template type 1 dented ntri 40 radius 0.002 amplitude 0.2 seed 7\n"
                     "pair_style trimesh eps 1e-4 stiffness 1e5 damping 10 method hybrid continuation -1",
                     r"ERROR.*continuation '-1' must be an integer in \[0, 32\]"),
    "newton_steps": ("fix shapes all trimesh/template type 1 dented ntri 40 radius 0.002 amplitude 0.2 seed 7\n"
                     "pair_style trimesh eps 1e-4 stiffness 1e5 damping 10 continuation 4 iterations 29",
                     r"ERROR.*iterations 29 \+ continuation 4 must be <= 32"),
    "continuation_method": ("fix shapes all trimesh/template type 1 dented ntri 40 radius 0.002 amplitude 0.2 seed 7\n"
                            "pair_style trimesh eps 1e-4 stiffness 1e5 damping 10 method penalty continuation 4",
                            r"ERROR.*continuation needs method hybrid"),
    "dented_ntri": ("fix shapes all trimesh/template type 1 dented ntri 10 radius 0.002 amplitude 0.2 seed 7",
                    r"ERROR.*dented needs ntri >= 12"),
    "open_mesh": ("fix shapes all trimesh/template type 1 file open.stl",
                  r"ERROR.*open\.stl.*open surface"),
    "atom_style": ("fix shapes all trimesh/template type 1 dented ntri 40 radius 0.002 amplitude 0.2 seed 7",
                   r"ERROR.*requires atom_style sphere or granular"),
    "insertion_template_order": ("fix shapes all trimesh/template type 1 dented ntri 40 radius 0.002 amplitude 0.2 seed 7\n"
                                 "fix pts all particletemplate/trimesh 15485863 atom_type 1",
                                 r"ERROR.*particletemplate/trimesh needs pair_style trimesh defined before it"),
    "insertion_template_type": ("fix shapes all trimesh/template type 1 dented ntri 40 radius 0.002 amplitude 0.2 seed 7 "
                                "type 2 file cube.stl fixed\n"
                                "pair_style trimesh eps 1e-4 stiffness 1e5 damping 10\n"
                                "fix pts all particletemplate/trimesh 15485863 atom_type 2",
                                r"ERROR.*particletemplate/trimesh: atom type 2 is a fixed obstacle"),
    "two_templates": ("fix shapes all trimesh/template type 1 dented ntri 40 radius 0.002 amplitude 0.2 seed 7\n"
                      "fix shapes2 all trimesh/template type 2 dented ntri 40 radius 0.002 amplitude 0.2 seed 7\n"
                      "pair_style trimesh eps 1e-4 stiffness 1e5 damping 10\n"
                      "fix pts all particletemplate/trimesh 15485863 atom_type 1",
                      r"ERROR.*particletemplate/trimesh: more than one fix trimesh/template"),
}


def case_bad(a):
    wd = a.workdir
    tris = box_triangles((0, 0, 0), (1, 1, 1))[:-1]
    write_stl(os.path.join(wd, "open.stl"), tris)
    write_stl(os.path.join(wd, "cube.stl"), box_triangles((0.1, 0.1, 0.1), (0.9, 0.9, 0.9)))
    for name, (lines, rx) in BAD.items():
        style = "atomic" if name == "atom_style" else "granular"
        deck = os.path.join(wd, "in." + name)
        with open(deck, "w") as f:
            f.write("atom_style %s\nboundary f f f\nnewton off\ncommunicate single vel yes\nunits si\n"
                    "region box block 0 1 0 1 0 1\ncreate_box 2 box\n%s\n" % (style, lines))
        p = subprocess.run([a.exe, "-in", deck, "-echo", "none", "-log", "none"], cwd=wd,
                           stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, errors="replace",
                           timeout=60)
        m = re.search(rx, p.stdout)
        check(p.returncode != 0 and m, "bad %s: %s" % (name, m.group(0) if m else p.stdout[-300:]))
    # the Newton-step schedule as printed: defaults (two-stage hybrid 5 + 4), the keywords, and a
    # repeated pair_style line back at the defaults (LIGGGHTS 3.8 creates a new pair style)
    deck = os.path.join(wd, "in.schedule")
    with open(deck, "w") as f:
        f.write("atom_style granular\nboundary f f f\nnewton off\ncommunicate single vel yes\nunits si\n"
                "region box block 0 1 0 1 0 1\ncreate_box 1 box\n"
                "pair_style trimesh eps 1e-4 stiffness 1e5 damping 10\n"
                "pair_style trimesh eps 1e-4 stiffness 1e5 damping 10 iterations 8 continuation 0\n"
                "pair_style trimesh eps 1e-4 stiffness 1e5 damping 10 method hybrid\n"
                "pair_style trimesh eps 1e-4 stiffness 1e5 damping 10 method penalty\n")
    p = subprocess.run([a.exe, "-in", deck, "-echo", "none", "-log", "none"], cwd=wd, stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, text=True, errors="replace", timeout=60)
    got = re.findall(r"pair_style trimesh: method (\w+), (\d+) Newton steps( \+ \d+| \(single stage\))?", p.stdout)
    want = [("hybrid", "5", " + 4"), ("hybrid", "8", " (single stage)"), ("hybrid", "5", " + 4"), ("penalty", "8", "")]
    check(p.returncode == 0 and got == want,
          "schedule: default hybrid 5 + 4, iterations 8 continuation 0 single stage, repeated line back at "
          "the default, penalty 8 (%s)" % got)


def case_hopper(a):
    wd = a.workdir
    gen = os.path.join(ROOT, "inputs", "hopper", "make_hopper.py")
    subprocess.run([sys.executable, gen, os.path.join(wd, "hopper.stl"), os.path.join(wd, "floor.stl")], check=True)
    n = a.hopper_steps
    rc, out, log = run(a, os.path.join(ROOT, "inputs", "hopper", "in.hopper"), wd, "hopper",
                       dict(n=n, nx=a.hopper_nx, a=0.007, zlo=0.05, v0=2.0, dumpevery=n, th=10, meshdir=".",
                            nstyle=a.hopper_neighbor), np_=2)
    check(rc == 0, "hopper: short run on 2 ranks")
    if rc != 0:
        return
    t = thermo(log)
    natoms = t[:, 1]
    check(natoms.min() == natoms.max() == natoms[0], "hopper: no particle lost (%d atoms throughout)" % natoms[0])
    pen = t[:, 3].max()
    # penetration eps means the rigid surfaces touch (d = 0): it must stay below
    check(pen < 5e-5, "hopper: largest penetration %.3g < eps 5e-5 (surfaces never touch)" % pen)
    check(t[:, 2].max() >= 1, "hopper: grains touch the hopper/floor/each other (max contacts %d)" % t[:, 2].max())
    zmean = t[:, 4]
    check(zmean[-1] < zmean[0] - 0.003, "hopper: grains fall (mean z %.4f -> %.4f)" % (zmean[0], zmean[-1]))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("case", choices=["collide", "floor", "edge", "insert", "pose", "big_obstacle", "ranks",
                                     "restart", "bad", "hopper"])
    ap.add_argument("--exe", required=True)
    ap.add_argument("--workdir", required=True)
    ap.add_argument("--mpiexec", default="mpirun")
    ap.add_argument("--mpiexec-flags", default="--allow-run-as-root;--oversubscribe")
    ap.add_argument("--hopper-steps", type=int, default=2500)
    ap.add_argument("--hopper-nx", type=int, default=4)
    ap.add_argument("--hopper-neighbor", default="spacetree")
    a = ap.parse_args()
    a.exe = os.path.abspath(a.exe)
    os.makedirs(a.workdir, exist_ok=True)
    for f in glob.glob(os.path.join(a.workdir, "*.vtk")):
        os.remove(f)
    globals()["case_" + a.case](a)
    return 0 if OK else 1


if __name__ == "__main__":
    sys.exit(main())
