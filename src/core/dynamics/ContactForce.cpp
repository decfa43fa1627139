#include "dynamics/ContactForce.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace spacetree::dynamics {

ContactKinematics contactKinematics(const RigidBody& first, const RigidBody& second,
                                    const contact::ContactPoint& contact) {
  ContactKinematics k;
  k.point = contact.point;
  k.normal = contact.normal;
  k.penetration = contact.penetration;
  k.relativeVelocity = second.velocityAt(contact.point) - first.velocityAt(contact.point);
  k.normalVelocity = k.relativeVelocity.dot(contact.normal);
  const double inverseMasses = first.inverseMass + second.inverseMass;
  k.effectiveMass = inverseMasses > 0.0 ? 1.0 / inverseMasses : 0.0;
  return k;
}

NormalSpringDashpot::NormalSpringDashpot(double spring, double damping)
    : spring_(spring), damping_(damping) {
  if (!(spring > 0.0) || !std::isfinite(spring))
    throw std::invalid_argument("NormalSpringDashpot: spring coefficient must be > 0");
  if (!(damping >= 0.0) || !std::isfinite(damping))
    throw std::invalid_argument("NormalSpringDashpot: damping coefficient must be >= 0");
}

double NormalSpringDashpot::normalForce(const ContactKinematics& k) const {
  double force = spring_ * k.penetration;
  if (k.normalVelocity < 0.0)  // approaching: pseudo-elastic damping
    force -= 2.0 * damping_ * std::sqrt(k.effectiveMass) * k.normalVelocity;
  return force > 0.0 ? force : 0.0;
}

double NormalSpringDashpot::dampingRatio() const { return damping_ * std::sqrt(2.0 / spring_); }

double NormalSpringDashpot::dampingForRestitution(double spring, double restitution) {
  if (!(restitution > 0.0 && restitution <= 1.0))
    throw std::invalid_argument("dampingForRestitution: restitution must be in (0, 1]");
  if (restitution == 1.0) return 0.0;
  // springDashpotRestitution decreases monotonically in zeta: bisection.
  double lo = 0.0, hi = 1.0;
  while (springDashpotRestitution(hi) > restitution) hi *= 2.0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (springDashpotRestitution(mid) > restitution ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi) * std::sqrt(spring / 2.0);
}

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

CoulombFriction::CoulombFriction(double coefficient, double viscousDamping)
    : coefficient_(coefficient), viscousDamping_(viscousDamping) {
  if (!(coefficient >= 0.0) || !(viscousDamping >= 0.0))
    throw std::invalid_argument("CoulombFriction: coefficients must be >= 0");
}

Eigen::Vector3d CoulombFriction::forceOnFirst(const ContactKinematics& k, double normalForce) const {
  const Eigen::Vector3d sliding = k.relativeVelocity - k.normalVelocity * k.normal;
  const double speed = sliding.norm();
  if (!(speed > 0.0)) return Eigen::Vector3d::Zero();
  const double magnitude = std::min(viscousDamping_ * speed, coefficient_ * normalForce);
  return (magnitude / speed) * sliding;
}

void applyContactForce(const RigidBody& first, const RigidBody& second,
                       const Eigen::Vector3d& point, const Eigen::Vector3d& forceOnFirst,
                       BodyLoad& firstLoad, BodyLoad& secondLoad) {
  firstLoad.force += forceOnFirst;
  firstLoad.torque += (point - first.position).cross(forceOnFirst);
  secondLoad.force -= forceOnFirst;
  secondLoad.torque -= (point - second.position).cross(forceOnFirst);
}

}  // namespace spacetree::dynamics
