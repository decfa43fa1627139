#include "geometry/HybridTriangleDistance.h"

#include <vector>

#include "geometry/IsaDispatch.h"
#include "geometry/PenaltyTriangleDistance.h"
#include "geometry/TriangleDistance.h"
#include "geometry/TrianglePairSources.h"

namespace spacetree::geometry {
namespace {

template <class PairSource>
SPACETREE_INLINE_INTO_CLONES void hybridDistancesOf(const PairSource& pairs, const HybridOptions& options,
                       TriangleDistanceResult* results, HybridStatistics* statistics) {
  const std::size_t count = pairs.count();
  PenaltyOptions penaltyOptions;
  penaltyOptions.newtonIterations = options.newtonIterations;
  penaltyOptions.tightGap = options.relativeTolerance;
  penaltyOptions.tightGapPerLength = options.lengthScaleTolerance;
  const double threshold = options.contactDistance;
  HybridStatistics counts;
  counts.pairs = count;

  const double relativeTolerance = options.relativeTolerance;
  const double lengthScaleTolerance = options.lengthScaleTolerance;
  const bool band = threshold > 0.0;
  TrianglePairBatch batch;
  PenaltyBatchResult penalty;
  for (std::size_t begin = 0; begin < count; begin += kTrianglePairBatchSize) {
    const int lanes = pairs.loadBatch(batch, begin);
    penaltyTriangleDistanceBatch(batch, penaltyOptions, penalty);
    // The acceptance tests for the whole batch first (branch-free), then the results.
    int verdict[kTrianglePairBatchSize];  // 0 accepted, 1 residual, 2 contact band fallback
    for (int l = 0; l < kTrianglePairBatchSize; ++l) {
      const double upper = penalty.distance[l];
      const double lower = penalty.lowerBound[l];
      const double h = penalty.lengthScale[l];
      // Written so that a NaN anywhere fails the check and falls back.
      const bool accurate =
          upper - lower <= relativeTolerance * upper + lengthScaleTolerance * h;
      const double slack = kRoundingSlack * (upper + 2.0 * h);
      const bool straddlesThreshold =
          band & (lower - slack < threshold) & (upper + slack >= threshold);
      verdict[l] = accurate ? (straddlesThreshold ? 2 : 0) : 1;
    }
    // Every lane's penalty result first (a branch-free copy), then the fallbacks over it.
    TriangleDistanceResult* out = results + begin;
    for (int l = 0; l < lanes; ++l) out[l] = penalty.lane(l);
    for (int l = 0; l < lanes; ++l) {
      if (verdict[l] == 0) continue;
      const std::size_t k = begin + std::size_t(l);
      ++(verdict[l] == 2 ? counts.contactBandFallbacks : counts.residualFallbacks);
      results[k] = triangleDistance(pairs.first(k), pairs.second(k));
    }
  }
  if (statistics) *statistics += counts;
}

// Per thread, kept between calls: the packed second mesh of the all-pairs form.
std::vector<double>& packingBuffer() {
  thread_local std::vector<double> buffer;
  return buffer;
}

// The batching loops (loads, acceptance tests, result copies) compiled per instruction set
// like the kernel, so that they vectorise too.
SPACETREE_DISPATCH_BY_ISA
void hybridDistancesOfElementwisePairs(const ElementwisePairs& pairs, const HybridOptions& options,
                                       TriangleDistanceResult* results,
                                       HybridStatistics* statistics) {
  hybridDistancesOf(pairs, options, results, statistics);
}

SPACETREE_DISPATCH_BY_ISA
void hybridDistancesOfOneAgainstMany(const OneAgainstMany& pairs, const HybridOptions& options,
                                     TriangleDistanceResult* results,
                                     HybridStatistics* statistics) {
  hybridDistancesOf(pairs, options, results, statistics);
}

SPACETREE_DISPATCH_BY_ISA
void hybridDistancesOfPackedAllPairs(const PackedAllPairs& pairs, const HybridOptions& options,
                                     TriangleDistanceResult* results,
                                     HybridStatistics* statistics) {
  hybridDistancesOf(pairs, options, results, statistics);
}

}  // namespace

void hybridTriangleDistances(const Triangle* first, const Triangle* second, std::size_t count,
                             const HybridOptions& options, TriangleDistanceResult* results,
                             HybridStatistics* statistics) {
  hybridDistancesOfElementwisePairs(ElementwisePairs{first, second, count}, options, results,
                                    statistics);
}

void hybridTriangleDistances(const Triangle& first, const Triangle* second, std::size_t count,
                             const HybridOptions& options, TriangleDistanceResult* results,
                             HybridStatistics* statistics) {
  hybridDistancesOfOneAgainstMany(OneAgainstMany{&first, second, count}, options, results,
                                  statistics);
}

void hybridTriangleDistancesOfAllPairs(const Triangle* first, std::size_t firstCount,
                                       const Triangle* second, std::size_t secondCount,
                                       const HybridOptions& options,
                                       TriangleDistanceResult* results,
                                       HybridStatistics* statistics) {
  if (firstCount == 0 || secondCount == 0) return;
  std::vector<double>& buffer = packingBuffer();
  buffer.resize(9 * PackedAllPairs::strideFor(secondCount));
  PackedAllPairs::pack(second, secondCount, buffer.data());
  hybridDistancesOfPackedAllPairs(PackedAllPairs{first, firstCount, second, secondCount,
                                                 buffer.data(),
                                                 PackedAllPairs::strideFor(secondCount)},
                                  options, results, statistics);
}

}  // namespace spacetree::geometry
