// Contacts of a sphere with a posed triangulated body (SphereMeshContact.h): the epsilon
// convention on a cube's face, edge and vertex, the local-minimum filter near an edge, inner
// corners (three contacts), the prechecks, the triangle index (same contacts as the loop), frame
// covariance, and the deepest contact against a brute-force closest distance on dented spheres.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "contact/SphereMeshContact.h"
#include "geometry/DentedSphere.h"
#include "geometry/PointTriangleDistance.h"
#include "geometry/PrimitiveMeshes.h"
#include "geometry/RigidShape.h"

using namespace spacetree;
using namespace spacetree::contact;
using geometry::RigidShape;
using Eigen::Quaterniond;
using Eigen::Vector3d;

namespace {

const double kEps = 0.01;

MeshContactOptions options() {
  MeshContactOptions o;
  o.epsilon = kEps;
  return o;
}

// A cube of edge 1 placed as its mesh is (faces on x, y, z = +-0.5).
struct PlacedCube {
  RigidShape shape = RigidShape::fromMesh(geometry::boxMesh(Vector3d(1, 1, 1)));
  Pose pose{shape.centreOfMassInMesh, shape.bodyOrientationFor()};
};

std::vector<ContactPoint> contactsOf(const RigidShape& body, const Pose& pose, const Vector3d& c,
                                     double r, MeshContactOptions o = options(),
                                     MeshContactStatistics* stats = nullptr) {
  std::vector<ContactPoint> contacts;
  SphereMeshContactFinder(o).find(body, pose, c, r, contacts, stats);
  return contacts;
}

TEST(SphereMeshContact, FaceContactFollowsTheHaloConvention) {
  const PlacedCube cube;
  const double r = 0.2, d = 0.012;  // core radius r - eps, surface distance d < 2 eps
  const Vector3d c(0.1, -0.15, 0.5 + (r - kEps) + d);
  MeshContactStatistics stats;
  const auto contacts = contactsOf(cube.shape, cube.pose, c, r, options(), &stats);
  ASSERT_EQ(contacts.size(), 1u);
  EXPECT_LT((contacts[0].normal - Vector3d::UnitZ()).norm(), 1e-12);
  EXPECT_NEAR(contacts[0].distance, d, 1e-12);
  EXPECT_NEAR(contacts[0].penetration, kEps - d / 2, 1e-12);
  EXPECT_LT((contacts[0].point - Vector3d(0.1, -0.15, 0.5 + d / 2)).norm(), 1e-12);
  EXPECT_EQ(contacts[0].secondTriangle, -1);
  EXPECT_EQ(stats.contacts, 1u);
  // Just out of reach (d = 2 eps): none; just inside: one.
  EXPECT_TRUE(contactsOf(cube.shape, cube.pose, c + Vector3d(0, 0, 2 * kEps - d + 1e-9), r).empty());
  EXPECT_EQ(contactsOf(cube.shape, cube.pose, c + Vector3d(0, 0, 2 * kEps - d - 1e-9), r).size(), 1u);
}

TEST(SphereMeshContact, EdgeAndVertexGiveOneContactAlongTheRadialDirection) {
  const PlacedCube cube;
  const double r = 0.3, d = 0.008;
  const double reachOut = r - kEps + d;
  struct Case { Vector3d foot, direction; int mergedAtLeast; };
  const Case cases[] = {
      {Vector3d(0.5, 0.1, 0.5), Vector3d(1, 0, 1).normalized(), 2},      // edge of two faces
      {Vector3d(0.5, 0.5, 0.5), Vector3d(1, 1, 1).normalized(), 3},      // corner of three
  };
  for (const Case& k : cases) {
    const auto contacts = contactsOf(cube.shape, cube.pose, k.foot + reachOut * k.direction, r);
    ASSERT_EQ(contacts.size(), 1u);
    EXPECT_LT((contacts[0].normal - k.direction).norm(), 1e-12);
    EXPECT_NEAR(contacts[0].penetration, kEps - d / 2, 1e-12);
    EXPECT_LT((contacts[0].point - (k.foot + d / 2 * k.direction)).norm(), 1e-12);
    EXPECT_GE(contacts[0].mergedCount, k.mergedAtLeast);
  }
}

TEST(SphereMeshContact, OnlyTheLocalMinimumNearAnEdgeCounts) {
  // Above the top face, 0.02 from its edge x = 0.5: the side face's closest point is on the
  // edge and within reach, but the top face descends towards the centre from there.
  const PlacedCube cube;
  const double r = 0.3, d = 0.004;
  const Vector3d c(0.48, 0.0, 0.5 + r - kEps + d);
  MeshContactStatistics stats;
  const auto filtered = contactsOf(cube.shape, cube.pose, c, r, options(), &stats);
  ASSERT_EQ(filtered.size(), 1u);
  EXPECT_LT((filtered[0].normal - Vector3d::UnitZ()).norm(), 1e-12);
  EXPECT_NEAR(filtered[0].penetration, kEps - d / 2, 1e-12);
  EXPECT_GT(stats.nonMinimumContacts, 0u);
  // Without the filter the edge contact is merged in and tilts the normal.
  MeshContactOptions all = options();
  all.localMinimaOnly = false;
  const auto unfiltered = contactsOf(cube.shape, cube.pose, c, r, all);
  ASSERT_EQ(unfiltered.size(), 1u);
  EXPECT_GT(std::abs(unfiltered[0].normal.x()), 1e-3);
}

TEST(SphereMeshContact, InsideACornerOfAHollowBodyThreeContactsPushInwards) {
  // A sphere inside the cube near the corner (+,+,+): the three faces' inner sides.
  const PlacedCube cube;
  const double r = 0.1, d = 0.005;
  const double off = 0.5 - (r - kEps) - d;
  const auto contacts = contactsOf(cube.shape, cube.pose, Vector3d(off, off, off), r);
  ASSERT_EQ(contacts.size(), 3u);
  for (const ContactPoint& c : contacts) {
    EXPECT_NEAR(c.penetration, kEps - d / 2, 1e-12);
    EXPECT_NEAR(c.normal.minCoeff(), -1.0, 1e-12);  // along -x, -y or -z: into the cavity
    EXPECT_NEAR(c.normal.norm(), 1.0, 1e-12);
  }
}

TEST(SphereMeshContact, PrechecksAndBadArguments) {
  const PlacedCube cube;
  MeshContactStatistics stats;
  EXPECT_TRUE(contactsOf(cube.shape, cube.pose, Vector3d(5, 0, 0), 0.1, options(), &stats).empty());
  EXPECT_EQ(stats.boundingSphereRejections, 1u);
  // Inside the bounding sphere (radius sqrt(3)/2) but clear of the box.
  stats = MeshContactStatistics();
  EXPECT_TRUE(contactsOf(cube.shape, cube.pose, Vector3d(0.8, 0, 0), 0.1, options(), &stats).empty());
  EXPECT_EQ(stats.boundingBoxRejections, 1u);
  std::vector<ContactPoint> contacts;
  EXPECT_THROW(SphereMeshContactFinder(options()).find(cube.shape, cube.pose, Vector3d(0, 0, 1),
                                                        kEps, contacts),
               std::invalid_argument);
  MeshContactOptions none = options();
  none.epsilon = 0.0;
  EXPECT_THROW(SphereMeshContactFinder(none).find(cube.shape, cube.pose, Vector3d(0, 0, 1), 0.1,
                                                   contacts),
               std::invalid_argument);
}

// Deepest contact = brute-force closest distance over all triangles; a contact exactly when that
// distance is below 2 eps; the index and the culls change nothing; the scene's rigid motion
// moves the contacts with it.
TEST(SphereMeshContact, AgreesWithBruteForceOnDentedSpheres) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int withContact = 0, checked = 0;
  for (int shapeSeed = 1; shapeSeed <= 4; ++shapeSeed) {
    geometry::DentedSphereOptions o;
    o.triangles = shapeSeed % 2 ? 80 : 320;  // 320: indexed
    o.amplitude = 0.3;
    o.seed = std::uint64_t(shapeSeed);
    const RigidShape body = RigidShape::fromMesh(geometry::dentedSphere(o));
    for (int trial = 0; trial < 300; ++trial) {
      const Pose pose{Vector3d(unit(rng), unit(rng), unit(rng)),
                      Quaterniond(unit(rng), unit(rng), unit(rng), unit(rng)).normalized()};
      const double r = 0.05 + 0.3 * (unit(rng) + 1.0);
      const Vector3d dir = Vector3d(unit(rng), unit(rng), unit(rng)).normalized();
      // Centre at about the body's surface distance + core radius + [-eps, 3 eps].
      const Vector3d c = pose.position + dir * (body.boundingRadius * (0.6 + 0.4 * (unit(rng) + 1) / 2) + r);
      double closest = std::numeric_limits<double>::infinity();
      const Vector3d cb = pose.orientation.conjugate() * (c - pose.position);
      for (const auto& t : body.bodyTriangles)
        closest = std::min(closest, std::sqrt(geometry::pointTriangleSquaredDistance(cb, t)));
      const double d = closest - (r - kEps);
      MeshContactStatistics stats;
      const auto contacts = contactsOf(body, pose, c, r, options(), &stats);
      ++checked;
      EXPECT_EQ(!contacts.empty(), d < 2 * kEps) << "seed " << shapeSeed << " trial " << trial;
      if (contacts.empty()) continue;
      ++withContact;
      double deepest = 0.0;
      for (const ContactPoint& k : contacts) deepest = std::max(deepest, k.penetration);
      // de-duplication averages penetrations of merged contacts: the deepest is at most eps - d/2
      EXPECT_LE(deepest, kEps - d / 2 + 1e-12);
      MeshContactOptions reference = options();
      reference.triangleIndex = false;
      reference.triangleCulling = false;
      const auto plain = contactsOf(body, pose, c, r, reference);
      ASSERT_EQ(plain.size(), contacts.size());
      for (std::size_t k = 0; k < plain.size(); ++k) {
        EXPECT_EQ(plain[k].point, contacts[k].point);
        EXPECT_EQ(plain[k].normal, contacts[k].normal);
        EXPECT_EQ(plain[k].penetration, contacts[k].penetration);
      }
      // A rigid motion of the scene moves the contacts.
      const Quaterniond q = Quaterniond(0.3, -0.2, 0.9, 0.1).normalized();
      const Vector3d shift(0.4, -1.3, 2.2);
      const Pose moved{q * pose.position + shift, q * pose.orientation};
      const auto movedContacts = contactsOf(body, moved, q * c + shift, r);
      ASSERT_EQ(movedContacts.size(), contacts.size());
      for (std::size_t k = 0; k < contacts.size(); ++k) {
        EXPECT_LT((movedContacts[k].point - (q * contacts[k].point + shift)).norm(), 1e-12);
        EXPECT_LT((movedContacts[k].normal - q * contacts[k].normal).norm(), 1e-9);
        EXPECT_NEAR(movedContacts[k].penetration, contacts[k].penetration, 1e-12);
      }
    }
  }
  EXPECT_GT(withContact, checked / 10);  // the scenes do touch
}

}  // namespace
