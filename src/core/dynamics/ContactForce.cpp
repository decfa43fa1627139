#include "dynamics/ContactForce.h"

namespace spacetree::dynamics {

void applyContactForce(const RigidBody& first, const RigidBody& second,
                       const Eigen::Vector3d& point, const Eigen::Vector3d& forceOnFirst,
                       BodyLoad& firstLoad, BodyLoad& secondLoad) {
  firstLoad.force += forceOnFirst;
  firstLoad.torque += (point - first.position).cross(forceOnFirst);
  secondLoad.force -= forceOnFirst;
  secondLoad.torque -= (point - second.position).cross(forceOnFirst);
}

}  // namespace spacetree::dynamics
