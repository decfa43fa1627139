#!/usr/bin/env python3
"""Regression test of `fix adapt/timestep` (deck in.collide beside it).

  check_adapt_timestep.py --exe EXE --workdir DIR

- collision: two equal spheres meet head-on with the hooke (linear spring-dashpot) model and
  coefficientRestitution 0.5 under `fix adapt/timestep creep 1.1`: the measured restitution
  (relative speed after / before) is 0.5 within 1 %, the veto cut the step at least once before
  impact, the step went back to its ceiling afterwards, and time = sum of the steps taken.
- the same collision without the veto (`veto no`) keeps the ceiling step all along.
- bad input: an unknown keyword stops with an ERROR naming it.
Exit status 0 = pass, 1 = fail.
"""
import argparse
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))


def run(exe, workdir, name, adapt, extra=()):
    log = os.path.join(workdir, "log." + name)
    cmd = [exe, "-in", os.path.join(HERE, "in.collide"), "-log", log, "-echo", "none",
           "-var", "nstyle", "spacetree", "-var", "e", "0.5", "-var", "dt0", "2e-6",
           "-var", "th", "1", "-var", "n", "12000", "-var", "adapt", adapt, *extra]
    p = subprocess.run(cmd, cwd=workdir, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, errors="replace",
                       text=True, timeout=120)
    return p.returncode, p.stdout, log


def thermo(log):
    rows, on = [], False
    for line in open(log, errors="replace"):
        if line.strip().startswith("Step"):
            on = True
            continue
        if on:
            if line.startswith("Loop time"):
                break
            parts = line.split()
            try:
                rows.append([float(t) for t in parts])
            except ValueError:
                pass
    return rows  # step time dt vrel gap


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--exe", required=True)
    ap.add_argument("--workdir", required=True)
    a = ap.parse_args()
    os.makedirs(a.workdir, exist_ok=True)
    ok = True

    def check(cond, what):
        nonlocal ok
        print(("PASS " if cond else "FAIL ") + what)
        ok = ok and cond

    hist = os.path.join(a.workdir, "dt_history.txt")
    rc, out, log = run(a.exe, a.workdir, "veto",
                       "fix dtv all adapt/timestep creep 1.1 dtmin 1e-8 file " + hist)
    check(rc == 0, "adaptive run finished (rc %d)" % rc)
    if rc != 0:
        print(out[-2000:])
        return 1
    rows = thermo(log)
    before, after = -rows[0][3], rows[-1][3]
    e = after / before
    print("  restitution %.6f (expected 0.5), %d steps, simulated time %.6g s" % (e, len(rows) - 1, rows[-1][1]))
    check(abs(e - 0.5) <= 0.005, "restitution within 1 % of coefficientRestitution 0.5")
    dts = [r[2] for r in rows]
    check(min(dts) < 2e-6 and dts[-1] == 2e-6, "the step shrank near impact and crept back to its "
          "ceiling (min %.3g, last %.3g)" % (min(dts), dts[-1]))
    vetoed = [l.split() for l in open(hist) if not l.startswith("#")]
    nveto = sum(int(v[4]) for v in vetoed)
    check(nveto >= 1, "the veto cut the step %d time(s)" % nveto)
    # elapsed time is the sum of the steps taken (update_time before every change)
    total = sum(float(v[2]) for v in vetoed[:-1])
    check(abs(total - rows[-1][1]) <= 1e-12 + 1e-9 * rows[-1][1],
          "thermo time %.12g equals the sum of the steps %.12g" % (rows[-1][1], total))
    gaps_in_contact = [r[4] for r in rows if r[4] < 0]
    check(len(gaps_in_contact) > 0, "the spheres did collide (max overlap %.3g m)" % -min(r[4] for r in rows))

    rc, out, log = run(a.exe, a.workdir, "noveto", "fix dtv all adapt/timestep creep 1.1 veto no")
    rows = thermo(log)
    check(rc == 0 and all(r[2] == 2e-6 for r in rows), "veto no keeps the ceiling step")

    rc, out, log = run(a.exe, a.workdir, "bad", "fix dtv all adapt/timestep creep 1.1 bogus 3")
    msg = (open(log, errors="replace").read() if os.path.exists(log) else "") + out
    check(rc != 0 and "unknown keyword 'bogus'" in msg, "an unknown keyword stops with an ERROR naming it")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
