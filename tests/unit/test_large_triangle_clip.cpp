// The hybrid's scale-aware path (LargeTriangleClip.h): a large triangle clipped to a small
// one's neighbourhood keeps the pair's distance, the clip's bounds are rigorous, and the hybrid
// with it decides contacts like the exact method while falling back rarely at size ratios
// where the plain penalty kernel cannot certify anything. (CGAL checks of the same sets:
// test_triangle_distance.cpp, "size-ratio-*".)
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "geometry/DentedSphere.h"
#include "geometry/HybridTriangleDistance.h"
#include "geometry/LargeTriangleClip.h"
#include "geometry/RigidShape.h"
#include "geometry/TriangleDistance.h"

using namespace spacetree::geometry;
using Eigen::Vector3d;

namespace {

struct Pair {
  Triangle small, large;
};

// Barycentric coordinates (w0, w1, w2) of p with respect to t, from areas in t's plane.
Vector3d barycentric(const Triangle& t, const Vector3d& p) {
  const Vector3d n = (t[1] - t[0]).cross(t[2] - t[0]);
  const double a1 = (p - t[0]).cross(t[2] - t[0]).dot(n) / n.squaredNorm();
  const double a2 = (t[1] - t[0]).cross(p - t[0]).dot(n) / n.squaredNorm();
  return {1.0 - a1 - a2, a1, a2};
}

// A unit-size random triangle near a random face point, edge point or vertex of a triangle
// `ratio` times larger, at distances from 0 (touching or piercing) to a few sizes.
std::vector<Pair> nearPairs(double ratio, int count, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const auto cube = [&] { return Vector3d(2 * u(rng) - 1, 2 * u(rng) - 1, 2 * u(rng) - 1); };
  std::vector<Pair> pairs;
  while (int(pairs.size()) < count) {
    Triangle large(cube(), cube(), cube());
    if ((large[1] - large[0]).cross(large[2] - large[0]).norm() < 0.3) continue;
    for (int i = 0; i < 3; ++i) large[i] *= ratio;
    const Vector3d n = (large[1] - large[0]).cross(large[2] - large[0]).normalized();
    double w1 = u(rng), w2 = u(rng);
    if (w1 + w2 > 1) { w1 = 1 - w1; w2 = 1 - w2; }
    Vector3d anchor = large[0] + w1 * (large[1] - large[0]) + w2 * (large[2] - large[0]);
    const double kind = u(rng);
    if (kind > 0.7) {
      anchor = large[int(3 * u(rng)) % 3];
    } else if (kind > 0.5) {
      anchor = large[0] + u(rng) * (large[1] - large[0]);
    }
    const Vector3d centre = anchor + n * (3.0 * u(rng) - 0.5) + 0.5 * cube();
    pairs.push_back({Triangle(centre + 0.6 * cube(), centre + 0.6 * cube(), centre + 0.6 * cube()),
                     large});
  }
  return pairs;
}

// All triangles of a dented-sphere grain (size 1) within 0.3 of the plane of a large triangle
// that it rests on at a random orientation with its lowest vertex 0 .. 0.1 above: the pairs a
// grain on a coarse obstacle face hands to the distance method.
std::vector<Pair> grainOnFacePairs(double ratio, int count, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> g;
  DentedSphereOptions o;
  o.triangles = 40;
  o.radius = 1.0;
  o.amplitude = 0.2;
  o.seed = 7;
  const RigidShape grain = RigidShape::fromMesh(dentedSphere(o));
  const Triangle large(Vector3d(-0.5, -0.3, 0) * ratio, Vector3d(0.5, -0.3, 0) * ratio,
                       Vector3d(0.05, 0.6, 0) * ratio);
  std::vector<Pair> pairs;
  while (int(pairs.size()) < count) {
    const Eigen::Matrix3d r =
        Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
    double w1 = u(rng), w2 = u(rng);
    if (w1 + w2 > 1) { w1 = 1 - w1; w2 = 1 - w2; }
    Vector3d at = large[0] + w1 * (large[1] - large[0]) + w2 * (large[2] - large[0]);
    double lowest = INFINITY;
    for (const Vector3d& v : grain.bodyMesh.vertices) lowest = std::min(lowest, (r * v).z());
    at.z() = 0.1 * u(rng) - lowest;
    for (const Triangle& t : grain.bodyTriangles) {
      const Triangle w(r * t[0] + at, r * t[1] + at, r * t[2] + at);
      if (std::min({w[0].z(), w[1].z(), w[2].z()}) < 0.3) pairs.push_back({w, large});
    }
  }
  pairs.resize(std::size_t(count));
  return pairs;
}

struct HybridRun {
  std::vector<TriangleDistanceResult> results;
  HybridStatistics statistics;
};

// Hybrid on the pairs, the small triangle first (largeFirst = false) or second.
HybridRun hybridOf(const std::vector<Pair>& pairs, HybridOptions options, bool largeFirst) {
  std::vector<Triangle> first, second;
  for (const Pair& p : pairs) {
    first.push_back(largeFirst ? p.large : p.small);
    second.push_back(largeFirst ? p.small : p.large);
  }
  HybridRun run;
  run.results.resize(pairs.size());
  hybridTriangleDistances(first.data(), second.data(), pairs.size(), options, run.results.data(),
                          &run.statistics);
  return run;
}

}  // namespace

TEST(LargeTriangleClip, WhichTriangleIsLarge) {
  const Triangle unit(Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0, 1, 0));
  const auto scaled = [&](double s) {
    return Triangle(unit[0] * s, unit[1] * s, unit[2] * s + Vector3d(0, 0, 1));
  };
  EXPECT_EQ(largeTriangleOfPair(unit, scaled(3.9)), -1);
  EXPECT_EQ(largeTriangleOfPair(scaled(3.9), unit), -1);
  EXPECT_EQ(largeTriangleOfPair(unit, scaled(4.1)), 1);
  EXPECT_EQ(largeTriangleOfPair(scaled(4.1), unit), 0);
  // A degenerate large triangle is not clipped.
  const Triangle line(Vector3d(0, 0, 0), Vector3d(100, 0, 0), Vector3d(50, 0, 0));
  EXPECT_FALSE(clipLargeTriangle(line, unit).clipped);
}

TEST(LargeTriangleClip, PartLiesInTheLargeTriangleAndKeepsTheDistance) {
  std::size_t clipped = 0, total = 0;
  double worstDistance = 0.0, worstScale = 0.0;
  for (double ratio : {1e1, 1e2, 1e4, 1e6}) {
    for (const Pair& p : nearPairs(ratio, 4000, unsigned(ratio) + 3)) {
      ++total;
      const double hl = p.large.longestEdge();
      const double round = 1e-13 * hl;  // a few hundred ulps of the large triangle
      const TriangleDistanceResult exact = triangleDistance(p.small, p.large);
      const LargeTriangleClip clip = clipLargeTriangle(p.large, p.small);
      if (!clip.clipped) continue;
      ++clipped;
      // Bounds: rigorous, and their points are where they claim to be.
      ASSERT_GE(clip.upperBound, exact.distance - round);
      ASSERT_LE(clip.lowerBound, exact.distance + round);
      ASSERT_GE(clip.lowerBound, 0.0);
      ASSERT_NEAR((clip.pointOnSmall - clip.pointOnLarge).norm(), clip.upperBound, round);
      const Triangle onLarge(clip.pointOnLarge, clip.pointOnLarge, clip.pointOnLarge);
      const Triangle onSmall(clip.pointOnSmall, clip.pointOnSmall, clip.pointOnSmall);
      ASSERT_LE(triangleDistance(onLarge, p.large).distance, round);
      ASSERT_LE(triangleDistance(onSmall, p.small).distance, round);
      // The part: inside the large triangle, its edges parallel to the large one's, at most
      // kClipMaximumScale of its size.
      for (int i = 0; i < 3; ++i) {
        const Vector3d w = barycentric(p.large, clip.part[i]);
        ASSERT_GE(w.minCoeff(), -1e-12) << "ratio " << ratio;
        ASSERT_LE(w.maxCoeff(), 1.0 + 1e-12) << "ratio " << ratio;
        const Vector3d partEdge = clip.part[(i + 1) % 3] - clip.part[i];
        const Vector3d largeEdge = p.large[(i + 1) % 3] - p.large[i];
        ASSERT_LE(partEdge.cross(largeEdge).norm(), 1e-12 * largeEdge.squaredNorm());
        ASSERT_GE(partEdge.dot(largeEdge), 0.0);
      }
      const double scale = clip.part.longestEdge() / hl;
      ASSERT_LE(scale, kClipMaximumScale * (1 + 1e-12));
      worstScale = std::max(worstScale, scale);
      // The distance (and, by the exact method, the decision at any threshold) is kept.
      const double partDistance = triangleDistance(p.small, clip.part).distance;
      worstDistance = std::max(worstDistance, std::abs(partDistance - exact.distance) / hl);
      ASSERT_NEAR(partDistance, exact.distance, round) << "ratio " << ratio;
    }
  }
  std::printf("[ report   ] clipped %zu of %zu near pairs (ratios 1e1..1e6); distance kept to "
              "%.2e of the large edge; part at most %.3g of the large triangle\n",
              clipped, total, worstDistance, worstScale);
  // Near pairs are clipped (a pair near a vertex or edge of a 1:10 triangle may not be).
  EXPECT_GT(clipped, 9 * total / 10);
}

TEST(LargeTriangleClip, HybridDecidesLikeExactAndFallsBackRarely) {
  for (double ratio : {1e2, 1e4, 1e6}) {
    for (bool grain : {true, false}) {
      const std::vector<Pair> pairs =
          grain ? grainOnFacePairs(ratio, 6000, 5) : nearPairs(ratio, 6000, 7);
      // The exact method in both orders (not symmetric to the last ulp: a tie may differ).
      std::vector<TriangleDistanceResult> smallFirst, largeFirstExact;
      for (const Pair& p : pairs) {
        smallFirst.push_back(triangleDistance(p.small, p.large));
        largeFirstExact.push_back(triangleDistance(p.large, p.small));
      }
      const std::vector<TriangleDistanceResult>& exact = smallFirst;
      // Thresholds: fixed ones and ones right at pair distances (ties and 1e-11 either side,
      // where a slack taken from the clipped part instead of the pair would not cover the
      // rounding of the part's vertices).
      std::vector<double> thresholds = {0.02, 0.2};
      for (std::size_t k = 0; k < pairs.size(); k += 397)
        if (exact[k].distance > 0.0)
          for (double f : {-1e-11, 0.0, 1e-11}) thresholds.push_back(exact[k].distance + f);
      for (bool largeFirst : {false, true}) {
        const std::vector<TriangleDistanceResult>& reference = largeFirst ? largeFirstExact : exact;
        for (double t : thresholds) {
          HybridOptions o;
          o.contactDistance = t;
          const HybridRun run = hybridOf(pairs, o, largeFirst);
          std::size_t differing = 0;
          for (std::size_t k = 0; k < pairs.size(); ++k)
            differing += (run.results[k].distance < t) != (reference[k].distance < t);
          ASSERT_EQ(differing, 0u) << "ratio " << ratio << " threshold " << t;
        }
        HybridOptions o;
        o.contactDistance = 0.2;
        const HybridRun run = hybridOf(pairs, o, largeFirst);
        for (std::size_t k = 0; k < pairs.size(); ++k) {
          const double hl = pairs[k].large.longestEdge();
          ASSERT_LE(std::abs(run.results[k].distance - reference[k].distance),
                    1e-11 * reference[k].distance + 1e-13 * hl)
              << "ratio " << ratio << " pair " << k;
          const TriangleDistanceResult& r = run.results[k];
          ASSERT_NEAR((r.pointOnFirst - r.pointOnSecond).norm(), r.distance, 1e-13 * hl);
        }
        HybridOptions plain = o;
        plain.clipLargeTriangles = false;
        const HybridRun without = hybridOf(pairs, plain, largeFirst);
        std::printf("[ report   ] 1:%.0e %s (%s first): fallback %.2f %% (clipped %.1f %%), "
                    "without the clip %.2f %%\n",
                    ratio, grain ? "grain on a face" : "near pairs", largeFirst ? "large" : "small",
                    100.0 * run.statistics.fallbackFraction(),
                    100.0 * double(run.statistics.clipped) / double(pairs.size()),
                    100.0 * without.statistics.fallbackFraction());
        EXPECT_LE(run.statistics.fallbackFraction(), grain ? 0.01 : 0.02) << "ratio " << ratio;
        if (ratio >= 1e4) {
          EXPECT_GT(without.statistics.fallbackFraction(), 0.3);
        }
        EXPECT_GT(run.statistics.clipped, pairs.size() / 20);
      }
    }
  }
}
