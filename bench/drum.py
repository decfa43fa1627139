#!/usr/bin/env python3
"""Rotating drum: 300 spheres and 300 dented grains in a closed drum obstacle turning at constant
angular velocity (inputs/drum/in.drum, meshes and start lattice by inputs/drum/make_drum.py).
Reports, per dumped frame, whether every particle is inside the cavity, the drum's rotation
angle against omega t, and the bed's dynamic angle of repose; writes CSV and PNG.

  drum.py [--exe build/liggghts-spacetree] [--np 1] [--turns 2] [--period 1.2] [--settle 10000]
          [--dt 4e-5] [--every 1000] [--scene full|small] [--out bench/results/drum]
          [--workdir DIR] [--replot]

Scenes: full (the default: cavity radius 35 mm, length 20 mm, 300 spheres of 4 mm and 300 dented
grains of radius 2 mm) and small (the CTest's drum, for long runs: radius 15 mm, length 12 mm, 20
spheres of 3 mm and 20 grains of radius 1.5 mm).

Inside: the particle centre lies within the cavity (axisymmetric: radius from the y axis, |y|)
shrunk by the particle's inscribed radius (spheres: their core, radius - eps; dented grains: the
smallest radius of the dented sphere, 1.5 mm), less eps: a particle that crossed the drum's wall
would fail it by millimetres. Drum angle: the angle of q(t) q(t0)^-1 (the dumped orientation of the drum
atom against its orientation when the rotation started) about +y, compared with omega t
(unwrapped). Angle of repose: the free surface of the bed seen along the axis (x-z plane):
in bins 2 mm wide over the middle 60 % of the bed's width, the highest particle top (centre +
radius); a least-squares line through those points; its inclination. Frames from half a turn on
are averaged (the bed needs that long to reach its steady rolling state).

Writes OUT.csv (per frame: time, turns, particles, all_inside, worst_margin_m, drum_angle_error_rad,
repose_deg, surface points used), OUT_profile.csv (the last frame's free-surface points and fit)
and OUT.png (the last frame's cross-section with the fitted surface; repose angle over time)."""
import argparse
import csv
import math
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
DRUM = os.path.join(ROOT, "inputs", "drum")
sys.path.insert(0, os.path.join(ROOT, "tests", "liggghts"))
from common.outputs import parse_dump_rows  # noqa: E402  (dump custom reader)
sys.path.insert(0, DRUM)
from drum_analysis import Cavity, angle_error_about_y, free_surface  # noqa: E402

# per scene: the cavity (radius, length, halo, sphere and grain radii), make_drum.py's arguments
# and in.drum's variables (full: in.drum's and make_drum.py's defaults)
SCENES = {
    "full": dict(cavity=Cavity(R=0.035, L=0.02, eps=5e-5, sphere_radius=0.002, grain_radius=0.002),
                 make=[], deck={}),
    "small": dict(cavity=Cavity(R=0.015, L=0.012, eps=5e-5, sphere_radius=0.0015, grain_radius=0.0015),
                  make=["--radius", "0.015", "--length", "0.012", "--wall", "0.002", "--segments", "36",
                        "--particles", "40", "--particle-radius", "0.0015", "--spacing", "0.0034"],
                  deck=dict(diameter=0.003, grain=0.0015, half=0.02, halfy=0.01)),
}
CAVITY = SCENES["full"]["cavity"]


def run(args):
    os.makedirs(args.workdir, exist_ok=True)
    subprocess.run([sys.executable, os.path.join(DRUM, "make_drum.py"),
                    os.path.join(args.workdir, "drum.stl"), os.path.join(args.workdir, "positions.in")]
                   + SCENES[args.scene]["make"], check=True)
    cmd = [args.exe, "-in", os.path.join(DRUM, "in.drum"), "-echo", "none", "-log", "log.drum"]
    for k, v in [("turns", args.turns), ("period", args.period), ("settle", args.settle),
                 ("dt", args.dt), ("every", args.every), ("out", "drum")] + list(SCENES[args.scene]["deck"].items()):
        cmd += ["-var", k, str(v)]
    if args.np > 1:
        cmd = ["mpirun", "-np", str(args.np)] + cmd
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               OMPI_MCA_rmaps_base_oversubscribe="1")
    t0 = time.time()
    p = subprocess.run(cmd, cwd=args.workdir, env=env, stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, universal_newlines=True)
    print("run: %.0f s wall, exit %d" % (time.time() - t0, p.returncode))
    if p.returncode != 0:
        print(p.stdout[-3000:])
        sys.exit(1)


def analyse(args):
    parts = [(step, list(rows.values())) for step, rows in
             parse_dump_rows(os.path.join(args.workdir, "drum.particles"))]
    drum = [(step, list(rows.values())) for step, rows in
            parse_dump_rows(os.path.join(args.workdir, "drum.drum"))]
    omega = 2 * math.pi / args.period
    settle_steps = args.settle
    q0 = None
    rows = []
    for (step, p), (step_d, d) in zip(parts, drum):
        assert step == step_d
        q = tuple(next(r for r in d if r[1] == 3)[2:6])
        if q0 is None:
            q0 = q
        t = (step - settle_steps) * args.dt
        error = angle_error_about_y(q, q0, omega * t)
        worst = CAVITY.worst_margin(p)
        pts, repose, _, _ = free_surface(p, CAVITY)
        rows.append(dict(step=step, time_s=t, turns=t / args.period, particles=len(p),
                         all_inside=int(worst > -CAVITY.eps), worst_margin_m=worst,
                         drum_angle_error_rad=error, repose_deg=repose, surface_points=len(pts)))
    with open(args.out + ".csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    last = parts[-1][1]
    pts, repose, a, b = free_surface(last, CAVITY)
    with open(args.out + "_profile.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["x_m", "z_top_m", "z_fit_m"])
        for x, z in pts:
            w.writerow([x, z, a * x + b])
    steady = [r for r in rows if r["turns"] >= 0.5]
    mean = sum(r["repose_deg"] for r in steady) / len(steady) if steady else float("nan")
    sd = (math.sqrt(sum((r["repose_deg"] - mean) ** 2 for r in steady) / max(1, len(steady) - 1))
          if steady else float("nan"))
    print("frames %d, particles %d..%d, all inside: %s, worst margin %.3g m"
          % (len(rows), min(r["particles"] for r in rows), max(r["particles"] for r in rows),
             all(r["all_inside"] for r in rows), min(r["worst_margin_m"] for r in rows)))
    print("drum angle vs omega t: max |error| %.3g rad over %.2f turns"
          % (max(abs(r["drum_angle_error_rad"]) for r in rows), rows[-1]["turns"]))
    print("dynamic angle of repose: %.1f +- %.1f deg (mean, sd over %d frames from half a turn on)"
          % (mean, sd, len(steady)))
    plot(args, last, pts, a, b, rows, mean)


def plot(args, last, pts, a, b, rows, mean):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import Circle
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 4.8))
    for kind, colour, label in ((1, "tab:blue", "spheres"), (2, "tab:orange", "dented grains")):
        sel = [r for r in last if r[1] == kind]
        rad = CAVITY.sphere_radius if kind == 1 else CAVITY.grain_radius
        for r in sel:
            ax.add_patch(Circle((r[2] * 1e3, r[4] * 1e3), rad * 1e3, color=colour, alpha=0.5, lw=0))
        ax.plot([], [], "o", color=colour, label=label)
    R = CAVITY.R
    ax.add_patch(Circle((0, 0), R * 1e3, fill=False, color="k"))
    xs = [p[0] for p in pts]
    ax.plot([p[0] * 1e3 for p in pts], [p[1] * 1e3 for p in pts], "k.", ms=4, label="free surface")
    if xs:
        x0, x1 = min(xs), max(xs)
        ax.plot([x0 * 1e3, x1 * 1e3], [(a * x0 + b) * 1e3, (a * x1 + b) * 1e3], "r-", lw=2,
                label="fit: %.1f deg" % math.degrees(math.atan(abs(a))))
    ax.set_xlim(-R * 1.1e3, R * 1.1e3)
    ax.set_ylim(-R * 1.1e3, R * 1.1e3)
    ax.set_aspect("equal")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("z (mm)")
    ax.set_title("last frame, seen along the drum axis (%.2f turns)" % rows[-1]["turns"])
    ax.legend(loc="upper left", fontsize=8)
    bx.plot([r["turns"] for r in rows], [r["repose_deg"] for r in rows], "o-", ms=3)
    bx.axvline(0.5, color="grey", ls=":")
    bx.axhline(mean, color="r", ls="--", label="mean from 0.5 turns: %.1f deg" % mean)
    bx.set_xlabel("drum turns")
    bx.set_ylabel("dynamic angle of repose (deg)")
    bx.set_title("free-surface inclination")
    bx.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(args.out + ".png", dpi=110)
    print("wrote %s.csv, %s_profile.csv, %s.png" % (args.out, args.out, args.out))


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--exe", default=os.path.join(ROOT, "build", "liggghts-spacetree"))
    p.add_argument("--np", type=int, default=1)
    p.add_argument("--turns", type=float, default=2.0)
    p.add_argument("--period", type=float, default=1.2)
    p.add_argument("--settle", type=int, default=10000)
    p.add_argument("--dt", type=float, default=4e-5)
    p.add_argument("--every", type=int, default=1000)
    p.add_argument("--scene", choices=sorted(SCENES), default="full")
    p.add_argument("--out", default=os.path.join(ROOT, "bench", "results", "drum"))
    p.add_argument("--workdir", default=os.path.join(ROOT, "build", "bench_drum"))
    p.add_argument("--replot", action="store_true", help="analyse the dumps in --workdir again")
    args = p.parse_args()
    global CAVITY
    CAVITY = SCENES[args.scene]["cavity"]
    if args.settle % args.every:
        # the first dump is then after the rotation started: it would not be the drum's start pose
        p.error("--every must divide --settle (the first dumped frame is the drum at rest)")
    if not args.replot:
        run(args)
    analyse(args)


if __name__ == "__main__":
    main()
