#!/usr/bin/env python3
"""Decks a careless or hostile user may write, each of which once ran to the end (or crashed)
without saying what was wrong. Every case must now stop with an ERROR naming the problem, or (for
`teardown`) run cleanly.

  teardown      fix spacetree through unfix, a replacing `fix` command, `clear` and exit, with
                freed memory overwritten (MALLOC_PERTURB_): no stale read of the deleted Neighbor
  fix_replace   fix particletemplate/trimesh replaced by a `fix` command with its ID (crashed)
  nan_mesh      an STL whose one corner is (x, nan, z): refused with the file and line (it was
                merged into a valid vertex and accepted); a directory given as the mesh file
  dented_limit  dented ntri 2000000000: refused at once (it hung in an O(N^2) search)
  adapt_twice   a second fix adapt/timestep: refused (both set the global time step)
  creep         creep 1e300: refused (the step jumps to its caps; restitution is lost)
  hybrid_types  pair_style hybrid/overlay with trimesh named for type 1 only: the grains of
                types 1 and 2 would meet as gran spheres; refused
  grain_box     grains wider than the fixed box, or than a periodic box with the skin, with
                neighbor bin: refused (spacetree refused them; bin ran on)
  error_one     an error->one on one rank with the output redirected to a file: the message
                reaches that file and the log (it was lost with everything before it)

Usage: check_reliability.py CASE --exe liggghts-spacetree --workdir DIR
"""
import argparse
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ok = True


def check(cond, what):
    global ok
    ok = ok and bool(cond)
    print(("PASS " if cond else "FAIL ") + what, flush=True)


def run(a, deck, name, variables=None, env=None, stdout_file=None, timeout=120):
    """Runs a deck on one rank; returns (return code, screen text, log text)."""
    log = os.path.join(a.workdir, "log." + name)
    if os.path.exists(log):
        os.remove(log)
    cmd = [a.exe, "-in", os.path.join(HERE, deck), "-echo", "none", "-log", log]
    for k, v in (variables or {}).items():
        cmd += ["-var", k, str(v)]
    full_env = dict(os.environ, **(env or {}))
    if stdout_file:
        with open(stdout_file, "w") as out:
            p = subprocess.run(cmd, cwd=a.workdir, stdout=out, stderr=subprocess.STDOUT,
                               env=full_env, timeout=timeout)
        text = open(stdout_file, errors="replace").read()
    else:
        p = subprocess.run(cmd, cwd=a.workdir, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                           text=True, errors="replace", env=full_env, timeout=timeout)
        text = p.stdout
    log_text = open(log, errors="replace").read() if os.path.exists(log) else ""
    return p.returncode, text, log_text


def expect_error(a, deck, name, variables, pattern, timeout=120):
    try:
        rc, text, _ = run(a, deck, name, variables, timeout=timeout)
    except subprocess.TimeoutExpired:
        check(False, "%s: no answer within %d s (expected ERROR %s)" % (name, timeout, pattern))
        return
    m = re.search(pattern, text)
    check(rc != 0 and m, "%s: %s" % (name, m.group(0) if m else "rc %d, expected %s; output ends: %s"
                                     % (rc, pattern, text[-400:])))


def cube_stl(path, nan_corner):
    """The cube [0,1]^3 as ASCII STL; corner number `nan_corner` (0..35) gets a nan y."""
    v = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
    faces = [(0, 2, 1), (0, 3, 2), (4, 5, 6), (4, 6, 7), (0, 1, 5), (0, 5, 4),
             (1, 2, 6), (1, 6, 5), (2, 3, 7), (2, 7, 6), (3, 0, 4), (3, 4, 7)]
    lines, k, line_of_nan = ["solid cube"], 0, None
    for f in faces:
        lines += ["facet normal 0 0 0", "outer loop"]
        for i in f:
            x, y, z = v[i]
            if k == nan_corner:
                lines.append("vertex %g nan %g" % (x, z))
                line_of_nan = len(lines)
            else:
                lines.append("vertex %g %g %g" % (x, y, z))
            k += 1
        lines += ["endloop", "endfacet"]
    lines.append("endsolid cube")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    return line_of_nan


def case_teardown(a):
    # MALLOC_PERTURB_: glibc fills freed blocks with a byte pattern, so reading the deleted
    # Neighbor yields a wild pointer and a crash instead of a silently stale value
    rc, text, _ = run(a, "in.grid_teardown", "teardown", env={"MALLOC_PERTURB_": "165"})
    check(rc == 0 and "teardown: after clear" in text,
          "teardown: unfix, replacing fix spacetree, clear and exit run cleanly (rc %d)" % rc)


def case_fix_replace(a):
    rc, text, _ = run(a, "in.replace_template", "fix_replace")
    atoms = re.findall(r"^\s+10\s+(\d+)\s", text, re.M)
    check(rc == 0 and "replace_template: done" in text and atoms == ["5"],
          "fix_replace: particletemplate/trimesh given twice with one ID, then 5 grains inserted "
          "(rc %d, atoms %s)" % (rc, atoms))


def case_nan_mesh(a):
    grains = {"pstyle": "pair_style trimesh eps 1e-4 stiffness 1e5 damping 1", "n": 0}
    # corner 3 (triangle 1, corner 0): one of the 15 of 36 whose (x, nan, z) the ordered vertex
    # map merged into the vertex (x, y, z), so that the mesh was accepted and the run went on
    line = cube_stl(os.path.join(a.workdir, "nan_cube.stl"), 3)
    deck = os.path.join(a.workdir, "in.nan_mesh")
    with open(os.path.join(HERE, "in.grains")) as f:
        text = f.read()
    for name, source, pattern in (
            ("nan_mesh", "file nan_cube.stl scale 0.005",
             r"ERROR: Fix trimesh/template: type 1: nan_cube\.stl: line %d: non-finite vertex "
             r"coordinate \(0, nan, 0\)" % line),
            ("directory_mesh", "file %s" % a.workdir,
             r"ERROR: Fix trimesh/template: type 1: %s: is a directory" % re.escape(a.workdir))):
        with open(deck, "w") as f:
            f.write(text.replace("type 1 dented ntri 40 radius 0.006 amplitude 0.1 seed 7", "type 1 " + source))
        expect_error(a, deck, name, grains, pattern)


def case_dented_limit(a):
    deck = os.path.join(a.workdir, "in.dented_limit")
    with open(os.path.join(HERE, "in.grains")) as f:
        text = f.read()
    with open(deck, "w") as f:
        f.write(text.replace("ntri 40 radius 0.006 amplitude 0.1 seed 9", "ntri 2000000000 radius 0.006 amplitude 0.1 seed 9"))
    expect_error(a, deck, "dented_limit", {"n": 0},
                 r"ERROR: Illegal fix trimesh/template command: dented needs ntri >= 12 and <= 1000000",
                 timeout=60)


def case_adapt_twice(a):
    expect_error(a, "in.spheres", "adapt_twice",
                 {"adapt1": "fix dt1 all adapt/timestep creep 1.1", "adapt2": "fix dt2 all adapt/timestep creep 1.2"},
                 r"ERROR: Fix adapt/timestep: only one fix adapt/timestep may exist")
    # replacing it under the same ID is not a second one
    rc, text, _ = run(a, "in.spheres", "adapt_replaced",
                      {"adapt1": "fix dt1 all adapt/timestep creep 1.1", "adapt2": "fix dt1 all adapt/timestep creep 1.2"})
    check(rc == 0 and "ERROR" not in text, "adapt_replaced: the same fix ID given again replaces it (rc %d)" % rc)


def case_creep(a):
    for c in ("1e300", "2.5", "0.9"):
        expect_error(a, "in.spheres", "creep_" + c, {"adapt1": "fix dtv all adapt/timestep creep " + c},
                     r"ERROR: Illegal fix adapt/timestep command: creep must be in \[1, 2\]")
    rc, text, _ = run(a, "in.spheres", "creep_2", {"adapt1": "fix dtv all adapt/timestep creep 2"})
    check(rc == 0 and "ERROR" not in text, "creep_2: creep 2 is accepted (rc %d)" % rc)


def case_hybrid_types(a):
    overlay = "pair_style hybrid/overlay trimesh eps 1e-4 stiffness 1e5 damping 1 gran model hertz tangential history"
    expect_error(a, "in.grains", "hybrid_overlay",
                 {"pstyle": overlay, "coeff1": "pair_coeff 1 1 trimesh", "coeff2": "pair_coeff * * gran"},
                 r"ERROR: Pair style trimesh: atom types 1 and 2 have trimesh templates but no "
                 r"'pair_coeff 1 2 trimesh' \(pair_style hybrid/overlay\)")
    plain = "pair_style hybrid trimesh eps 1e-4 stiffness 1e5 damping 1"
    expect_error(a, "in.grains", "hybrid_cross",
                 {"pstyle": plain, "coeff1": "pair_coeff 1 1 trimesh", "coeff2": "pair_coeff 2 2 trimesh"},
                 r"ERROR: Pair style trimesh: atom types 1 and 2 have trimesh templates but no "
                 r"'pair_coeff 1 2 trimesh' \(pair_style hybrid\)")
    # every pair named: the grains meet (head-on at 1 m/s, they separate after the contact)
    rc, text, log = run(a, "in.grains", "hybrid_all", {"pstyle": plain, "coeff1": "pair_coeff * * trimesh"})
    rows = [l.split() for l in log.splitlines() if re.match(r"\s+12000\s", l)]
    check(rc == 0 and rows and float(rows[-1][2]) > 0.0,
          "hybrid_all: with pair_coeff * * trimesh the grains collide and separate (v_rel %s)"
          % (rows[-1][2] if rows else "none"))


def case_grain_box(a):
    for nstyle in ("bin", "spacetree"):
        expect_error(a, "in.grains", "grain_box_fixed_" + nstyle, {"hw": 0.005, "bnd": "f", "nstyle": nstyle},
                     r"ERROR: Pair style trimesh: grains of type 1 do not fit in the box: bounding "
                     r"diameter \+ 2 eps 0\.01\d+ exceeds the fixed box length 0\.01 in y")
        expect_error(a, "in.grains", "grain_box_periodic_" + nstyle, {"hw": 0.005, "bnd": "p", "nstyle": nstyle},
                     r"ERROR: Pair style trimesh: grains of type 1 reach their own periodic image")
    # in a box wide enough the same grains collide and separate
    rc, text, log = run(a, "in.grains", "grain_box_wide", {"hw": 0.02, "bnd": "f"})
    rows = [l.split() for l in log.splitlines() if re.match(r"\s+12000\s", l)]
    check(rc == 0 and rows and float(rows[-1][2]) > 0.0,
          "grain_box_wide: in a box 0.04 m wide the grains collide and separate (v_rel %s)"
          % (rows[-1][2] if rows else "none"))


def case_error_one(a):
    out = os.path.join(a.workdir, "screen.error_one")
    rc, text, log = run(a, "in.spheres", "error_one",
                        {"adapt1": "fix dtv all adapt/timestep creep 1.1 file no_such_directory/dt.txt"},
                        stdout_file=out)
    want = "ERROR on proc 0: Fix adapt/timestep cannot open file 'no_such_directory/dt.txt'"
    check(rc != 0 and want in text, "error_one: the message reaches the redirected screen output (rc %d)" % rc)
    check("LIGGGHTS (Version" in text, "error_one: so does what was printed before it")
    check(want in log, "error_one: and the log file")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("case", choices=["teardown", "fix_replace", "nan_mesh", "dented_limit", "adapt_twice", "creep",
                                     "hybrid_types", "grain_box", "error_one"])
    ap.add_argument("--exe", required=True)
    ap.add_argument("--workdir", required=True)
    ap.add_argument("--mpiexec", default="mpirun")   # the common CTest arguments; 1 rank only
    a = ap.parse_args()
    os.makedirs(a.workdir, exist_ok=True)
    globals()["case_" + a.case](a)
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
