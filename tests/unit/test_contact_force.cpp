// Contact force models of eq. (1): spring-dashpot with damping only while approaching,
// Coulomb-capped friction, lever-arm torques, fixed bodies, and the closed-form restitution
// against a direct integration of the one-contact equation of motion.
#include <gtest/gtest.h>

#include <cmath>

#include "dynamics/ContactForce.h"

using namespace spacetree;
using namespace spacetree::dynamics;
using Eigen::Vector3d;

namespace {

contact::ContactPoint contactAt(const Vector3d& point, const Vector3d& normal, double penetration) {
  contact::ContactPoint c;
  c.point = point;
  c.normal = normal.normalized();
  c.penetration = penetration;
  return c;
}

TEST(ContactForce, KinematicsIncludeRotationAndEffectiveMass) {
  RigidBody a = RigidBody::free(2.0, Vector3d(1, 1, 1));
  RigidBody b = RigidBody::free(6.0, Vector3d(1, 1, 1), Vector3d(1, 0, 0));
  a.velocity = Vector3d(1, 0, 0);
  b.setAngularVelocity(Vector3d(0, 0, 2));  // point (0.5, 0, 0) of b moves at (0, -1, 0)
  const ContactKinematics k = contactKinematics(a, b, contactAt(Vector3d(0.5, 0, 0), Vector3d::UnitX(), 0.1));
  EXPECT_LT((k.relativeVelocity - Vector3d(-1, -1, 0)).norm(), 1e-15);
  EXPECT_DOUBLE_EQ(k.normalVelocity, -1.0);
  EXPECT_DOUBLE_EQ(k.effectiveMass, 1.5);
  const RigidBody floor = RigidBody::fixed();
  EXPECT_DOUBLE_EQ(contactKinematics(a, floor, contactAt(Vector3d::Zero(), Vector3d::UnitZ(), 0.1)).effectiveMass, 2.0);
}

TEST(ContactForce, SpringAlwaysDampingOnlyWhileApproaching) {
  const NormalSpringDashpot model(1e4, 30.0);
  ContactKinematics k;
  k.normal = Vector3d::UnitZ();
  k.penetration = 1e-3;
  k.effectiveMass = 0.25;
  k.normalVelocity = 0.0;
  EXPECT_DOUBLE_EQ(model.normalForce(k), 10.0);
  k.normalVelocity = -0.2;  // approaching: + 2 D sqrt(m) 0.2 = 6
  EXPECT_DOUBLE_EQ(model.normalForce(k), 16.0);
  k.normalVelocity = +0.2;  // separating: spring only
  EXPECT_DOUBLE_EQ(model.normalForce(k), 10.0);
  EXPECT_LT((model.forceOnFirst(k) - Vector3d(0, 0, -10)).norm(), 1e-15);  // pushes i away from j
  k.penetration = 0.0;
  EXPECT_EQ(model.normalForce(k), 0.0);  // never attractive
  EXPECT_THROW(NormalSpringDashpot(0.0, 1.0), std::invalid_argument);
  EXPECT_THROW(NormalSpringDashpot(1.0, -1.0), std::invalid_argument);
}

TEST(ContactForce, FrictionIsViscousUpToTheCoulombCap) {
  const CoulombFriction friction(0.5, 2.0);
  ContactKinematics k;
  k.normal = Vector3d::UnitZ();
  k.relativeVelocity = Vector3d(0.3, -0.4, -7.0);  // sliding 0.5 along (0.6, -0.8, 0)
  k.normalVelocity = -7.0;
  // Viscous: 2 * 0.5 = 1 < 0.5 * 10.
  EXPECT_LT((friction.forceOnFirst(k, 10.0) - Vector3d(0.6, -0.8, 0.0)).norm(), 1e-15);
  // Capped: 0.5 * 1 = 0.5.
  EXPECT_LT((friction.forceOnFirst(k, 1.0) - Vector3d(0.3, -0.4, 0.0)).norm(), 1e-15);
  k.relativeVelocity = Vector3d(0, 0, -7.0);
  EXPECT_EQ(friction.forceOnFirst(k, 10.0), Vector3d::Zero());
}

TEST(ContactForce, LeverArmTorquesAndNewtonsThirdLaw) {
  RigidBody a = RigidBody::free(1.0, Vector3d(1, 1, 1), Vector3d(0, 0, 0));
  RigidBody b = RigidBody::free(1.0, Vector3d(1, 1, 1), Vector3d(2, 1, 0));
  BodyLoad la, lb;
  const Vector3d point(1, 0.5, 0.25), force(-3, 0.5, 1);
  applyContactForce(a, b, point, force, la, lb);
  EXPECT_EQ(la.force, force);
  EXPECT_EQ(lb.force, -force);
  EXPECT_LT((la.torque - point.cross(force)).norm(), 1e-15);
  EXPECT_LT((lb.torque - (point - b.position).cross(-force)).norm(), 1e-15);
  // Total angular momentum about the origin is conserved: sum of r_c x F + tau = 0.
  const Vector3d total = la.torque + lb.torque + a.position.cross(la.force) + b.position.cross(lb.force);
  EXPECT_LT(total.norm(), 1e-14);
}

// Direct integration of m x'' = -(S/2) x - 2 D sqrt(m) x' (approach), -(S/2) x (separation).
double integratedRestitution(double spring, double damping, double mass) {
  const double omega = std::sqrt(spring / (2 * mass));
  const double dt = 1e-4 / omega;
  double x = 0.0, v = 1.0;
  while (x >= 0.0) {
    const double a = (-(spring / 2) * x - (v > 0 ? 2 * damping * std::sqrt(mass) * v : 0.0)) / mass;
    // velocity Verlet-like midpoint step (damping explicit): fine at 1e-4 / omega
    const double vHalf = v + 0.5 * dt * a;
    x += dt * vHalf;
    const double a2 = (-(spring / 2) * x - (vHalf > 0 ? 2 * damping * std::sqrt(mass) * vHalf : 0.0)) / mass;
    v = vHalf + 0.5 * dt * a2;
  }
  return -v;
}

TEST(ContactForce, ClosedFormRestitutionMatchesIntegration) {
  EXPECT_EQ(springDashpotRestitution(0.0), 1.0);
  for (double zeta : {0.05, 0.3, 0.7, 1.0, 1.5}) {
    const double spring = 2e5, mass = 0.37;
    const double damping = zeta * std::sqrt(spring / 2.0);
    EXPECT_NEAR(NormalSpringDashpot(spring, damping).dampingRatio(), zeta, 1e-14);
    EXPECT_NEAR(integratedRestitution(spring, damping, mass), springDashpotRestitution(zeta), 2e-4) << zeta;
    EXPECT_NEAR(springDashpotRestitution(
                    NormalSpringDashpot::dampingForRestitution(spring, springDashpotRestitution(zeta)) *
                    std::sqrt(2.0 / spring)),
                springDashpotRestitution(zeta), 1e-12);
  }
  // Monotone decreasing.
  EXPECT_GT(springDashpotRestitution(0.2), springDashpotRestitution(0.4));
  EXPECT_GT(springDashpotRestitution(0.99), springDashpotRestitution(1.01));
}

}  // namespace
