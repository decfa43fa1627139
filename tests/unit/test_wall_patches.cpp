// Walls of a DEM deck for triangulated grains: a plane as a triangulated patch (WallPatches.h,
// RigidShape::fromSurface) meets a grain exactly as the top face of a box obstacle of the same
// surface, on either side; cylinder patches (the outer side) stay within their sagitta of the
// cylinder and close into a ring; inside a cylinder (CylinderWallContact.h) the contacts are the
// closest vertices, exactly.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <random>
#include <vector>

#include "contact/CylinderWallContact.h"
#include "contact/MeshContact.h"
#include "geometry/DentedSphere.h"
#include "geometry/PrimitiveMeshes.h"
#include "geometry/RigidShape.h"
#include "geometry/WallPatches.h"

using namespace spacetree;
using namespace spacetree::contact;
using geometry::RigidShape;
using Eigen::Quaterniond;
using Eigen::Vector3d;

namespace {

const double kEps = 1e-4;

RigidShape grain() {
  geometry::DentedSphereOptions o;
  o.triangles = 40;
  o.radius = 0.005;
  o.amplitude = 0.3;
  o.seed = 7;
  return RigidShape::fromMesh(geometry::dentedSphere(o));
}

MeshContactOptions options() {
  MeshContactOptions o;
  o.epsilon = kEps;
  return o;
}

TEST(WallPatches, PlanePatchMeetsAGrainAsABoxFloorDoes) {
  const RigidShape g = grain();
  const RigidShape patch = RigidShape::fromSurface(geometry::planeWallPatch(0.03));
  EXPECT_EQ(patch.triangleCount(), 2u);
  EXPECT_EQ(patch.volume, 0.0);
  // the diagonal is shared, the rim is not
  int shared = 0;
  for (const auto& e : patch.edgeApex)
    for (int a : e) shared += a >= 0;
  EXPECT_EQ(shared, 2);
  // a box floor whose top face is z = 0, as an obstacle placed as its mesh is
  const RigidShape box = RigidShape::fromMesh(geometry::boxMesh(Vector3d(0.06, 0.06, 0.01)));
  const Pose boxPose{Vector3d(0, 0, -0.005) + box.centreOfMassInMesh, box.bodyOrientationFor()};
  const Quaterniond q = Quaterniond(0.8, 0.3, -0.2, 0.4).normalized();
  // lowest vertex of the grain in this orientation
  double lowest = 1e9;
  for (const Vector3d& v : g.bodyMesh.vertices) lowest = std::min(lowest, (q * v).z());
  for (double gap : {0.5 * kEps, 1.5 * kEps, 2.5 * kEps}) {
    const Pose gp{Vector3d(0.001, -0.002, gap - lowest), q};
    MeshContactFinder finder(options());
    std::vector<ContactPoint> onPatch, onBox;
    const geometry::WallPatchPlacement place =
        geometry::WallPatchPlacement::onPlane(Vector3d::Zero(), Vector3d::UnitZ(), gp.position);
    EXPECT_LT((place.position - Vector3d(0.001, -0.002, 0)).norm(), 1e-15);
    finder.find(g, gp, patch, Pose{place.position, place.orientation}, onPatch);
    finder.find(g, gp, box, boxPose, onBox);
    ASSERT_EQ(onPatch.size(), onBox.size()) << gap;
    EXPECT_EQ(onPatch.empty(), gap >= 2 * kEps);
    for (std::size_t k = 0; k < onPatch.size(); ++k) {
      EXPECT_NEAR(onPatch[k].penetration, onBox[k].penetration, 1e-15);
      EXPECT_NEAR(onPatch[k].penetration, kEps - gap / 2, 1e-12);
      EXPECT_LT((onPatch[k].normal - Vector3d(0, 0, -1)).norm(), 1e-12);  // grain -> wall
    }
  }
  // below the plane the patch turns over: the same contact, mirrored
  const Pose below{Vector3d(0, 0, -(0.5 * kEps - lowest)), q * Quaterniond(0, 1, 0, 0)};
  const geometry::WallPatchPlacement flip =
      geometry::WallPatchPlacement::onPlane(Vector3d::Zero(), Vector3d::UnitZ(), below.position);
  EXPECT_LT((flip.orientation * Vector3d::UnitZ() - Vector3d(0, 0, -1)).norm(), 1e-15);
}

TEST(WallPatches, CylinderPatchesFollowTheCylinder) {
  const double R = 0.1, sag = 1e-7;
  for (double halfAngle : {0.2, 4.0}) {
    const geometry::TriangleMesh m = geometry::cylinderWallPatch(R, halfAngle, 0.01, sag);
    double worstOff = 0.0;
    for (std::size_t t = 0; t < m.triangleCount(); ++t) {
      const geometry::Triangle tri = m.triangle(t);
      for (const Vector3d& v : tri.vertex) EXPECT_NEAR(std::hypot(v.x(), v.y()), R, 1e-15);
      const Vector3d c = (tri[0] + tri[1] + tri[2]) / 3.0;
      const Vector3d n = m.areaVector(t).normalized();
      EXPECT_NEAR(n.dot(Vector3d(c.x(), c.y(), 0).normalized()), 1.0, 1e-6);  // away from the axis
      for (int k = 0; k < 3; ++k) {  // chord midpoints
        const Vector3d mid = 0.5 * (tri[k] + tri[(k + 1) % 3]);
        worstOff = std::max(worstOff, R - std::hypot(mid.x(), mid.y()));
      }
    }
    EXPECT_LE(worstOff, sag * (1 + 1e-6));
    EXPECT_GT(worstOff, 0.25 * sag);
    // the whole circle closes: only the two rims are open edges
    const RigidShape s = RigidShape::fromSurface(m);
    int open = 0;
    for (const auto& e : s.edgeApex)
      for (int a : e) open += a < 0;
    if (halfAngle > M_PI) EXPECT_EQ(open, int(m.triangleCount()));
  }
  EXPECT_THROW(geometry::cylinderWallPatch(R, 0.1, 0.01, R), std::invalid_argument);
  EXPECT_THROW(geometry::planeWallPatch(0.0), std::invalid_argument);
}

// Inside a cylinder the contacts are the vertices that are local minima of the gap R - rho:
// the deepest contact is the brute-force closest vertex; a contact exactly when a vertex is
// within 2 eps; normals radial; the wall's axis in any direction and position.
TEST(CylinderWallContact, DeepestContactIsTheClosestVertex) {
  const RigidShape g = grain();
  const double R = 0.02;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int touching = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const Vector3d axis = Vector3d(u(rng), u(rng), u(rng)).normalized();
    const Vector3d point(u(rng), u(rng), u(rng));
    const Quaterniond q = Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized();
    const Vector3d side = axis.unitOrthogonal();
    // the grain near the wall: its closest vertex at a gap of about [0.2, 3] eps
    const double target = kEps * (1.6 + 1.4 * u(rng));
    const double along = 0.3 * u(rng);
    const auto closestGap = [&](double d) {
      double closest = 1e9;
      for (const Vector3d& v : g.bodyMesh.vertices) {
        const Vector3d r = q * v + along * axis + d * side;
        closest = std::min(closest, R - (r - r.dot(axis) * axis).norm());
      }
      return closest;
    };
    double d = R - g.boundingRadius;
    for (int k = 0; k < 4; ++k) d += closestGap(d) - target;
    const Vector3d centre = point + along * axis + d * side;
    const double closest = closestGap(d);
    std::vector<ContactPoint> contacts;
    MeshContactStatistics stats;
    contact::CylinderWallContactFinder(options()).find(g, Pose{centre, q}, point, axis, R, contacts, &stats);
    EXPECT_EQ(!contacts.empty(), closest < 2 * kEps) << trial;
    if (contacts.empty()) continue;
    ++touching;
    double deepest = 0.0;
    for (const ContactPoint& c : contacts) {
      deepest = std::max(deepest, c.penetration);
      const Vector3d r = c.point - point;
      const Vector3d radial = (r - r.dot(axis) * axis).normalized();
      EXPECT_LT((c.normal - radial).norm(), 1e-9);
      // the point lies halfway between the vertex and the wall
      EXPECT_NEAR((r - r.dot(axis) * axis).norm(), R - c.distance / 2, 1e-12);
    }
    EXPECT_NEAR(deepest, kEps - closest / 2, 1e-12);
  }
  EXPECT_GT(touching, 40);
  EXPECT_LT(touching, 200);
}

}  // namespace
