// What the adaptive time step needs about triangulated bodies: the surface gap within a band
// (SurfaceGapProbe) against the exact distance of cube configurations, the closing-speed bound
// against the measured rate of change of the surface distance of rotating concave bodies, and
// the halo-gap veto (TimestepVeto::considerGap with haloGap).
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "contact/MeshContact.h"
#include "contact/SurfaceGapProbe.h"
#include "dynamics/TimestepVeto.h"
#include "geometry/DentedSphere.h"
#include "geometry/PrimitiveMeshes.h"
#include "geometry/RigidShape.h"

using namespace spacetree;
using namespace spacetree::contact;
using geometry::RigidShape;
using Eigen::AngleAxisd;
using Eigen::Quaterniond;
using Eigen::Vector3d;

namespace {

const double kHalo = 0.01;

RigidShape unitCube() { return RigidShape::fromMesh(geometry::boxMesh(Vector3d(1, 1, 1))); }

MeshContactOptions haloOptions(TriangleDistanceMethod method) {
  MeshContactOptions o;
  o.epsilon = kHalo;
  o.method = method;
  return o;
}

// Smallest surface distance found by the exact method with a halo wide enough to see it.
double exactDistance(const RigidShape& a, const Pose& pa, const RigidShape& b, const Pose& pb) {
  MeshContactOptions o = haloOptions(TriangleDistanceMethod::Exact);
  o.epsilon = 10.0;
  o.deduplicate = false;
  MeshContactFinder finder(o);
  std::vector<ContactPoint> found;
  finder.find(a, pa, b, pb, found);
  double d = 1e300;
  for (const ContactPoint& c : found) d = std::min(d, c.distance);
  return d;
}

}  // namespace

TEST(SurfaceGapProbe, FindsTheNearestPointsWithinTheBandOnly) {
  const RigidShape cube = unitCube();
  // face to face along x, the second cube turned about x (its face stays parallel)
  for (const double gap : {0.005, 0.03, 0.07}) {
    const Pose a{Vector3d(0.2, 0.1, -0.3), Quaterniond::Identity()};
    const Pose b{a.position + Vector3d(1.0 + gap, 0.1, 0.05), Quaterniond(AngleAxisd(0.3, Vector3d::UnitX()))};
    for (auto method : {TriangleDistanceMethod::Exact, TriangleDistanceMethod::Hybrid}) {
      SurfaceGapProbe probe(haloOptions(method));
      const auto wide = probe.nearest(cube, a, cube, b, 0.1);
      ASSERT_TRUE(wide.has_value()) << gap;
      EXPECT_NEAR(wide->distance, gap, 1e-12);
      EXPECT_NEAR(wide->normal.x(), 1.0, 1e-9);
      EXPECT_NEAR(wide->penetration, kHalo - gap / 2, 1e-12);
      // a band below the gap: nothing (the smallest band class at or above it may be wider
      // than asked, but no point beyond the band is reported)
      const auto narrow = probe.nearest(cube, a, cube, b, std::max(2 * kHalo, 0.9 * gap));
      EXPECT_EQ(narrow.has_value(), 0.9 * gap <= 2 * kHalo && gap < 2 * kHalo) << gap;
    }
  }
}

TEST(SurfaceGapProbe, GapOfCornerAgainstFaceEqualsTheGeometry) {
  const RigidShape cube = unitCube();
  const Quaterniond corner = Quaterniond::FromTwoVectors(Vector3d(1, 1, 1).normalized(), Vector3d::UnitX());
  const double gap = 0.043;
  const Pose a{Vector3d::Zero(), corner};
  const Pose b{Vector3d(std::sqrt(3.0) / 2 + 0.5 + gap, 0.0, 0.0), Quaterniond::Identity()};
  SurfaceGapProbe probe(haloOptions(TriangleDistanceMethod::Hybrid));
  const auto c = probe.nearest(cube, a, cube, b, 0.05);
  ASSERT_TRUE(c.has_value());
  EXPECT_NEAR(c->distance, gap, 1e-9);
  EXPECT_LT((c->point - Vector3d(std::sqrt(3.0) / 2 + gap / 2, 0, 0)).norm(), 1e-9);
  EXPECT_FALSE(probe.nearest(cube, a, cube, b, 0.042).has_value());
  EXPECT_THROW(probe.nearest(cube, a, cube, b, kHalo), std::invalid_argument);   // below 2 eps
}

// Concave dented spheres tumbling past each other: over a short interval the surface distance
// never falls faster than the bound (rigid motion: x + v t, orientation exp(w t)).
TEST(SurfaceGapProbe, ClosingSpeedBoundHoldsForTumblingConcaveBodies) {
  geometry::DentedSphereOptions dented;
  dented.triangles = 40;
  dented.amplitude = 0.3;
  dented.seed = 5;
  const RigidShape grain = RigidShape::fromMesh(geometry::dentedSphere(dented));
  const double R = grain.boundingRadius;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int checked = 0;
  double tightest = 0.0;   // largest (measured closing rate) / bound
  for (int trial = 0; trial < 200; ++trial) {
    const Vector3d va(u(rng), u(rng), u(rng)), vb(u(rng), u(rng), u(rng));
    const Vector3d wa(3 * u(rng), 3 * u(rng), 3 * u(rng)), wb(3 * u(rng), 3 * u(rng), 3 * u(rng));
    const Quaterniond qa = Quaterniond(AngleAxisd(3 * u(rng), Vector3d(u(rng), u(rng), u(rng)).normalized()));
    const Quaterniond qb = Quaterniond(AngleAxisd(3 * u(rng), Vector3d(u(rng), u(rng), u(rng)).normalized()));
    const Vector3d xa(0, 0, 0), xb = Vector3d(u(rng), u(rng), u(rng)).normalized() * (2 * R * (0.85 + 0.1 * (u(rng) + 1)));
    const auto pose = [](const Vector3d& x, const Quaterniond& q, const Vector3d& v, const Vector3d& w, double t) {
      const double angle = w.norm() * t;
      const Quaterniond turn = angle > 0 ? Quaterniond(AngleAxisd(angle, w.normalized())) : Quaterniond::Identity();
      return Pose{x + v * t, (turn * q).normalized()};
    };
    const double dt = 1e-3;
    const double d0 = exactDistance(grain, pose(xa, qa, va, wa, 0), grain, pose(xb, qb, vb, wb, 0));
    const double d1 = exactDistance(grain, pose(xa, qa, va, wa, dt), grain, pose(xb, qb, vb, wb, dt));
    if (!(d0 > 1e-3 && d1 > 1e-3 && d0 < 1e299)) continue;   // interpenetrating or too far
    const double bound = surfaceClosingSpeedBound(va, wa, R, vb, wb, R);
    const double rate = (d0 - d1) / dt;
    EXPECT_LE(rate, bound * (1 + 1e-9)) << trial;
    tightest = std::max(tightest, rate / bound);
    ++checked;
  }
  EXPECT_GT(checked, 100);
  EXPECT_GT(tightest, 0.2) << "largest measured rate / bound";   // the bound is not vacuous
  std::printf("closing-speed bound: %d pairs, largest rate / bound %.3f\n", checked, tightest);
}

TEST(TimestepVeto, HaloGapVetoKeepsTheHaloPenetrationWithinTheAllowedOne) {
  const double halo = 1e-4, allowed = 0.5e-4;
  spacetree::TimestepVeto veto(0.0, 0.8, 0.0);
  // surfaces 2.5 halo apart closing at 1 m/s: the penetration halo - d/2 reaches `allowed` once
  // d = 2 (halo - allowed) = 1e-4, i.e. after closing 1.5e-4 m
  const double d = 2.5e-4;
  EXPECT_DOUBLE_EQ(spacetree::haloGap(d, halo, allowed), 1.5e-4);
  EXPECT_FALSE(veto.considerGap(spacetree::haloGap(d, halo, allowed), 1.0, 1e-4));   // 1e-4 < 0.8 * 1.5e-4
  EXPECT_TRUE(veto.considerGap(spacetree::haloGap(d, halo, allowed), 1.0, 1.3e-4));
  EXPECT_NEAR(veto.limit(), 0.8 * 1.5e-4, 1e-18);
  // receding, or already deeper than allowed: not critical
  EXPECT_FALSE(veto.considerGap(spacetree::haloGap(d, halo, allowed), -1.0, 1.0));
  EXPECT_FALSE(veto.considerGap(spacetree::haloGap(0.9e-4, halo, allowed), 1.0, 1.0));
  EXPECT_EQ(veto.criticalPairs(), 1u);
  // the sphere form gives the same decision for the same gap
  spacetree::TimestepVeto spheres(0.0, 0.8, 0.0);
  const double xi[3] = {0, 0, 0}, xj[3] = {1.0 + 1.5e-4, 0, 0}, vi[3] = {0.5, 0, 0}, vj[3] = {-0.5, 0, 0};
  EXPECT_TRUE(spheres.consider(xi, vi, 0.5, xj, vj, 0.5, 1.3e-4));
  EXPECT_NEAR(spheres.limit(), veto.limit(), 1e-15);
}
