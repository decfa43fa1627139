// The contact model composed from sub-models (contact_model/): the generic contact's kinematics,
// the halo spring with damping only while approaching (paper eq. (1)), Coulomb-capped viscous
// friction, the registry (unknown keywords, missing or negative coefficients, only named slots
// built), per-type-pair tables, lever-arm torques, and the closed-form restitution against a
// direct integration of the one-contact equation of motion.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "contact_model/ContactHistory.h"
#include "contact_model/ContactModel.h"
#include "contact_model/DampingApproach.h"
#include "contact_model/MaterialMapping.h"
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

namespace {

ContactParameters historyParameters(double mu, double kt, double dt) {
  ContactParameters p = eq1(1e4, 0.0);
  p.set("friction", mu);
  p.set("tangentialStiffness", kt);
  p.set("tangentialDamping", dt);
  return p;
}

ContactModelSpec historySpec() {
  ContactModelSpec spec;
  spec.tangential = "history";
  return spec;
}

TEST(ContactModel, TangentialSpringHoldsUpToTheCoulombCapThenSlides) {
  const ContactModel model(historySpec(), historyParameters(0.5, 2e3, 0.0));
  ASSERT_EQ(model.historySize(), 3);
  Contact k;
  k.normal = Vector3d::UnitZ();
  k.penetration = 1e-3;  // F = 10 N, cap 5 N
  k.effectiveMass = 1.0;
  double xi[3] = {0, 0, 0};
  const double dt = 1e-3;
  // j slides along +x at 0.1 m/s relative to i: i is pulled along +x by k_t xi
  k.relativeVelocity = Vector3d(0.1, 0, 0);
  ContactForces f;
  for (int s = 0; s < 10; ++s) f = model.evaluate(k, xi, dt);
  EXPECT_NEAR(xi[0], 10 * 0.1 * dt, 1e-15);
  EXPECT_NEAR(f.forceOnFirst.x(), 2e3 * 1e-3, 1e-12);  // 2 N < 5 N: spring
  EXPECT_NEAR(f.forceOnFirst.z(), -10.0, 1e-12);
  // at rest the spring keeps its force (static friction); the viscous model would give 0
  k.relativeVelocity = Vector3d::Zero();
  f = model.evaluate(k, xi, dt);
  EXPECT_NEAR(f.forceOnFirst.x(), 2.0, 1e-12);
  // more displacement: capped at mu F = 5 N, xi rescaled to the cap
  k.relativeVelocity = Vector3d(0.1, 0, 0);
  for (int s = 0; s < 100; ++s) f = model.evaluate(k, xi, dt);
  EXPECT_NEAR(f.forceOnFirst.x(), 5.0, 1e-12);
  EXPECT_NEAR(xi[0], 5.0 / 2e3, 1e-15);
  // reversing: the spring unloads at once (no longer at the cap)
  k.relativeVelocity = Vector3d(-0.1, 0, 0);
  f = model.evaluate(k, xi, dt);
  EXPECT_NEAR(f.forceOnFirst.x(), 5.0 - 2e3 * 1e-4, 1e-12);
}

TEST(ContactModel, TangentialSpringIsRotatedIntoTheNewTangentPlaneKeepingItsLength) {
  const ContactModel model(historySpec(), historyParameters(10.0, 1e3, 0.0));
  Contact k;
  k.penetration = 1e-3;
  k.effectiveMass = 1.0;
  double xi[3] = {2e-3, 0, 0};
  // the contact plane tilted by 30 degrees about y: xi loses its normal part, keeps 2e-3
  k.normal = Vector3d(std::sin(M_PI / 6), 0, std::cos(M_PI / 6));
  const ContactForces f = model.evaluate(k, xi, 1e-3);
  const Vector3d x(xi[0], xi[1], xi[2]);
  EXPECT_NEAR(x.norm(), 2e-3, 1e-15);
  EXPECT_NEAR(x.dot(k.normal), 0.0, 1e-18);
  EXPECT_GT(x.x(), 0.0);
  EXPECT_NEAR((f.forceOnFirst + 10.0 * k.normal - 1e3 * x).norm(), 0.0, 1e-12);
}

TEST(ContactModel, TangentialDashpotDampsTheSpringAndStaysWithinTheCap) {
  // one contact point of tangential mass m_t = 1 kg: xi'' = -k_t xi - 2 D_t v; damping ratio
  // D_t / sqrt(k_t)
  const double kt = 1e4, zeta = 0.2;
  const ContactModel model(historySpec(), historyParameters(100.0, kt, zeta * std::sqrt(kt)));
  Contact k;
  k.normal = Vector3d::UnitZ();
  k.penetration = 1.0;
  k.effectiveMass = 1.0;
  k.tangentialMass = 1.0;
  double xi[3] = {0, 0, 0};
  double x = 0.0, v = 1.0, peak1 = 0.0, peak2 = 0.0;
  const double dt = 1e-5;
  int crossings = 0;
  for (int s = 0; s < 200000 && crossings < 3; ++s) {
    k.relativeVelocity = Vector3d(-v, 0, 0);  // j relative to i: i moves at +v
    const double force = model.evaluate(k, xi, dt).forceOnFirst.x();
    const double vOld = v;
    v += force * dt;
    x += v * dt;
    if (vOld > 0 && v <= 0) (crossings == 0 ? peak1 : peak2) = x, ++crossings;
    if (vOld < 0 && v >= 0) ++crossings;
  }
  // amplitude ratio over one period: exp(-2 pi zeta / sqrt(1 - zeta^2))
  EXPECT_NEAR(peak2 / peak1, std::exp(-2 * M_PI * zeta / std::sqrt(1 - zeta * zeta)), 2e-3);
}

TEST(ContactModel, CohesionPullsWhileTheHalosOverlap) {
  ContactModelSpec spec;
  spec.cohesion = "sjkr";
  ContactParameters p = eq1(1e4, 0.0);
  p.set("cohesionEnergyDensity", 1e5);
  p.set("characteristicRadius", 2e-3);
  p.set("haloDepth", 1e-4);
  const ContactModel model(spec, p);
  const double fc = 2 * M_PI * 2e-3 * 1e-4 * 1e5;  // 0.1257 N
  Contact k;
  k.normal = Vector3d::UnitZ();
  k.penetration = 1e-6;  // spring 0.01 N
  EXPECT_NEAR(model.evaluate(k, nullptr, 1e-5).forceOnFirst.z(), -0.01 + fc, 1e-14);
  k.penetration = 0.0;
  EXPECT_EQ(model.evaluate(k, nullptr, 1e-5).forceOnFirst.z(), 0.0);
  EXPECT_EQ(model.historySize(), 0);
  ContactParameters missing = eq1(1e4, 0.0);
  missing.set("cohesionEnergyDensity", 1e5);
  missing.set("haloDepth", 1e-4);
  EXPECT_THROW(ContactModel(spec, missing), std::invalid_argument);
}

struct Anchor {
  Vector3d point, normal;
};

TEST(ContactHistory, MatchesByPositionInTheFirstBodysFrameWhateverTheOrder) {
  ContactHistoryMatcher matcher(3, {0.01, 0.9});
  contact::Pose pose;
  pose.position = Vector3d(1, 2, 3);
  pose.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Vector3d(1, 1, 0).normalized()));
  std::vector<Anchor> first = {{pose.position + pose.orientation * Vector3d(0.1, 0, 0), Vector3d::UnitZ()},
                               {pose.position + pose.orientation * Vector3d(-0.1, 0, 0), Vector3d::UnitZ()},
                               {pose.position + pose.orientation * Vector3d(0, 0.1, 0), Vector3d::UnitX()}};
  std::vector<double> records, next;
  ContactHistoryMatchStatistics stats;
  matcher.match(records.data(), 0, first, pose, next, &stats);
  ASSERT_EQ(next.size(), 3u * 9u);
  EXPECT_EQ(stats.started, 3u);
  for (int k = 0; k < 3; ++k) next[std::size_t(k) * 9 + 6] = 10.0 * (k + 1);  // histories 10, 20, 30
  records = next;
  // the pair moved rigidly, the points come in another order, one moved a little, one jumped
  // across its face (same normal: the same patch)
  contact::Pose moved;
  moved.position = Vector3d(-1, 0, 0.5);
  moved.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(1.1, Vector3d(0, 1, 1).normalized()));
  const auto at = [&](const Vector3d& body) { return Vector3d(moved.position + moved.orientation * body); };
  std::vector<Anchor> second = {{at(Vector3d(0.3, 0.3, 0)), moved.orientation * Vector3d::UnitZ()},
                                {at(Vector3d(0.002, 0.1, 0)), moved.orientation * Vector3d::UnitX()},
                                {at(Vector3d(0.1, 0, 0)), moved.orientation * Vector3d::UnitZ()}};
  stats = {};
  matcher.match(records.data(), 3, second, moved, next, &stats);
  EXPECT_EQ(stats.kept, 3u);
  EXPECT_EQ(stats.moved, 1u);
  EXPECT_EQ(stats.started, 0u);
  EXPECT_EQ(stats.dropped, 0u);
  EXPECT_EQ(next[0 * 9 + 6], 20.0);  // jumped: continues the second
  EXPECT_EQ(next[1 * 9 + 6], 30.0);  // continues the third
  EXPECT_EQ(next[2 * 9 + 6], 10.0);  // continues the first
  EXPECT_NEAR(next[1 * 9 + 0], 0.002, 1e-15);  // anchor follows the point
  EXPECT_NEAR(next[0 * 9 + 1], 0.3, 1e-15);
}

TEST(ContactHistory, OpenedContactsEndMergedOnesAddUpNewOnesStartAtZero) {
  ContactHistoryMatcher matcher(1, {0.01, 0.9});
  contact::Pose pose;
  // two records with normal +z (h 5 and 7), one with normal +x (h 3)
  const std::vector<double> records = {0, 0, 0, 0, 0, 1, 5.0,   0.1, 0, 0, 0, 0, 1, 7.0,
                                       0, 0.2, 0, 1, 0, 0, 3.0};
  std::vector<double> next;
  ContactHistoryMatchStatistics stats;
  // one +z point near the first: continues it and absorbs the second (merged); the +x contact
  // opened; a new point with normal +y starts at zero
  std::vector<Anchor> now = {{Vector3d(0.001, 0, 0), Vector3d::UnitZ()}, {Vector3d(0, 0, 0.3), Vector3d::UnitY()}};
  matcher.match(records.data(), 3, now, pose, next, &stats);
  EXPECT_EQ(next[6], 12.0);
  EXPECT_EQ(next[7 + 6], 0.0);
  EXPECT_EQ(stats.kept, 1u);
  EXPECT_EQ(stats.merged, 1u);
  EXPECT_EQ(stats.dropped, 1u);
  EXPECT_EQ(stats.started, 1u);
  // a normal turned beyond the merge cosine (0.71 < 0.9) is another contact
  std::vector<Anchor> turned = {{Vector3d::Zero(), Vector3d(1, 0, 1).normalized()}};
  matcher.match(records.data(), 1, turned, pose, next);
  EXPECT_EQ(next[6], 0.0);
  // two points compete for one record: the closer one continues it, the other starts at zero
  std::vector<Anchor> two = {{Vector3d(0.005, 0, 0), Vector3d::UnitZ()}, {Vector3d(0.001, 0, 0), Vector3d::UnitZ()}};
  matcher.match(records.data(), 1, two, pose, next);
  EXPECT_EQ(next[6], 0.0);
  EXPECT_EQ(next[7 + 6], 5.0);
}

}  // namespace

namespace {
TEST(ContactModel, ZeroTimeStepRepeatsTheForceAndKeepsTheHistory) {
  const ContactModel model(historySpec(), historyParameters(0.5, 2e3, 30.0));
  Contact k;
  k.normal = Vector3d::UnitZ();
  k.penetration = 1e-3;
  k.effectiveMass = 1.0;
  k.relativeVelocity = Vector3d(0.3, 0.1, 0);
  double xi[3] = {0, 0, 0};
  for (int s = 0; s < 30; ++s) model.evaluate(k, xi, 1e-3);  // slides: xi at the cap
  const Vector3d last = model.evaluate(k, xi, 1e-3).forceOnFirst;
  const double after[3] = {xi[0], xi[1], xi[2]};
  const Vector3d again = model.evaluate(k, xi, 0.0).forceOnFirst;
  EXPECT_EQ(std::memcmp(after, xi, sizeof(xi)), 0);                  // unchanged
  EXPECT_EQ(std::memcmp(last.data(), again.data(), sizeof(double) * 3), 0);  // same bits
  k.relativeVelocity = Vector3d(-0.3, 0.1, 0);  // (a real step does move it)
  model.evaluate(k, xi, 1e-3);
  EXPECT_NE(std::memcmp(after, xi, sizeof(xi)), 0);
}
}  // namespace

namespace {
TEST(MaterialMapping, HertzEffectiveQuantitiesAndTheHaloStiffness) {
  const double inf = std::numeric_limits<double>::infinity();
  // one material, nu = 0: S = E r between grains (Yade's FrictPhys for equal spheres), 2 E r on a wall
  EXPECT_DOUBLE_EQ(haloStiffness(effectiveModulus(1e7, 0.0, 1e7, 0.0), effectiveRadius(0.01, 0.01)), 1e7 * 0.01);
  EXPECT_DOUBLE_EQ(haloStiffness(effectiveModulus(1e7, 0.0, 1e7, 0.0), effectiveRadius(0.01, inf)), 2 * 1e7 * 0.01);
  // E* with nu: E / (2 (1 - nu^2)) for one material
  EXPECT_NEAR(effectiveModulus(2e9, 0.3, 2e9, 0.3), 2e9 / (2 * (1 - 0.09)), 1e-3);
  // a soft wall lowers the stiffness: E* of 1e7 and 1e6
  EXPECT_NEAR(effectiveModulus(1e7, 0.0, 1e6, 0.0), 1.0 / (1e-7 + 1e-6), 1e-6);
  // Mindlin: 2 (1 - nu) / (2 - nu) for one material
  EXPECT_NEAR(mindlinStiffnessRatio(5e6, 0.3, 5e6, 0.3), 2 * 0.7 / 1.7, 1e-14);
  EXPECT_NEAR(mindlinStiffnessRatio(5e6, 0.0, 5e6, 0.0), 1.0, 1e-14);
  EXPECT_THROW(effectiveModulus(-1.0, 0.3, 1e7, 0.3), std::invalid_argument);
  EXPECT_THROW(effectiveModulus(1e7, 0.5, 1e7, 0.3), std::invalid_argument);
  EXPECT_THROW(effectiveModulus(std::nan(""), 0.3, 1e7, 0.3), std::invalid_argument);
}

TEST(MaterialMapping, ContactTimeMatchesADirectIntegration) {
  for (double zeta : {0.0, 0.3, 0.9, 1.0, 1.4}) {
    const double spring = 4e5, mass = 0.02, damping = zeta * std::sqrt(spring / 2);
    const ContactTiming t = contactTiming(spring, damping, mass, 0.0, 0.0, mass);
    // m x'' = -(S/2) x - 2 D sqrt(m) x' (approach), -(S/2) x (release), from x = 0, x' = 1
    const double dt = 1e-5 / t.normalFrequency;
    double x = 0.0, v = 1.0, time = 0.0;
    do {
      const double a = (-(spring / 2) * x - (v > 0 ? 2 * damping * std::sqrt(mass) * v : 0.0)) / mass;
      v += a * dt;
      x += v * dt;
      time += dt;
    } while (x > 0.0);
    EXPECT_NEAR(time / t.contactTime, 1.0, 1e-4) << zeta;
    EXPECT_NEAR(t.stableStep, dampedStableStep(t.normalFrequency, zeta), 1e-18);
  }
  // the stable step on the lightest contact point, the tangential spring's if faster
  const ContactTiming withSpring = contactTiming(4e5, 0.0, 0.02, 3e5, 0.0, 0.005);
  EXPECT_NEAR(withSpring.stableStep, 2.0 / std::sqrt(3e5 / 0.005), 1e-15);
  const ContactTiming lighter = contactTiming(4e5, 0.0, 0.02, 0.0, 0.0, 0.005);
  EXPECT_NEAR(lighter.stableStep, 2.0 / std::sqrt(4e5 / (2 * 0.005)), 1e-15);
  EXPECT_NEAR(lighter.normalFrequency, std::sqrt(4e5 / (2 * 0.02)), 1e-9);  // contact time: m_eff
}

// m x'' = -k x - c x' integrated as LIGGGHTS' nve integrators (half kick, drift, force from the
// half-step velocity, half kick) for `steps` steps from x = 1: the largest |x| of the last
// hundred steps.
double leapfrogAmplitude(double omega, double zeta, double dt, int steps) {
  const double k = omega * omega, c = 2 * zeta * omega;  // unit mass
  double x = 1.0, v = 0.0, a = -k * x, late = 0.0;
  for (int s = 0; s < steps; ++s) {
    v += 0.5 * dt * a;
    x += dt * v;
    a = -k * x - c * v;
    v += 0.5 * dt * a;
    if (!std::isfinite(x)) return std::numeric_limits<double>::infinity();
    if (s >= steps - 100) late = std::max(late, std::abs(x));
  }
  return late;
}

TEST(MaterialMapping, DampedStableStepIsTheIntegratorsLimit) {
  // below the limit the oscillation decays, above it grows: the dashpot lowers the limit
  // 2 / omega of the undamped spring to 2 (sqrt(1 + zeta^2) - zeta) / omega
  for (double zeta : {0.0, 0.358, 1.336}) {
    const double omega = 1000.0, limit = dampedStableStep(omega, zeta);
    EXPECT_LT(leapfrogAmplitude(omega, zeta, 0.98 * limit, 4000), 1.0) << zeta;
    EXPECT_GT(leapfrogAmplitude(omega, zeta, 1.02 * limit, 4000), 1.0) << zeta;
  }
  EXPECT_NEAR(dampedStableStep(1000.0, 1.336) * 1000.0, 2 * (std::sqrt(1 + 1.336 * 1.336) - 1.336), 1e-15);
}

TEST(MaterialMapping, TangentialDashpotGivesTheNormalRestitution) {
  // the tangential dashpot acts throughout: a free tangential oscillation loses the factor e
  // of its amplitude per half period, as the normal approach dashpot gives a collision e
  const double S = 500.0, kt = 400.0;
  for (double e : {0.3, 0.7, 0.95}) {
    const double D = dampingForRestitution(S, e), Dt = tangentialDampingFor(S, D, kt);
    const double zetaT = Dt / std::sqrt(kt);
    EXPECT_NEAR(std::exp(-M_PI * zetaT / std::sqrt(1 - zetaT * zetaT)), e, 1e-12) << e;
    EXPECT_LT(zetaT, D * std::sqrt(2.0 / S)) << e;  // weaker than the approach-only ratio
  }
  EXPECT_EQ(tangentialDampingFor(S, 0.0, kt), 0.0);
}
}  // namespace
