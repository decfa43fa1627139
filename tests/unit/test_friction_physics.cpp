// Static friction, cohesion and the contact identity of the history, on triangulated boxes in
// the core driver (rigid_contact_driver.h; no LIGGGHTS), against closed forms:
//   - incline: a cube on a plane tilted by theta (gravity tilted) with the tangential spring
//     stays put for tan theta = 0.9 mu (displacement < 1e-3 of its edge over 1 s) and slides
//     with g (sin theta - mu cos theta) within 2 % for tan theta = 1.1 mu; the viscous model
//     creeps at 0.9 mu (what static friction is for);
//   - tangential spring: pushed sideways by F < mu N (force through the contact plane) the cube
//     reaches the static offset F / (n k_t) (n contact points in parallel) within 2 %; by
//     F > mu N it slides with (F - mu N) / m;
//   - cohesion: a cube corner held on a cube face by the sjkr-like cohesion comes off when pulled
//     by the sub-model's pull-off force 2 pi R* eps k_c, within 2 %;
//   - contact identity through the de-duplication: the same incline with the box's triangles
//     in another order in every other step (the merged points' triangle indices change, their
//     positions do not) keeps every history and gives the same trajectory to round-off.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include "contact/MeshContact.h"
#include "contact_model/ContactModel.h"
#include "dynamics/RigidBody.h"
#include "geometry/PrimitiveMeshes.h"
#include "geometry/RigidShape.h"
#include "rigid_contact_driver.h"

using namespace spacetree;
using contact_model::ContactModel;
using contact_model::ContactModelSpec;
using contact_model::ContactParameters;
using dynamics::RigidBody;
using geometry::RigidShape;
using spacetree::testing::Particle;
using spacetree::testing::RigidContactDriver;
using Eigen::Vector3d;

namespace {

constexpr double kEdge = 0.05, kEps = 2.5e-4, kDensity = 2500.0, kG = 9.81;
constexpr double kSpring = 2e5, kMu = 0.5, kDt = 2e-5;

contact::MeshContactOptions options() {
  contact::MeshContactOptions o;
  o.epsilon = kEps;
  return o;
}

ContactParameters coefficients(double tangentialStiffness = 0.8 * kSpring) {
  ContactParameters p;
  p.set("stiffness", kSpring);
  p.set("damping", 0.7 * std::sqrt(kSpring / 2));             // normal damping ratio 0.7
  p.set("friction", kMu);
  p.set("tangentialStiffness", tangentialStiffness);
  p.set("tangentialDamping", 0.5 * std::sqrt(tangentialStiffness));  // tangential ratio 0.5
  p.set("slidingDamping", 5.0);                                // viscous: N s/m
  return p;
}

ContactModelSpec withTangential(const char* tangential) {
  ContactModelSpec spec;
  spec.tangential = tangential;
  return spec;
}

// A cube resting on a wide fixed floor (top face z = 0), settled under vertical gravity.
struct Scene {
  RigidShape cube, floor;
  std::vector<Particle> particles;
  explicit Scene(const RigidShape& cubeShape)
      : cube(cubeShape), floor(RigidShape::fromMesh(geometry::boxMesh(Vector3d(2.0, 2.0, 0.1)))) {
    // put down: its bottom face at the resting halo overlap of its four corners, m g / (4 S)
    const double rest = cube.mass(kDensity) * kG / (4 * kSpring);
    const double halfHeight = std::abs(cube.bodyMesh.vertices[0].z());
    particles = {{&cube, RigidBody::free(cube.mass(kDensity), cube.principalInertia(kDensity),
                                         Vector3d(0, 0, halfHeight + 2 * (kEps - rest)))},
                 {&floor, RigidBody::fixed(Vector3d(0, 0, -0.05))}};
  }
  double mass() const { return particles[0].body.mass(); }
  void settle(RigidContactDriver& driver) {
    driver.setGravity(Vector3d(0, 0, -kG));
    for (int s = 0; s < 5000; ++s) driver.step(particles, kDt);  // 0.1 s
    ASSERT_LT(particles[0].body.velocity.norm(), 1e-4);
  }
};

Vector3d tiltedGravity(double theta) { return kG * Vector3d(std::sin(theta), 0, -std::cos(theta)); }

// Displacement along the slope over `seconds` after tilting, and the mean acceleration over
// the last half of that time.
struct Slide {
  double displacement, acceleration;
};

Slide tiltAndRun(const ContactModelSpec& spec, double tanTheta, double seconds) {
  Scene scene(RigidShape::fromMesh(geometry::boxMesh(Vector3d(kEdge, kEdge, kEdge))));
  const ContactModel model(spec, coefficients());
  // the plane tilted from the start: the cube is put down on it at rest
  RigidContactDriver driver(options(), model, tiltedGravity(std::atan(tanTheta)));
  const double x0 = scene.particles[0].body.position.x();
  const int steps = int(std::lround(seconds / kDt));
  double vHalf = 0.0;
  for (int s = 0; s < steps; ++s) {
    driver.step(scene.particles, kDt);
    if (s + 1 == steps / 2) vHalf = scene.particles[0].body.velocity.x();
  }
  const double v = scene.particles[0].body.velocity.x();
  return {scene.particles[0].body.position.x() - x0, (v - vHalf) / (kDt * (steps - steps / 2))};
}

TEST(FrictionPhysics, CubeOnAnInclineStaysBelowTheFrictionAngleAndSlidesAbove) {
  const Slide hold = tiltAndRun(withTangential("history"), 0.9 * kMu, 1.0);
  EXPECT_LT(std::abs(hold.displacement), 1e-3 * kEdge) << hold.displacement;
  const double theta = std::atan(1.1 * kMu);
  const Slide slide = tiltAndRun(withTangential("history"), 1.1 * kMu, 0.4);
  const double expected = kG * (std::sin(theta) - kMu * std::cos(theta));
  EXPECT_NEAR(slide.acceleration / expected, 1.0, 0.02) << slide.acceleration << " vs " << expected;
  // viscous friction exerts nothing at rest: the cube creeps down the slope it should hold
  const Slide creep = tiltAndRun(withTangential("viscous"), 0.9 * kMu, 1.0);
  EXPECT_GT(std::abs(creep.displacement), 1e-3 * kEdge) << creep.displacement;
  std::printf("[ incline ] tan = 0.9 mu: history moves %.3g edge, viscous %.3g edge in 1 s; "
              "tan = 1.1 mu: a = %.5f vs g(sin - mu cos) = %.5f m/s^2\n",
              hold.displacement / kEdge, creep.displacement / kEdge, slide.acceleration, expected);
}

TEST(FrictionPhysics, TangentialSpringGivesTheStaticOffsetAndSlidesAboveTheCap) {
  const double kt = 0.8 * kSpring;
  for (double fraction : {0.5, 1.5}) {
    Scene scene(RigidShape::fromMesh(geometry::boxMesh(Vector3d(kEdge, kEdge, kEdge))));
    const ContactModel model(withTangential("history"), coefficients(kt));
    RigidContactDriver driver(options(), model, Vector3d::Zero());
    scene.settle(driver);
    const Vector3d x0 = scene.particles[0].body.position;
    const double weight = scene.mass() * kG;
    // the push acts through the contact plane (force at the centre plus the torque that moves
    // it down to the plane): no tilt, every contact point shares the displacement
    const double h = kEdge / 2 + 0.5 * (x0.z() - kEdge / 2);
    const double push = fraction * kMu * weight;
    std::size_t contacts = 0;
    const int ramp = 5000, steps = 15000;  // the push grows over 0.1 s, then stays
    double vHalf = 0.0;
    for (int s = 0; s < steps; ++s) {
      const double f = push * std::min(1.0, double(s + 1) / ramp);
      // with the torque of the push about the centre had it acted at the contact plane
      driver.setExternalLoad(0, Vector3d(f, 0, 0), Vector3d(0, -h * f, 0));
      contacts = driver.step(scene.particles, kDt).contacts;
      if (s + 1 == (ramp + steps) / 2) vHalf = scene.particles[0].body.velocity.x();
    }
    const double offset = scene.particles[0].body.position.x() - x0.x();
    if (fraction < 1.0) {
      const double expected = push / (double(contacts) * kt);
      EXPECT_NEAR(offset / expected, 1.0, 0.02) << offset << " vs " << expected << " (" << contacts << " points)";
      EXPECT_LT(scene.particles[0].body.velocity.norm(), 1e-6);
      std::printf("[ tangential spring ] F = 0.5 mu N: offset %.5g m vs F/(%zu k_t) = %.5g m\n", offset,
                  contacts, expected);
    } else {
      const double a = (scene.particles[0].body.velocity.x() - vHalf) / (kDt * (steps - (ramp + steps) / 2));
      const double expected = (push - kMu * weight) / scene.mass();
      EXPECT_NEAR(a / expected, 1.0, 0.02) << a << " vs " << expected;
      std::printf("[ tangential spring ] F = 1.5 mu N: a = %.5f vs (F - mu N)/m = %.5f m/s^2\n", a, expected);
    }
  }
}

TEST(FrictionPhysics, CohesiveCornerComesOffAtThePullOffForce) {
  const RigidShape cube = RigidShape::fromMesh(geometry::boxMesh(Vector3d(kEdge, kEdge, kEdge)));
  ContactModelSpec spec;
  spec.cohesion = "sjkr";
  ContactParameters p = coefficients();
  const double radius = 0.01, energyDensity = 1e5;
  p.set("characteristicRadius", radius);
  p.set("haloDepth", kEps);
  p.set("cohesionEnergyDensity", energyDensity);
  const ContactModel model(spec, p);
  const double pullOff = 2 * M_PI * radius * kEps * energyDensity;  // 0.785 N
  ASSERT_LT(pullOff, 0.5 * kSpring * kEps);  // rests inside the halo
  RigidContactDriver driver(options(), model, Vector3d::Zero());
  // A's corner on the line of centres at the resting penetration F_coh / S in B's face (B fixed)
  const Eigen::Quaterniond corner = Eigen::Quaterniond::FromTwoVectors(Vector3d(1, 1, 1).normalized(), Vector3d::UnitX());
  std::vector<Particle> p2 = {
      {&cube, RigidBody::free(cube.mass(kDensity), cube.principalInertia(kDensity), Vector3d::Zero(), corner)},
      {&cube, RigidBody::fixed(Vector3d(kEdge * std::sqrt(3.0) / 2 + kEdge / 2 + 2 * (kEps - pullOff / kSpring), 0, 0))}};
  for (int s = 0; s < 5000; ++s) driver.step(p2, kDt);  // drawn in and settled
  ASSERT_EQ(driver.step(p2, kDt).contacts, 1u);
  const double rate = pullOff / 0.2;  // N/s
  double detached = -1.0;
  for (int s = 1; s < 30000 && detached < 0; ++s) {
    const double force = rate * s * kDt;
    driver.setExternalLoad(0, Vector3d(-force, 0, 0));
    if (driver.step(p2, kDt).contacts == 0) detached = force;
  }
  ASSERT_GT(detached, 0.0);
  EXPECT_NEAR(detached / pullOff, 1.0, 0.02) << detached << " vs " << pullOff;
  std::printf("[ cohesion ] pull-off %.5f N vs 2 pi R* eps k_c = %.5f N\n", detached, pullOff);
}

// The same box (distinct sides: well-defined principal axes) with its triangles in a random
// order.
geometry::TriangleMesh shuffledTriangles(geometry::TriangleMesh mesh, unsigned seed) {
  std::mt19937 rng(seed);
  std::shuffle(mesh.triangles.begin(), mesh.triangles.end(), rng);
  return mesh;
}

TEST(FrictionPhysics, HistorySurvivesTheContactMergeWhateverTheTriangleOrder) {
  const geometry::TriangleMesh box = geometry::boxMesh(Vector3d(kEdge, 0.9 * kEdge, 0.8 * kEdge));
  const RigidShape ordered = RigidShape::fromMesh(box);
  const RigidShape shuffled = RigidShape::fromMesh(shuffledTriangles(box, 5));
  ASSERT_LT((ordered.meshRotation - shuffled.meshRotation).norm(), 1e-14);
  ASSERT_LT((ordered.centreOfMassInMesh - shuffled.centreOfMassInMesh).norm(), 1e-16);
  const ContactModel model(withTangential("history"), coefficients());
  std::vector<Vector3d> trajectories[2];
  std::size_t continued = 0, points = 0;  // once landed (0.04 s)
  for (int alternate = 0; alternate < 2; ++alternate) {
    Scene scene(ordered);
    RigidContactDriver driver(options(), model, Vector3d::Zero());
    driver.setGravity(tiltedGravity(std::atan(0.9 * kMu)));  // tilted from the start
    for (int s = 0; s < 10000; ++s) {
      scene.particles[0].shape = alternate && s % 2 ? &shuffled : &ordered;
      const auto r = driver.step(scene.particles, kDt);
      if (alternate && s > 2000) continued += r.historiesKept, points += r.contacts;
      trajectories[alternate].push_back(scene.particles[0].body.position);
    }
  }
  EXPECT_EQ(continued, points);  // every contact point continued its history
  double largest = 0.0;
  for (std::size_t s = 0; s < trajectories[0].size(); ++s)
    largest = std::max(largest, (trajectories[0][s] - trajectories[1][s]).norm());
  EXPECT_LT(largest, 1e-12 * kEdge);
  std::printf("[ merge identity ] triangles reordered every other step: trajectory differs by %.3g m at most\n",
              largest);
}

}  // namespace
