// The contact search against coarse obstacles (MeshContact step 3 beyond the bounding spheres:
// the other body's box, true distances of large triangles, the small triangle's sphere against
// a large triangle): a grain on slabs meshed with 12, ~100 and ~1000 triangles, and on a slab
// 10^4 times its size. The culls change which triangle pairs reach the distance method, never
// the contacts: with the exact method they are bit for bit those of the bounding-sphere-only
// search, with the hybrid those of the exact method; and the coarse slab then costs about as
// many triangle pairs as the fine one.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "contact/MeshContact.h"
#include "geometry/PrimitiveMeshes.h"
#include "geometry/RigidShape.h"
#include "grain_on_slab_scenes.h"

using namespace spacetree;
using namespace spacetree::contact;
using geometry::RigidShape;
using Eigen::Quaterniond;
using Eigen::Vector3d;

namespace {

const double kEps = 0.01;  // grain radius 1

using grain_on_slab::grain;
using grain_on_slab::Scene;

std::vector<Scene> scenes(const RigidShape& g, const Vector3d& size, int count, unsigned seed) {
  return grain_on_slab::scenes(g, size, kEps, count, seed);
}

struct Outcome {
  std::vector<std::vector<ContactPoint>> contacts;
  MeshContactStatistics stats;
};

// Both orders (the slab first, as pair_style trimesh puts the body with more triangles, and the
// grain first).
Outcome run(MeshContactOptions o, const RigidShape& slab, const RigidShape& g,
            const std::vector<Scene>& all) {
  o.epsilon = kEps;
  MeshContactFinder finder(o);
  Outcome out;
  for (const Scene& s : all) {
    out.contacts.emplace_back();
    finder.find(slab, s.slab, g, s.grain, out.contacts.back(), &out.stats);
    out.contacts.emplace_back();
    finder.find(g, s.grain, slab, s.slab, out.contacts.back(), &out.stats);
  }
  return out;
}

void expectBitIdentical(const Outcome& a, const Outcome& b, const char* what) {
  ASSERT_EQ(a.contacts.size(), b.contacts.size());
  for (std::size_t s = 0; s < a.contacts.size(); ++s) {
    ASSERT_EQ(a.contacts[s].size(), b.contacts[s].size()) << what << " scene " << s;
    for (std::size_t k = 0; k < a.contacts[s].size(); ++k) {
      const ContactPoint &p = a.contacts[s][k], &q = b.contacts[s][k];
      ASSERT_EQ(p.point, q.point) << what << " scene " << s;
      ASSERT_EQ(p.normal, q.normal) << what << " scene " << s;
      ASSERT_EQ(p.penetration, q.penetration) << what << " scene " << s;
      ASSERT_EQ(p.firstTriangle, q.firstTriangle) << what << " scene " << s;
      ASSERT_EQ(p.secondTriangle, q.secondTriangle) << what << " scene " << s;
      ASSERT_EQ(p.mergedCount, q.mergedCount) << what << " scene " << s;
    }
  }
}

void expectSameContacts(const Outcome& exact, const Outcome& other, double scale,
                        const char* what) {
  ASSERT_EQ(exact.contacts.size(), other.contacts.size());
  for (std::size_t s = 0; s < exact.contacts.size(); ++s) {
    ASSERT_EQ(exact.contacts[s].size(), other.contacts[s].size()) << what << " scene " << s;
    for (std::size_t k = 0; k < exact.contacts[s].size(); ++k) {
      const ContactPoint &p = exact.contacts[s][k], &q = other.contacts[s][k];
      EXPECT_EQ(p.firstTriangle, q.firstTriangle) << what << " scene " << s;
      EXPECT_EQ(p.secondTriangle, q.secondTriangle) << what << " scene " << s;
      // A grain edge almost parallel to the face has an ill-conditioned closest point (its
      // error is the distance's divided by the angle): 1e-7, not 1e-9.
      EXPECT_LT((p.point - q.point).norm(), 1e-7 * scale) << what << " scene " << s;
      EXPECT_NEAR(p.penetration, q.penetration, 1e-9 * scale) << what << " scene " << s;
    }
  }
}

MeshContactOptions method(TriangleDistanceMethod m, bool cull) {
  MeshContactOptions o;
  o.method = m;
  o.triangleCulling = cull;
  return o;
}

}  // namespace

TEST(MeshContactCulling, CoarseAndFineSlabsGiveTheUnculledContactsAtTheFineSlabsCost) {
  const RigidShape g = grain();
  const Vector3d size(12.0, 10.0, 2.0);
  struct Slab {
    const char* name;
    RigidShape shape;
  };
  const std::vector<Slab> slabs = {
      {"12 triangles", RigidShape::fromMesh(geometry::boxMesh(size))},
      {"~100 triangles", RigidShape::fromMesh(geometry::gridBoxMesh(size, {4, 3, 1}))},
      {"~1000 triangles", RigidShape::fromMesh(geometry::gridBoxMesh(size, {14, 12, 2}))},
  };
  const std::vector<Scene> all = scenes(g, size, 200, 3);
  std::vector<double> perScene, fallbacks;
  for (const Slab& slab : slabs) {
    SCOPED_TRACE(slab.name);
    const Outcome reference = run(method(TriangleDistanceMethod::Exact, false), slab.shape, g, all);
    const Outcome culled = run(method(TriangleDistanceMethod::Exact, true), slab.shape, g, all);
    const Outcome hybrid = run(method(TriangleDistanceMethod::Hybrid, true), slab.shape, g, all);
    MeshContactOptions linear = method(TriangleDistanceMethod::Exact, true);
    linear.triangleIndex = false;
    const Outcome unindexed = run(linear, slab.shape, g, all);
    ASSERT_GT(reference.stats.contacts, all.size());  // most scenes are in contact
    expectBitIdentical(reference, culled, "exact, culled");
    expectBitIdentical(reference, unindexed, "exact, culled, no index");
    expectSameContacts(reference, hybrid, 1.0, "hybrid, culled");
    const double checked = double(culled.stats.trianglePairsChecked);
    perScene.push_back(checked / double(2 * all.size()));
    std::printf("[ report   ] grain on a slab of %zu triangles: triangle pairs %zu -> %zu "
                "(%.1f per body pair), hybrid fallbacks %.2f %%, contacts %zu\n",
                slab.shape.triangleCount(), reference.stats.trianglePairsChecked,
                culled.stats.trianglePairsChecked, perScene.back(),
                100.0 * double(hybrid.stats.fallbacks) / checked, culled.stats.contacts);
    EXPECT_LE(culled.stats.trianglePairsChecked, reference.stats.trianglePairsChecked);
    fallbacks.push_back(double(hybrid.stats.fallbacks) / checked);
  }
  // The coarse slab's big triangles (10 grain triangles wide) take the scale-aware path and
  // rarely fall back; the fine slabs' grain-sized triangles fall back like grain-grain pairs
  // at contact (a few per cent: nearly parallel faces, the penalty kernel's weak case).
  EXPECT_LE(fallbacks[0], 0.01);
  // The 12-triangle slab: its two big top triangles now meet only the grain triangles facing
  // them, no more pairs than the fine slabs' small triangles.
  EXPECT_LE(perScene[0], 1.2 * std::max(perScene[1], perScene[2]));
}

TEST(MeshContactCulling, ObstaclesUpToAMillionTimesTheGrainDecideLikeExactAndRarelyFallBack) {
  const RigidShape g = grain();
  for (double ratio : {1e2, 1e4, 1e6}) {
    const Vector3d size(ratio, 0.8 * ratio, 0.1 * ratio);
    const RigidShape slab = RigidShape::fromMesh(geometry::boxMesh(size));
    const std::vector<Scene> all = scenes(g, size, 150, 5);
    const Outcome reference = run(method(TriangleDistanceMethod::Exact, false), slab, g, all);
    const Outcome culled = run(method(TriangleDistanceMethod::Exact, true), slab, g, all);
    const Outcome hybrid = run(method(TriangleDistanceMethod::Hybrid, true), slab, g, all);
    SCOPED_TRACE(ratio);
    ASSERT_GT(reference.stats.contacts, all.size());
    expectBitIdentical(reference, culled, "exact, culled");
    // Contact points relative to the obstacle's rounding (coordinates up to 1e6 grain sizes).
    expectSameContacts(reference, hybrid, 1.0 + 1e-4 * ratio, "hybrid, culled");
    const double fallbacks =
        double(hybrid.stats.fallbacks) / double(hybrid.stats.trianglePairsChecked);
    std::printf("[ report   ] grain on a 12-triangle slab 1:%.0e: %.1f triangle pairs per body "
                "pair (unculled %.1f), hybrid fallbacks %.2f %%\n",
                ratio, double(culled.stats.trianglePairsChecked) / double(2 * all.size()),
                double(reference.stats.trianglePairsChecked) / double(2 * all.size()),
                100.0 * fallbacks);
    EXPECT_LE(fallbacks, 0.01);
  }
}

TEST(MeshContactCulling, AGrainInsideASlabsBoundingSphereButClearOfItsBoxIsRejectedAtOnce) {
  const RigidShape g = grain();
  const RigidShape slab = RigidShape::fromMesh(geometry::boxMesh(Vector3d(12.0, 10.0, 2.0)));
  const Quaterniond turn(Eigen::AngleAxisd(0.7, Vector3d(1, -1, 2).normalized()));
  const Pose slabPose{Vector3d(0.5, 0.2, -0.1), turn};
  for (double gap : {0.5, 1.5 * kEps, 2.5 * kEps}) {
    // Above the top face, the grain's bounding sphere `gap` from the slab's box.
    const Pose grainPose{slabPose.position + turn * Vector3d(2.0, -1.0, 1.0 + g.boundingRadius + gap),
                         Quaterniond::Identity()};
    for (bool cull : {true, false}) {
      MeshContactOptions o = method(TriangleDistanceMethod::Exact, cull);
      o.epsilon = kEps;
      MeshContactFinder finder(o);
      std::vector<ContactPoint> contacts;
      MeshContactStatistics first, second;
      finder.find(slab, slabPose, g, grainPose, contacts, &first);
      finder.find(g, grainPose, slab, slabPose, contacts, &second);
      EXPECT_TRUE(contacts.empty());
      const bool rejected = cull && gap > 2.0 * kEps;
      EXPECT_EQ(first.boundingBoxRejections, rejected ? 1u : 0u) << "gap " << gap;
      EXPECT_EQ(second.boundingBoxRejections, rejected ? 1u : 0u) << "gap " << gap;
      EXPECT_EQ(first.boundingSphereRejections + second.boundingSphereRejections, 0u);
    }
  }
}

TEST(PrimitiveMeshes, GridBoxIsAClosedBoxOfTheGivenCells) {
  const Vector3d size(3.0, 2.0, 1.0);
  const geometry::TriangleMesh mesh = geometry::gridBoxMesh(size, {3, 2, 4});
  EXPECT_EQ(mesh.triangleCount(), std::size_t(4 * (3 * 2 + 2 * 4 + 4 * 3)));
  const RigidShape shape = RigidShape::fromMesh(mesh);
  EXPECT_NEAR(shape.volume, 6.0, 1e-12);
  EXPECT_NEAR(mesh.surfaceArea(), 2.0 * (6.0 + 2.0 + 3.0), 1e-12);
  for (const auto& across : shape.edgeApex)
    for (int apex : across) EXPECT_GE(apex, 0);  // every edge has a neighbour: closed
  EXPECT_THROW(geometry::gridBoxMesh(size, {0, 1, 1}), std::invalid_argument);
}
