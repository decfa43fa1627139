#include "contact_model/DampingApproach.h"

#include <stdexcept>

namespace spacetree::contact_model {

DampingApproach::DampingApproach(const ContactParameters& p)
    : damping_(p.require("damping", "damping approach")) {}

double springDashpotRestitution(double zeta) {
  if (!(zeta >= 0.0)) throw std::invalid_argument("springDashpotRestitution: zeta must be >= 0");
  if (zeta == 0.0) return 1.0;
  if (zeta < 1.0) {
    const double s = std::sqrt(1.0 - zeta * zeta);
    return std::exp(-zeta / s * std::atan(s / zeta));
  }
  if (zeta == 1.0) return std::exp(-1.0);
  const double s = std::sqrt(zeta * zeta - 1.0);
  return std::exp(-zeta / s * std::atanh(s / zeta));
}

double dampingForRestitution(double stiffness, double restitution) {
  if (!(restitution > 0.0 && restitution <= 1.0))
    throw std::invalid_argument("dampingForRestitution: restitution must be in (0, 1]");
  if (!(stiffness > 0.0) || !std::isfinite(stiffness))
    throw std::invalid_argument("dampingForRestitution: stiffness must be > 0");
  if (restitution == 1.0) return 0.0;
  // springDashpotRestitution decreases monotonically in zeta: bisection.
  double lo = 0.0, hi = 1.0;
  while (springDashpotRestitution(hi) > restitution) hi *= 2.0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (springDashpotRestitution(mid) > restitution ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi) * std::sqrt(stiffness / 2.0);
}

}  // namespace spacetree::contact_model
