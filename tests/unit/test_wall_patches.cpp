// Walls as triangulated patches (WallPatches.h, RigidShape::fromSurface): a grain meets a plane
// patch exactly as it meets the top face of a box obstacle of the same surface; the patch goes
// under the grain on either side; cylinder patches stay within their sagitta of the cylinder,
// face the requested side, close into a ring; a grain inside a cylinder touches it where its
// vertices are within 2 eps of the true surface.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <vector>

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
  for (bool inward : {false, true})
    for (double halfAngle : {0.2, 4.0}) {
      const geometry::TriangleMesh m = geometry::cylinderWallPatch(R, halfAngle, 0.01, sag, inward);
      double worstOff = 0.0;
      for (std::size_t t = 0; t < m.triangleCount(); ++t) {
        const geometry::Triangle tri = m.triangle(t);
        for (const Vector3d& v : tri.vertex) EXPECT_NEAR(std::hypot(v.x(), v.y()), R, 1e-15);
        const Vector3d c = (tri[0] + tri[1] + tri[2]) / 3.0;
        const Vector3d n = m.areaVector(t).normalized();
        const Vector3d radial = Vector3d(c.x(), c.y(), 0).normalized();
        EXPECT_NEAR(n.dot(radial), inward ? -1.0 : 1.0, 1e-6);
        // midpoint of the facet's chord across the azimuth
        for (int k = 0; k < 3; ++k) {
          const Vector3d mid = 0.5 * (tri[k] + tri[(k + 1) % 3]);
          worstOff = std::max(worstOff, R - std::hypot(mid.x(), mid.y()));
        }
      }
      EXPECT_LE(worstOff, sag * (1 + 1e-6));
      EXPECT_GT(worstOff, 0.25 * sag);
      const RigidShape s = RigidShape::fromSurface(m);
      int open = 0;
      for (const auto& e : s.edgeApex)
        for (int a : e) open += a < 0;
      if (halfAngle > M_PI) EXPECT_EQ(open, 2 * int(m.triangleCount()) / 2 * 1);  // only the two rims
    }
  EXPECT_THROW(geometry::cylinderWallPatch(R, 0.1, 0.01, R, false), std::invalid_argument);
  EXPECT_THROW(geometry::planeWallPatch(0.0), std::invalid_argument);
}

TEST(WallPatches, GrainInsideACylinderTouchesWhereItsVerticesAre) {
  const RigidShape g = grain();
  const double R = 0.02, sag = 1e-3 * kEps;
  const RigidShape inside = RigidShape::fromSurface(geometry::cylinderWallPatch(R, 1.0, 0.012, sag, true));
  const Quaterniond q = Quaterniond(0.2, 0.9, -0.1, 0.3).normalized();
  // the vertex farthest from the axis (z) when the grain sits at (x, 0, 0)
  for (double gap : {0.3 * kEps, 1.2 * kEps}) {
    double far = 0.0;
    Vector3d centre(0, 0, 0.003);
    // place the grain so that its farthest vertex is `gap` inside the cylinder along +x
    double reach = 0.0;
    for (const Vector3d& v : g.bodyMesh.vertices) reach = std::max(reach, (q * v).x());
    centre.x() = R - gap - reach;
    for (const Vector3d& v : g.bodyMesh.vertices) far = std::max(far, std::hypot((q * v + centre).x(), (q * v + centre).y()));
    const double trueGap = R - far;
    const geometry::WallPatchPlacement place =
        geometry::WallPatchPlacement::onCylinder(Vector3d::Zero(), Vector3d::UnitZ(), centre);
    std::vector<ContactPoint> contacts;
    const Pose wall{place.position + place.orientation * inside.centreOfMassInMesh, place.orientation};
    MeshContactFinder(options()).find(g, Pose{centre, q}, inside, wall, contacts);
    ASSERT_FALSE(contacts.empty());
    double deepest = 0.0;
    for (const ContactPoint& c : contacts) deepest = std::max(deepest, c.penetration);
    EXPECT_NEAR(deepest, kEps - trueGap / 2, sag + 1e-12) << gap;
  }
}

}  // namespace
