// The contact search with the two-stage hybrid (MeshContactOptions::continuationIterations,
// the default of method Hybrid): the triangle pairs that stage 1 leaves uncertified continue
// more Newton steps before the exact fallback. On dented-grain pairs at contact distance (the
// hopper's kind of scene) and the cube scenes of test_mesh_contact.cpp: stage 2 runs and takes
// pairs off the fallback, and the contacts are those of the exact method.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "contact/MeshContact.h"
#include "geometry/DentedSphere.h"
#include "geometry/PenaltyTriangleDistance.h"
#include "geometry/PrimitiveMeshes.h"
#include "geometry/RigidShape.h"

using namespace spacetree;
using namespace spacetree::contact;
using geometry::RigidShape;
using Eigen::Quaterniond;
using Eigen::Vector3d;

namespace {

const double kEps = 0.01;

MeshContactOptions optionsFor(TriangleDistanceMethod method) {
  MeshContactOptions o;
  o.epsilon = kEps;
  o.method = method;
  return o;
}

struct Scene {
  const RigidShape* first;
  const RigidShape* second;
  Pose a, b;
};

// Pairs of one dented grain, randomly turned, the second moved along x to `inside` times eps
// within first contact (bisection on the exact contact count).
std::vector<Scene> grainScenes(const RigidShape& grain, int count, unsigned seed, double inside) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n;
  const auto turn = [&] { return Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized(); };
  MeshContactFinder exact(optionsFor(TriangleDistanceMethod::Exact));
  std::vector<Scene> scenes;
  std::vector<ContactPoint> contacts;
  for (int s = 0; s < count; ++s) {
    Scene scene{&grain, &grain, Pose{Vector3d::Zero(), turn()}, Pose{Vector3d::Zero(), turn()}};
    double lo = 0.5, hi = 3.0;
    for (int i = 0; i < 60; ++i) {
      scene.b.position.x() = 0.5 * (lo + hi);
      contacts.clear();
      (exact.find(grain, scene.a, grain, scene.b, contacts) > 0 ? lo : hi) = scene.b.position.x();
    }
    scene.b.position.x() = lo - inside * kEps;
    scenes.push_back(scene);
  }
  return scenes;
}

struct Outcome {
  std::vector<std::vector<ContactPoint>> contacts;  // per scene
  MeshContactStatistics stats;
};

Outcome run(const MeshContactOptions& options, const std::vector<Scene>& scenes) {
  MeshContactFinder finder(options);
  Outcome out;
  for (const Scene& s : scenes) {
    out.contacts.emplace_back();
    finder.find(*s.first, s.a, *s.second, s.b, out.contacts.back(), &out.stats);
  }
  return out;
}

// Same contacts (count, triangles, point, normal, distance) scene by scene.
void expectSameContacts(const Outcome& exact, const Outcome& other, const char* what) {
  ASSERT_EQ(exact.contacts.size(), other.contacts.size());
  EXPECT_EQ(exact.stats.rawContacts, other.stats.rawContacts) << what;
  EXPECT_EQ(exact.stats.nonMinimumContacts, other.stats.nonMinimumContacts) << what;
  for (std::size_t s = 0; s < exact.contacts.size(); ++s) {
    const auto& e = exact.contacts[s];
    const auto& o = other.contacts[s];
    ASSERT_EQ(e.size(), o.size()) << what << ", scene " << s;
    for (std::size_t k = 0; k < e.size(); ++k) {
      EXPECT_EQ(e[k].firstTriangle, o[k].firstTriangle) << what << ", scene " << s;
      EXPECT_EQ(e[k].secondTriangle, o[k].secondTriangle) << what << ", scene " << s;
      EXPECT_EQ(e[k].mergedCount, o[k].mergedCount) << what << ", scene " << s;
      EXPECT_LT((e[k].point - o[k].point).norm(), 1e-9) << what << ", scene " << s;
      EXPECT_LT((e[k].normal - o[k].normal).norm(), 1e-6) << what << ", scene " << s;
      EXPECT_NEAR(e[k].distance, o[k].distance, 1e-9) << what << ", scene " << s;
    }
  }
}

TEST(MeshContactTwoStage, DefaultScheduleIsTheCoresTwoStageHybrid) {
  MeshContactOptions o = optionsFor(TriangleDistanceMethod::Hybrid);
  const geometry::HybridOptions core;
  EXPECT_EQ(newtonIterationsOf(o), core.newtonIterations);
  EXPECT_EQ(continuationIterationsOf(o), core.continuationIterations);
  EXPECT_GT(continuationIterationsOf(o), 0);
  o.method = TriangleDistanceMethod::Penalty;
  EXPECT_EQ(newtonIterationsOf(o), geometry::PenaltyOptions{}.newtonIterations);
  EXPECT_EQ(continuationIterationsOf(o), 0);  // stage 2 belongs to the hybrid only
  o.method = TriangleDistanceMethod::Exact;
  EXPECT_EQ(newtonIterationsOf(o), 0);
  o.method = TriangleDistanceMethod::Hybrid;
  o.newtonIterations = 8;
  o.continuationIterations = 0;
  EXPECT_EQ(newtonIterationsOf(o), 8);
  EXPECT_EQ(continuationIterationsOf(o), 0);
}

TEST(MeshContactTwoStage, RejectsBadStepCounts) {
  MeshContactOptions o = optionsFor(TriangleDistanceMethod::Hybrid);
  o.continuationIterations = -1;
  EXPECT_THROW(MeshContactFinder{o}, std::invalid_argument);
  o.continuationIterations = 4;
  o.newtonIterations = -2;
  EXPECT_THROW(MeshContactFinder{o}, std::invalid_argument);
  o.newtonIterations = geometry::kMaxNewtonIterations - 4;
  EXPECT_NO_THROW(MeshContactFinder{o});
  o.newtonIterations += 1;  // 29 + 4 > 32
  EXPECT_THROW(MeshContactFinder{o}, std::invalid_argument);
  o.method = TriangleDistanceMethod::Penalty;  // the continuation does not count for penalty
  EXPECT_NO_THROW(MeshContactFinder{o});
  o.newtonIterations = geometry::kMaxNewtonIterations + 1;
  EXPECT_THROW(MeshContactFinder{o}, std::invalid_argument);
}

TEST(MeshContactTwoStage, DentedGrainsStageTwoRunsAndContactsEqualExact) {
  for (int triangles : {40, 160}) {
    geometry::DentedSphereOptions d;
    d.triangles = triangles;
    d.amplitude = 0.2;
    d.seed = 7;
    const RigidShape grain = RigidShape::fromMesh(geometry::dentedSphere(d));
    std::vector<Scene> scenes = grainScenes(grain, 12, 11u + unsigned(triangles), 0.5);
    const std::vector<Scene> deeper = grainScenes(grain, 12, 23u + unsigned(triangles), 1.5);
    scenes.insert(scenes.end(), deeper.begin(), deeper.end());

    const Outcome exact = run(optionsFor(TriangleDistanceMethod::Exact), scenes);
    const Outcome twoStage = run(optionsFor(TriangleDistanceMethod::Hybrid), scenes);
    MeshContactOptions single = optionsFor(TriangleDistanceMethod::Hybrid);
    single.newtonIterations = newtonIterationsOf(single);
    single.continuationIterations = 0;
    const Outcome oneStage = run(single, scenes);
    const std::string what = std::to_string(triangles) + " triangles";
    SCOPED_TRACE(what);

    ASSERT_GT(exact.stats.contacts, scenes.size() / 2);
    expectSameContacts(exact, twoStage, "two-stage hybrid");
    expectSameContacts(exact, oneStage, "single-stage hybrid");
    // Stage 2 ran, and it certified pairs that the single stage (same stage 1) sends to the
    // exact method: the continuation is applied, not ignored.
    EXPECT_EQ(oneStage.stats.continued, 0u);
    EXPECT_GT(twoStage.stats.continued, 0u);
    EXPECT_LT(twoStage.stats.fallbacks, oneStage.stats.fallbacks);
    EXPECT_LE(twoStage.stats.fallbacks, twoStage.stats.continued + oneStage.stats.fallbacks);
    std::printf("%s: %zu triangle pairs, single stage %zu fallbacks, two-stage %zu continued, "
                "%zu fallbacks\n", what.c_str(), twoStage.stats.trianglePairsChecked,
                oneStage.stats.fallbacks, twoStage.stats.continued, twoStage.stats.fallbacks);
  }
}

TEST(MeshContactTwoStage, CubeScenesDecisionsAndContactsEqualExact) {
  // The cube scenes of test_mesh_contact.cpp: vertex on face, edge on edge, face on face (with a
  // gap, slightly turned, touching). Every triangle pair decides as exact's, with its distance
  // and normal (raw contacts: no filter, no merging). Parallel faces have no unique closest
  // points (either method may return any point of the overlap, so the merged contacts may
  // differ, and so may the feature normal of touching faces, d = 0); the other scenes have, and
  // give exact's contacts.
  const RigidShape cube = RigidShape::fromMesh(geometry::boxMesh(Vector3d(1, 1, 1)));
  const Quaterniond corner = Quaterniond::FromTwoVectors(Vector3d(1, 1, 1).normalized(), Vector3d::UnitX());
  const Quaterniond edge(Eigen::AngleAxisd(M_PI / 4, Vector3d::UnitZ()));
  const Quaterniond edgeAcross = Quaterniond(Eigen::AngleAxisd(M_PI / 2, Vector3d::UnitX())) * edge;
  const Quaterniond tilt(Eigen::AngleAxisd(0.004, Vector3d(0, 1, 1).normalized()));
  const Vector3d o(0.1, -0.2, 0.3);
  const std::vector<Scene> unique = {
      {&cube, &cube, {o, corner}, {o + Vector3d(std::sqrt(3.0) / 2 + 0.5 + 0.006, 0, 0), Quaterniond::Identity()}},
      {&cube, &cube, {o, edge}, {o + Vector3d(std::sqrt(2.0) + 0.015, 0.0, 0.0), edgeAcross}},
  };
  const std::vector<Scene> faces = {
      {&cube, &cube, {o, Quaterniond::Identity()}, {o + Vector3d(1.0 + 0.012, 0.3, -0.1), Quaterniond::Identity()}},
      {&cube, &cube, {o, Quaterniond::Identity()}, {o + Vector3d(1.0 + 0.01, 0.2, 0.1), tilt}},
      {&cube, &cube, {o, Quaterniond::Identity()}, {o + Vector3d(1.0, 0.25, 0.25), Quaterniond::Identity()}},
  };
  std::vector<Scene> all = unique;
  all.insert(all.end(), faces.begin(), faces.end());

  MeshContactOptions exactRaw = optionsFor(TriangleDistanceMethod::Exact);
  exactRaw.deduplicate = exactRaw.localMinimaOnly = false;
  MeshContactOptions hybridRaw = exactRaw;
  hybridRaw.method = TriangleDistanceMethod::Hybrid;
  const Outcome e = run(exactRaw, all), h = run(hybridRaw, all);
  for (std::size_t s = 0; s < all.size(); ++s) {
    ASSERT_GE(e.contacts[s].size(), 1u) << "scene " << s;
    ASSERT_EQ(e.contacts[s].size(), h.contacts[s].size()) << "scene " << s;
    for (std::size_t k = 0; k < e.contacts[s].size(); ++k) {
      const ContactPoint &a = e.contacts[s][k], &b = h.contacts[s][k];
      EXPECT_EQ(a.firstTriangle, b.firstTriangle) << "scene " << s;
      EXPECT_EQ(a.secondTriangle, b.secondTriangle) << "scene " << s;
      EXPECT_NEAR(a.distance, b.distance, 1e-9) << "scene " << s;
      // at d = 0 the normal comes from the contact features, not unique for touching faces
      if (a.distance > 1e-9) {
        EXPECT_LT((a.normal - b.normal).norm(), 1e-6) << "scene " << s;
      }
    }
  }
  expectSameContacts(run(optionsFor(TriangleDistanceMethod::Exact), unique),
                     run(optionsFor(TriangleDistanceMethod::Hybrid), unique), "two-stage hybrid");
}

}  // namespace
