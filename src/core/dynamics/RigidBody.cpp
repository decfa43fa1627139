#include "dynamics/RigidBody.h"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace spacetree::dynamics {
namespace {

double reciprocalOrInfinity(double x) {
  return x > 0.0 ? 1.0 / x : std::numeric_limits<double>::infinity();
}

}  // namespace

RigidBody RigidBody::free(double mass, const Eigen::Vector3d& principalInertia,
                          const Eigen::Vector3d& position, const Eigen::Quaterniond& orientation) {
  if (!(mass > 0.0) || !(principalInertia.minCoeff() > 0.0) || !std::isfinite(mass) ||
      !principalInertia.allFinite())
    throw std::invalid_argument("RigidBody::free: mass and principal moments must be finite and > 0");
  RigidBody body;
  body.position = position;
  body.orientation = orientation.normalized();
  body.inverseMass = 1.0 / mass;
  body.inverseInertia = principalInertia.cwiseInverse();
  return body;
}

RigidBody RigidBody::fixed(const Eigen::Vector3d& position, const Eigen::Quaterniond& orientation) {
  RigidBody body;
  body.position = position;
  body.orientation = orientation.normalized();
  return body;
}

double RigidBody::mass() const { return reciprocalOrInfinity(inverseMass); }

Eigen::Vector3d RigidBody::principalInertia() const {
  return {reciprocalOrInfinity(inverseInertia.x()), reciprocalOrInfinity(inverseInertia.y()),
          reciprocalOrInfinity(inverseInertia.z())};
}

Eigen::Vector3d RigidBody::angularVelocity() const {
  if (isFixed()) return prescribedAngularVelocity;
  const Eigen::Vector3d bodyMomentum = orientation.conjugate() * angularMomentum;
  return orientation * inverseInertia.cwiseProduct(bodyMomentum);
}

Eigen::Matrix3d RigidBody::inverseInertiaWorld() const {
  const Eigen::Matrix3d r = rotation();
  return r * inverseInertia.asDiagonal() * r.transpose();
}

Eigen::Vector3d RigidBody::velocityAt(const Eigen::Vector3d& worldPoint) const {
  return velocity + angularVelocity().cross(worldPoint - position);
}

double RigidBody::translationalEnergy() const {
  return inverseMass > 0.0 ? 0.5 * velocity.squaredNorm() / inverseMass : 0.0;
}

double RigidBody::rotationalEnergy() const {
  return 0.5 * angularMomentum.dot(angularVelocity());
}

void RigidBody::setAngularVelocity(const Eigen::Vector3d& omega) {
  const Eigen::Vector3d bodyOmega = orientation.conjugate() * omega;
  Eigen::Vector3d bodyMomentum;
  for (int k = 0; k < 3; ++k)
    bodyMomentum[k] = inverseInertia[k] > 0.0 ? bodyOmega[k] / inverseInertia[k] : 0.0;
  angularMomentum = orientation * bodyMomentum;
}

void RigidBody::kick(const Eigen::Vector3d& force, const Eigen::Vector3d& torque, double dt) {
  velocity += (inverseMass * dt) * force;
  if (inverseInertia.squaredNorm() > 0.0) angularMomentum += dt * torque;
}

void RigidBody::drift(double dt) {
  position += dt * velocity;
  rotateFreely(dt);
}

void RigidBody::rotateFreely(double dt) {
  if (inverseInertia.squaredNorm() == 0.0) return;
  Eigen::Vector3d bodyMomentum = orientation.conjugate() * angularMomentum;
  // Sub-flow k over time h: the body turns by theta = Lb_k h / I_k about its axis k, so that
  // q <- q * exp(theta/2 e_k) and, L being fixed in the world, Lb <- rot(-theta, e_k) Lb.
  const auto subRotation = [&](int k, double h) {
    const double theta = bodyMomentum[k] * inverseInertia[k] * h;
    const double c = std::cos(0.5 * theta), s = std::sin(0.5 * theta);
    Eigen::Quaterniond turn(c, 0.0, 0.0, 0.0);
    turn.vec()[k] = s;
    orientation = orientation * turn;
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const double ct = std::cos(theta), st = std::sin(theta);
    const double li = bodyMomentum[i], lj = bodyMomentum[j];
    bodyMomentum[i] = ct * li + st * lj;
    bodyMomentum[j] = -st * li + ct * lj;
  };
  subRotation(0, 0.5 * dt);
  subRotation(1, 0.5 * dt);
  subRotation(2, dt);
  subRotation(1, 0.5 * dt);
  subRotation(0, 0.5 * dt);
  orientation.normalize();
}

}  // namespace spacetree::dynamics
