#!/usr/bin/env python3
"""Hard cases for `fix adapt/timestep` (veto + rollback, `neighbor ... spacetree`): each must stay
stable: no NaN, no lost particle, no overlap deeper than eps at any step, no energy created in
elastic runs, plus the closed-form outcome where symmetry or mass ratio gives one.

  check_hardcases.py CASE[:NP] --exe EXE --workdir DIR [--mpiexec M] [--stack-steps N]

CASE: impact100, impact100veto (paper mode: eps 0, no dtcontact), ratio1000, stack, stackrest (the
stack with the state-dependent contact ceiling vimpact/tcontact), squeeze,
threebody (NP MPI ranks where the deck allows).
Exit status 0 = pass, 1 = fail.
"""
import argparse
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "timestep"))
import lg  # noqa: E402

RHO = 2500.0
# elastic runs: relative kinetic-energy gain allowed from the discretisation (dtcontact = tc/1000
# gives a symplectic error of about (pi/1000)^2 / 4 ~ 2.5e-6 of the contact energy)
ENERGY_TOL = 1e-5


def stiffness(young, d_i, d_j, v_char):
    m_i, m_j = lg.sphere_mass(d_i, RHO), lg.sphere_mass(d_j, RHO)
    h = lg.hooke(young, 0.3, d_i / 2, d_j / 2, m_i, m_j, 0.5, v_char)
    return h["kn"], m_i, m_j


def adapt_line(eps, dtcontact, dtmax, extra=""):
    return ("fix dtv all adapt/timestep creep 1.1 dtmax %.6g dtmin %.6g dtcontact %.6g eps %.6g "
            "rollback yes %s" % (dtmax, dtcontact * 1e-3, dtcontact, eps, extra))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("case")
    ap.add_argument("--exe", required=True)
    ap.add_argument("--workdir", required=True)
    ap.add_argument("--mpiexec", default="mpirun")
    ap.add_argument("--stack-steps", type=int, default=100000)
    a = ap.parse_args()
    case, _, np_ = a.case.partition(":")
    nprocs = int(np_ or 1)
    ok = True

    def check(cond, what):
        nonlocal ok
        print(("PASS " if cond else "FAIL ") + what)
        ok = ok and bool(cond)

    def run(deck, variables):
        v = dict(dir=HERE, mu=0.0, e=1.0, th=1)
        v.update(variables)
        if nprocs > 1:
            v["procs"] = "%d 1 1" % nprocs
        rc, out, log = lg.run_deck(a.exe, os.path.join(HERE, deck), a.workdir, case, v, nprocs=nprocs,
                                   mpiexec=a.mpiexec, timeout=600)
        if rc != 0:
            print(out[-3000:])
            check(False, "%s finished (rc %d)" % (deck, rc))
            return None, None
        names, rows = lg.thermo(log)
        return names, rows

    def common_checks(names, rows, natoms, eps, elastic):
        col = lambda n: lg.column(names, rows, n)  # noqa: E731
        finite = all(math.isfinite(x) for r in rows for x in r)
        check(finite, "no NaN/inf in %d thermo rows" % len(rows))
        check(all(n == natoms for n in col("Atoms")), "no particle lost (%d atoms all along)" % natoms)
        peak = col("f_dtv[8]")[-1]
        check(max(col("f_dtv[7]")) <= eps and peak <= eps,
              "overlap <= eps = %.4g at every step (peak %.4g = %.3f eps)" % (eps, peak, peak / eps))
        check(col("f_dtv[6]")[-1] == 0, "no rollback refused or exhausted")
        print("  %d steps, %d vetoed, %d rollbacks, dt from %.3g to %.3g"
              % (col("Step")[-1], col("f_dtv[2]")[-1], col("f_dtv[5]")[-1], min(col("Dt")), max(col("Dt"))))
        if elastic:
            ke = col("KinEng")
            gain = max(ke) / ke[0] - 1
            check(gain <= ENERGY_TOL, "no kinetic energy created: max KE / KE0 - 1 = %.2e <= %.0e"
                  % (gain, ENERGY_TOL))
        return col

    if case == "impact100":
        young, v, d = 5e8, 100.0, 0.01
        kn, m, _ = stiffness(young, d, d, v)
        peak = v / math.sqrt(kn / (m / 2))
        tc = math.pi / math.sqrt(kn / (m / 2))
        eps = 2.5 * peak
        names, rows = run("in.impact100", dict(young=young, vchar=v, skin=0.002, dtmax=1e-4, n=1500,
                                               adapt=adapt_line(eps, tc / 1000, 1e-4)))
        if names is None:
            return 1
        col = common_checks(names, rows, 2, eps, True)
        v1, v2 = col("v_v1")[-1], col("v_v2")[-1]
        print("  closed form: the striker stops, the target leaves at 100 m/s; got %.6g, %.6g m/s" % (v1, v2))
        check(abs(v1) <= 1e-3 * v and abs(v2 - v) <= 1e-3 * v, "velocities exchanged within 0.1 %")
    elif case == "impact100veto":
        # the paper's mode: no dtcontact, eps = 0 (the veto keeps the surfaces apart and the step
        # collapses to dtmin at impact, then creeps through the contact)
        young, v, d = 5e8, 100.0, 0.01
        kn, m, _ = stiffness(young, d, d, v)
        peak = v / math.sqrt(kn / (m / 2))
        names, rows = run("in.impact100", dict(young=young, vchar=v, skin=0.002, dtmax=1e-4, n=1500,
                          adapt="fix dtv all adapt/timestep creep 1.1 dtmax 1e-4 dtmin 9e-9 eps 0"))
        if names is None:
            return 1
        col = lambda n: lg.column(names, rows, n)  # noqa: E731
        check(all(math.isfinite(x) for r in rows for x in r), "no NaN/inf in %d thermo rows" % len(rows))
        check(all(n == 2 for n in col("Atoms")), "no particle lost")
        check(col("f_dtv[2]")[-1] >= 1, "the veto cut the step %d times before impact" % col("f_dtv[2]")[-1])
        check(col("f_dtv[8]")[-1] <= 1.01 * peak, "peak overlap %.4g within 1 %% of the closed form %.4g"
              % (col("f_dtv[8]")[-1], peak))
        ke = col("KinEng")
        check(max(ke) / ke[0] - 1 <= ENERGY_TOL, "no kinetic energy created (max KE / KE0 - 1 = %.2e)" % (max(ke) / ke[0] - 1))
        v1, v2 = col("v_v1")[-1], col("v_v2")[-1]
        print("  veto only: %d vetoed steps, min dt %.3g, striker %.4g m/s, target %.6g m/s"
              % (col("f_dtv[2]")[-1], min(col("Dt")), v1, v2))
        check(abs(v1) <= 1e-3 * v and abs(v2 - v) <= 1e-3 * v, "velocities exchanged within 0.1 %")
    elif case == "ratio1000":
        young, v, big, small = 5e7, 2.0, 1.0, 0.001
        kn, _, m = stiffness(young, big, small, v)
        omega = math.sqrt(kn / m)
        eps = 2.5 * v / omega
        names, rows = run("in.ratio1000", dict(young=young, vchar=v, skin=0.0005, dtmax=1e-3, n=1500,
                                               adapt=adapt_line(eps, math.pi / omega / 1000, 1e-3)))
        if names is None:
            return 1
        col = common_checks(names, rows, 2, eps, True)
        v2, vy2 = col("v_v2")[-1], col("v_vy2")[-1]
        speed = math.hypot(v2, vy2)
        print("  small sphere after: vx %.6g, |v| %.6g m/s (closed form: reflected at 2 m/s)" % (v2, speed))
        check(v2 > 0 and abs(speed - v) <= 1e-3 * v, "the small sphere bounces off at its speed within 0.1 %")
    elif case == "squeeze":
        young, v, big, small = 5e7, 5.0, 0.02, 0.005
        kn, m_big, _ = stiffness(young, big, small, v)
        omega = math.sqrt(kn / m_big)       # the small sphere stays put by symmetry
        eps = 2.5 * v / omega
        names, rows = run("in.squeeze", dict(young=young, vchar=v, skin=0.002, dtmax=1e-4, n=1100,
                                             adapt=adapt_line(eps, math.pi / omega / 1000, 1e-4)))
        if names is None:
            return 1
        col = common_checks(names, rows, 3, eps, True)
        v1, v2, v3, x2 = col("v_v1")[-1], col("v_v2")[-1], col("v_v3")[-1], max(abs(x) for x in col("v_x2"))
        print("  after: big %.6g / %.6g m/s, small %.3g m/s, small sphere moved at most %.3g m" % (v1, v3, v2, x2))
        check(abs(v1 + v) <= 1e-3 * v and abs(v3 - v) <= 1e-3 * v, "both big spheres bounce back at 5 m/s within 0.1 %")
        check(abs(v2) <= 1e-6 and x2 <= 1e-9, "the squeezed sphere stays at rest in the middle (symmetry)")
    elif case == "threebody":
        young, v, d = 5e7, 3.0, 0.01
        kn, m, _ = stiffness(young, d, d, v)
        omega = math.sqrt(kn / m)           # the centre sphere stays put by symmetry
        eps = 2.5 * v / omega
        names, rows = run("in.threebody", dict(young=young, vchar=v, skin=0.002, dtmax=1e-4, n=1600,
                                               adapt=adapt_line(eps, math.pi / omega / 1000, 1e-4)))
        if names is None:
            return 1
        col = common_checks(names, rows, 4, eps, True)
        sp = [col(n)[-1] for n in ("v_sp2", "v_sp3", "v_sp4")]
        drift = max(max(abs(x) for x in col("v_x1")), max(abs(y) for y in col("v_y1")))
        p = max(max(abs(x) for x in col("v_px")), max(abs(y) for y in col("v_py")))
        print("  outer speeds after %s m/s, centre moved %.3g m, |momentum| <= %.3g" % (sp, drift, p))
        check(all(abs(s - v) <= 1e-3 * v for s in sp), "each outer sphere rebounds at 3 m/s within 0.1 %")
        check(drift <= 1e-9, "the centre sphere stays at rest (symmetry)")
        check(p <= 1e-9 * lg.sphere_mass(d, RHO) * v, "total momentum stays zero")
    elif case in ("stack", "stackrest"):
        young, d, n_stack, g = 5e6, 0.01, 30, 9.81
        kn, m, _ = stiffness(young, d, d, 0.1)
        tc = math.pi / math.sqrt(kn / (m / 2))
        # equilibrium: the contact under sphere k carries the spheres k..n: delta = (n - k + 1) m g / kn
        dmg = m * g / kn
        deltas = [(n_stack - k + 1) * dmg for k in range(1, n_stack + 1)]
        comp_exact = sum(deltas)
        eps = 6.0 * deltas[0]
        # stackrest: the state-dependent contact ceiling (vimpact = the characteristic velocity of the
        # stiffness); the resting column's contact speed is omega * delta <= 30 g / omega << vimpact,
        # so it runs at dtrest = tc/10 instead of dtcontact = tc/50, 10^4 steps for the same time
        # as 5 * 10^4 at dtcontact. The fix's group is the column: the held base sphere is outside
        # it (its force is no acceleration)
        nsteps = a.stack_steps if case == "stack" else a.stack_steps // 10
        extra = "" if case == "stack" else "vimpact 0.1 tcontact %.9g" % tc
        names, rows = run("in.stack", dict(young=young, vchar=0.1, e=0.3, skin=0.001, dtmax=1e-3,
                                           nstack=n_stack, ntop=n_stack + 1, n=nsteps, dmg="%.17g" % dmg,
                                           th=max(1, nsteps // 200),
                                           adapt=adapt_line(eps, tc / 50, 1e-3, extra).replace(
                                               "dtv all", "dtv all" if case == "stack" else "dtv column")))
        if names is None:
            return 1
        col = common_checks(names, rows, n_stack + 1, eps, False)
        e = col("v_emech")
        steps = col("Step")[-1]
        check(max(e) <= e[0] + 1e-9 * abs(e[0]), "mechanical energy never exceeds its start (damped column)")
        comp = [n_stack * d - z for z in col("v_ztop")]
        worst = max(abs(c - comp_exact) for c in comp)
        print("  column height n d %.17g m, closed-form top compression %.17g m" % (n_stack * d, comp_exact))
        print("  %d steps (%.3g s): top compression %.6e .. %.6e m (closed form %.6e), final KE %.3g J, %g contacts"
              % (steps, col("Time")[-1], min(comp), max(comp), comp_exact, col("KinEng")[-1], col("f_dtv[9]")[-1]))
        check(steps == nsteps, "held for %d steps" % nsteps)
        if case == "stackrest":
            dts = col("Dt")
            check(max(dts) <= tc / 10 * (1 + 1e-9), "the step never exceeds dtrest = tc/10 (max %.4g tc)"
                  % (max(dts) / tc))
            check(dts[-1] >= 0.99 * tc / 10, "the resting column runs at dtrest = tc/10, not at dtcontact = "
                  "tc/50 (final dt %.4g tc)" % (dts[-1] / tc))
        check(worst <= 0.01 * comp_exact, "the column stays within 1 %% of its closed-form compression "
              "sum (n-k+1) m g / kn (worst %.2e of it)" % (worst / comp_exact))
        check(col("f_dtv[9]")[-1] == n_stack, "all %d contacts held" % n_stack)
        check(max(col("KinEng")) <= 1e-6 * m * g * comp_exact, "the column stays at rest (max KE %.3g J)"
              % max(col("KinEng")))
    else:
        print("unknown case", case)
        return 1
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
