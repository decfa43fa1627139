// Rolling resistance (rolling epsd, RollingEpsd.h): the law on one contact point, and a
// triangulated cube standing on one corner on a fixed floor (one contact point, pressed by an
// external force F through its centre, gravity off) in the core driver against closed forms:
//   - rolling at the cap: the cube turning about its corner is decelerated by the constant
//     torque mu_r R_r F (R_r = |corner - centre|, the floor contributes none) about the corner,
//     I_c alpha = -mu_r R_r F + F R_r sin(theta) (the inverted pendulum of F), within 2 %;
//     without rolling resistance it turns on unslowed;
//   - below the cap: a torque M about a tangential axis is held by the static rotation
//     M / (k_r - F R_r) (the rolling spring k_r = 2.25 (S/2) mu_r^2 R_r^2 less the pendulum)
//     within 2 %; without rolling resistance the cube tips over.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <vector>

#include "contact/MeshContact.h"
#include "contact_model/ContactModel.h"
#include "contact_model/RollingEpsd.h"
#include "dynamics/RigidBody.h"
#include "geometry/PrimitiveMeshes.h"
#include "geometry/RigidShape.h"
#include "rigid_contact_driver.h"

using namespace spacetree;
using contact_model::Contact;
using contact_model::ContactModel;
using contact_model::ContactModelSpec;
using contact_model::ContactParameters;
using contact_model::RollingEpsd;
using dynamics::RigidBody;
using geometry::RigidShape;
using spacetree::testing::Particle;
using spacetree::testing::RigidContactDriver;
using Eigen::Vector3d;

namespace {

constexpr double kEdge = 0.05, kEps = 2.5e-4, kDensity = 2500.0;
constexpr double kSpring = 2e6, kMu = 0.5, kMuR = 0.3, kEtaR = 0.5, kDt = 2e-5, kPress = 10.0;

ContactParameters coefficients() {
  ContactParameters p;
  p.set("stiffness", kSpring);
  p.set("damping", 0.7 * std::sqrt(kSpring / 2));
  p.set("friction", kMu);
  p.set("tangentialStiffness", 0.8 * kSpring);
  p.set("tangentialDamping", 0.5 * std::sqrt(0.8 * kSpring));
  p.set("rollingFriction", kMuR);
  p.set("rollingDamping", kEtaR);
  return p;
}

ContactModelSpec spec(const char* rolling) {
  ContactModelSpec s;
  s.tangential = "history";
  s.rolling = rolling;
  return s;
}

// One contact point: normal +z, lever arm 0.1 m on a free body over a fixed floor.
Contact pointContact(const Vector3d& relativeAngularVelocity, const Vector3d& normal = Vector3d::UnitZ()) {
  Contact c;
  c.normal = normal;
  c.relativeAngularVelocity = relativeAngularVelocity;
  c.rollingRadius = 0.1;
  c.rollingInertia = 2e-3;
  return c;
}

TEST(RollingEpsd, SpringGrowsWithTheRollingAngleUpToTheCapAndOpposesIt) {
  const RollingEpsd law(coefficients());
  const double F = 50.0, R = 0.1, kr = 2.25 * 0.5 * kSpring * kMuR * kMuR * R * R;
  EXPECT_DOUBLE_EQ(law.stiffness(R), kr);
  // the first body turns at +1 rad/s about x relative to the second (w_r = omega_j - omega_i):
  // the spring's torque on it is -k_r theta about x; a twist about the normal adds nothing
  const Contact c = pointContact(Vector3d(-1e-3, 0.0, 7.0));
  double history[3] = {0, 0, 0};
  const double dt = 1e-6;
  Vector3d tau;
  for (int s = 0; s < 10; ++s) tau = law.torqueOnFirst(c, F, history, dt);
  EXPECT_NEAR(history[0], -kr * 1e-3 * 10 * dt, 1e-12 * kr);
  EXPECT_EQ(history[1], 0.0);
  EXPECT_EQ(history[2], 0.0);
  // below the cap the dashpot 2 eta_r sqrt(I_r k_r) w_r adds to the spring
  EXPECT_NEAR(tau.x(), -(kr * 10 * dt + 2 * kEtaR * std::sqrt(c.rollingInertia * kr)) * 1e-3, 1e-12);
  // on until the cap mu_r R_r F: the spring stays there, spring plus dashpot capped to it
  const double cap = kMuR * R * F;
  for (int s = 0; s < 2000; ++s) tau = law.torqueOnFirst(c, F, history, 1e-3);
  EXPECT_NEAR(Vector3d(history[0], history[1], history[2]).norm(), cap, 1e-12 * cap);
  EXPECT_NEAR(tau.x(), -cap, 1e-12 * cap);
  EXPECT_NEAR(tau.norm(), cap, 1e-12 * cap);
  // dt = 0: the stored torque, history unchanged
  const double before = history[0];
  EXPECT_NEAR(law.torqueOnFirst(c, F, history, 0.0).x(), -cap, 1e-12 * cap);
  EXPECT_EQ(history[0], before);
  // a smaller normal force lowers the cap at once
  EXPECT_NEAR(law.torqueOnFirst(c, 0.5 * F, history, dt).norm(), 0.5 * cap, 1e-12 * cap);
}

TEST(RollingEpsd, TorqueIsContinuousAtTheCap) {
  // a spring at the cap within round-off, the contact turning back (unloading): the dashpot acts
  // on either side of the cap, so round-off in |M_r| cannot switch the torque
  const RollingEpsd law(coefficients());
  const double F = 50.0, cap = kMuR * 0.1 * F;
  const Contact c = pointContact(Vector3d(-1e-3, 0.0, 0.0));
  double below[3] = {cap * (1 - 1e-15), 0, 0}, above[3] = {cap * (1 + 1e-15), 0, 0};
  const Vector3d a = law.torqueOnFirst(c, F, below, 0.0), b = law.torqueOnFirst(c, F, above, 0.0);
  EXPECT_LT(a.x(), cap * (1 - 1e-6));  // the dashpot unloads it
  EXPECT_NEAR(a.x(), b.x(), 1e-12 * cap);
}

TEST(RollingEpsd, HistoryTurnsWithTheContactPlaneKeepingItsLength) {
  const RollingEpsd law(coefficients());
  double history[3] = {-0.2, 0.0, 0.0};
  // the contact plane tilts by 30 degrees about y: the stored torque follows it
  const double a = M_PI / 6;
  const Vector3d normal(std::sin(a), 0.0, std::cos(a));
  law.torqueOnFirst(pointContact(Vector3d::Zero(), normal), 1e6, history, 1e-6);
  const Vector3d m(history[0], history[1], history[2]);
  EXPECT_NEAR(m.norm(), 0.2, 1e-14);
  EXPECT_NEAR(m.dot(normal), 0.0, 1e-14);
  EXPECT_LT(m.x(), 0.0);
}

TEST(RollingEpsd, BadCoefficientsAreRefusedByName) {
  for (double bad : {-0.1, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    ContactParameters p = coefficients();
    p.set("rollingFriction", bad);
    try {
      ContactModel model(spec("epsd"), p);
      FAIL() << "rollingFriction " << bad << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("rollingFriction"), std::string::npos) << e.what();
    }
  }
  ContactParameters missing = coefficients();
  missing.set("rollingDamping", -1.0);
  EXPECT_THROW(ContactModel(spec("epsd"), missing), std::invalid_argument);
  ContactParameters none;
  none.set("stiffness", kSpring);
  none.set("damping", 1.0);
  try {
    ContactModel model(ContactModelSpec{"halo", "approach", "none", "epsd", "none"}, none);
    FAIL() << "missing rollingFriction accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("rollingFriction missing"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ContactModelSpec({"halo", "approach", "none", "sds", "none"}).validate(), std::invalid_argument);
}

// A cube standing on its corner (body diagonal along z) on a fixed floor whose top face is
// z = 0, pressed down by kPress through its centre: one contact point at the corner.
struct CornerScene {
  RigidShape cube = RigidShape::fromMesh(geometry::boxMesh(Vector3d(kEdge, kEdge, kEdge)));
  RigidShape floor = RigidShape::fromMesh(geometry::boxMesh(Vector3d(2.0, 2.0, 0.1)));
  std::vector<Particle> particles;
  double lever = kEdge * std::sqrt(3.0) / 2;  // R_r = |corner - centre|
  Eigen::Quaterniond start;
  CornerScene() {
    start = Eigen::Quaterniond::FromTwoVectors(-Vector3d::Ones().normalized(), -Vector3d::UnitZ());
    const double rest = kPress / kSpring;  // halo overlap of the one point under kPress
    particles = {{&cube, RigidBody::free(cube.mass(kDensity), cube.principalInertia(kDensity),
                                         Vector3d(0, 0, lever + 2 * (kEps - rest)), start)},
                 {&floor, RigidBody::fixed(Vector3d(0, 0, -0.05))}};
  }
  RigidBody& body() { return particles[0].body; }
  double inertia() const { return cube.principalInertia(kDensity).x(); }  // isotropic
  // rotation about x since the start [rad]
  double angle() {
    const Eigen::AngleAxisd turn(body().orientation * start.conjugate());
    return turn.angle() * turn.axis().x();
  }
};

contact::MeshContactOptions options() {
  contact::MeshContactOptions o;
  o.epsilon = kEps;
  return o;
}

struct Rolling {
  double measured, expected;  // angular acceleration about x over the window [rad/s^2]
};

// The cube turning at omega0 about the x axis through its corner (the corner at rest).
Rolling rollAboutTheCorner(const char* rolling, double omega0) {
  CornerScene scene;
  const ContactModel model(spec(rolling), coefficients());
  RigidContactDriver driver(options(), model, Vector3d::Zero());
  driver.setExternalLoad(0, Vector3d(0, 0, -kPress));
  for (int s = 0; s < 2000; ++s) driver.step(scene.particles, kDt);  // settle the halo (0.04 s)
  const double m = scene.body().mass(), L = scene.lever;
  const double cornerInertia = scene.inertia() + m * L * L;
  scene.start = scene.body().orientation;
  scene.body().setAngularVelocity(Vector3d(omega0, 0, 0));
  scene.body().velocity = Vector3d(omega0, 0, 0).cross(Vector3d(0, 0, L));
  // window: from 1 ms (the spring has reached the cap) over 4 ms
  const int first = 50, last = 250;
  double w1 = 0, w2 = 0, expectedChange = 0;
  for (int s = 0; s < last; ++s) {
    if (s >= first) expectedChange += kDt * kPress * L * (-kMuR + std::sin(scene.angle())) / cornerInertia;
    driver.step(scene.particles, kDt);
    if (s + 1 == first) w1 = scene.body().angularVelocity().x();
  }
  w2 = scene.body().angularVelocity().x();
  EXPECT_GT(w2, 0.0);  // still turning: the window is before the stop
  const double span = kDt * (last - first);
  return {(w2 - w1) / span, expectedChange / span};
}

TEST(RollingPhysics, CubeRollingOnItsCornerIsDeceleratedByTheCappedTorque) {
  const Rolling r = rollAboutTheCorner("epsd", 2.0);
  std::printf("[ rolling at the cap ] alpha = %.5g vs (F L (sin theta - mu_r)) / I_c = %.5g rad/s^2\n",
              r.measured, r.expected);
  EXPECT_NEAR(r.measured, r.expected, 0.02 * std::abs(r.expected));
  // no rolling resistance: the corner is a pivot and the cube turns on (the pendulum speeds it)
  const Rolling free = rollAboutTheCorner("none", 2.0);
  std::printf("[ rolling at the cap ] rolling none: alpha = %.5g rad/s^2\n", free.measured);
  EXPECT_GT(free.measured, 0.0);
}

// Static rotation under a torque M about x: M + F L sin(theta) = k_r theta.
double staticRotation(const char* rolling, double torque, double seconds) {
  CornerScene scene;
  const ContactModel model(spec(rolling), coefficients());
  RigidContactDriver driver(options(), model, Vector3d::Zero());
  driver.setExternalLoad(0, Vector3d(0, 0, -kPress), Vector3d(torque, 0, 0));
  const int steps = int(std::lround(seconds / kDt));
  for (int s = 0; s < steps; ++s) driver.step(scene.particles, kDt);
  return scene.angle();
}

TEST(RollingPhysics, TorqueBelowTheCapIsHeldByTheStaticRollingRotation) {
  const double L = kEdge * std::sqrt(3.0) / 2;
  const double kr = 2.25 * 0.5 * kSpring * kMuR * kMuR * L * L, cap = kMuR * L * kPress;
  const double torque = 0.3 * cap;
  const double theta = staticRotation("epsd", torque, 0.1);
  std::printf("[ rolling spring ] M = 0.3 mu_r R_r F: theta = %.5g vs M / (k_r - F L) = %.5g rad\n",
              theta, torque / (kr - kPress * L));
  EXPECT_NEAR(theta, torque / (kr - kPress * L), 0.02 * torque / kr);
  // without rolling resistance nothing holds the torque: the cube tips far beyond that angle
  const double tipped = staticRotation("none", torque, 0.1);
  std::printf("[ rolling spring ] rolling none: theta = %.5g rad after 0.1 s\n", tipped);
  EXPECT_GT(tipped, 10 * torque / kr);
}

}  // namespace
