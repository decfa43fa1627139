// State and time stepping of one rigid particle: pose (centre-of-mass position, unit
// quaternion body -> world), linear velocity, and angular momentum in the world frame with a
// diagonal (principal-axes) inertia tensor in the body frame (geometry::RigidShape gives the
// principal moments). A body of infinite mass (inverseMass = 0, inverseInertia = 0) is a fixed
// obstacle: forces and torques do not move it (it may still move with a prescribed velocity
// and angular velocity: a moving obstacle, PrescribedMotion.h).
//
// Time stepping is split so that callers compose their integrator (e.g. symplectic Euler
// kick(F, tau, dt) then drift(dt), or velocity Verlet kick(dt/2) drift(dt) kick(dt/2)):
//   - kick: v += F / m dt, L += tau dt (world frame);
//   - drift: x += v dt, and the torque-free rotation over dt by the symmetric splitting of the
//     kinetic energy T = sum_k Lb_k^2 / (2 I_k) into its three body-axis parts (Dullweber,
//     Reich and Leimkuhler 1997, "symplectic splitting"): rotations about body axes 1, 2, 3, 2, 1
//     by the angles Lb_k / I_k * (dt/2, dt/2, dt, dt/2, dt/2), each an exact rotation
//     (quaternion product with a unit quaternion). Its properties, all tested:
//       * |L| and L itself (world frame) are conserved exactly (L is not touched; the body-frame
//         components are only rotated);
//       * symplectic and time-reversible, second order: the kinetic energy error stays bounded
//         (no drift) over millions of steps;
//       * rotation about a principal axis is exact (a single sub-rotation);
//       * |q| stays 1: each step multiplies by unit quaternions and renormalises (a division,
//         no projection error to speak of), so the norm does not drift.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace spacetree::dynamics {

struct RigidBody {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();   // centre of mass, world frame
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  // body -> world, unit
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();   // of the centre of mass
  Eigen::Vector3d angularMomentum = Eigen::Vector3d::Zero();  // world frame, about the c.o.m.
  double inverseMass = 0.0;                              // 0: infinite mass
  Eigen::Vector3d inverseInertia = Eigen::Vector3d::Zero();  // 1 / principal moments (body)
  // Angular velocity (world frame) of a body of infinite mass, prescribed rather than from L.
  Eigen::Vector3d prescribedAngularVelocity = Eigen::Vector3d::Zero();

  // A free body of the given mass and principal moments (both > 0; std::invalid_argument
  // otherwise), at rest.
  static RigidBody free(double mass, const Eigen::Vector3d& principalInertia,
                        const Eigen::Vector3d& position = Eigen::Vector3d::Zero(),
                        const Eigen::Quaterniond& orientation = Eigen::Quaterniond::Identity());
  // A fixed obstacle (infinite mass and inertia).
  static RigidBody fixed(const Eigen::Vector3d& position = Eigen::Vector3d::Zero(),
                         const Eigen::Quaterniond& orientation = Eigen::Quaterniond::Identity());

  bool isFixed() const { return inverseMass == 0.0; }
  double mass() const;  // infinity when fixed
  Eigen::Vector3d principalInertia() const;  // infinity per axis where inverseInertia is 0

  Eigen::Matrix3d rotation() const { return orientation.toRotationMatrix(); }
  Eigen::Vector3d toWorld(const Eigen::Vector3d& bodyPoint) const {
    return orientation * bodyPoint + position;
  }
  // omega = R diag(1/I) R^T L (world frame); prescribedAngularVelocity for a fixed body.
  Eigen::Vector3d angularVelocity() const;
  // Inverse inertia tensor in the world frame: R diag(1/I) R^T.
  Eigen::Matrix3d inverseInertiaWorld() const;
  // Velocity of the body's material point at worldPoint: v + omega x (worldPoint - position).
  Eigen::Vector3d velocityAt(const Eigen::Vector3d& worldPoint) const;
  // 1/2 m |v|^2 + 1/2 L . omega (finite parts only: 0 for a fixed body).
  double translationalEnergy() const;
  double rotationalEnergy() const;
  double kineticEnergy() const { return translationalEnergy() + rotationalEnergy(); }
  // Sets L so that the angular velocity becomes omega (world frame).
  void setAngularVelocity(const Eigen::Vector3d& omega);

  // v += F / m dt and L += tau dt (nothing for a fixed body's infinite parts).
  void kick(const Eigen::Vector3d& force, const Eigen::Vector3d& torque, double dt);
  // x += v dt and rotateFreely(dt).
  void drift(double dt);
  // Torque-free rotation over dt (the splitting described above).
  void rotateFreely(double dt);
};

}  // namespace spacetree::dynamics
