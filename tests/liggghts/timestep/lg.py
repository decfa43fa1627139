"""Shared helpers of the adaptive-time-step tests and benchmarks: run a LIGGGHTS deck, read its
thermo table, the closed form of the LIGGGHTS hooke (linear spring-dashpot) contact."""
import math
import os
import subprocess


def run_deck(exe, deck, workdir, name, variables, nprocs=1, mpiexec="mpirun", timeout=300):
    """Run `deck` with -var k v for every item; returns (rc, screen text, log path)."""
    os.makedirs(workdir, exist_ok=True)
    log = os.path.join(workdir, "log." + name)
    cmd = [exe, "-in", deck, "-log", log, "-echo", "none"]
    for k, v in variables.items():
        cmd += ["-var", k, str(v)]
    if nprocs > 1:
        cmd = [mpiexec, "--oversubscribe", "-np", str(nprocs)] + cmd
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               OMPI_MCA_rmaps_base_oversubscribe="1")
    p = subprocess.run(cmd, cwd=workdir, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       errors="replace", text=True, timeout=timeout, env=env)
    return p.returncode, p.stdout, log


def thermo(log):
    """The last thermo table of a log: (column names, rows of floats)."""
    names, rows, tables, on = None, [], [], False
    for line in open(log, errors="replace"):
        s = line.split()
        if s and s[0] == "Step":
            names, rows, on = s, [], True
            continue
        if on:
            if line.startswith("Loop time"):
                tables.append((names, rows))
                on = False
                continue
            try:
                vals = [float(t) for t in s]
            except ValueError:
                continue
            if len(vals) == len(names):
                rows.append(vals)
    if on:
        tables.append((names, rows))
    return tables[-1] if tables else (None, [])


def column(names, rows, name):
    """A thermo column by its input name (thermo headers drop the v_ / f_ / c_ prefix)."""
    k = names.index(name) if name in names else names.index(name[2:])
    return [r[k] for r in rows]


def hooke(young, poisson, radius_i, radius_j, mass_i, mass_j, restitution, char_vel):
    """LIGGGHTS 3.8 normal_model_hooke.h: stiffness, damping, contact time, restitution."""
    y_eff = young / (2.0 * (1.0 - poisson ** 2))
    r_eff = radius_i * radius_j / (radius_i + radius_j)
    m_eff = mass_i * mass_j / (mass_i + mass_j)
    sq = math.sqrt(r_eff)
    kn = 16.0 / 15.0 * sq * y_eff * (15.0 * m_eff * char_vel ** 2 / (16.0 * sq * y_eff)) ** 0.2
    log_e = math.log(restitution)
    gamma = math.sqrt(4.0 * m_eff * kn * log_e ** 2 / (log_e ** 2 + math.pi ** 2))
    beta = gamma / (2.0 * m_eff)
    omega_d = math.sqrt(kn / m_eff - beta ** 2)
    return dict(kn=kn, gamma=gamma, m_eff=m_eff, beta=beta, omega_d=omega_d,
                contact_time=math.pi / omega_d, restitution=math.exp(-beta * math.pi / omega_d))


def peak_overlap(h, closing_speed):
    """Largest overlap of the damped oscillator delta'' = -w0^2 delta - 2 beta delta', delta'(0) = v."""
    t = math.atan2(h["omega_d"], h["beta"]) / h["omega_d"]
    return closing_speed / h["omega_d"] * math.exp(-h["beta"] * t) * math.sin(h["omega_d"] * t)


def crossings(t, gap):
    """Times where gap changes sign, linearly interpolated within the step."""
    out = []
    for k in range(1, len(gap)):
        if (gap[k - 1] > 0.0) != (gap[k] > 0.0):
            out.append(t[k - 1] + (t[k] - t[k - 1]) * gap[k - 1] / (gap[k - 1] - gap[k]))
    return out


def sphere_mass(diameter, density):
    return density * math.pi / 6.0 * diameter ** 3
