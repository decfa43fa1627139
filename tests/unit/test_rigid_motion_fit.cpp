// RigidMotionFit: the rigid motion of a point set (a moving mesh wall) from three well-spread
// points, verified on all: recovered to rounding for random rotations and shifts, refused for a
// deformation, a swapped pair of points and a collinear set.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <random>
#include <vector>

#include "geometry/RigidMotionFit.h"

using spacetree::geometry::RigidMotionFit;
using Eigen::Matrix3d;
using Eigen::Quaterniond;
using Eigen::Vector3d;

TEST(RigidMotionFit, RecoversRigidMotionsAndRefusesOthers) {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vector3d> ref;
  for (int i = 0; i < 200; ++i) ref.emplace_back(0.1 * u(rng), 0.05 * u(rng), 0.02 * u(rng));
  const RigidMotionFit fit(ref);
  ASSERT_TRUE(fit.valid());
  for (int trial = 0; trial < 50; ++trial) {
    const Matrix3d r = Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized().toRotationMatrix();
    const Vector3d t(u(rng), u(rng), u(rng));
    std::vector<Vector3d> cur;
    for (const Vector3d& p : ref) cur.push_back(r * p + t);
    Matrix3d rr;
    Vector3d tt;
    ASSERT_TRUE(fit.fit(ref, cur, 1e-12, rr, tt));
    EXPECT_LT((rr - r).norm(), 1e-13);
    EXPECT_LT((tt - t).norm(), 1e-13);
    // one point off by 1e-9: refused at tolerance 1e-10, accepted at 1e-8
    std::vector<Vector3d> bent = cur;
    bent[77] += Vector3d(0, 1e-9, 0);
    EXPECT_FALSE(fit.fit(ref, bent, 1e-10, rr, tt));
    EXPECT_TRUE(fit.fit(ref, bent, 1e-8, rr, tt));
    // two points swapped (a rearranged set)
    std::vector<Vector3d> swapped = cur;
    std::swap(swapped[10], swapped[11]);
    EXPECT_FALSE(fit.fit(ref, swapped, 1e-10, rr, tt));
  }
  std::vector<Vector3d> line = {Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(2, 0, 0)};
  EXPECT_FALSE(RigidMotionFit(line).valid());
  EXPECT_FALSE(RigidMotionFit(std::vector<Vector3d>(2, Vector3d::Zero())).valid());
}
