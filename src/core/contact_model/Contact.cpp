#include "contact_model/Contact.h"

namespace spacetree::contact_model {

double inverseMassAt(const dynamics::RigidBody& body, const Eigen::Vector3d& point,
                     const Eigen::Vector3d& direction) {
  if (body.inverseInertia.squaredNorm() == 0.0) return body.inverseMass;
  // (r x u) . R diag(1/I) R^T (r x u), in the body frame
  const Eigen::Vector3d arm = body.orientation.conjugate() * (point - body.position).cross(direction);
  return body.inverseMass + arm.dot(body.inverseInertia.cwiseProduct(arm));
}

double inverseInertiaAbout(const dynamics::RigidBody& body, const Eigen::Vector3d& axis) {
  const Eigen::Vector3d local = body.orientation.conjugate() * axis;
  return local.dot(body.inverseInertia.cwiseProduct(local));
}

Contact makeContact(const dynamics::RigidBody& first, const dynamics::RigidBody& second,
                    const Eigen::Vector3d& point, const Eigen::Vector3d& normal, double penetration,
                    bool rolling) {
  Contact c;
  c.point = point;
  c.normal = normal;
  c.penetration = penetration;
  c.relativeVelocity = second.velocityAt(point) - first.velocityAt(point);
  c.normalVelocity = c.relativeVelocity.dot(normal);
  const Eigen::Vector3d sliding = c.relativeVelocity - c.normalVelocity * normal;
  const double slidingNorm = sliding.norm();
  const double inverseNormal = inverseMassAt(first, point, normal) + inverseMassAt(second, point, normal);
  c.effectiveMass = inverseNormal > 0.0 ? 1.0 / inverseNormal : 0.0;
  c.tangentialMass = c.effectiveMass;
  if (slidingNorm > 0.0) {
    const Eigen::Vector3d t = sliding / slidingNorm;
    const double inverseTangential = inverseMassAt(first, point, t) + inverseMassAt(second, point, t);
    c.tangentialMass = inverseTangential > 0.0 ? 1.0 / inverseTangential : 0.0;
  }
  if (!rolling) return c;
  c.relativeAngularVelocity = second.angularVelocity() - first.angularVelocity();
  const double armFirst = first.isFixed() ? 0.0 : (point - first.position).norm();
  const double armSecond = second.isFixed() ? 0.0 : (point - second.position).norm();
  c.rollingRadius = armFirst > 0.0 && armSecond > 0.0 ? armFirst * armSecond / (armFirst + armSecond)
                                                      : armFirst + armSecond;
  const Eigen::Vector3d turning = tangentialPart(c.relativeAngularVelocity, normal);
  const double turningNorm = turning.norm();
  if (turningNorm > 0.0) {
    const Eigen::Vector3d u = turning / turningNorm;
    const double inverseRolling = inverseInertiaAbout(first, u) + inverseInertiaAbout(second, u);
    c.rollingInertia = inverseRolling > 0.0 ? 1.0 / inverseRolling : 0.0;
  }
  return c;
}

}  // namespace spacetree::contact_model
