// Adding a contact force to two rigid bodies: the force on the first body at the contact point
// and its opposite on the second, with the torques about their centres of mass (the paper's
// f_|| = l_i x f_perp: lever arm l = contact point - centre). The force itself comes from the
// contact model (contact_model/ContactModel.h).
#pragma once

#include <Eigen/Core>

#include "dynamics/RigidBody.h"

namespace spacetree::dynamics {

// Accumulated force and torque (about the centre of mass, world frame) of one body.
struct BodyLoad {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();
};

// Adds forceOnFirst at `point` to the first body and its opposite to the second, with the
// torques (point - centre of mass) x force.
void applyContactForce(const RigidBody& first, const RigidBody& second,
                       const Eigen::Vector3d& point, const Eigen::Vector3d& forceOnFirst,
                       BodyLoad& firstLoad, BodyLoad& secondLoad);

}  // namespace spacetree::dynamics
