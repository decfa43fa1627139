#include "contact_model/TangentialViscous.h"

#include <algorithm>

namespace spacetree::contact_model {

TangentialViscous::TangentialViscous(const ContactParameters& p)
    : friction_(p.require("friction", "tangential viscous")),
      slidingDamping_(p.require("slidingDamping", "tangential viscous")) {}

Eigen::Vector3d TangentialViscous::forceOnFirst(const Contact& c, double normalForce, double*,
                                                double) const {
  const Eigen::Vector3d sliding = c.relativeVelocity - c.normalVelocity * c.normal;
  const double speed = sliding.norm();
  if (!(speed > 0.0)) return Eigen::Vector3d::Zero();
  const double magnitude = std::min(slidingDamping_ * speed, friction_ * normalForce);
  return (magnitude / speed) * sliding;
}

}  // namespace spacetree::contact_model
