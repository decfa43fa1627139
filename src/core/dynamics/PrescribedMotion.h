// Prescribed rigid motion of an obstacle (a rotating drum, a moving plate, a mixer blade): a
// rotation at constant angular velocity about an axis through a point that itself translates at
// constant velocity, as LIGGGHTS' fix move/mesh offers with `rotate` and `linear`.
//
// The pose is evaluated from the elapsed time t, never integrated, so that it does not drift
// over long runs: with the start pose (p0, q0) and o(t) = origin + v t,
//   R(t) = rotation by omega t about axis,   p(t) = o(t) + R(t) (p0 - origin),   q(t) = R(t) q0,
// the velocity of the material point at x is v + w x (x - o(t)) with w = omega axis.
// The angle omega t is reduced modulo 2 pi in full turns before the rotation is built (the
// reduction is exact in floating point; only omega t itself is rounded).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace spacetree::dynamics {

struct PrescribedMotion {
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  // translation (of the axis point too)
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();    // a point of the rotation axis at t = 0
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();     // unit
  double angularSpeed = 0.0;                           // rad/s, right-handed about axis

  // Throws std::invalid_argument for a non-finite field or a zero axis; normalises the axis.
  static PrescribedMotion make(const Eigen::Vector3d& velocity, const Eigen::Vector3d& origin,
                               const Eigen::Vector3d& axis, double angularSpeed);

  Eigen::Vector3d angularVelocity() const { return angularSpeed * axis; }
  // The rotation angle at time t in [0, 2 pi) (omega t reduced by full turns).
  double angleAt(double t) const;
  Eigen::Quaterniond rotationAt(double t) const;
  // Pose at time t of a body whose pose at t = 0 was (startPosition, startOrientation).
  void poseAt(const Eigen::Vector3d& startPosition, const Eigen::Quaterniond& startOrientation,
              double t, Eigen::Vector3d& position, Eigen::Quaterniond& orientation) const;
  // Velocity at time t of the material point now at x.
  Eigen::Vector3d velocityAt(const Eigen::Vector3d& x, double t) const;
};

}  // namespace spacetree::dynamics
