#include "geometry/HybridTriangleDistance.h"

#include "geometry/PenaltyTriangleDistance.h"
#include "geometry/TriangleDistance.h"
#include "geometry/TrianglePairSources.h"

namespace spacetree::geometry {
namespace {

template <class PairSource>
void hybridDistancesOf(const PairSource& pairs, const HybridOptions& options,
                       TriangleDistanceResult* results, HybridStatistics* statistics) {
  const std::size_t count = pairs.count();
  PenaltyOptions penaltyOptions;
  penaltyOptions.newtonIterations = options.newtonIterations;
  penaltyOptions.tightGap = options.relativeTolerance;
  penaltyOptions.tightGapPerLength = options.lengthScaleTolerance;
  const double threshold = options.contactDistance;
  HybridStatistics counts;
  counts.pairs = count;

  TrianglePairBatch batch;
  PenaltyBatchResult penalty;
  for (std::size_t begin = 0; begin < count; begin += kTrianglePairBatchSize) {
    const int lanes = pairs.loadBatch(batch, begin);
    penaltyTriangleDistanceBatch(batch, penaltyOptions, penalty);
    for (int l = 0; l < lanes; ++l) {
      const std::size_t k = begin + std::size_t(l);
      const double upper = penalty.distance[l];
      const double lower = penalty.lowerBound[l];
      const double h = penalty.lengthScale[l];
      // Written so that a NaN anywhere fails the check and falls back.
      const bool accurate = upper - lower <= options.relativeTolerance * upper +
                                                 options.lengthScaleTolerance * h;
      const double slack = kRoundingSlack * (upper + 2.0 * h);
      const bool straddlesThreshold =
          threshold > 0.0 && lower - slack < threshold && upper + slack >= threshold;
      if (accurate && !straddlesThreshold) {
        results[k] = penalty.lane(l);
        continue;
      }
      ++(accurate ? counts.contactBandFallbacks : counts.residualFallbacks);
      results[k] = triangleDistance(pairs.first(k), pairs.second(k));
    }
  }
  if (statistics) *statistics += counts;
}

}  // namespace

void hybridTriangleDistances(const Triangle* first, const Triangle* second, std::size_t count,
                             const HybridOptions& options, TriangleDistanceResult* results,
                             HybridStatistics* statistics) {
  hybridDistancesOf(ElementwisePairs{first, second, count}, options, results, statistics);
}

void hybridTriangleDistances(const Triangle& first, const Triangle* second, std::size_t count,
                             const HybridOptions& options, TriangleDistanceResult* results,
                             HybridStatistics* statistics) {
  hybridDistancesOf(OneAgainstMany{&first, second, count}, options, results, statistics);
}

void hybridTriangleDistancesOfAllPairs(const Triangle* first, std::size_t firstCount,
                                       const Triangle* second, std::size_t secondCount,
                                       const HybridOptions& options,
                                       TriangleDistanceResult* results,
                                       HybridStatistics* statistics) {
  hybridDistancesOf(AllPairs{first, firstCount, second, secondCount}, options, results,
                    statistics);
}

}  // namespace spacetree::geometry
