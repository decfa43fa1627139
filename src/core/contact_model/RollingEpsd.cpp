#include "contact_model/RollingEpsd.h"

#include <cmath>

namespace spacetree::contact_model {

RollingEpsd::RollingEpsd(const ContactParameters& p)
    : friction_(p.require("rollingFriction", "rolling epsd")),
      damping_(p.require("rollingDamping", "rolling epsd")),
      normalStiffness_(p.require("stiffness", "rolling epsd", true)) {}

Eigen::Vector3d RollingEpsd::torqueOnFirst(const Contact& c, double normalForce, double* history,
                                           double dt) const {
  Eigen::Map<Eigen::Vector3d> spring(history);
  const Eigen::Vector3d rolling = tangentialPart(c.relativeAngularVelocity, c.normal);
  const double cap = friction_ * c.rollingRadius * normalForce;
  const double kr = stiffness(c.rollingRadius);
  if (dt > 0.0) {
    keepInTangentPlane(spring, c.normal);
    spring += (kr * dt) * rolling;
    const double length = spring.norm();
    if (length > cap) spring *= cap / length;  // full mobilisation: the spring holds mu_r R_r F
  }
  // spring plus dashpot, capped as a whole: continuous at the cap (a dashpot switched off there
  // by comparing |M_r| with the cap would switch on round-off)
  Eigen::Vector3d torque = spring + (2.0 * damping_ * std::sqrt(c.rollingInertia * kr)) * rolling;
  const double magnitude = torque.norm();
  if (magnitude > cap) torque *= cap / magnitude;
  return torque;
}

}  // namespace spacetree::contact_model
