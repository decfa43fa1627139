#!/usr/bin/env python3
"""What the composed contact model costs a scene that names none of its new sub-models.

The same deck (tests/liggghts/trimesh/threads_hopper.in: 64 dented grains of 40 triangles and
two obstacles, the hopper of 1536 triangles and a floor, `pair_style trimesh eps 5e-5 stiffness
5e5 damping 60 friction 0.4 0.3`, i.e. the paper's law with viscous friction, no history, no
materials; threads 1) run by two executables: `before` (built from the commit before the
contact model, e.g. a worktree at ed52ec1) and `after` (this tree). The runs alternate inside each
repetition (the order swaps from one repetition to the next). Per run: the process's user + sys
CPU time (wait4), which the machine's load affects far less than the wall clock, and LIGGGHTS'
loop time. Reported: medians and the ratio after/before as the median of the per-repetition
paired ratios with its min..max.

    bench/contact_model_cost.py --before PATH/liggghts-spacetree [--after build/liggghts-spacetree]
                                [--reps 7] [--steps 3000]

Writes bench/results/contact_model_cost.csv (one row per run) and contact_model_cost_summary.csv.
"""

import argparse
import csv
import os
import re
import statistics
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
DECK = os.path.join(ROOT, "tests", "liggghts", "trimesh", "threads_hopper.in")
OUT = os.path.join(HERE, "results", "contact_model_cost")


def run(exe, wd, steps):
    cmd = [exe, "-in", DECK, "-log", "log.run", "-echo", "none", "-var", "threads", "1", "-var", "n",
           str(steps), "-var", "every", str(10 * steps), "-var", "tag", "cost"]
    p = subprocess.Popen(cmd, cwd=wd, stdout=subprocess.DEVNULL, stderr=subprocess.STDOUT)
    _, status, usage = os.wait4(p.pid, 0)
    if status != 0:
        raise SystemExit("run failed: %s" % " ".join(cmd))
    log = open(os.path.join(wd, "log.run")).read()
    loop = float(re.search(r"Loop time of ([0-9.eE+-]+)", log).group(1))
    return usage.ru_utime + usage.ru_stime, loop


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--before", required=True)
    ap.add_argument("--after", default=os.path.join(ROOT, "build", "liggghts-spacetree"))
    ap.add_argument("--reps", type=int, default=7)
    ap.add_argument("--steps", type=int, default=3000)
    a = ap.parse_args()
    wd = tempfile.mkdtemp(prefix="contact_model_cost_")
    subprocess.run([sys.executable, os.path.join(ROOT, "inputs", "hopper", "make_hopper.py"),
                    os.path.join(wd, "hopper.stl"), os.path.join(wd, "floor.stl")], check=True,
                   stdout=subprocess.DEVNULL)
    rows = []
    for rep in range(a.reps):
        order = ["before", "after"] if rep % 2 == 0 else ["after", "before"]
        for which in order:
            cpu, loop = run(a.before if which == "before" else a.after, wd, a.steps)
            load = os.getloadavg()[0]
            rows.append(dict(rep=rep, exe=which, cpu_s=cpu, loop_s=loop, load=load))
            print("rep %d %-6s cpu %.3f s loop %.3f s load %.1f" % (rep, which, cpu, loop, load), flush=True)
    os.makedirs(os.path.dirname(OUT), exist_ok=True)
    with open(OUT + ".csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=["rep", "exe", "cpu_s", "loop_s", "load"])
        w.writeheader()
        w.writerows(rows)
    summary = []
    for measure in ("cpu_s", "loop_s"):
        by = {(r["rep"], r["exe"]): r[measure] for r in rows}
        ratios = [by[(k, "after")] / by[(k, "before")] for k in range(a.reps)]
        summary.append(dict(measure=measure,
                            before_median=statistics.median(by[(k, "before")] for k in range(a.reps)),
                            after_median=statistics.median(by[(k, "after")] for k in range(a.reps)),
                            ratio_median=statistics.median(ratios), ratio_min=min(ratios),
                            ratio_max=max(ratios), reps=a.reps, steps=a.steps,
                            load="%.1f-%.1f" % (min(r["load"] for r in rows), max(r["load"] for r in rows))))
        print("%s: before %.3f s, after %.3f s, paired ratio median %.4f (min %.4f, max %.4f)"
              % (measure, summary[-1]["before_median"], summary[-1]["after_median"],
                 summary[-1]["ratio_median"], summary[-1]["ratio_min"], summary[-1]["ratio_max"]))
    with open(OUT + "_summary.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(summary[0].keys()))
        w.writeheader()
        w.writerows(summary)
    return 0


if __name__ == "__main__":
    sys.exit(main())
