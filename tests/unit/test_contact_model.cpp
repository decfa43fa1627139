// The contact model composed from sub-models (contact_model/): the generic contact's kinematics,
// the halo spring with damping only while approaching (paper eq. (1)), Coulomb-capped viscous
// friction, the registry (unknown keywords, missing or negative coefficients, only named slots
// built), per-type-pair tables, lever-arm torques, and the closed-form restitution against a
// direct integration of the one-contact equation of motion.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "contact_model/ContactModel.h"
#include "contact_model/DampingApproach.h"
#include "contact_model/SubModelRegistry.h"
#include "dynamics/ContactForce.h"

using namespace spacetree;
using namespace spacetree::contact_model;
using namespace spacetree::dynamics;
using Eigen::Vector3d;

namespace {

ContactParameters eq1(double spring, double damping) {
  ContactParameters p;
  p.set("stiffness", spring);
  p.set("damping", damping);
  return p;
}

TEST(ContactModel, KinematicsIncludeRotationAndEffectiveMass) {
  RigidBody a = RigidBody::free(2.0, Vector3d(1, 1, 1));
  RigidBody b = RigidBody::free(6.0, Vector3d(1, 1, 1), Vector3d(1, 0, 0));
  a.velocity = Vector3d(1, 0, 0);
  b.setAngularVelocity(Vector3d(0, 0, 2));  // point (0.5, 0, 0) of b moves at (0, -1, 0)
  const Contact k = makeContact(a, b, Vector3d(0.5, 0, 0), Vector3d::UnitX(), 0.1);
  EXPECT_LT((k.relativeVelocity - Vector3d(-1, -1, 0)).norm(), 1e-15);
  EXPECT_DOUBLE_EQ(k.normalVelocity, -1.0);
  EXPECT_DOUBLE_EQ(k.effectiveMass, 1.5);
  EXPECT_DOUBLE_EQ(k.penetration, 0.1);
  const RigidBody floor = RigidBody::fixed();
  EXPECT_DOUBLE_EQ(makeContact(a, floor, Vector3d::Zero(), Vector3d::UnitZ(), 0.1).effectiveMass, 2.0);
}

TEST(ContactModel, SpringAlwaysDampingOnlyWhileApproaching) {
  const ContactModel model(ContactModelSpec{}, eq1(1e4, 30.0));
  Contact k;
  k.normal = Vector3d::UnitZ();
  k.penetration = 1e-3;
  k.effectiveMass = 0.25;
  k.normalVelocity = 0.0;
  EXPECT_DOUBLE_EQ(model.evaluate(k, nullptr, 1e-5).normalForce, 10.0);
  k.normalVelocity = -0.2;  // approaching: + 2 D sqrt(m) 0.2 = 6
  EXPECT_DOUBLE_EQ(model.evaluate(k, nullptr, 1e-5).normalForce, 16.0);
  k.normalVelocity = +0.2;  // separating: spring only
  EXPECT_DOUBLE_EQ(model.evaluate(k, nullptr, 1e-5).normalForce, 10.0);
  // pushes i away from j
  EXPECT_LT((model.evaluate(k, nullptr, 1e-5).forceOnFirst - Vector3d(0, 0, -10)).norm(), 1e-15);
  k.penetration = 1e-4;
  k.normalVelocity = +5.0;
  EXPECT_EQ(model.evaluate(k, nullptr, 1e-5).normalForce, 1.0);  // damping never pulls
  k.penetration = 0.0;
  k.normalVelocity = 0.0;
  EXPECT_EQ(model.evaluate(k, nullptr, 1e-5).normalForce, 0.0);  // never attractive
  EXPECT_EQ(model.historySize(), 0);
  EXPECT_EQ(model.tangential(), nullptr);  // not named: not built
  EXPECT_EQ(model.cohesion(), nullptr);
  EXPECT_EQ(model.rolling(), nullptr);
  ContactModelSpec springOnly;
  springOnly.damping = "none";
  k.normalVelocity = -0.2;
  k.penetration = 1e-3;
  EXPECT_DOUBLE_EQ(ContactModel(springOnly, eq1(1e4, 30.0)).evaluate(k, nullptr, 1e-5).normalForce, 10.0);
}

TEST(ContactModel, BadCoefficientsAndKeywordsAreRefusedByName) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto message = [](const ContactModelSpec& spec, const ContactParameters& p) {
    try {
      ContactModel m(spec, p);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  EXPECT_NE(message({}, eq1(0.0, 1.0)).find("stiffness = 0 must be a finite number > 0"), std::string::npos);
  EXPECT_NE(message({}, eq1(1.0, -1.0)).find("damping = -1"), std::string::npos);
  EXPECT_NE(message({}, eq1(nan, 1.0)).find("stiffness = nan"), std::string::npos);
  ContactParameters noDamping;
  noDamping.set("stiffness", 1.0);
  EXPECT_NE(message({}, noDamping).find("coefficient damping missing"), std::string::npos);
  ContactModelSpec unknown;
  unknown.tangential = "sticky";
  EXPECT_NE(message(unknown, eq1(1, 1)).find("unknown tangential sub-model 'sticky' (one of: none, viscous"),
            std::string::npos)
      << message(unknown, eq1(1, 1));
  ContactModelSpec noNormal;
  noNormal.normal = "none";
  EXPECT_NE(message(noNormal, eq1(1, 1)).find("unknown normal sub-model 'none'"), std::string::npos);
  ContactModelSpec viscous;
  viscous.tangential = "viscous";
  EXPECT_NE(message(viscous, eq1(1, 1)).find("tangential viscous: coefficient friction missing"),
            std::string::npos);
}

TEST(ContactModel, FrictionIsViscousUpToTheCoulombCap) {
  ContactModelSpec spec;
  spec.tangential = "viscous";
  spec.damping = "none";
  ContactParameters p = eq1(1e4, 0.0);
  p.set("friction", 0.5);
  p.set("slidingDamping", 2.0);
  const ContactModel model(spec, p);
  Contact k;
  k.normal = Vector3d::UnitZ();
  k.relativeVelocity = Vector3d(0.3, -0.4, -7.0);  // sliding 0.5 along (0.6, -0.8, 0)
  k.normalVelocity = -7.0;
  k.effectiveMass = 1.0;
  // Viscous: 2 * 0.5 = 1 < 0.5 * 10.
  k.penetration = 1e-3;
  EXPECT_LT((model.evaluate(k, nullptr, 1e-5).forceOnFirst - Vector3d(0.6, -0.8, -10.0)).norm(), 1e-14);
  // Capped: 0.5 * 1 = 0.5.
  k.penetration = 1e-4;
  EXPECT_LT((model.evaluate(k, nullptr, 1e-5).forceOnFirst - Vector3d(0.3, -0.4, -1.0)).norm(), 1e-14);
  k.relativeVelocity = Vector3d(0, 0, -7.0);
  EXPECT_EQ(model.evaluate(k, nullptr, 1e-5).forceOnFirst, Vector3d(0, 0, -1.0));
}

TEST(ContactModel, TableHoldsOneModelPerTypePair) {
  const ContactModelTable table(3, ContactModelSpec{}, [](int i, int j) { return eq1(100.0 * i + j, 0.0); });
  Contact k;
  k.normal = Vector3d::UnitZ();
  k.penetration = 1.0;
  EXPECT_EQ(table.at(1, 3).evaluate(k, nullptr, 1.0).normalForce, 103.0);
  EXPECT_EQ(table.at(3, 1).evaluate(k, nullptr, 1.0).normalForce, 103.0);
  EXPECT_EQ(table.at(2, 2).evaluate(k, nullptr, 1.0).normalForce, 202.0);
  try {
    ContactModelTable bad(2, ContactModelSpec{}, [](int i, int j) { return eq1(i == 1 && j == 2 ? -1.0 : 1.0, 0.0); });
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("type pair 1 2: normal halo: coefficient stiffness = -1"), std::string::npos)
        << e.what();
  }
}

TEST(ContactModel, LeverArmTorquesAndNewtonsThirdLaw) {
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

TEST(ContactModel, ClosedFormRestitutionMatchesIntegration) {
  EXPECT_EQ(springDashpotRestitution(0.0), 1.0);
  for (double zeta : {0.05, 0.3, 0.7, 1.0, 1.5}) {
    const double spring = 2e5, mass = 0.37;
    const double damping = zeta * std::sqrt(spring / 2.0);
    EXPECT_NEAR(DampingApproach(eq1(spring, damping)).dampingRatio(spring), zeta, 1e-14);
    EXPECT_NEAR(integratedRestitution(spring, damping, mass), springDashpotRestitution(zeta), 2e-4) << zeta;
    EXPECT_NEAR(springDashpotRestitution(
                    dampingForRestitution(spring, springDashpotRestitution(zeta)) *
                    std::sqrt(2.0 / spring)),
                springDashpotRestitution(zeta), 1e-12);
  }
  // Monotone decreasing.
  EXPECT_GT(springDashpotRestitution(0.2), springDashpotRestitution(0.4));
  EXPECT_GT(springDashpotRestitution(0.99), springDashpotRestitution(1.01));
}

}  // namespace
