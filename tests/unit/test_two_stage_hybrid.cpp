// The two-stage hybrid (HybridOptions::continuationIterations > 0): stage 1 runs the penalty
// kernel on every pair, the pairs it cannot certify are gathered into new batches and continue
// from their last iterate (stage 2), the rest falls back to the exact method. These tests pin
// the definition bit for bit: the kernel's continuation equals one run of the concatenated
// schedule, and every hybrid result is the stage-1 result, the stage-2 result of that same
// pair, or the exact one, by the acceptance rule - computed here without any compaction.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include "geometry/HybridTriangleDistance.h"
#include "geometry/PenaltyTriangleDistance.h"
#include "geometry/SphereMesh.h"
#include "geometry/TriangleDistance.h"
#include "random_triangle_pairs.h"

using namespace spacetree::geometry;
using Eigen::Vector3d;

namespace {

constexpr int kLanes = kTrianglePairBatchSize;

// Two 40-triangle spheres of radius 1, randomly turned, about 0.01 apart (all pairs): the
// benchmark's kind of scene, where a quarter of the pairs needs more than four steps.
void spheres(unsigned seed, std::vector<Triangle>& a, std::vector<Triangle>& b) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n;
  const std::vector<Triangle> mesh = latitudeLongitudeSphereWithAbout(40, 1.0);
  const auto turned = [&](double x) {
    const Eigen::Matrix3d r =
        Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix();
    std::vector<Triangle> out = mesh;
    for (Triangle& t : out)
      for (int i = 0; i < 3; ++i) t[i] = r * t[i] + Vector3d(x, 0, 0);
    return out;
  };
  a = turned(0.0);
  b = turned(2.01);
}

bool accepted(const PenaltyBatchResult& r, int l, const HybridOptions& o) {
  return r.distance[l] - r.lowerBound[l] <=
         o.relativeTolerance * r.distance[l] + o.lengthScaleTolerance * r.lengthScale[l];
}

TrianglePairBatch batchOf(const std::vector<Triangle>& first, const std::vector<Triangle>& second,
                          std::size_t begin) {
  TrianglePairBatch batch;
  for (int l = 0; l < kLanes; ++l) {
    const std::size_t k = std::min(begin + std::size_t(l), first.size() - 1);
    batch.set(l, first[k], second[k]);
  }
  return batch;
}

// The two-stage hybrid's definition (contact band off), lane by lane, without compaction:
// stage 2 runs on the stage-1 batch itself, from its own iterates.
struct Expected {
  std::vector<TriangleDistanceResult> results;
  std::size_t continued = 0, fallbacks = 0;
};

Expected expectedTwoStage(const std::vector<Triangle>& first, const std::vector<Triangle>& second,
                          const HybridOptions& o) {
  Expected e;
  PenaltyOptions p;
  p.newtonIterations = o.newtonIterations;
  p.tightGap = o.relativeTolerance;
  p.tightGapPerLength = o.lengthScaleTolerance;
  // Stage 1 certifies with the cheap bound only (HybridOptions::continuationIterations).
  PenaltyOptions p1 = p;
  p1.tightGap = std::numeric_limits<double>::infinity();
  const int total = o.newtonIterations + o.continuationIterations;
  const double* tail = penaltyWeightSchedule(total) + o.newtonIterations;
  for (std::size_t begin = 0; begin < first.size(); begin += kLanes) {
    const TrianglePairBatch batch = batchOf(first, second, begin);
    PenaltyBatchResult stage1, stage2;
    penaltyTriangleDistanceBatch(batch, p1, stage1);
    penaltyTriangleDistanceBatchContinued(batch, tail, o.continuationIterations, stage1.iterate,
                                          p, stage2);
    for (int l = 0; l < kLanes && begin + std::size_t(l) < first.size(); ++l) {
      const std::size_t k = begin + std::size_t(l);
      if (accepted(stage1, l, o)) {
        e.results.push_back(stage1.lane(l));
        continue;
      }
      ++e.continued;
      if (accepted(stage2, l, o)) {
        e.results.push_back(stage2.lane(l));
      } else {
        ++e.fallbacks;
        e.results.push_back(triangleDistance(first[k], second[k]));
      }
    }
  }
  return e;
}

void expectSame(const TriangleDistanceResult& a, const TriangleDistanceResult& b, std::size_t k) {
  ASSERT_EQ(a.distance, b.distance) << "pair " << k;
  ASSERT_EQ(a.pointOnFirst, b.pointOnFirst) << "pair " << k;
  ASSERT_EQ(a.pointOnSecond, b.pointOnSecond) << "pair " << k;
}

}  // namespace

TEST(PenaltyContinuation, TwoCallsEqualOneRunOfTheConcatenatedSchedule) {
  std::vector<Triangle> first, second;
  randomTrianglePairs(4096, 5, first, second);
  PenaltyOptions p;
  const double* four = penaltyWeightSchedule(4);
  const double* eight = penaltyWeightSchedule(8);
  double concatenated[8];
  std::copy(four, four + 4, concatenated);
  std::copy(eight + 4, eight + 8, concatenated + 4);
  std::size_t moved = 0;
  for (std::size_t begin = 0; begin < first.size(); begin += kLanes) {
    const TrianglePairBatch batch = batchOf(first, second, begin);
    PenaltyBatchResult once, stage1, stage2;
    penaltyTriangleDistanceBatchContinued(batch, concatenated, 8, nullptr, p, once);
    penaltyTriangleDistanceBatchContinued(batch, four, 4, nullptr, p, stage1);
    penaltyTriangleDistanceBatchContinued(batch, eight + 4, 4, stage1.iterate, p, stage2);
    for (int l = 0; l < kLanes; ++l) {
      expectSame(once.lane(l), stage2.lane(l), begin + std::size_t(l));
      for (int i = 0; i < 4; ++i) ASSERT_EQ(once.iterate[i][l], stage2.iterate[i][l]);
      moved += stage1.distance[l] != stage2.distance[l];
    }
  }
  EXPECT_GT(moved, first.size() / 10);  // the continuation does change results
  // With the default schedule and no start, the continued kernel is the plain one.
  const TrianglePairBatch batch = batchOf(first, second, 0);
  PenaltyBatchResult plain, continued;
  p.newtonIterations = 8;
  penaltyTriangleDistanceBatch(batch, p, plain);
  penaltyTriangleDistanceBatchContinued(batch, eight, 8, nullptr, p, continued);
  for (int l = 0; l < kLanes; ++l) expectSame(plain.lane(l), continued.lane(l), std::size_t(l));
  EXPECT_THROW(penaltyTriangleDistanceBatchContinued(batch, eight, 0, nullptr, p, continued),
               std::invalid_argument);
}

TEST(TwoStageHybrid, EveryResultIsTheStageOneTheStageTwoOrTheExactOne) {
  HybridOptions o;
  o.newtonIterations = 4;
  o.continuationIterations = 4;
  // The definition of the two stages alone; a few random pairs have triangles more than
  // kClipSizeRatio apart in size, which the scale-aware path would take (test_large_triangle_clip).
  o.clipLargeTriangles = false;
  std::vector<Triangle> first, second;
  randomTrianglePairs(20000, 9, first, second);
  std::vector<Triangle> a, b;
  spheres(3, a, b);
  for (const Triangle& s : a)
    for (const Triangle& t : b) {
      first.push_back(s);
      second.push_back(t);
    }
  const Expected e = expectedTwoStage(first, second, o);
  std::vector<TriangleDistanceResult> hybrid(first.size());
  HybridStatistics statistics;
  hybridTriangleDistances(first.data(), second.data(), first.size(), o, hybrid.data(),
                          &statistics);
  for (std::size_t k = 0; k < first.size(); ++k) expectSame(hybrid[k], e.results[k], k);
  EXPECT_EQ(statistics.continued, e.continued);
  EXPECT_EQ(statistics.fallbacks(), e.fallbacks);
  std::printf("[ report   ] two-stage 4+4 on %zu pairs: stage 2 %.2f %%, fallback %.2f %%\n",
              first.size(), 100.0 * double(e.continued) / double(first.size()),
              100.0 * statistics.fallbackFraction());
  // Stage 2 is exercised and certifies most of its pairs.
  EXPECT_GT(e.continued, first.size() / 50);
  EXPECT_LT(2 * e.fallbacks, e.continued);
  // Certified means accurate: against the exact method to the hybrid's tolerance.
  for (std::size_t k = 0; k < first.size(); ++k) {
    const double d = triangleDistance(first[k], second[k]).distance;
    const double h = std::max(first[k].longestEdge(), second[k].longestEdge());
    ASSERT_LE(std::abs(hybrid[k].distance - d), 1e-10 * d + 1e-13 * h) << "pair " << k;
  }
  // Single-stage 4 steps: the same results wherever it certified, more fallbacks.
  HybridOptions single = o;
  single.continuationIterations = 0;
  std::vector<TriangleDistanceResult> once(first.size());
  HybridStatistics onceStatistics;
  hybridTriangleDistances(first.data(), second.data(), first.size(), single, once.data(),
                          &onceStatistics);
  // Stage 1 without feature bounds continues every pair the single stage falls back on (its
  // bound is never tighter), and some more.
  EXPECT_LE(onceStatistics.fallbacks(), e.continued);
  EXPECT_LT(statistics.fallbacks(), onceStatistics.fallbacks());
  EXPECT_EQ(onceStatistics.continued, 0u);
  // Schedules past the weight table are rejected, not truncated.
  HybridOptions tooLong = o;
  tooLong.continuationIterations = kMaxNewtonIterations - o.newtonIterations + 1;
  EXPECT_THROW(hybridTriangleDistances(first.data(), second.data(), 16, tooLong, once.data()),
               std::invalid_argument);
}

TEST(TwoStageHybrid, AllPairsFormsAgreeAndContactDecisionsEqualExact) {
  std::vector<Triangle> a, b;
  spheres(11, a, b);
  for (double contact : {0.0, 0.02}) {
    HybridOptions o;
    o.newtonIterations = 4;
    o.continuationIterations = 4;
    o.contactDistance = contact;
    std::vector<TriangleDistanceResult> all(a.size() * b.size()), exact(a.size() * b.size());
    HybridStatistics statistics;
    hybridTriangleDistancesOfAllPairs(a.data(), a.size(), b.data(), b.size(), o, all.data(),
                                      &statistics);
    triangleDistancesOfAllPairs(a.data(), a.size(), b.data(), b.size(), exact.data());
    std::vector<Triangle> first, second;
    for (const Triangle& s : a)
      for (const Triangle& t : b) {
        first.push_back(s);
        second.push_back(t);
      }
    std::vector<TriangleDistanceResult> elementwise(first.size());
    hybridTriangleDistances(first.data(), second.data(), first.size(), o, elementwise.data());
    EXPECT_GT(statistics.continued, 0u);
    for (std::size_t k = 0; k < all.size(); ++k) {
      // Bitwise without the band: its verdict also reads the lower bound, which is tighter
      // when another lane of the batch asked for the feature bounds.
      if (contact == 0.0) {
        expectSame(all[k], elementwise[k], k);
      }
      if (contact > 0.0) {
        ASSERT_EQ(all[k].distance < contact, exact[k].distance < contact) << "pair " << k;
      }
    }
  }
}
