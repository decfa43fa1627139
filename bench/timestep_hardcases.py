#!/usr/bin/env python3
"""Hard-case suite of `fix adapt/timestep` at benchmark length: the CTest cases
(tests/liggghts/hardcases) with the resting column held for 10^6 steps instead of 10^5.
Writes bench/results/timestep_hardcases.csv (case, seconds, passed, checks, info),
timestep_hardcases_stack.csv (the resting column's top compression and kinetic energy over the
run) and timestep_hardcases_stack.png (drawn from it; --replot: only the PNG).

  /usr/bin/python3 bench/timestep_hardcases.py [--exe build/liggghts-spacetree] [--stack-steps 1000000] [--replot]
"""
import argparse
import csv
import os
import re
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DRIVER = os.path.join(ROOT, "tests", "liggghts", "hardcases", "check_hardcases.py")
sys.path.insert(0, os.path.join(ROOT, "tests", "liggghts", "timestep"))
import lg  # noqa: E402


def plot(results):
    """Draws timestep_hardcases_stack.png from timestep_hardcases_stack.csv: the relative error of
    the resting column's top compression against the closed form, beside the test's 1 % bound, and
    the column's kinetic energy."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    rows = list(csv.DictReader(open(os.path.join(results, "timestep_hardcases_stack.csv"))))
    steps = [int(r["step"]) for r in rows]
    error = [abs(float(r["top_compression_m"]) / float(r["closed_form_m"]) - 1.0) for r in rows]
    ke = [float(r["kinetic_energy_J"]) for r in rows]
    floor = 1e-17  # below the double rounding of the compression: drawn for an error of exactly 0
    fig, (dev, kin) = plt.subplots(1, 2, figsize=(12, 4))
    dev.semilogy(steps, [max(e, floor) for e in error], ".-", ms=3, lw=0.8,
                 label="|top compression / closed form - 1|")
    dev.axhline(0.01, color="tab:red", ls="--", lw=1, label="test tolerance (1 %)")
    dev.axhline(2.2e-16, color="grey", ls=":", lw=1, label="double precision (2.2e-16)")
    dev.set_ylim(floor / 2, 1)
    dev.set_ylabel("relative error of the compression")
    dev.set_title("30-sphere column at rest: compression = closed form to %.1e (largest)" % max(error), fontsize=9)
    dev.legend(fontsize=8, loc="center right")
    kin.semilogy(steps, [max(k, 1e-40) for k in ke], ".-", ms=3, lw=0.8)
    kin.set_ylabel("kinetic energy of the column (J)")
    kin.set_title("kinetic energy: at most %.1e J (rounding of the forces)" % max(ke), fontsize=9)
    for ax in (dev, kin):
        ax.set_xlabel("step")
        ax.grid(True, which="both", alpha=0.3)
    fig.suptitle("fix adapt/timestep, resting column, %d steps" % steps[-1])
    fig.tight_layout()
    fig.savefig(os.path.join(results, "timestep_hardcases_stack.png"), dpi=100)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "liggghts-spacetree"))
    ap.add_argument("--stack-steps", type=int, default=1000000)
    ap.add_argument("--results", default=os.path.join(ROOT, "bench", "results"))
    ap.add_argument("--replot", action="store_true", help="only redraw the PNG from the stored CSV")
    a = ap.parse_args()
    if a.replot:
        plot(a.results)
        return 0
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
        # the resting column's trace: how far the top sphere's compression is from the closed form
        stack = next(r for r in rows if r["case"] == "stack")
        height, exact = (float(v) for v in re.search(
            r"column height n d (\S+) m, closed-form top compression (\S+) m", stack["info"]).groups())
        names, data = lg.thermo(log)
        with open(os.path.join(a.results, "timestep_hardcases_stack.csv"), "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["step", "top_compression_m", "closed_form_m", "kinetic_energy_J"])
            for step, z, ke in zip(lg.column(names, data, "Step"), lg.column(names, data, "v_ztop"),
                                   lg.column(names, data, "KinEng")):
                w.writerow(["%d" % step, "%.17g" % (height - z), "%.17g" % exact, "%.6g" % ke])
    plot(a.results)
    print("wrote", os.path.join(a.results, "timestep_hardcases.csv"))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
