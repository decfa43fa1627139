// Contact forces between rigid triangulated particles, paper eq. (1), one class per physical
// effect (LAMMPS granular style): the caller composes what the scene asks for, so a scene
// without friction never evaluates the friction model.
//
// Conventions (see contact/MeshContact.h): body i is the first body of a contact, j the
// second; the contact normal n^ (unit) points from i towards j; the penetration is
// eps - |n| = eps - d / 2 >= 0 (d: surface distance); v_ij = v_j - v_i is the relative
// velocity of the two bodies' material points at the contact point (rotation included);
// v_n = v_ij . n^ < 0 while the bodies approach.
//
// Normal force (NormalSpringDashpot), magnitude F >= 0, pushing i along -n^ and j along +n^:
//   F = S (eps - |n|) + 2 D sqrt(1 / (1/m_i + 1/m_j)) (-v_n)   while approaching (v_n < 0),
//   F = S (eps - |n|)                                           otherwise,
// i.e. the paper's spring plus "pseudo-elastic" damping that acts only during compression. The
// damping term is written with the sign that dissipates energy (the paper's sign follows its
// own orientation of v_ij); F is never attractive. For one contact point the overlap of the
// halos x = 2 eps - d obeys m_eff x'' = -(S/2) x - 2 D sqrt(m_eff) x' during approach and is
// undamped during separation: damping ratio zeta = D sqrt(2 / S), independent of the masses,
// and the coefficient of restitution is springDashpotRestitution(zeta) (derivation in
// docs/triangulated_particles_core.md). A body of infinite mass (inverseMass 0, a fixed
// obstacle) gives m_eff = m of the other body.
//
// Tangential force (CoulombFriction): viscous sliding friction capped by Coulomb's law,
//   f_t = min(gamma |v_t|, mu F) v_t / |v_t|  on body i (j gets -f_t), v_t = v_ij - v_n n^,
// so i is dragged along with j's sliding and the relative sliding is damped; no tangential
// spring and no history (the paper has none). The paper's f_|| = l_i x f_perp is the torque
// of the contact force about i's centre of mass: here applyContactForce() computes the torques
// of the total (normal + tangential) force from the lever arms l = contact point - centre.
#pragma once

#include <Eigen/Core>

#include "contact/MeshContact.h"
#include "dynamics/RigidBody.h"

namespace spacetree::dynamics {

struct ContactKinematics {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX();  // unit, i -> j
  double penetration = 0.0;                            // eps - |n|
  Eigen::Vector3d relativeVelocity = Eigen::Vector3d::Zero();  // v_j - v_i at the point
  double normalVelocity = 0.0;  // relativeVelocity . normal (< 0: approaching)
  double effectiveMass = 0.0;   // 1 / (1/m_i + 1/m_j); 0 when both are fixed
};

ContactKinematics contactKinematics(const RigidBody& first, const RigidBody& second,
                                    const contact::ContactPoint& contact);

class NormalSpringDashpot {
 public:
  // spring S [N/m] > 0, damping D [sqrt(N/m) = sqrt(kg)/s] >= 0; std::invalid_argument else.
  NormalSpringDashpot(double spring, double damping);
  double spring() const { return spring_; }
  double damping() const { return damping_; }

  // F >= 0 as defined above.
  double normalForce(const ContactKinematics& k) const;
  // Force on the first body: -F n^.
  Eigen::Vector3d forceOnFirst(const ContactKinematics& k) const { return -normalForce(k) * k.normal; }

  // zeta = D sqrt(2 / S) (one contact point, see above).
  double dampingRatio() const;
  // D giving the restitution e in (0, 1] for spring S (inverse of springDashpotRestitution).
  static double dampingForRestitution(double spring, double restitution);

 private:
  double spring_, damping_;
};

// Coefficient of restitution of the approach-damped linear spring with damping ratio zeta >= 0:
//   zeta < 1: exp(-zeta / sqrt(1 - zeta^2) * atan(sqrt(1 - zeta^2) / zeta)),
//   zeta = 1: exp(-1),  zeta > 1: exp(-zeta / sqrt(zeta^2 - 1) * atanh(sqrt(zeta^2 - 1) / zeta)).
double springDashpotRestitution(double zeta);

class CoulombFriction {
 public:
  // mu >= 0 (Coulomb coefficient), gamma >= 0 [N s/m] (viscous sliding coefficient).
  CoulombFriction(double coefficient, double viscousDamping);
  // Tangential force on the first body for a normal force magnitude F.
  Eigen::Vector3d forceOnFirst(const ContactKinematics& k, double normalForce) const;

 private:
  double coefficient_, viscousDamping_;
};

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
