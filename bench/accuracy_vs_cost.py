#!/usr/bin/env python3
"""Accuracy versus cost of the time step: fixed steps against `fix adapt/timestep`.

  /usr/bin/python3 bench/accuracy_vs_cost.py [--exe build/liggghts-spacetree] [--repeats 3]

Two problems (decks in inputs/accuracy/):
  two_spheres  two equal spheres head-on with the hooke model, 5 diameters apart at 1 m/s each;
               e = 0.5 for the restitution error, e = 1 for the energy error, peak overlap
               against the closed form (tests/liggghts/timestep/lg.py);
  pour         216 spheres of 2/3/4 mm falling on a floor, elastic and frictionless: the energy
               error is the drift of kinetic + gravitational + spring energy.
Policies: fixed dt = tc/k (tc the shortest contact time), and the adaptive step (creep 1.1,
veto, eps, dtcontact = the finest fixed dt; with and without rollback).
Writes docs/accuracy_vs_cost.md (tables), bench/results/accuracy_vs_cost.csv and
bench/results/accuracy_vs_cost_*.png (--replot: only the PNGs, from the stored CSV). Wall time: median of --repeats runs ("Loop time" sums).
"""
import argparse
import csv
import math
import os
import statistics
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tests", "liggghts", "timestep"))
import lg  # noqa: E402

G = 9.81
# adaptive rows in the plots: state-independent ceiling (stars), rollback (square), vimpact (diamonds)
MARKERS = ("r*", "m*", "k*", "gs", "bD", "cD", "yD")


def loop_time(log):
    return sum(float(l.split()[3]) for l in open(log, errors="replace") if l.startswith("Loop time of"))


def last_row(log):
    names, rows = lg.thermo(log)
    return dict(zip(names, rows[-1]))


def fixed_line(dt):
    # creep 1, no veto: the step stays dt; the fix only reports overlaps (f_dtv[8])
    return "fix dtv all adapt/timestep creep 1.0 dtmax %.9g veto no" % dt


def adaptive_line(dtcontact, eps, rollback, dtmax=1e-3, vimpact=None, tc=None, history=None):
    """vimpact/tc: the state-dependent contact ceiling (dtcontact resolves a contact of speed vimpact)."""
    return ("fix dtv all adapt/timestep creep 1.1 dtmax %.9g dtmin %.9g dtcontact %.9g eps %.9g%s%s%s"
            % (dtmax, dtcontact / 100, dtcontact, eps, " rollback yes penetration 0.9" if rollback else "",
               " vimpact %.9g tcontact %.9g" % (vimpact, tc) if vimpact else "",
               " file %s" % history if history else ""))


class Runner:
    def __init__(self, exe, work, repeats):
        self.exe, self.work, self.repeats = exe, work, repeats

    def run(self, deck, name, variables):
        walls, log = [], None
        for k in range(self.repeats):
            rc, out, log = lg.run_deck(self.exe, deck, self.work, "%s.%d" % (name, k), variables, timeout=900)
            if rc != 0:
                raise RuntimeError("%s failed:\n%s" % (name, out[-2000:]))
            walls.append(loop_time(log))
        return log, statistics.median(walls)


def two_spheres(runner, rows):
    deck = os.path.join(ROOT, "inputs", "accuracy", "in.two_spheres")
    d, rho, v0, gap0 = 0.01, 2500.0, 1.0, 0.05
    m = lg.sphere_mass(d, rho)
    h = lg.hooke(5e6, 0.45, d / 2, d / 2, m, m, 0.5, 2.0)
    tc, peak = h["contact_time"], lg.peak_overlap(h, 2 * v0)
    h1 = lg.hooke(5e6, 0.45, d / 2, d / 2, m, m, 0.999999999, 2.0)
    tc1 = math.pi / math.sqrt(h1["kn"] / h1["m_eff"])
    gaps = [gap0 + k * 1.37e-4 for k in range(5)]
    tend = gaps[-1] / (2 * v0) + 3 * tc
    eps = 1.5 * peak
    ks = [5, 10, 20, 50, 100, 200]
    policies = [("fixed tc/%d" % k, tc / k, fixed_line(tc / k)) for k in ks]
    policies += [("adaptive dtcontact tc/%d" % k, tc / 1000, adaptive_line(tc / k, eps, False)) for k in (100, 200, 400)]
    policies += [("adaptive dtcontact tc/400 + rollback", tc / 1000, adaptive_line(tc / 400, eps, True))]
    # state-dependent ceiling: dtcontact resolves the impact speed of the setup (2 v0 closing)
    policies += [("adaptive dtcontact tc/%d vimpact %g" % (k, 2 * v0), tc / 1000,
                  adaptive_line(tc / k, eps, False, vimpact=2 * v0, tc=tc1)) for k in (200, 400)]
    for label, dt0, line in policies:
        tag = label.replace(" ", "_").replace("/", "").replace("+", "_").replace(".", "p")
        per_phase = []
        # the entry and exit of a contact fall at a random phase of the step: every policy runs
        # from several separations and the median over them is reported
        for k, gap in enumerate(gaps):
            log, wall = runner.run(deck, "ts_%s_%d" % (tag, k),
                                   dict(e=0.5, gap0=gap, tend=tend, dt0=dt0, adapt=line))
            r = last_row(log)
            log1, _ = runner.run(deck, "ts1_%s_%d" % (tag, k),
                                 dict(e=1.0, gap0=gap, tend=tend, dt0=dt0, adapt=line))
            r1 = last_row(log1)
            per_phase.append(dict(steps=r["Step"], sim_time=r["Time"], wall_s=wall,
                                  restitution_error=abs(r["vrel"] / (2 * v0) - 0.5) / 0.5,
                                  peak_overlap=r["dtv[8]"], peak_overlap_error=abs(r["dtv[8]"] - peak) / peak,
                                  energy_error=abs(r1["KinEng"] / (m * v0 ** 2) - 1.0)))
        row = dict(case="two_spheres", policy=label, eps=eps)
        for key in per_phase[0]:
            row[key] = statistics.median(p[key] for p in per_phase)
        row["steps"] = int(row["steps"])
        row["energy_error_max"] = max(p["energy_error"] for p in per_phase)
        row["restitution_error_max"] = max(p["restitution_error"] for p in per_phase)
        rows.append(row)
        print("two_spheres %-36s steps %7d wall %.4f s  e err %.2e  peak err %.2e  energy err %.2e (max %.2e)"
              % (label, row["steps"], row["wall_s"], row["restitution_error"], row["peak_overlap_error"],
                 row["energy_error"], row["energy_error_max"]))
    return dict(tc=tc, peak=peak, tend=tend, eps=eps, tc_elastic=tc1)


def read_dump(path):
    lines = open(path).read().split("\n")
    k = lines.index(next(l for l in lines if l.startswith("ITEM: ATOMS")))
    cols = lines[k].split()[2:]
    box = [tuple(map(float, lines[k - 3 + i].split()[:2])) for i in range(3)]
    atoms = [dict(zip(cols, map(float, l.split()))) for l in lines[k + 1:] if l.strip()]
    return box, atoms


def pour_energy(path, young, poisson, v_char):
    """Kinetic + gravitational + spring energy (hooke, no damping: 1/2 kn delta^2 per contact)."""
    box, atoms = read_dump(path)
    lx, ly = box[0][1] - box[0][0], box[1][1] - box[1][0]
    e = 0.0
    for a in atoms:
        e += 0.5 * a["mass"] * (a["vx"] ** 2 + a["vy"] ** 2 + a["vz"] ** 2) + a["mass"] * G * a["z"]
        if a["z"] < a["radius"]:   # floor at z = 0: reff = r, meff = m
            h = lg.hooke(young, poisson, a["radius"], 1e30, a["mass"], 1e30, 0.5, v_char)
            e += 0.5 * h["kn"] * (a["radius"] - a["z"]) ** 2
    for i in range(len(atoms)):
        a = atoms[i]
        for j in range(i + 1, len(atoms)):
            b = atoms[j]
            dx = b["x"] - a["x"]
            dy = b["y"] - a["y"]
            dx -= lx * round(dx / lx)
            dy -= ly * round(dy / ly)
            dz = b["z"] - a["z"]
            delta = a["radius"] + b["radius"] - math.sqrt(dx * dx + dy * dy + dz * dz)
            if delta > 0.0:
                h = lg.hooke(young, poisson, a["radius"], b["radius"], a["mass"], b["mass"], 0.5, v_char)
                e += 0.5 * h["kn"] * delta ** 2
    return e


# the dense pour (216 spheres, 6 mm lattice from 12 to 48 mm) and a dilute rain (54 spheres, 12 mm
# lattice from 50 to 120 mm: layers reach the floor one after another, flights between impacts)
POURS = {"pour": dict(tend=0.12, eps=5e-4, ztop_cloud=0.048, deck={}),
         "rain": dict(tend=0.25, eps=1e-3, ztop_cloud=0.114,
                      deck=dict(spacing=0.012, zlo=0.05, zhi=0.12, ztop=0.14))}


def pour(runner, rows, case="pour"):
    cfg = POURS[case]
    deck = os.path.join(ROOT, "inputs", "accuracy", "in.pour")
    young, poisson, v_char, rho = 5e6, 0.3, 1.0, 2500.0
    # shortest contact time: every size pair and every size on the floor
    ds = [0.002, 0.003, 0.004]
    tcs = []
    for a in ds:
        ma = lg.sphere_mass(a, rho)
        tcs.append(lg.hooke(young, poisson, a / 2, 1e30, ma, 1e30, 0.999999999, v_char)["contact_time"])
        for b in ds:
            mb = lg.sphere_mass(b, rho)
            tcs.append(lg.hooke(young, poisson, a / 2, b / 2, ma, mb, 0.999999999, v_char)["contact_time"])
    tc = min(tcs)
    tend, eps = cfg["tend"], cfg["eps"]
    # impact speed of the setup: a sphere falling from the top of the cloud to the floor
    vdrop = math.sqrt(2 * G * cfg["ztop_cloud"])
    ks = [5, 10, 20, 50, 100, 200]
    policies = [("fixed tc/%d" % k, tc / k, fixed_line(tc / k)) for k in ks]
    policies += [("adaptive dtcontact tc/%d" % k, tc / 1000, adaptive_line(tc / k, eps, False)) for k in (50, 100, 200)]
    policies += [("adaptive dtcontact tc/100 + rollback", tc / 1000, adaptive_line(tc / 100, eps, True))]
    policies += [("adaptive dtcontact tc/%d vimpact %.2f" % (k, vdrop), tc / 1000,
                  adaptive_line(tc / k, eps, False, vimpact=vdrop, tc=tc)) for k in (25, 50, 100)]
    # the lattice jitter decides which contacts the (chaotic) pour visits: every policy runs every
    # seed; medians and the worst over the seeds are reported
    seeds = [15485863, 32452843, 49979687]
    history = None
    for label, dt0, line in policies:
        tag = case + "_" + label.replace(" ", "_").replace("/", "").replace("+", "_").replace(".", "p")
        per_seed = []
        for seed in seeds:
            stem = os.path.join(runner.work, "%s_%d" % (tag, seed))
            hist = stem + ".dt" if (seed == seeds[0] and "vimpact" in label and "tc/100" in label) else None
            if hist:
                line_s = line + " file " + hist
                history = hist
            else:
                line_s = line
            variables = dict(tend=tend, dt0=dt0, adapt=line_s, initial=stem + ".initial",
                             final=stem + ".final", seed=seed)
            variables.update(cfg["deck"])
            log, wall = runner.run(deck, "%s_%d" % (tag, seed), variables)
            r = last_row(log)
            e0 = pour_energy(stem + ".initial", young, poisson, v_char)
            e1 = pour_energy(stem + ".final", young, poisson, v_char)
            per_seed.append(dict(steps=r["Step"], sim_time=r["Time"], wall_s=wall, peak_overlap=r["dtv[8]"],
                                 energy_error=abs(e1 - e0) / e0))
        row = dict(case=case, policy=label, restitution_error=float("nan"), peak_overlap_error=float("nan"),
                   eps=eps)
        for key in per_seed[0]:
            row[key] = statistics.median(p[key] for p in per_seed)
        row["steps"] = int(row["steps"])
        row["energy_error_max"] = max(p["energy_error"] for p in per_seed)
        row["peak_overlap"] = max(p["peak_overlap"] for p in per_seed)
        rows.append(row)
        print("%-11s %-36s steps %7d wall %.3f s  peak overlap %.3e  energy err %.2e (max %.2e)"
              % (case, label, row["steps"], row["wall_s"], row["peak_overlap"], row["energy_error"], row["energy_error_max"]))
    # where the steps go in the state-dependent run (seed 1): time before the first contact, and the
    # largest contact speed present at each step of the contact phase
    info = dict(tc=tc, tend=tend, eps=eps, vdrop=vdrop, seeds=seeds)
    if history:
        h = [l.split() for l in open(history) if not l.startswith("#")]
        contact = [x for x in h if float(x[7]) > 0]
        w = sorted(float(x[11]) for x in contact)
        info.update(first_contact=float(contact[0][1]), steps_total=len(h), steps_contact=len(contact),
                    w_quantiles=[w[int(q * (len(w) - 1))] for q in (0.1, 0.5, 0.9)],
                    share_above=sum(1 for x in w if x > vdrop) / len(w))
    return info


def verdict(rows, case, metrics):
    """Definition (a), the target's wording: best fixed = the most accurate fixed row studied (by the
    sum of the metrics); the adaptive row reaches it if each metric is <= 1.1 x the best fixed one."""
    sub = [r for r in rows if r["case"] == case]
    fixed = [r for r in sub if r["policy"].startswith("fixed")]
    if not fixed:
        return []
    best = min(fixed, key=lambda r: sum(r[m] for m in metrics))  # the most accurate fixed step
    out = []
    for r in sub:
        if not r["policy"].startswith("adaptive"):
            continue
        ratio = r["steps"] / best["steps"]
        reaches = all(r[m] <= 1.1 * best[m] + 1e-12 for m in metrics)
        out.append((r["policy"], best["policy"], ratio, r["wall_s"] / best["wall_s"], reaches,
                    {m: (r[m], best[m]) for m in metrics}))
    return out


def equal_accuracy(rows, case, metrics):
    """Definition (b): for each adaptive row, the largest fixed step (fewest steps) that is at least
    as accurate in every metric; None when no fixed row studied is (then the finest fixed row is
    a lower bound of the fixed cost and the ratio against it an upper bound)."""
    sub = [r for r in rows if r["case"] == case]
    fixed = sorted([r for r in sub if r["policy"].startswith("fixed")], key=lambda r: r["steps"])
    out = []
    for r in sub:
        if not r["policy"].startswith("adaptive"):
            continue
        match = next((f for f in fixed if all(f[m] <= r[m] for m in metrics)), None)
        ref = match or fixed[-1]
        out.append((r["policy"], ref["policy"], match is not None, r["steps"] / ref["steps"]))
    return out


def vimpact_reading(by):
    """The state-dependent ceiling on the two spheres (e = 0.5: the contact speed falls as the
    dashpot takes energy, so the rebound half of the contact gets coarser steps)."""
    k = ("two_spheres", "adaptive dtcontact tc/400 vimpact 2")
    p = ("two_spheres", "adaptive dtcontact tc/400")
    if k not in by or p not in by:
        return []
    v, q = by[k], by[p]
    return ["* `vimpact` on the two spheres (tc/400): %d steps instead of %d, median restitution error"
            % (v["steps"], q["steps"]),
            "  %.2e instead of %.2e, but the worst of the five phases %.2e instead of %.2e: with e = 0.5"
            % (v["restitution_error"], q["restitution_error"], v["restitution_error_max"], q["restitution_error_max"]),
            "  the dashpot takes energy, the contact speed falls and the rebound is stepped more coarsely",
            "  (the ceiling bounds the absolute error per contact, not the relative one)."]


def pour_reading(info, case):
    """Numbers on where the pour's steps go (from the time-step history of the vimpact tc/100 run)."""
    if "steps_contact" not in info:
        return []
    q = info["w_quantiles"]
    if case == "rain":
        return ["* The rain, measured the same way: first contact at t = %.4f s of %.3g s; %d of %d steps"
                % (info["first_contact"], info["tend"], info["steps_contact"], info["steps_total"]),
                "  have a pair in contact or about to touch; largest contact speed %.2f / %.2f / %.2f m/s"
                % tuple(q),
                "  (10 / 50 / 90 %%), above vimpact = %.2f m/s at %.0f %% of them."
                % (info["vdrop"], 100 * info["share_above"])]
    return ["* The pour, measured (seed 1, `vimpact` tc/100 run, time-step history): the first contact",
            "  is at t = %.4f s of %.3g s (%.0f %% of the simulated time is contact-free); %d of its %d"
            % (info["first_contact"], info["tend"], 100 * info["first_contact"] / info["tend"],
               info["steps_contact"], info["steps_total"]),
            "  steps have a pair in contact or about to touch. The largest contact speed present at a",
            "  step of the contact phase (f_ID[11]) is %.2f / %.2f / %.2f m/s (10 / 50 / 90 %%), above the"
            % tuple(q),
            "  drop speed vimpact = %.2f m/s at %.0f %% of those steps: an elastic pour never calms down"
            % (info["vdrop"], 100 * info["share_above"]),
            "  (no dissipation), and elastic collisions hand the large spheres' energy to small ones,",
            "  which fly faster than anything dropped. A global step has to resolve the fastest contact",
            "  present, and one is present at almost every step; so the state-dependent ceiling cannot",
            "  relax it here: it refines the step wherever a contact is faster than vimpact (compare the",
            "  vimpact rows with the plain rows of the same dtcontact above). Enduring contacts (a resting",
            "  column: `liggghts.hardcase.stackrest`, contact speed ~0, dt = dtrest = tc/10 instead of",
            "  tc/50) are where it saves steps; a settled dissipative pour would be such a case, but it",
            "  has no conserved energy to measure the error with and is not in this study.",
            "* Why the pour misses 1/5, as a bound: the energy error comes from the contacts, so the",
            "  adaptive run matches the fixed step tc/k only with a contact resolution of about tc/k, and",
            "  it takes that step whenever a contact exists, i.e. from the first contact on. Its steps are",
            "  then at least (t_end - t_first)/t_end = %.2f of the fixed run's; measured at equal"
            % (1 - info["first_contact"] / info["tend"]),
            "  resolution (adaptive tc/200 vs fixed tc/200, table above) %.3f. Only a coarser contact"
            % info.get("ratio_equal_resolution", float("nan")),
            "  resolution that is as accurate by chance could beat that bound; adaptive tc/100 (%.3f of"
            % info.get("ratio_coarse", float("nan")),
            "  fixed tc/200's steps) is not (energy error %.2e against %.2e). Below 1/5 needs a"
            % (info.get("err_coarse", float("nan")), info.get("err_fine", float("nan"))),
            "  contact-free share of the run above 4/5, or a step that is not global (local time stepping)."]


def fmt(x):
    if isinstance(x, float):
        if math.isnan(x):
            return "-"
        return "%.3g" % x
    return str(x)


def plot(rows, results, repeats):
    """Draws accuracy_vs_cost_steps.png and accuracy_vs_cost_wall.png into `results`."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 4, figsize=(20, 5.6))
    for ax, case, metric, title in ((axes[0], "two_spheres", "restitution_error", "two spheres, e = 0.5"),
                                    (axes[1], "two_spheres", "energy_error", "two spheres, e = 1"),
                                    (axes[2], "pour", "energy_error", "polydisperse pour, elastic"),
                                    (axes[3], "rain", "energy_error", "dilute rain, elastic")):
        sub = [r for r in rows if r["case"] == case]
        fx = [r for r in sub if r["policy"].startswith("fixed")]
        ax.loglog([r["steps"] for r in fx], [max(r[metric], 1e-16) for r in fx], "o-", label="fixed dt = tc/k")
        for r in fx:
            ax.annotate(r["policy"].split()[1], (r["steps"], max(r[metric], 1e-16)), fontsize=7)
        for r, mk in zip([r for r in sub if r["policy"].startswith("adaptive")], MARKERS):
            ax.loglog([r["steps"]], [max(r[metric], 1e-16)], mk, ms=10 if mk != "gs" else 14, mfc="none" if mk in ("gs", "bD", "cD") else None,
                      label=r["policy"])
        ax.set_xlabel("steps")
        ax.set_ylabel(metric.replace("_", " ") + " (relative)")
        ax.set_title(title)
        ax.grid(True, which="both", alpha=0.3)
        # below the panel: the markers sit where a legend inside would cover them
        ax.legend(fontsize=7, ncol=2, loc="upper center", bbox_to_anchor=(0.5, -0.16))
    fig.tight_layout()
    fig.savefig(os.path.join(results, "accuracy_vs_cost_steps.png"), dpi=100)
    fig, axes = plt.subplots(1, 3, figsize=(15, 5.6))
    for ax, case, metric in ((axes[0], "two_spheres", "restitution_error"), (axes[1], "pour", "energy_error"),
                             (axes[2], "rain", "energy_error")):
        sub = [r for r in rows if r["case"] == case]
        fx = [r for r in sub if r["policy"].startswith("fixed")]
        ax.loglog([r["wall_s"] for r in fx], [max(r[metric], 1e-16) for r in fx], "o-", label="fixed dt = tc/k")
        for r, mk in zip([r for r in sub if r["policy"].startswith("adaptive")], MARKERS):
            ax.loglog([r["wall_s"]], [max(r[metric], 1e-16)], mk, ms=10 if mk != "gs" else 14, mfc="none" if mk in ("gs", "bD", "cD") else None,
                      label=r["policy"])
        ax.set_xlabel("wall time (s, median of %d)" % repeats)
        ax.set_ylabel(metric.replace("_", " "))
        ax.set_title(case)
        ax.grid(True, which="both", alpha=0.3)
        # below the panel: the markers sit where a legend inside would cover them
        ax.legend(fontsize=7, ncol=2, loc="upper center", bbox_to_anchor=(0.5, -0.16))
    fig.tight_layout()
    fig.savefig(os.path.join(results, "accuracy_vs_cost_wall.png"), dpi=100)


def read_rows(path):
    """The rows of accuracy_vs_cost.csv, numbers as floats (steps as int)."""
    rows = []
    for row in csv.DictReader(open(path)):
        r = {}
        for k, v in row.items():
            try:
                r[k] = int(v) if k == "steps" else float(v)
            except ValueError:
                r[k] = v
        rows.append(r)
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "liggghts-spacetree"))
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--skip-pour", action="store_true", help="two-sphere case only (quick look)")
    ap.add_argument("--docs", default=os.path.join(ROOT, "docs"))
    ap.add_argument("--results", default=os.path.join(ROOT, "bench", "results"))
    ap.add_argument("--replot", action="store_true",
                    help="only redraw the two PNGs from the stored CSV (give --repeats as measured)")
    a = ap.parse_args()
    if a.replot:
        plot(read_rows(os.path.join(a.results, "accuracy_vs_cost.csv")), a.results, a.repeats)
        return
    work = os.path.join(ROOT, "build", "bench_accuracy_vs_cost")
    runner = Runner(a.exe, work, a.repeats)
    rows = []
    info_ts = two_spheres(runner, rows)
    info_pour = pour(runner, rows) if not a.skip_pour else dict(tc=0, tend=0, eps=0)
    info_rain = pour(runner, rows, "rain") if not a.skip_pour else dict(tc=0, tend=0, eps=0)

    os.makedirs(a.results, exist_ok=True)
    keys = ["case", "policy", "steps", "sim_time", "wall_s", "restitution_error", "restitution_error_max",
            "peak_overlap", "peak_overlap_error", "eps", "energy_error", "energy_error_max"]
    with open(os.path.join(a.results, "accuracy_vs_cost.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys, restval="")
        w.writeheader()
        for r in rows:
            w.writerow(r)

    # numbers for the pour's bound (Reading): equal contact resolution, and one step coarser
    by = {(r["case"], r["policy"]): r for r in rows}
    if ("pour", "fixed tc/200") in by:
        fine = by[("pour", "fixed tc/200")]
        info_pour["ratio_equal_resolution"] = by[("pour", "adaptive dtcontact tc/200")]["steps"] / fine["steps"]
        info_pour["ratio_coarse"] = by[("pour", "adaptive dtcontact tc/100")]["steps"] / fine["steps"]
        info_pour["err_coarse"] = by[("pour", "adaptive dtcontact tc/100")]["energy_error"]
        info_pour["err_fine"] = fine["energy_error"]
    v_ts = verdict(rows, "two_spheres", ["restitution_error", "energy_error"])
    v_pour = verdict(rows, "pour", ["energy_error"])
    eq_ts = equal_accuracy(rows, "two_spheres", ["restitution_error", "energy_error"])
    eq_pour = equal_accuracy(rows, "pour", ["energy_error"])
    v_rain = verdict(rows, "rain", ["energy_error"])
    eq_rain = equal_accuracy(rows, "rain", ["energy_error"])

    plot(rows, a.results, a.repeats)

    md = ["# Accuracy versus cost of the time step",
          "",
          "Generated by `/usr/bin/python3 bench/accuracy_vs_cost.py` (decks `inputs/accuracy/`, raw numbers",
          "in [accuracy_vs_cost.csv](../bench/results/accuracy_vs_cost.csv)); do not edit by hand. Wall time: median of %d runs"
          % a.repeats,
          "of the LIGGGHTS loop on this machine (2 shared cores). Every policy, fixed ones included, runs",
          "`fix adapt/timestep` (fixed: `creep 1.0 veto no`, which keeps dt and only reports overlaps), so",
          "the per-step cost of the overlap scan is in every row.",
          "",
          "Adaptive policy: `creep 1.1 dtmax 1e-3 dtcontact tc/k eps <eps>` (veto on) for several k; the",
          "`+ rollback` row adds `rollback yes penetration 0.9`. Between contacts the step grows up to",
          "the skin and list look-ahead caps and `dtmax`; while any pair is in contact or may touch within",
          "the next step it is at most `dtcontact`.",
          "",
          "## Two spheres head-on (hooke)",
          "",
          "d = 0.01 m, 2500 kg/m^3, +-1 m/s, 0.05 m apart (five runs, 0.05 + k 1.37e-4 m, k = 0..4: the",
          "contact starts and ends at a different phase of the step in each; medians, and the worst of the",
          "five in brackets), run to t = %.4g s; closed form: contact time" % info_ts["tend"],
          "tc = %.4e s, peak overlap %.4e m (e = 0.5); eps = %.3e m. Restitution error: |e - 0.5|/0.5;"
          % (info_ts["tc"], info_ts["peak"], info_ts["eps"]),
          "energy error: |KE after / KE before - 1| of the same run with e = 1; peak-overlap error against",
          "the closed form.",
          "",
          "| policy | steps | wall (s) | restitution error (worst) | peak overlap (m) | peak-overlap error | energy error, e = 1 (worst) |",
          "|---|---|---|---|---|---|---|"]
    for r in rows:
        if r["case"] == "two_spheres":
            md.append("| %s | %d | %s | %s (%s) | %s | %s | %s (%s) |" % (r["policy"], r["steps"], fmt(r["wall_s"]),
                      fmt(r["restitution_error"]), fmt(r["restitution_error_max"]), fmt(r["peak_overlap"]),
                      fmt(r["peak_overlap_error"]), fmt(r["energy_error"]), fmt(r["energy_error_max"])))
    md += ["",
           "## Polydisperse pour (elastic, frictionless)",
           "",
           "216 spheres of d = 2, 3, 4 mm on a jittered 6 mm lattice fall onto a floor (`fix wall/gran",
           "primitive zplane`), periodic in x and y, run to t = %.3g s; tc = %.4e s is the shortest contact"
           % (info_pour["tend"], info_pour["tc"]),
           "time (all size pairs and the floor). Energy error: |E(t_end) - E(0)| / E(0) with E = kinetic +",
           "gravitational + spring energy (1/2 kn delta^2 per contact, computed from full-precision dumps);",
           "eps = %.1e m."
           % info_pour["eps"],
           "The pour is chaotic (each run visits other contacts), so every policy runs three lattice",
           "jitters (seeds %s): steps, wall time and energy error are medians over them, the worst"
           % ", ".join(str(x) for x in info_pour.get("seeds", [])),
           "energy error in brackets, the peak overlap the largest of the three. `vimpact %.2f` is the"
           % info_pour.get("vdrop", 0.0),
           "impact speed of a fall from the top of the cloud, sqrt(2 g 0.048 m), `tcontact` = tc.",
           "",
           "| policy | steps | wall (s) | peak overlap (m) | energy error (worst) |",
           "|---|---|---|---|---|"]
    for r in rows:
        if r["case"] == "pour":
            md.append("| %s | %d | %s | %s | %s (%s) |" % (r["policy"], r["steps"], fmt(r["wall_s"]),
                      fmt(r["peak_overlap"]), fmt(r["energy_error"]), fmt(r.get("energy_error_max", float("nan")))))
    md += ["",
           "## Dilute rain (elastic, frictionless)",
           "",
           "The same deck with 54 spheres (2, 3, 4 mm) on a 12 mm lattice from z = 0.05 to 0.12 m (3 x 3 per",
           "layer, six layers): the layers land one after another and bounce, with flights between",
           "impacts. Run to t = %.3g s, eps = %.1e m, `vimpact %.2f` = sqrt(2 g 0.114 m), otherwise as"
           % (info_rain["tend"], info_rain["eps"], info_rain.get("vdrop", 0.0)),
           "the pour (three seeds, medians, worst energy error in brackets). Added beside the dense pour,",
           "which stays the harder case; neither scene was tuned to the policy.",
           "",
           "| policy | steps | wall (s) | peak overlap (m) | energy error (worst) |",
           "|---|---|---|---|---|"]
    for r in rows:
        if r["case"] == "rain":
            md.append("| %s | %d | %s | %s | %s (%s) |" % (r["policy"], r["steps"], fmt(r["wall_s"]),
                      fmt(r["peak_overlap"]), fmt(r["energy_error"]), fmt(r.get("energy_error_max", float("nan")))))
    md += ["", "## Target: the accuracy of the best fixed step in <= 1/5 of its steps", "",
           "Two definitions of the fixed step to compare with, both stated because they answer",
           "different questions. (a) *Best fixed step* (the target's wording, used for \"target met\"):",
           "the most accurate fixed row studied (the finest one here); an adaptive row reaches its",
           "accuracy if each error metric (medians) is at most 1.1 times the best fixed one.",
           "(b) *Equal accuracy*: the largest fixed step studied that is at least as accurate as the",
           "adaptive row in every metric — the fixed run a user would need for the adaptive row's",
           "accuracy; the steps ratio against it is the saving at equal accuracy. Errors are the",
           "medians over the contact phases (two spheres) or seeds (pour, rain).", "",
           "| case | adaptive policy | best fixed | steps ratio | wall ratio | reaches its accuracy | errors (adaptive / best fixed) | target met |",
           "|---|---|---|---|---|---|---|---|"]
    for case, vs in (("two_spheres", v_ts), ("pour", v_pour), ("rain", v_rain)):
        for pol, bestpol, ratio, wratio, reaches, errs in vs:
            md.append("| %s | %s | %s | %.3f (1/%.1f) | %.3f | %s | %s | %s |" % (
                case, pol, bestpol, ratio, 1 / ratio, wratio, "yes" if reaches else "no",
                ", ".join("%s %.2e / %.2e" % (m.replace("_error", ""), x, y) for m, (x, y) in errs.items()),
                "yes" if reaches and ratio <= 0.2 else "no"))
    md += ["", "Equal accuracy (b): the largest fixed step at least as accurate as the adaptive row.", "",
           "| case | adaptive policy | fixed step at equal accuracy | steps ratio |",
           "|---|---|---|---|"]
    for case, eq in (("two_spheres", eq_ts), ("pour", eq_pour), ("rain", eq_rain)):
        for pol, ref, found, ratio in eq:
            md.append("| %s | %s | %s | %s |" % (case, pol, ref if found else "none studied (finest: %s)" % ref,
                      ("%.3f (1/%.1f)" % (ratio, 1 / ratio)) if found else "< %.3f (1/%.1f)" % (ratio, 1 / ratio)))
    met = [(case, pol, ratio) for case, vs in (("two_spheres", v_ts), ("pour", v_pour), ("rain", v_rain))
           for pol, bestpol, ratio, wratio, reaches, errs in vs if reaches and ratio <= 0.2]
    cheapest = {}
    for case, vs in (("two_spheres", v_ts), ("pour", v_pour), ("rain", v_rain)):
        ok = [(ratio, pol) for pol, bestpol, ratio, wratio, reaches, errs in vs if reaches]
        cheapest[case] = min(ok) if ok else None
    md += ["", "## Reading", "",
           "* Target met: %s." % ("; ".join("%s with %s at %.3f of the steps" % m for m in met) if met else "nowhere"),
           "* Cheapest adaptive row that reaches the best fixed accuracy: %s."
           % "; ".join("%s: %s" % (c, ("%s, steps ratio %.3f" % (v[1], v[0])) if v else "none")
                       for c, v in cheapest.items()),
           "* Where the saving comes from: the global step is only large while no pair is in contact",
           "  or about to touch. The two spheres spend most of the run in free flight (steps at the skin",
           "  and list look-ahead caps), so the adaptive run can afford a contact resolution finer than",
           "  the best fixed step and still take far fewer steps."] + vimpact_reading(by) + \
        pour_reading(info_pour, "pour") + \
        pour_reading(info_rain, "rain") + [
           "* The fixed-step energy error of the pour is not monotone in dt: the pour is chaotic and each",
           "  run visits different contacts (hence the medians over three seeds); the two-sphere medians",
           "  over five contact phases are the cleaner convergence measure.",
           "* Rollback never triggered here (no step penetrated beyond 0.9 eps): identical results; its",
           "  cost is the per-step copy of the state and of the contact history (the wall-ratio difference).",
           "", "![error vs steps](../bench/results/accuracy_vs_cost_steps.png)", "",
           "![error vs wall time](../bench/results/accuracy_vs_cost_wall.png)", ""]
    with open(os.path.join(a.docs, "accuracy_vs_cost.md"), "w") as f:
        f.write("\n".join(md))
    for case, vs in (("two_spheres", v_ts), ("pour", v_pour), ("rain", v_rain)):
        for pol, bestpol, ratio, wratio, reaches, errs in vs:
            print("%s %s vs %s: steps ratio %.3f, wall ratio %.3f, reaches accuracy: %s"
                  % (case, pol, bestpol, ratio, wratio, reaches))
    print("wrote", os.path.join(a.docs, "accuracy_vs_cost.md"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
