// Contacts of two posed rigid shapes: the epsilon convention (point, normal, penetration) on
// cube face-face and vertex-face configurations, de-duplication, d = 0 normals, the prechecks
// and pruning, frame covariance, exchange of the bodies, and the three distance methods.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <vector>

#include "contact/MeshContact.h"
#include "geometry/DentedSphere.h"
#include "geometry/MeshValidation.h"
#include "geometry/PrimitiveMeshes.h"
#include "geometry/RigidShape.h"

using namespace spacetree;
using namespace spacetree::contact;
using geometry::RigidShape;
using Eigen::Quaterniond;
using Eigen::Vector3d;

namespace {

RigidShape unitCube() { return RigidShape::fromMesh(geometry::boxMesh(Vector3d(1, 1, 1))); }

// Orientation that turns the cube's corner (+1,+1,+1)/2 onto +x: its vertex then points at a
// body on the +x side, at distance sqrt(3)/2 from the centre.
Quaterniond cornerAlongX() {
  return Quaterniond::FromTwoVectors(Vector3d(1, 1, 1).normalized(), Vector3d::UnitX());
}

const double kEps = 0.01;

MeshContactOptions optionsFor(TriangleDistanceMethod method) {
  MeshContactOptions o;
  o.epsilon = kEps;
  o.method = method;
  return o;
}

TEST(MeshContact, VertexOnFaceGivesOneContactWithThePapersConvention) {
  const RigidShape cube = unitCube();
  const double gap = 0.006;  // < 2 eps
  const Pose a{Vector3d(0.1, -0.2, 0.3), cornerAlongX()};
  const Pose b{a.position + Vector3d(std::sqrt(3.0) / 2 + 0.5 + gap, 0.0, 0.0), Quaterniond::Identity()};
  for (auto method : {TriangleDistanceMethod::Exact, TriangleDistanceMethod::Penalty,
                      TriangleDistanceMethod::Hybrid}) {
    MeshContactFinder finder(optionsFor(method));
    std::vector<ContactPoint> contacts;
    MeshContactStatistics stats;
    ASSERT_EQ(finder.find(cube, a, cube, b, contacts, &stats), 1u) << triangleDistanceMethodName(method);
    const ContactPoint& c = contacts[0];
    const Vector3d vertex = a.position + Vector3d(std::sqrt(3.0) / 2, 0, 0);
    EXPECT_LT((c.point - (vertex + Vector3d(gap / 2, 0, 0))).norm(), 1e-9);
    EXPECT_LT((c.normal - Vector3d::UnitX()).norm(), 1e-9);
    EXPECT_NEAR(c.distance, gap, 1e-9);
    EXPECT_NEAR(c.penetration, kEps - gap / 2, 1e-9);
    // Three faces (six triangles) meet at the vertex; the foot lies on the face's diagonal,
    // shared by its two triangles: duplicates merged into one.
    EXPECT_GE(c.mergedCount, 3);
    EXPECT_EQ(stats.rawContacts, std::size_t(c.mergedCount));
    EXPECT_GT(stats.trianglePairsPruned, 0u);
    EXPECT_EQ(stats.trianglePairsChecked + stats.trianglePairsPruned, 144u);
  }
  // Without de-duplication every triangle pair is its own contact.
  MeshContactOptions raw = optionsFor(TriangleDistanceMethod::Exact);
  raw.deduplicate = false;
  std::vector<ContactPoint> contacts;
  EXPECT_GE(MeshContactFinder(raw).find(cube, a, cube, b, contacts), 3u);
}

TEST(MeshContact, ExchangingTheBodiesFlipsTheNormal) {
  const RigidShape cube = unitCube();
  const Pose a{Vector3d::Zero(), cornerAlongX()};
  const Pose b{Vector3d(std::sqrt(3.0) / 2 + 0.5 + 0.004, 0.0, 0.0), Quaterniond::Identity()};
  MeshContactFinder finder(optionsFor(TriangleDistanceMethod::Hybrid));
  std::vector<ContactPoint> ab, ba;
  ASSERT_EQ(finder.find(cube, a, cube, b, ab), 1u);
  ASSERT_EQ(finder.find(cube, b, cube, a, ba), 1u);
  EXPECT_LT((ab[0].point - ba[0].point).norm(), 1e-12);
  EXPECT_LT((ab[0].normal + ba[0].normal).norm(), 1e-12);
  EXPECT_NEAR(ab[0].penetration, ba[0].penetration, 1e-12);
}

TEST(MeshContact, FaceOnFaceContactsAllCarryTheFaceNormalAndGap) {
  const RigidShape cube = unitCube();
  const double gap = 0.012;
  const Pose a{Vector3d::Zero(), Quaterniond::Identity()};
  const Pose b{Vector3d(1.0 + gap, 0.0, 0.0), Quaterniond::Identity()};
  MeshContactFinder finder(optionsFor(TriangleDistanceMethod::Exact));
  std::vector<ContactPoint> contacts;
  MeshContactStatistics stats;
  const std::size_t n = finder.find(cube, a, cube, b, contacts, &stats);
  ASSERT_GE(n, 1u);
  EXPECT_LT(n, stats.rawContacts);  // duplicates merged
  for (const ContactPoint& c : contacts) {
    EXPECT_LT((c.normal - Vector3d::UnitX()).norm(), 1e-12);
    EXPECT_NEAR(c.point.x(), 0.5 + gap / 2, 1e-12);
    EXPECT_NEAR(c.penetration, kEps - gap / 2, 1e-12);
    EXPECT_LE(std::abs(c.point.y()), 0.5 + 1e-12);
    EXPECT_LE(std::abs(c.point.z()), 0.5 + 1e-12);
  }
}

TEST(MeshContact, TouchingAndIntersectingTrianglesGetARobustNormal) {
  const RigidShape cube = unitCube();
  // Touching: d = 0 up to rounding, the segment has no direction.
  {
    const Pose a{Vector3d::Zero(), cornerAlongX()};
    const Pose b{Vector3d(std::sqrt(3.0) / 2 + 0.5, 0.0, 0.0), Quaterniond::Identity()};
    MeshContactFinder finder(optionsFor(TriangleDistanceMethod::Hybrid));
    std::vector<ContactPoint> contacts;
    ASSERT_EQ(finder.find(cube, a, cube, b, contacts), 1u);
    EXPECT_LT((contacts[0].normal - Vector3d::UnitX()).norm(), 1e-9);
    EXPECT_NEAR(contacts[0].penetration, kEps, 1e-14);
    EXPECT_LT(contacts[0].distance, 1e-14);
  }
  // Interpenetrated by 0.002 (beyond the halo model): every triangle pair that intersects
  // (d = 0) gets a normal from the triangle normals, pointing from the first body to the second.
  {
    const Pose a{Vector3d::Zero(), cornerAlongX()};
    const Pose b{Vector3d(std::sqrt(3.0) / 2 + 0.5 - 0.002, 0.0, 0.0), Quaterniond::Identity()};
    MeshContactOptions options = optionsFor(TriangleDistanceMethod::Hybrid);
    options.deduplicate = false;
    std::vector<ContactPoint> contacts;
    MeshContactFinder(options).find(cube, a, cube, b, contacts);
    int intersecting = 0;
    for (const ContactPoint& c : contacts)
      if (c.distance < 1e-12) {
        ++intersecting;
        EXPECT_NEAR(c.normal.norm(), 1.0, 1e-12);
        EXPECT_GT(c.normal.x(), 0.5);
        EXPECT_NEAR(c.penetration, kEps, 1e-12);
      }
    EXPECT_GE(intersecting, 3);
  }
}

TEST(MeshContact, PrechecksRejectFarAndHookedPairs) {
  const RigidShape cube = unitCube();
  MeshContactOptions options = optionsFor(TriangleDistanceMethod::Exact);
  MeshContactStatistics stats;
  std::vector<ContactPoint> contacts;
  const Pose a{};
  // Spheres apart: rejected before any triangle.
  MeshContactFinder(options).find(cube, a, cube, Pose{Vector3d(1.8, 0, 0), Quaterniond::Identity()}, contacts, &stats);
  EXPECT_EQ(stats.boundingSphereRejections, 1u);
  EXPECT_EQ(stats.trianglePairsChecked, 0u);
  EXPECT_FALSE(boundingSpheresWithinContactDistance(cube, a, cube, Pose{Vector3d(1.8, 0, 0), Quaterniond::Identity()}, kEps));
  // Spheres overlap but the faces are 2 eps + 0.001 apart: checked, no contact.
  stats = {};
  const Pose near{Vector3d(1.0 + 2 * kEps + 0.001, 0, 0), Quaterniond::Identity()};
  EXPECT_EQ(MeshContactFinder(options).find(cube, a, cube, near, contacts, &stats), 0u);
  EXPECT_GT(stats.trianglePairsChecked, 0u);
  // Hook: skipped, and it saw the bounding-sphere gap.
  double seenGap = 0.0;
  options.approachPrecheck = [&](const Pose&, const Pose&, double gap) {
    seenGap = gap;
    return false;
  };
  stats = {};
  const Pose touching{Vector3d(1.005, 0, 0), Quaterniond::Identity()};
  EXPECT_EQ(MeshContactFinder(options).find(cube, a, cube, touching, contacts, &stats), 0u);
  EXPECT_EQ(stats.approachRejections, 1u);
  EXPECT_NEAR(seenGap, 1.005 - std::sqrt(3.0), 1e-12);
  EXPECT_TRUE(contacts.empty());
  options.epsilon = 0.0;
  EXPECT_THROW(MeshContactFinder(options).find(cube, a, cube, touching, contacts), std::invalid_argument);
}

TEST(MeshContact, ContactsMoveWithARigidMotionOfTheScene) {
  geometry::DentedSphereOptions d;
  d.triangles = 160;
  d.amplitude = 0.2;
  geometry::TriangleMesh mesh = geometry::dentedSphere(d);
  geometry::validateMesh(mesh, "dented");
  const RigidShape grain = RigidShape::fromMesh(mesh);
  const Pose a{Vector3d(0.1, 0.0, 0.0), Quaterniond(Eigen::AngleAxisd(0.3, Vector3d::UnitZ()))};
  Pose b{Vector3d(0.0, 0.0, 0.0), Quaterniond(Eigen::AngleAxisd(1.1, Vector3d(1, 2, 0).normalized()))};
  // Move b along x until the surfaces are within 2 eps (bisection on the contact count).
  MeshContactFinder finder(optionsFor(TriangleDistanceMethod::Exact));
  double lo = 0.5, hi = 3.0;
  std::vector<ContactPoint> contacts;
  for (int i = 0; i < 60; ++i) {
    b.position.x() = 0.5 * (lo + hi);
    contacts.clear();
    (finder.find(grain, a, grain, b, contacts) > 0 ? lo : hi) = b.position.x();
  }
  b.position.x() = lo - 0.5 * kEps;  // somewhat inside the contact range
  contacts.clear();
  ASSERT_GE(finder.find(grain, a, grain, b, contacts), 1u);

  const Quaterniond turn(Eigen::AngleAxisd(2.0, Vector3d(-1, 0.5, 0.25).normalized()));
  const Vector3d move(100.0, -50.0, 25.0);
  const Pose a2{turn * a.position + move, turn * a.orientation};
  const Pose b2{turn * b.position + move, turn * b.orientation};
  std::vector<ContactPoint> moved;
  ASSERT_EQ(finder.find(grain, a2, grain, b2, moved), contacts.size());
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    EXPECT_LT((moved[k].point - (turn * contacts[k].point + move)).norm(), 1e-9);
    EXPECT_LT((moved[k].normal - turn * contacts[k].normal).norm(), 1e-6);
    EXPECT_NEAR(moved[k].penetration, contacts[k].penetration, 1e-9);
  }
  // The hybrid method finds the same raw contacts (identical decisions by construction).
  MeshContactFinder hybrid(optionsFor(TriangleDistanceMethod::Hybrid));
  MeshContactStatistics exactStats, hybridStats;
  std::vector<ContactPoint> ce, ch;
  MeshContactFinder(optionsFor(TriangleDistanceMethod::Exact)).find(grain, a, grain, b, ce, &exactStats);
  hybrid.find(grain, a, grain, b, ch, &hybridStats);
  EXPECT_EQ(exactStats.rawContacts, hybridStats.rawContacts);
  ASSERT_EQ(ce.size(), ch.size());
  for (std::size_t k = 0; k < ce.size(); ++k) EXPECT_LT((ce[k].point - ch[k].point).norm(), 1e-9);
  EXPECT_GT(exactStats.trianglePairsPruned, exactStats.trianglePairsChecked);
}

TEST(MeshContact, OnlyLocalMinimaOfTheSurfaceDistanceCount) {
  // A cube corner resting next to the interior diagonal (x = y) of a flat floor face: the
  // pairs with the floor triangle across the diagonal have slanted edge-edge closest points.
  const RigidShape cube = unitCube();
  const RigidShape floorShape = RigidShape::fromMesh(geometry::boxMesh(Vector3d(10, 10, 1)));
  const Quaterniond q = Quaterniond::FromTwoVectors(Vector3d(-1, -1, -1).normalized(), -Vector3d::UnitZ());
  const Pose floor{Vector3d(0, 0, -0.5), Quaterniond::Identity()};
  const Pose grain{Vector3d(0.01, 0.005, std::sqrt(3.0) / 2 + kEps), q};
  MeshContactOptions options = optionsFor(TriangleDistanceMethod::Exact);
  options.deduplicate = false;
  std::vector<ContactPoint> filtered, all;
  MeshContactStatistics stats;
  MeshContactFinder(options).find(cube, grain, floorShape, floor, filtered, &stats);
  ASSERT_GE(filtered.size(), 3u);
  EXPECT_GT(stats.nonMinimumContacts, 0u);
  for (const ContactPoint& c : filtered) {
    EXPECT_LT((c.normal + Vector3d::UnitZ()).norm(), 1e-9);
    EXPECT_NEAR(c.penetration, kEps / 2, 1e-9);
  }
  options.localMinimaOnly = false;
  MeshContactFinder(options).find(cube, grain, floorShape, floor, all);
  EXPECT_EQ(all.size(), filtered.size() + stats.nonMinimumContacts);
  double largestTilt = 0.0;
  for (const ContactPoint& c : all) largestTilt = std::max(largestTilt, std::hypot(c.normal.x(), c.normal.y()));
  EXPECT_GT(largestTilt, 1e-3);
}

// A rail (a long square bar turned by 45 degrees about its axis: a ridge below) lying across a
// plate with a square top face and sides sloping down by 22 degrees (as a dented grain's faces
// meet): the ridge touches the top face along a segment that ends at the top face's border
// creases, x = -0.5 and 0.5, where neither body has a vertex. Whichever way the rail is tilted,
// it is held at both ends along the face normal (step 4b'). The triangle kernel gives one point
// per triangle pair, the lower end, and the other end's pairs (the rail's faces with the plate's
// sloping side) are not local minima under the tilt: held at one end, the rail tilted the other
// way and was then held at the other end only.
TEST(MeshContact, RidgeAcrossAFaceIsHeldAtBothEndsOfTheSegment) {
  const RigidShape rail = RigidShape::fromMesh(geometry::boxMesh(Vector3d(3.0, 0.2, 0.2)));
  geometry::TriangleMesh frustum = geometry::boxMesh(Vector3d(1.0, 1.0, 0.2));
  for (Vector3d& v : frustum.vertices)
    if (v.z() < 0.0) v.head<2>() *= 2.0;  // bottom 2 x 2, top 1 x 1
  const RigidShape plate = RigidShape::fromMesh(frustum);
  double top = -1e9, x0 = 0.0;
  for (const Vector3d& v : plate.bodyMesh.vertices) top = std::max(top, v.z());
  for (const Vector3d& v : plate.bodyMesh.vertices)
    if (v.z() == top) x0 += 0.25 * v.x();  // the top face's centre (its edges are 1 long)
  const Pose platePose{Vector3d::Zero(), Quaterniond::Identity()};
  const double gap = kEps;
  for (double tilt : {1e-5, -1e-5, 0.0}) {
    const Quaterniond q = Quaterniond(Eigen::AngleAxisd(tilt, Vector3d::UnitY())) *
                          Quaterniond(Eigen::AngleAxisd(M_PI / 4, Vector3d::UnitX()));
    const Pose railPose{Vector3d(x0, 0.13, top + 0.1 * std::sqrt(2.0) + gap), q};
    std::vector<ContactPoint> contacts;
    MeshContactFinder(optionsFor(TriangleDistanceMethod::Hybrid)).find(rail, railPose, plate, platePose, contacts);
    int ends[2] = {0, 0};
    for (const ContactPoint& c : contacts) {
      EXPECT_LT((c.normal + Vector3d::UnitZ()).norm(), 1e-4) << tilt;  // rail -> plate: down
      EXPECT_NEAR(c.penetration, kEps - gap / 2, 1e-5) << tilt;
      for (int e = 0; e < 2; ++e)
        if (std::abs(c.point.x() - x0 - (e ? 0.5 : -0.5)) < 1e-4 && std::abs(c.point.y() - 0.13) < 1e-4) ++ends[e];
    }
    EXPECT_EQ(ends[0], 1) << "tilt " << tilt;
    EXPECT_EQ(ends[1], 1) << "tilt " << tilt;
  }
}

TEST(MeshContact, MethodNamesParse) {
  EXPECT_EQ(parseTriangleDistanceMethod("exact"), TriangleDistanceMethod::Exact);
  EXPECT_EQ(parseTriangleDistanceMethod("penalty"), TriangleDistanceMethod::Penalty);
  EXPECT_EQ(parseTriangleDistanceMethod("hybrid"), TriangleDistanceMethod::Hybrid);
  EXPECT_STREQ(triangleDistanceMethodName(TriangleDistanceMethod::Penalty), "penalty");
  EXPECT_THROW(parseTriangleDistanceMethod("fast"), std::invalid_argument);
}

}  // namespace
