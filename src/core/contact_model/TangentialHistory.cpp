#include "contact_model/TangentialHistory.h"

#include <cmath>

namespace spacetree::contact_model {

TangentialHistory::TangentialHistory(const ContactParameters& p)
    : friction_(p.require("friction", "tangential history")),
      stiffness_(p.require("tangentialStiffness", "tangential history", true)),
      damping_(p.require("tangentialDamping", "tangential history")) {}

Eigen::Vector3d TangentialHistory::forceOnFirst(const Contact& c, double normalForce,
                                                double* history, double dt) const {
  Eigen::Map<Eigen::Vector3d> xi(history);
  const Eigen::Vector3d sliding = c.relativeVelocity - c.normalVelocity * c.normal;
  const double cap = friction_ * normalForce;
  if (dt > 0.0) {
    keepInTangentPlane(xi, c.normal);
    xi += dt * sliding;
    const double spring = stiffness_ * xi.norm();
    if (spring > cap) xi *= cap / spring;  // sliding: the spring holds mu F
  }
  Eigen::Vector3d force = stiffness_ * xi + (2.0 * damping_ * std::sqrt(c.tangentialMass)) * sliding;
  const double magnitude = force.norm();
  if (magnitude > cap) force *= cap / magnitude;
  return force;
}

}  // namespace spacetree::contact_model
