// The generic contact a contact model evaluates: whatever found it (two triangulated grains, a
// grain and a wall, a sphere and a triangle) describes it by these few numbers, so every contact
// kind calls the very same ContactModel.
//
// Conventions (those of contact/MeshContact.h): body i is the first body, j the second; the unit
// normal points from i towards j; `penetration` is the halo overlap per side, eps - d/2 > 0 for a
// contact (d: surface distance; eps: halo depth); relativeVelocity = v_j - v_i of the two bodies'
// material points at the contact point (rotation included), normalVelocity = its component along
// the normal (< 0 while the bodies approach).
//
// Masses of the contact point (what a force at the point along a direction accelerates, the
// bodies' rotation included): 1/m = sum over the two bodies of 1/m_b + (r_b x u) . I_b^-1
// (r_b x u), r_b the lever arm from body b's centre of mass to the point, u the direction; a
// fixed obstacle contributes 0, a body without rotation (inverseInertia 0) only 1/m_b.
// effectiveMass takes u = the normal, tangentialMass u = the sliding direction (the tangential
// part of relativeVelocity; without sliding the normal's value). For a contact whose normal
// passes through both centres (two spheres) effectiveMass = 1 / (1/m_i + 1/m_j), the classic
// effective mass; a grain touched off-centre is lighter there (a point at its bounding radius
// over a lever arm normal to the force: ~1/5 of its mass). The dashpots scale with these
// masses, so that each contact point has the damping ratio of its coefficients and a time step
// that resolves the spring resolves the dashpot (scaled by the centre-of-mass mass, a dashpot
// on a lever arm is several times overdamped and beyond the integrator's limit c dt / m < 2 at
// that step: resting grains then chatter on for ever, bench/resting_energy.cpp).
//
// Rolling: relativeAngularVelocity = omega_j - omega_i; its tangential part (normal component
// removed) is the relative rolling. rollingRadius R_r = R_i R_j / (R_i + R_j), R_b = |point -
// centre of b| the lever arm (a fixed obstacle contributes only the other body's). rollingInertia:
// what a pure couple about the rolling axis u (the unit tangential relative angular velocity)
// turns, 1/I_r = sum over the bodies of u . I_b^-1 u (about the centres: a rolling torque is a
// couple and the lightest mode it drives; 0 without rolling).
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
  double effectiveMass = 0.0;                                  // along the normal [kg]
  double tangentialMass = 0.0;                                 // along the sliding [kg]
  Eigen::Vector3d relativeAngularVelocity = Eigen::Vector3d::Zero();  // omega_j - omega_i [rad/s]
  double rollingRadius = 0.0;                                  // R_r [m]
  double rollingInertia = 0.0;                                 // I_r about the rolling axis [kg m^2]
};

// The tangential part of v (its component along the unit normal removed).
inline Eigen::Vector3d tangentialPart(const Eigen::Vector3d& v, const Eigen::Vector3d& normal) {
  return v - v.dot(normal) * normal;
}

// A history vector of a contact point (a spring's displacement or torque) turned into the
// current tangent plane: its normal component removed, its length kept (the contact plane of a
// rolling or tilting pair turns from step to step).
template <class Vector>
void keepInTangentPlane(Vector&& history, const Eigen::Vector3d& normal) {
  const double along = history.dot(normal);
  if (along == 0.0) return;
  const double length = history.norm();
  history -= along * normal;
  const double projected = history.norm();
  history *= projected > 0.0 ? length / projected : 0.0;
}

// 1/m of `body` for a force at `point` along the unit `direction` (the sum's term above).
double inverseMassAt(const dynamics::RigidBody& body, const Eigen::Vector3d& point,
                     const Eigen::Vector3d& direction);

// u . I^-1 u of `body` for the unit world `axis` (0 for a fixed body or rotation off).
double inverseInertiaAbout(const dynamics::RigidBody& body, const Eigen::Vector3d& axis);

// The contact of two rigid bodies at `point` (velocities of their material points there); the
// rolling fields (relativeAngularVelocity, rollingRadius, rollingInertia) only with `rolling`
// (a model with a rolling sub-model: the others need not pay for them), zero otherwise.
Contact makeContact(const dynamics::RigidBody& first, const dynamics::RigidBody& second,
                    const Eigen::Vector3d& point, const Eigen::Vector3d& normal, double penetration,
                    bool rolling = false);

}  // namespace spacetree::contact_model
