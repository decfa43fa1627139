// Rigid-body state and stepping: exact rotation about a principal axis, the free asymmetric
// top (second-order convergence to an RK4 reference of Euler's equations, bounded energy
// error without drift and |q| = 1 over 10^6 steps, conserved angular momentum), kicks, fixed
// bodies.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>

#include "dynamics/RigidBody.h"

using namespace spacetree::dynamics;
using Eigen::Quaterniond;
using Eigen::Vector3d;

namespace {

double rotationDistance(const Quaterniond& a, const Quaterniond& b) {
  return a.angularDistance(b);
}

// RK4 on Euler's equations in the body frame, dLb/dt = Lb x (Lb ./ I), and
// dq/dt = q * (0, omega_b) / 2, with a tiny step: the reference solution.
Quaterniond referenceOrientation(Quaterniond q, Vector3d lb, const Vector3d& inertia, double t,
                                 int steps) {
  const double h = t / steps;
  using State = Eigen::Matrix<double, 7, 1>;
  const auto rate = [&](const State& s) {
    const Vector3d l = s.head<3>();
    const Vector3d w = l.cwiseQuotient(inertia);
    const Quaterniond qq(s[3], s[4], s[5], s[6]);
    const Quaterniond dq = qq * Quaterniond(0.0, w.x(), w.y(), w.z());
    State r;
    r.head<3>() = l.cross(w);
    r[3] = 0.5 * dq.w();
    r.tail<3>() = 0.5 * dq.vec();
    return r;
  };
  State s;
  s << lb, q.w(), q.x(), q.y(), q.z();
  for (int i = 0; i < steps; ++i) {
    const State k1 = rate(s), k2 = rate(s + 0.5 * h * k1), k3 = rate(s + 0.5 * h * k2),
                k4 = rate(s + h * k3);
    s += h / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4);
  }
  return Quaterniond(s[3], s[4], s[5], s[6]).normalized();
}

const Vector3d kInertia(0.7, 1.3, 2.1);  // asymmetric top

RigidBody asymmetricTop() {
  RigidBody body = RigidBody::free(2.5, kInertia, Vector3d(1, 2, 3),
                                   Quaterniond(Eigen::AngleAxisd(0.4, Vector3d(1, -1, 2).normalized())));
  body.angularMomentum = Vector3d(0.9, -1.7, 1.1);
  return body;
}

TEST(RigidBody, RotationAboutAPrincipalAxisIsExact) {
  const Quaterniond start(Eigen::AngleAxisd(1.0, Vector3d(0.2, 0.3, -1).normalized()));
  RigidBody body = RigidBody::free(1.0, kInertia, Vector3d::Zero(), start);
  const double omega = 3.7;
  // About body axis 3 (largest moment; axis 2 would be unstable: rounding grows like
  // exp(2 t) there, as for any method).
  body.setAngularVelocity(start * Vector3d(0, 0, omega));
  const double dt = 0.01;
  const int steps = 1000;
  for (int i = 0; i < steps; ++i) body.drift(dt);
  const Quaterniond expected = start * Quaterniond(Eigen::AngleAxisd(omega * dt * steps, Vector3d::UnitZ()));
  EXPECT_LT(rotationDistance(body.orientation, expected), 1e-11);
  EXPECT_LT((body.angularVelocity() - start * Vector3d(0, 0, omega)).norm(), 1e-12);
}

TEST(RigidBody, FreeAsymmetricTopConvergesAtSecondOrder) {
  const RigidBody start = asymmetricTop();
  const double t = 2.0;
  const Quaterniond reference =
      referenceOrientation(start.orientation, start.orientation.conjugate() * start.angularMomentum,
                           kInertia, t, 200000);
  double previous = 0.0;
  for (int steps : {200, 400, 800}) {
    RigidBody body = start;
    for (int i = 0; i < steps; ++i) body.drift(t / steps);
    const double error = rotationDistance(body.orientation, reference);
    if (previous > 0.0) {
      EXPECT_GT(previous / error, 3.5) << steps;  // 4 for second order
      EXPECT_LT(previous / error, 4.5) << steps;
    }
    previous = error;
  }
  EXPECT_LT(previous, 1e-4);
}

TEST(RigidBody, FreeTopMillionStepsEnergyBoundedAndQuaternionNormExact) {
  RigidBody body = asymmetricTop();
  const Vector3d momentum = body.angularMomentum;
  const double energy = body.rotationalEnergy();
  const int steps = 1000000;
  const double dt = 2e-3;  // about 1/1000 of the fastest rotation period
  double earlyError = 0.0, lateError = 0.0, normError = 0.0;
  for (int i = 0; i < steps; ++i) {
    body.drift(dt);
    if (i % 97 == 0) {
      const double error = std::abs(body.rotationalEnergy() - energy) / energy;
      if (i < steps / 10) earlyError = std::max(earlyError, error);
      if (i >= steps - steps / 10) lateError = std::max(lateError, error);
      normError = std::max(normError, std::abs(body.orientation.norm() - 1.0));
    }
  }
  // Bounded and not drifting: the late error band is no wider than the early one (a drifting
  // method, e.g. explicit Euler on q with renormalisation, grows by orders of magnitude).
  EXPECT_LT(earlyError, 1e-5);
  EXPECT_LT(lateError, 1.5 * earlyError);
  EXPECT_LT(normError, 1e-15);
  EXPECT_EQ(body.angularMomentum, momentum);  // world-frame L untouched by free rotation
  EXPECT_NEAR(body.position.x(), 1.0, 0.0);    // no velocity, no motion
}

TEST(RigidBody, KickDriftAndVelocities) {
  RigidBody body = RigidBody::free(2.0, Vector3d(1, 2, 3));
  body.kick(Vector3d(4, 0, 0), Vector3d(0, 0, 6), 0.5);
  EXPECT_LT((body.velocity - Vector3d(1, 0, 0)).norm(), 1e-15);
  EXPECT_LT((body.angularVelocity() - Vector3d(0, 0, 1)).norm(), 1e-15);  // L = 3, I3 = 3
  EXPECT_NEAR(body.kineticEnergy(), 0.5 * 2 * 1 + 0.5 * 3 * 1, 1e-15);
  EXPECT_LT((body.velocityAt(Vector3d(0, 1, 0)) - Vector3d(0, 0, 0)).norm(), 1e-15);  // 1 - 1
  EXPECT_LT((body.velocityAt(Vector3d(1, 0, 0)) - Vector3d(1, 1, 0)).norm(), 1e-15);
  body.drift(0.25);
  EXPECT_LT((body.position - Vector3d(0.25, 0, 0)).norm(), 1e-15);
  EXPECT_LT(rotationDistance(body.orientation, Quaterniond(Eigen::AngleAxisd(0.25, Vector3d::UnitZ()))), 1e-15);
  EXPECT_LT((body.inverseInertiaWorld() * body.angularMomentum - body.angularVelocity()).norm(), 1e-15);
}

TEST(RigidBody, FixedBodyIgnoresForcesAndTorques) {
  RigidBody floor = RigidBody::fixed(Vector3d(0, 0, -1));
  EXPECT_TRUE(floor.isFixed());
  EXPECT_TRUE(std::isinf(floor.mass()));
  floor.kick(Vector3d(1e9, 0, 0), Vector3d(0, 1e9, 0), 1.0);
  floor.drift(1.0);
  EXPECT_EQ(floor.position, Vector3d(0, 0, -1));
  EXPECT_EQ(floor.angularVelocity(), Vector3d::Zero());
  EXPECT_EQ(floor.kineticEnergy(), 0.0);
  EXPECT_THROW(RigidBody::free(0.0, Vector3d(1, 1, 1)), std::invalid_argument);
  EXPECT_THROW(RigidBody::free(1.0, Vector3d(1, -1, 1)), std::invalid_argument);
}

}  // namespace
