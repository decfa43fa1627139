// Grains that come to rest: dented grains with static friction (tangential history) and
// rotation, of the materials of inputs/heap/in.heap_grains (E 1e5 Pa, nu 0.3, e 0.3, mu 0.5,
// radius 2.5 mm, density 2500, halo 0.1 mm), dropped onto a fixed floor in the core driver
// (rigid_contact_driver.h) at half the stable step contactTiming gives: the kinetic energy must
// fall below 1e-12 of its peak within 1.5 s simulated and stay there. Coefficients from the
// materials as pair_style trimesh derives them (MaterialMapping.h). A tangential dashpot with
// the approach-only damping ratio (3.7 times larger at e = 0.3) on a contact point of a
// rotating grain exceeds the integrator's limit at this step: a single grain then rings on its
// three contact points at ~1e-5 of its peak energy for ever (the Coulomb cap bounds it).
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "contact/MeshContact.h"
#include "contact_model/ContactModel.h"
#include "contact_model/DampingApproach.h"
#include "contact_model/MaterialMapping.h"
#include "dynamics/RigidBody.h"
#include "geometry/DentedSphere.h"
#include "geometry/PrimitiveMeshes.h"
#include "geometry/RigidShape.h"
#include "rigid_contact_driver.h"

using namespace spacetree;
using namespace spacetree::contact_model;
using dynamics::RigidBody;
using geometry::RigidShape;
using spacetree::testing::Particle;
using spacetree::testing::RigidContactDriver;
using Eigen::Quaterniond;
using Eigen::Vector3d;

namespace {

constexpr double kYoungs = 1e5, kPoisson = 0.3, kRestitution = 0.3, kMu = 0.5, kEps = 1e-4;
constexpr double kDensity = 2500.0;

// The grain-floor pair's coefficients (R* = the grain's radius), as pair_style trimesh builds
// them from fix property/global (every pair here uses them: the driver has one model).
ContactParameters heapCoefficients(double radius) {
  const double S = haloStiffness(effectiveModulus(kYoungs, kPoisson, kYoungs, kPoisson), radius);
  const double D = dampingForRestitution(S, kRestitution);
  const double kt = S * mindlinStiffnessRatio(kYoungs, kPoisson, kYoungs, kPoisson);
  ContactParameters p;
  p.set("stiffness", S);
  p.set("damping", D);
  p.set("friction", kMu);
  p.set("tangentialStiffness", kt);
  p.set("tangentialDamping", tangentialDampingFor(S, D, kt));
  return p;
}

struct Rest {
  double peak = 0.0, last = 0.0, largestLate = 0.0;  // kinetic energies [J]
};

// `grains` dented grains, 2 x 2 per layer 5.5 mm apart, randomly turned, released 0.5 mm above
// the floor; `seconds` simulated. largestLate: the largest energy over the last 0.2 s.
Rest dropGrains(int grains, double seconds) {
  geometry::DentedSphereOptions d;
  d.triangles = 40;
  d.radius = 0.0025;
  d.amplitude = 0.2;
  d.seed = 7;
  const RigidShape grain = RigidShape::fromMesh(geometry::dentedSphere(d));
  const RigidShape floor = RigidShape::fromMesh(geometry::boxMesh(Vector3d(0.1, 0.1, 0.004)));
  const double radius = std::cbrt(3 * grain.volume / (4 * M_PI)), mass = grain.mass(kDensity);
  const ContactParameters p = heapCoefficients(radius);
  const ContactModel model(ContactModelSpec{"halo", "approach", "history", "none", "none"}, p);
  // half the stable step of the lightest contact point (lever arm: the bounding radius)
  const Vector3d inertia = grain.principalInertia(kDensity);
  const double pointMass =
      1.0 / (1.0 / mass + grain.boundingRadius * grain.boundingRadius / inertia.minCoeff());
  const double dt = 0.5 * contactTiming(p.values().at("stiffness"), p.values().at("damping"), mass,
                                        p.values().at("tangentialStiffness"),
                                        p.values().at("tangentialDamping"), pointMass)
                              .stableStep;
  contact::MeshContactOptions options;
  options.epsilon = kEps;
  RigidContactDriver driver(options, model, Vector3d(0, 0, -9.81));
  std::vector<Particle> particles{{&floor, RigidBody::fixed(Vector3d(0, 0, -0.002))}};
  std::mt19937_64 rng(7);
  std::normal_distribution<double> n;
  for (int g = 0; g < grains; ++g) {
    const Quaterniond q = Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized();
    double lowest = 1e9;
    for (const Vector3d& v : grain.bodyMesh.vertices) lowest = std::min(lowest, (q * v).z());
    const int layer = g / 4, k = g % 4;
    const Vector3d at((k % 2 - 0.5) * 0.0055, (k / 2 - 0.5) * 0.0055, 0.0005 - lowest + layer * 0.0055);
    particles.push_back({&grain, RigidBody::free(mass, inertia, at, q)});
  }
  Rest rest;
  const int steps = int(seconds / dt), late = int(0.2 / dt);
  for (int s = 0; s < steps; ++s) {
    driver.step(particles, dt);
    double energy = 0.0;
    for (const Particle& q : particles) energy += q.body.kineticEnergy();
    rest.peak = std::max(rest.peak, energy);
    rest.last = energy;
    if (s >= steps - late) rest.largestLate = std::max(rest.largestLate, energy);
  }
  std::printf("[ resting grains ] %d grain(s), dt %.3g s: peak %.3g J, last 0.2 s at most %.3g of it\n",
              grains, dt, rest.peak, rest.largestLate / rest.peak);
  return rest;
}

TEST(RestingGrains, OneDentedGrainWithStaticFrictionComesToRest) {
  const Rest r = dropGrains(1, 1.5);
  EXPECT_LT(r.largestLate, 1e-12 * r.peak);
}

TEST(RestingGrains, FourTouchingDentedGrainsComeToRest) {
  const Rest r = dropGrains(4, 1.5);
  EXPECT_LT(r.largestLate, 1e-12 * r.peak);
}

}  // namespace
