#include "dynamics/PrescribedMotion.h"

#include <cmath>
#include <stdexcept>

namespace spacetree::dynamics {

PrescribedMotion PrescribedMotion::make(const Eigen::Vector3d& velocity,
                                        const Eigen::Vector3d& origin,
                                        const Eigen::Vector3d& axis, double angularSpeed) {
  if (!velocity.allFinite() || !origin.allFinite() || !axis.allFinite() ||
      !std::isfinite(angularSpeed))
    throw std::invalid_argument("PrescribedMotion: velocity, origin, axis and angular speed must be finite");
  if (!(axis.norm() > 0.0)) throw std::invalid_argument("PrescribedMotion: the axis must not be zero");
  PrescribedMotion m;
  m.velocity = velocity;
  m.origin = origin;
  m.axis = axis.normalized();
  m.angularSpeed = angularSpeed;
  return m;
}

double PrescribedMotion::angleAt(double t) const {
  const double turns = angularSpeed * t / (2.0 * M_PI);
  return 2.0 * M_PI * (turns - std::floor(turns));
}

Eigen::Quaterniond PrescribedMotion::rotationAt(double t) const {
  return Eigen::Quaterniond(Eigen::AngleAxisd(angleAt(t), axis));
}

void PrescribedMotion::poseAt(const Eigen::Vector3d& startPosition,
                              const Eigen::Quaterniond& startOrientation, double t,
                              Eigen::Vector3d& position, Eigen::Quaterniond& orientation) const {
  const Eigen::Quaterniond r = rotationAt(t);
  position = origin + velocity * t + r * (startPosition - origin);
  orientation = (r * startOrientation).normalized();
}

Eigen::Vector3d PrescribedMotion::velocityAt(const Eigen::Vector3d& x, double t) const {
  return velocity + angularVelocity().cross(x - (origin + velocity * t));
}

}  // namespace spacetree::dynamics
