// TriangleBvh: the query equals the loop over all triangles exactly (random query spheres,
// spheres grazing a triangle's sphere), on dented spheres and a big thin shell (a torus of the
// hopper's size, ~1500 triangles); it prunes (a small query visits a few leaves); and
// MeshContactFinder gives bit-identical contacts and statistics with and without the index.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "contact/MeshContact.h"
#include "geometry/DentedSphere.h"
#include "geometry/PrimitiveMeshes.h"
#include "geometry/RigidShape.h"
#include "geometry/TriangleBvh.h"

using namespace spacetree;
using geometry::RigidShape;
using Eigen::Quaterniond;
using Eigen::Vector3d;

namespace {

RigidShape dented(int triangles, double radius, std::uint64_t seed) {
  geometry::DentedSphereOptions o;
  o.triangles = triangles;
  o.radius = radius;
  o.amplitude = 0.2;
  o.seed = seed;
  return RigidShape::fromMesh(geometry::dentedSphere(o));
}

// Hopper-sized thin shell: 64 x 12 x 2 = 1536 triangles, 0.1 m across, 8 mm thick.
RigidShape shell() { return RigidShape::fromMesh(geometry::torusMesh(0.05, 0.004, 64, 12)); }

std::vector<int> bruteForce(const RigidShape& s, const Vector3d& q, double radius) {
  std::vector<int> out;
  for (std::size_t i = 0; i < s.triangleCount(); ++i) {
    const double reach = s.triangleRadii[i] + radius;
    if ((s.triangleCentres[i] - q).squaredNorm() < reach * reach) out.push_back(int(i));
  }
  return out;
}

Vector3d randomUnit(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  Vector3d v(g(rng), g(rng), g(rng));
  return v.normalized();
}

void expectQueryEqualsBruteForce(const RigidShape& s, std::uint64_t seed) {
  ASSERT_EQ(s.triangleIndex.size(), s.triangleCount());
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<int> result;
  std::size_t nonEmpty = 0, partial = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const Vector3d q = randomUnit(rng) * s.boundingRadius * 1.5 * u(rng);
    const double radius = s.boundingRadius * std::pow(10.0, -3.0 + 3.3 * u(rng));
    s.triangleIndex.query(q, radius, result);
    const std::vector<int> expected = bruteForce(s, q, radius);
    ASSERT_EQ(result, expected) << "trial " << trial;
    nonEmpty += !expected.empty();
    partial += !expected.empty() && expected.size() < s.triangleCount();
  }
  EXPECT_GT(partial, 400u);  // the random queries do cut through the shape
  // Grazing queries: radius just at / just above |c_i - q| - r_i for a random triangle i.
  for (int trial = 0; trial < 2000; ++trial) {
    const std::size_t i = std::size_t(rng() % s.triangleCount());
    const Vector3d q = s.triangleCentres[i] +
                       randomUnit(rng) * (s.triangleRadii[i] * 1.001 + s.boundingRadius * 0.3 * u(rng));
    double radius = (s.triangleCentres[i] - q).norm() - s.triangleRadii[i];
    if (trial % 2) radius = std::nextafter(radius, 1e300);
    s.triangleIndex.query(q, radius, result);
    ASSERT_EQ(result, bruteForce(s, q, radius)) << "grazing trial " << trial;
  }
}

}  // namespace

TEST(TriangleBvh, QueryEqualsBruteForceOnDentedSpheres) {
  for (int triangles : {12, 40, 80, 320, 1000}) {
    SCOPED_TRACE(triangles);
    expectQueryEqualsBruteForce(dented(triangles, 0.0025, 7 + triangles), 11u + triangles);
  }
}

TEST(TriangleBvh, QueryEqualsBruteForceOnHopperSizedShell) {
  const RigidShape s = shell();
  ASSERT_EQ(s.triangleCount(), 1536u);
  expectQueryEqualsBruteForce(s, 5);
}

TEST(TriangleBvh, GrainSizedQueryVisitsFewTriangles) {
  const RigidShape s = shell();
  std::mt19937_64 rng(3);
  std::size_t worst = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const std::size_t i = std::size_t(rng() % s.triangleCount());
    std::size_t visited = 0;
    s.triangleIndex.forEachCandidate(s.triangleCentres[i], 0.003, [&](int) { ++visited; });
    worst = std::max(worst, visited);
  }
  EXPECT_LT(worst, s.triangleCount() / 10);  // a 3 mm query touches a few leaves of 1536
  EXPECT_GT(worst, 0u);
}

TEST(TriangleBvh, RejectsMismatchedInput) {
  EXPECT_THROW(geometry::TriangleBvh({Vector3d::Zero()}, {}), std::invalid_argument);
  const geometry::TriangleBvh empty({}, {});
  std::vector<int> out{1};
  empty.query(Vector3d::Zero(), 1.0, out);
  EXPECT_TRUE(out.empty());
}

namespace {

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
bool sameBits(const Vector3d& a, const Vector3d& b) {
  return sameBits(a.x(), b.x()) && sameBits(a.y(), b.y()) && sameBits(a.z(), b.z());
}

}  // namespace

// A grain placed at random just outside (or slightly into the halo of) a random triangle of the
// shell, randomly oriented; both orders of the bodies; every method.
TEST(TriangleBvh, MeshContactIdenticalWithAndWithoutIndex) {
  const RigidShape big = shell();
  const RigidShape grain = dented(40, 0.0025, 9);
  const RigidShape bigGrain = dented(320, 0.0025, 10);  // >= kTriangleIndexMinimum: indexed too
  const double eps = 5e-5;
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::size_t contacts = 0, pairsWithContacts = 0;
  for (auto method : {contact::TriangleDistanceMethod::Exact,
                      contact::TriangleDistanceMethod::Hybrid}) {
    contact::MeshContactOptions on;
    on.epsilon = eps;
    on.method = method;
    contact::MeshContactOptions off = on;
    off.triangleIndex = false;
    contact::MeshContactFinder withIndex(on), without(off);
    for (int trial = 0; trial < 600; ++trial) {
      const RigidShape& small = trial % 3 == 2 ? bigGrain : grain;
      const contact::Pose bigPose{Vector3d(0.01, -0.02, 0.07),
                         Quaterniond(Eigen::AngleAxisd(2 * M_PI * u(rng), randomUnit(rng)))};
      const std::size_t t = std::size_t(rng() % big.triangleCount());
      const geometry::Triangle& tri = big.bodyTriangles[t];
      const Vector3d normal = (tri[1] - tri[0]).cross(tri[2] - tri[0]).normalized();
      const double offset = small.boundingRadius * (0.6 + 0.45 * u(rng));
      const Vector3d local = big.triangleCentres[t] + offset * normal;
      const contact::Pose smallPose{
          bigPose.orientation * local + bigPose.position,
          Quaterniond(Eigen::AngleAxisd(2 * M_PI * u(rng), randomUnit(rng)))};
      for (bool bigFirst : {true, false}) {
        std::vector<contact::ContactPoint> a, b;
        contact::MeshContactStatistics sa, sb;
        if (bigFirst) {
          withIndex.find(big, bigPose, small, smallPose, a, &sa);
          without.find(big, bigPose, small, smallPose, b, &sb);
        } else {
          withIndex.find(small, smallPose, big, bigPose, a, &sa);
          without.find(small, smallPose, big, bigPose, b, &sb);
        }
        ASSERT_EQ(a.size(), b.size()) << "trial " << trial;
        for (std::size_t k = 0; k < a.size(); ++k) {
          EXPECT_TRUE(sameBits(a[k].point, b[k].point));
          EXPECT_TRUE(sameBits(a[k].normal, b[k].normal));
          EXPECT_TRUE(sameBits(a[k].distance, b[k].distance));
          EXPECT_TRUE(sameBits(a[k].penetration, b[k].penetration));
          EXPECT_EQ(a[k].firstTriangle, b[k].firstTriangle);
          EXPECT_EQ(a[k].secondTriangle, b[k].secondTriangle);
          EXPECT_EQ(a[k].mergedCount, b[k].mergedCount);
        }
        EXPECT_EQ(sa.trianglePairsChecked, sb.trianglePairsChecked);
        EXPECT_EQ(sa.trianglePairsPruned, sb.trianglePairsPruned);
        EXPECT_EQ(sa.rawContacts, sb.rawContacts);
        EXPECT_EQ(sa.nonMinimumContacts, sb.nonMinimumContacts);
        EXPECT_EQ(sa.fallbacks, sb.fallbacks);
        contacts += a.size();
        pairsWithContacts += !a.empty();
      }
    }
  }
  EXPECT_GT(pairsWithContacts, 200u);  // the placements do produce contacts
  EXPECT_GT(contacts, pairsWithContacts);
}
