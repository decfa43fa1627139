#include "contact_model/Contact.h"

namespace spacetree::contact_model {

Contact makeContact(const dynamics::RigidBody& first, const dynamics::RigidBody& second,
                    const Eigen::Vector3d& point, const Eigen::Vector3d& normal, double penetration) {
  Contact c;
  c.point = point;
  c.normal = normal;
  c.penetration = penetration;
  c.relativeVelocity = second.velocityAt(point) - first.velocityAt(point);
  c.normalVelocity = c.relativeVelocity.dot(normal);
  const double inverseMasses = first.inverseMass + second.inverseMass;
  c.effectiveMass = inverseMasses > 0.0 ? 1.0 / inverseMasses : 0.0;
  return c;
}

}  // namespace spacetree::contact_model
