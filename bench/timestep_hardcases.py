#!/usr/bin/env python3
"""Hard-case suite of `fix adapt/timestep` at benchmark length: the CTest cases
(tests/liggghts/hardcases) with the resting column held for 10^6 steps instead of 10^5.
Writes bench/results/timestep_hardcases.csv (case, steps, seconds, passed, checks) and
timestep_hardcases_stack.png (top-sphere compression error over the run).

  /usr/bin/python3 bench/timestep_hardcases.py [--exe build/liggghts-spacetree] [--stack-steps 1000000]
"""
import argparse
import csv
import os
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DRIVER = os.path.join(ROOT, "tests", "liggghts", "hardcases", "check_hardcases.py")
sys.path.insert(0, os.path.join(ROOT, "tests", "liggghts", "timestep"))
import lg  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "liggghts-spacetree"))
    ap.add_argument("--stack-steps", type=int, default=1000000)
    ap.add_argument("--results", default=os.path.join(ROOT, "bench", "results"))
    a = ap.parse_args()
    work = os.path.join(ROOT, "build", "bench_timestep_hardcases")
    os.makedirs(a.results, exist_ok=True)
    rows, ok = [], True
    for case in ("impact100", "impact100:2", "impact100veto", "ratio1000", "squeeze", "squeeze:2", "threebody", "stack"):
        t0 = time.perf_counter()
        p = subprocess.run([sys.executable, DRIVER, case, "--exe", a.exe, "--workdir",
                            os.path.join(work, case.replace(":", "_")), "--stack-steps", str(a.stack_steps)],
                           stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, errors="replace")
        seconds = time.perf_counter() - t0
        checks = [l for l in p.stdout.splitlines() if l.startswith(("PASS", "FAIL"))]
        info = [l.strip() for l in p.stdout.splitlines() if l.startswith("  ")]
        rows.append(dict(case=case, seconds="%.2f" % seconds, passed=int(p.returncode == 0),
                         checks=" | ".join(checks), info=" | ".join(info)))
        ok = ok and p.returncode == 0
        print("%-12s %s in %.1f s" % (case, "passed" if p.returncode == 0 else "FAILED", seconds))
        for l in info + [c for c in checks if c.startswith("FAIL")]:
            print("   ", l)
    with open(os.path.join(a.results, "timestep_hardcases.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=["case", "seconds", "passed", "checks", "info"])
        w.writeheader()
        w.writerows(rows)
    log = os.path.join(work, "stack", "log.stack")
    if os.path.exists(log):
        names, data = lg.thermo(log)
        steps = lg.column(names, data, "Step")
        ztop = lg.column(names, data, "v_ztop")
        import re
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        # The column starts at its closed-form compression (the driver prints it): draw how far
        # the top sphere moves from there, in units of that compression, beside the test's 1 %
        # tolerance, and the kinetic energy of the column.
        stack = next(r for r in rows if r["case"] == "stack")
        closed = float(re.search(r"closed form ([0-9.eE+-]+)", stack["info"]).group(1))
        ke = lg.column(names, data, "KinEng")
        fig, (dev, kin) = plt.subplots(1, 2, figsize=(12, 4))
        moved = [(z - ztop[0]) / closed for z in ztop]
        dev.plot(steps, moved, "-", label="(top height - start) / closed-form compression")
        dev.axhspan(-0.01, 0.01, color="0.85", label="test tolerance (1 %)")
        dev.set_ylim(-0.02, 0.02)
        dev.set_ylabel("relative to the closed-form compression")
        dev.set_title("top sphere of a 30-sphere column at rest: largest |change| %.1e"
                      % max(abs(v) for v in moved), fontsize=9)
        kin.semilogy(steps, [max(k, 1e-40) for k in ke], "-")
        kin.set_ylabel("kinetic energy of the column (J)")
        kin.set_title("kinetic energy (floor 1e-40 J: exactly zero)", fontsize=9)
        for ax in (dev, kin):
            ax.set_xlabel("step")
            ax.grid(True, which="both", alpha=0.3)
        dev.legend(fontsize=8, loc="upper right")
        fig.suptitle("fix adapt/timestep, %d steps" % steps[-1])
        fig.tight_layout()
        fig.savefig(os.path.join(a.results, "timestep_hardcases_stack.png"), dpi=100)
    print("wrote", os.path.join(a.results, "timestep_hardcases.csv"))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
