// Convergence of the penalty-Newton kernel, the part of the hybrid that its certification does
// not check: a kernel that converges worse still returns certified (hence correct) hybrid
// results, only with more exact fallbacks, i.e. slower. These tests pin the fraction of pairs
// the kernel gets right (to the hybrid's own tolerance) against the exact method, on random
// pairs and on the benchmark's scene (all triangle pairs of two 12-triangle spheres 0.01
// apart), with margins of about 1.5x over the measured rates.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "geometry/HybridTriangleDistance.h"
#include "geometry/PenaltyTriangleDistance.h"
#include "geometry/SphereMesh.h"
#include "geometry/TriangleDistance.h"
#include "random_triangle_pairs.h"

using namespace spacetree::geometry;
using Eigen::Vector3d;

namespace {

double longestEdge(const Triangle& a, const Triangle& b) {
  return std::max(a.longestEdge(), b.longestEdge());
}

// Fraction of pairs whose penalty distance is off the exact one by more than the hybrid's
// acceptance tolerance (1e-11 relative plus 1e-14 of the longest edge, here taken 10x looser).
double unconvergedFraction(const std::vector<Triangle>& first, const std::vector<Triangle>& second,
                           int newtonIterations) {
  PenaltyOptions options;
  options.newtonIterations = newtonIterations;
  std::vector<TriangleDistanceResult> penalty(first.size());
  penaltyTriangleDistances(first.data(), second.data(), first.size(), options, penalty.data());
  std::size_t off = 0;
  for (std::size_t k = 0; k < first.size(); ++k) {
    const double d = triangleDistance(first[k], second[k]).distance;
    const double h = longestEdge(first[k], second[k]);
    off += !(std::abs(penalty[k].distance - d) <= 1e-10 * d + 1e-13 * h);
  }
  return double(off) / double(first.size());
}

// All triangle pairs of two 12-triangle spheres of radius 1, randomly turned, 0.01 apart.
void spherePairs(std::vector<Triangle>& first, std::vector<Triangle>& second) {
  std::mt19937_64 rng(2024);
  std::normal_distribution<double> n;
  const std::vector<Triangle> mesh = latitudeLongitudeSphereWithAbout(12, 1.0);
  for (int scene = 0; scene < 8; ++scene) {
    const auto turned = [&](const Eigen::Matrix3d& r, double x) {
      std::vector<Triangle> out = mesh;
      for (Triangle& t : out)
        for (int i = 0; i < 3; ++i) t[i] = r * t[i] + Vector3d(x, 0, 0);
      return out;
    };
    const auto rotation = [&] {
      return Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix();
    };
    const std::vector<Triangle> a = turned(rotation(), 0.0);
    const Eigen::Matrix3d r = rotation();
    double x = 2.01;
    std::vector<Triangle> b;
    for (int step = 0; step < 8; ++step) {  // secant steps to a mesh distance of 0.01
      b = turned(r, x);
      double d = 1e300;
      for (const Triangle& s : a)
        for (const Triangle& t : b) d = std::min(d, triangleDistance(s, t).distance);
      if (std::abs(d - 0.01) < 1e-12) break;
      x += 0.01 - d;
    }
    for (const Triangle& s : a)
      for (const Triangle& t : b) {
        first.push_back(s);
        second.push_back(t);
      }
  }
}

}  // namespace

TEST(PenaltyConvergence, RandomPairsConvergeWithEightSteps) {
  std::vector<Triangle> first, second;
  randomTrianglePairs(20000, 77, first, second);
  const double off8 = unconvergedFraction(first, second, 8);
  const double off4 = unconvergedFraction(first, second, 4);
  std::printf("[ report   ] penalty unconverged on random pairs: 8 steps %.2f %%, 4 steps %.2f %%\n",
              100 * off8, 100 * off4);
  EXPECT_LT(off8, 0.05);
  EXPECT_LT(off8, off4);  // more steps converge more pairs
  HybridStatistics statistics;
  std::vector<TriangleDistanceResult> hybrid(first.size());
  hybridTriangleDistances(first.data(), second.data(), first.size(), HybridOptions{}, hybrid.data(),
                          &statistics);
  std::printf("[ report   ] hybrid fallback on random pairs: %.2f %%\n",
              100 * statistics.fallbackFraction());
  EXPECT_LT(statistics.fallbackFraction(), 0.055);
}

TEST(PenaltyConvergence, SphereContactSceneFallsBackRarely) {
  std::vector<Triangle> first, second;
  spherePairs(first, second);
  HybridOptions options;
  options.contactDistance = 0.02;
  HybridStatistics statistics;
  std::vector<TriangleDistanceResult> hybrid(first.size());
  hybridTriangleDistances(first.data(), second.data(), first.size(), options, hybrid.data(),
                          &statistics);
  const double off8 = unconvergedFraction(first, second, 8);
  std::printf("[ report   ] 12-triangle spheres 0.01 apart, %zu pairs: hybrid fallback %.2f %%, "
              "penalty unconverged %.2f %%\n",
              first.size(), 100 * statistics.fallbackFraction(), 100 * off8);
  EXPECT_LT(statistics.fallbackFraction(), 0.025);
  EXPECT_LT(off8, 0.025);
}
