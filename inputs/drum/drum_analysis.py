"""What a drum run's dumps say (bench/drum.py, tests/liggghts/move_trimesh): whether every
particle is inside the cavity, the drum's rotation angle, the bed's free surface.

Rows are dump custom rows `id type x y z ...` (spheres type 1, dented grains type 2) or, for the
drum, `id type quat1 quat2 quat3 quat4 ...`; the drum turns about +y through the origin."""
import math


class Cavity:
    """Cavity radius R and length L (m), halo eps, sphere radius, dented-grain radius and
    amplitude (in.drum's `diameter`/2, `grain`, 0.25)."""

    def __init__(self, R, L, eps, sphere_radius, grain_radius, amplitude=0.25):
        self.R, self.L, self.eps = R, L, eps
        self.sphere_radius, self.grain_radius, self.amplitude = sphere_radius, grain_radius, amplitude

    def inscribed(self, kind):
        """Inscribed radius: a sphere's core (radius - eps), a dented grain's smallest radius."""
        return self.sphere_radius - self.eps if kind == 1 else self.grain_radius * (1 - self.amplitude)

    def outer(self, kind):
        return self.sphere_radius if kind == 1 else self.grain_radius * (1 + self.amplitude)

    def worst_margin(self, rows):
        """Smallest distance by which a centre stays inside the cavity shrunk by the particle's
        inscribed radius (axisymmetric: distance from the y axis, |y|); a particle that crossed
        the drum's wall fails it by millimetres."""
        worst = float("inf")
        for r in rows:
            rad = self.inscribed(r[1])
            worst = min(worst, self.R - (math.hypot(r[2], r[4]) + rad), self.L / 2 - (abs(r[3]) + rad))
        return worst


def quat_mul(a, b):
    w1, x1, y1, z1 = a
    w2, x2, y2, z2 = b
    return (w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2, w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
            w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2, w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2)


def angle_error_about_y(q, q0, expected):
    """Angle of q q0^-1 about +y minus `expected` (rad), reduced to (-pi, pi]."""
    rel = quat_mul(q, (q0[0], -q0[1], -q0[2], -q0[3]))
    angle = 2.0 * math.atan2(rel[2], rel[0])
    return (angle - expected + math.pi) % (2 * math.pi) - math.pi


def free_surface(rows, cavity, bin_width=0.002):
    """(x, z_top) points of the bed's free surface seen along the axis (the highest particle top
    per bin over the middle 60 % of the bed's width) and the least-squares line through them:
    (points, inclination in degrees, slope, intercept)."""
    tops = [(r[2], r[4] + cavity.outer(r[1])) for r in rows]
    xs = [t[0] for t in tops]
    lo, hi = min(xs), max(xs)
    lo, hi = lo + 0.2 * (hi - lo), hi - 0.2 * (hi - lo)
    bins = {}
    for x, z in tops:
        if lo <= x <= hi:
            k = int((x - lo) // bin_width)
            if k not in bins or z > bins[k][1]:
                bins[k] = (x, z)
    pts = sorted(bins.values())
    n = len(pts)
    if n < 3:
        return pts, float("nan"), 0.0, 0.0
    mx = sum(p[0] for p in pts) / n
    mz = sum(p[1] for p in pts) / n
    a = sum((p[0] - mx) * (p[1] - mz) for p in pts) / sum((p[0] - mx) ** 2 for p in pts)
    return pts, math.degrees(math.atan(abs(a))), a, mz - a * mx
