#!/usr/bin/env python3
"""Thread-count independence of pair_style trimesh ... threads N (tests/liggghts/threads.cmake).

Cases:
  threads   deck threads_hopper.in on 1 rank with threads 1, 2 and 4: every dump (positions,
            velocities, angular velocities at %.17g; surfaces = orientations) byte-identical,
            the run shows contacts and moving grains, the log names the thread count
  ranks     the same deck on 2 ranks with threads 1, 2 and 0 (TBB's default shared by the ranks
            of the node, as the log reports): byte-identical dumps
  bad       threads -1 and a non-integer stop with a clear ERROR naming the keyword
"""
import argparse
import filecmp
import glob
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(HERE)))
DECK = os.path.join(HERE, "threads_hopper.in")
OK = True


def check(cond, what):
    global OK
    print(("PASS " if cond else "FAIL ") + what, flush=True)
    OK = OK and bool(cond)


def run(a, wd, tag, threads, np_=1, extra=()):
    cmd = [a.exe, "-in", DECK, "-log", "log.%s" % tag, "-var", "threads", str(threads), "-var", "tag", tag]
    cmd += list(extra)
    if np_ > 1:
        cmd = [a.mpiexec] + [f for f in a.mpiexec_flags.split(";") if f] + ["-np", str(np_)] + cmd
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    p = subprocess.run(cmd, cwd=wd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, errors="replace", env=env,
                       timeout=300)
    return p.returncode, p.stdout


def thermo(wd, tag):
    rows, on = [], False
    for line in open(os.path.join(wd, "log.%s" % tag)):
        w = line.split()
        if w[:2] == ["Step", "Atoms"]:
            on = True
            continue
        if on:
            try:
                rows.append([float(v) for v in w])
            except ValueError:
                on = False
    return rows


def dumps(wd, tag):
    names = [os.path.basename(f)[len(tag):] for f in glob.glob(os.path.join(wd, tag + "_*"))]
    return sorted(names, key=lambda n: (int(re.match(r"_(\d+)", n).group(1)), n))  # by step


def same_dumps(wd, ref, tag):
    files = dumps(wd, ref)
    if not files or files != dumps(wd, tag):
        return False, "different dump files: %s vs %s" % (files, dumps(wd, tag))
    for f in files:
        if not filecmp.cmp(os.path.join(wd, ref + f), os.path.join(wd, tag + f), shallow=False):
            return False, "%s%s differs from %s%s" % (tag, f, ref, f)
    return True, "%d dump files" % len(files)


def positions(path):
    with open(path) as f:
        lines = f.read().split("ITEM: ATOMS")[1].splitlines()[1:]
    return {int(l.split()[0]): [float(v) for v in l.split()[1:4]] for l in lines if l.strip()}


def meshes(wd):
    subprocess.run([sys.executable, os.path.join(ROOT, "inputs", "hopper", "make_hopper.py"),
                    os.path.join(wd, "hopper.stl"), os.path.join(wd, "floor.stl")], check=True,
                   stdout=subprocess.DEVNULL)


def compare(a, np_, counts):
    wd = a.workdir
    meshes(wd)
    ref = None
    for t in counts:
        tag = "np%d_t%d" % (np_, t)
        rc, out = run(a, wd, tag, t, np_)
        check(rc == 0, "%s: run on %d rank(s) with threads %d" % (tag, np_, t))
        if rc:
            print(out[-3000:])
            return
        if t == 0:
            # threads 0: TBB's default divided among the ranks of this node
            m = re.search(r"triangle checks on (\d+) thread\(s\) per rank \(threads 0: TBB default (\d+) "
                          r"shared by (\d+) rank", out)
            check(m is not None and int(m.group(3)) == np_ and
                  int(m.group(1)) == max(1, int(m.group(2)) // np_),
                  "%s: threads 0 takes TBB's default shared by the %d rank(s) of the node (%s)"
                  % (tag, np_, m and m.group(0)))
        else:
            check("triangle checks on %d thread(s)" % t in out, "%s: pair style reports %d thread(s)" % (tag, t))
        if ref is None:
            ref = tag
            rows = thermo(wd, tag)
            natoms = {r[1] for r in rows}
            check(natoms == {66.0}, "%s: 66 atoms in every thermo row (%s)" % (tag, sorted(natoms)))
            ncont = max(r[2] for r in rows)
            pen = max(r[3] for r in rows)
            check(ncont >= 5, "%s: contacts occur (max %d at a thermo row)" % (tag, ncont))
            check(0 < pen < 5e-5, "%s: largest penetration %.3g in (0, eps)" % (tag, pen))
            p0 = positions(os.path.join(wd, tag + "_0.dump"))
            p1 = positions(os.path.join(wd, tag + "_%d.dump" % a.steps))
            moved = max(abs(p1[i][2] - p0[i][2]) for i in p0)
            check(moved > 1e-3, "%s: grains move (largest |dz| %.3g m)" % (tag, moved))
        else:
            same, why = same_dumps(wd, ref, tag)
            check(same, "%s = %s bit for bit (%s)" % (tag, ref, why))


def case_bad(a):
    wd = a.workdir
    meshes(wd)
    for val, pat in (("-1", r"ERROR.*pair_style trimesh.*threads '-1' must be an integer >= 0"),
                     ("two", r"ERROR.*pair_style trimesh.*threads 'two' must be an integer"),
                     ("2.5", r"ERROR.*pair_style trimesh.*threads '2.5' must be an integer")):
        rc, out = run(a, wd, "bad", val)
        check(rc != 0 and re.search(pat, out), "threads %s stops with a clear ERROR (rc %d): %s" %
              (val, rc, (re.findall(r"ERROR.*", out) or ["no ERROR line"])[0]))


if __name__ == "__main__":
    ap = argparse.ArgumentParser()
    ap.add_argument("case", choices=["threads", "ranks", "bad"])
    ap.add_argument("--exe", required=True)
    ap.add_argument("--workdir", required=True)
    ap.add_argument("--mpiexec", default="mpirun")
    ap.add_argument("--mpiexec-flags", default="--oversubscribe")
    ap.add_argument("--steps", type=int, default=1500)
    a = ap.parse_args()
    os.makedirs(a.workdir, exist_ok=True)
    for f in glob.glob(os.path.join(a.workdir, "np*_t*")) + glob.glob(os.path.join(a.workdir, "log.*")):
        os.remove(f)
    if a.case == "threads":
        compare(a, 1, [1, 2, 4])
    elif a.case == "ranks":
        compare(a, 2, [1, 2, 0])
    else:
        case_bad(a)
    sys.exit(0 if OK else 1)
