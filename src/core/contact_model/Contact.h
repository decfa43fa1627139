// The generic contact a contact model evaluates: whatever found it (two triangulated grains, a
// grain and a wall, a sphere and a triangle) describes it by these few numbers, so every contact
// kind calls the very same ContactModel.
//
// Conventions (those of contact/MeshContact.h): body i is the first body, j the second; the unit
// normal points from i towards j; `penetration` is the halo overlap per side, eps - d/2 > 0 for a
// contact (d: surface distance; eps: halo depth); relativeVelocity = v_j - v_i of the two bodies'
// material points at the contact point (rotation included), normalVelocity = its component along
// the normal (< 0 while the bodies approach); effectiveMass = 1 / (1/m_i + 1/m_j), the mass of
// the other body for a fixed obstacle (inverse mass 0), 0 when both are fixed.
#pragma once

#include <Eigen/Core>

#include "dynamics/RigidBody.h"

namespace spacetree::contact_model {

struct Contact {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();             // world frame
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX();           // unit, i -> j
  double penetration = 0.0;                                    // eps - d/2 [m]
  Eigen::Vector3d relativeVelocity = Eigen::Vector3d::Zero();  // v_j - v_i at the point [m/s]
  double normalVelocity = 0.0;                                 // relativeVelocity . normal
  double effectiveMass = 0.0;                                  // [kg]
};

// The contact of two rigid bodies at `point` (velocities of their material points there).
Contact makeContact(const dynamics::RigidBody& first, const dynamics::RigidBody& second,
                    const Eigen::Vector3d& point, const Eigen::Vector3d& normal, double penetration);

}  // namespace spacetree::contact_model
