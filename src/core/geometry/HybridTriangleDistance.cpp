#include "geometry/HybridTriangleDistance.h"

#include <limits>
#include <stdexcept>
#include <vector>

#include "geometry/IsaDispatch.h"
#include "geometry/LargeTriangleClip.h"
#include "geometry/PenaltyTriangleDistance.h"
#include "geometry/TriangleDistance.h"
#include "geometry/TrianglePairSources.h"

namespace spacetree::geometry {
namespace {

// The acceptance tests of the header for upper bound U, lower bound L and length scale h
// (branch-free): 0 accepted, 1 residual, 2 contact band fallback.
SPACETREE_INLINE_INTO_CLONES int verdictOf(double upper, double lower, double h,
                                           const HybridOptions& options) {
  const double threshold = options.contactDistance;
  const bool band = threshold > 0.0;
  // Written so that a NaN anywhere fails the check and falls back.
  const bool accurate =
      upper - lower <= options.relativeTolerance * upper + options.lengthScaleTolerance * h;
  const double slack = kRoundingSlack * (upper + 2.0 * h);
  const bool straddlesThreshold =
      band & (lower - slack < threshold) & (upper + slack >= threshold);
  return accurate ? (straddlesThreshold ? 2 : 0) : 1;
}

// The same for all lanes of a batch.
SPACETREE_INLINE_INTO_CLONES void verdictsOf(const PenaltyBatchResult& penalty,
                                             const HybridOptions& options, int* verdict) {
  for (int l = 0; l < kTrianglePairBatchSize; ++l)
    verdict[l] = verdictOf(penalty.distance[l], penalty.lowerBound[l], penalty.lengthScale[l],
                           options);
}

// Stage 2 of the two-stage hybrid: the pairs whose stage-1 residual was too large, gathered
// (compacted) from any number of stage-1 batches into full batches, with their last iterates.
struct ContinuationQueue {
  TrianglePairBatch batch{};
  alignas(64) double start[4][kTrianglePairBatchSize] = {};
  std::size_t index[kTrianglePairBatchSize] = {};
  int size = 0;

  void push(const TrianglePairBatch& from, const PenaltyBatchResult& stage1, int l,
            std::size_t k) {
    for (int t = 0; t < 2; ++t)
      for (int v = 0; v < 3; ++v)
        for (int c = 0; c < 3; ++c) batch.coordinate[t][v][c][size] = from.coordinate[t][v][c][l];
    for (int i = 0; i < 4; ++i) start[i][size] = stage1.iterate[i][l];
    index[size] = k;
    ++size;
  }
};

// Lanes [size, 16) of a gathered batch repeat lane 0 (valid input, results unused).
SPACETREE_INLINE_INTO_CLONES void padWithLaneZero(TrianglePairBatch& batch, int size) {
  for (int l = size; l < kTrianglePairBatchSize; ++l)
    for (int t = 0; t < 2; ++t)
      for (int v = 0; v < 3; ++v)
        for (int c = 0; c < 3; ++c) batch.coordinate[t][v][c][l] = batch.coordinate[t][v][c][0];
}

// The results of a gathered batch's lanes [0, size), lane l holding pair index[l]: the lane's
// own where the acceptance tests pass, else the exact method's.
template <class PairSource>
SPACETREE_INLINE_INTO_CLONES void acceptOrFallBack(const PairSource& pairs,
                                                   const PenaltyBatchResult& penalty,
                                                   const std::size_t* index, int size,
                                                   const HybridOptions& options,
                                                   TriangleDistanceResult* results,
                                                   HybridStatistics& counts) {
  int verdict[kTrianglePairBatchSize];
  verdictsOf(penalty, options, verdict);
  for (int l = 0; l < size; ++l) {
    const std::size_t k = index[l];
    if (verdict[l] == 0) {
      results[k] = penalty.lane(l);
    } else {
      ++(verdict[l] == 2 ? counts.contactBandFallbacks : counts.residualFallbacks);
      results[k] = triangleDistance(pairs.first(k), pairs.second(k));
    }
  }
}

template <class PairSource>
SPACETREE_INLINE_INTO_CLONES void continueQueued(const PairSource& pairs, ContinuationQueue& queue,
                                                 const double* weights, int steps,
                                                 const PenaltyOptions& penaltyOptions,
                                                 const HybridOptions& options,
                                                 TriangleDistanceResult* results,
                                                 HybridStatistics& counts) {
  if (queue.size == 0) return;
  padWithLaneZero(queue.batch, queue.size);
  for (int l = queue.size; l < kTrianglePairBatchSize; ++l)
    for (int i = 0; i < 4; ++i) queue.start[i][l] = queue.start[i][0];
  PenaltyBatchResult penalty;
  penaltyTriangleDistanceBatchContinued(queue.batch, weights, steps, queue.start, penaltyOptions,
                                        penalty);
  counts.continued += std::size_t(queue.size);
  acceptOrFallBack(pairs, penalty, queue.index, queue.size, options, results, counts);
  queue.size = 0;
}

// The scale-aware path: pairs of very different triangle sizes that stage 1 leaves uncertified,
// with the large triangle clipped to the small one's neighbourhood (LargeTriangleClip.h). The
// clip's own bounds certify most of them (a vertex over the large face, a vertex or an edge at
// its edge); the others are gathered into full batches that run the whole schedule from the
// centroids on the clipped pair. Each lane carries the original pair's length scale (the
// certification's slack must cover the rounding of the clipped vertices, a few ulps of the
// large triangle) and the clip's bounds.
struct ClipQueue {
  TrianglePairBatch batch{};
  std::size_t index[kTrianglePairBatchSize] = {};
  double lengthScale[kTrianglePairBatchSize] = {};
  double upperBound[kTrianglePairBatchSize] = {};
  double lowerBound[kTrianglePairBatchSize] = {};
  double pointOnFirst[3][kTrianglePairBatchSize] = {};
  double pointOnSecond[3][kTrianglePairBatchSize] = {};
  int size = 0;

  // Queues pair k (first, second) with its large triangle (0 or 1) clipped.
  void push(const LargeTriangleClip& clip, const Triangle& first, const Triangle& second,
            int large, double h, std::size_t k) {
    batch.set(size, large == 0 ? clip.part : first, large == 1 ? clip.part : second);
    index[size] = k;
    lengthScale[size] = h;
    upperBound[size] = clip.upperBound;
    lowerBound[size] = clip.lowerBound;
    const Eigen::Vector3d& onFirst = large == 0 ? clip.pointOnLarge : clip.pointOnSmall;
    const Eigen::Vector3d& onSecond = large == 0 ? clip.pointOnSmall : clip.pointOnLarge;
    for (int c = 0; c < 3; ++c) {
      pointOnFirst[c][size] = onFirst[c];
      pointOnSecond[c][size] = onSecond[c];
    }
    ++size;
  }
};

// The clip's own pair of points as the result of pair (first, second).
TriangleDistanceResult clipResult(const LargeTriangleClip& clip, int large) {
  TriangleDistanceResult r;
  r.distance = clip.upperBound;
  r.pointOnFirst = large == 0 ? clip.pointOnLarge : clip.pointOnSmall;
  r.pointOnSecond = large == 0 ? clip.pointOnSmall : clip.pointOnLarge;
  return r;
}

template <class PairSource>
SPACETREE_INLINE_INTO_CLONES void runClipped(const PairSource& pairs, ClipQueue& queue,
                                             const double* weights, int steps,
                                             const PenaltyOptions& penaltyOptions,
                                             const HybridOptions& options,
                                             TriangleDistanceResult* results,
                                             HybridStatistics& counts) {
  if (queue.size == 0) return;
  padWithLaneZero(queue.batch, queue.size);
  PenaltyBatchResult penalty;
  penaltyTriangleDistanceBatchContinued(queue.batch, weights, steps, nullptr, penaltyOptions,
                                        penalty);
  // The better of the kernel's and the clip's bounds (both rigorous), the original scale.
  for (int l = 0; l < queue.size; ++l) {
    if (queue.upperBound[l] < penalty.distance[l]) {
      penalty.distance[l] = queue.upperBound[l];
      for (int c = 0; c < 3; ++c) {
        penalty.pointOnFirst[c][l] = queue.pointOnFirst[c][l];
        penalty.pointOnSecond[c][l] = queue.pointOnSecond[c][l];
      }
    }
    if (queue.lowerBound[l] > penalty.lowerBound[l]) penalty.lowerBound[l] = queue.lowerBound[l];
    penalty.lengthScale[l] = queue.lengthScale[l];
  }
  acceptOrFallBack(pairs, penalty, queue.index, queue.size, options, results, counts);
  queue.size = 0;
}

template <class PairSource>
SPACETREE_INLINE_INTO_CLONES void hybridDistancesOf(const PairSource& pairs, const HybridOptions& options,
                       TriangleDistanceResult* results, HybridStatistics* statistics) {
  const std::size_t count = pairs.count();
  const int continuation = options.continuationIterations;
  if (options.newtonIterations < 1 || continuation < 0 ||
      options.newtonIterations + continuation > kMaxNewtonIterations)
    throw std::invalid_argument("hybridTriangleDistances: Newton iterations out of range");
  PenaltyOptions penaltyOptions;
  penaltyOptions.newtonIterations = options.newtonIterations;
  penaltyOptions.tightGap = options.relativeTolerance;
  penaltyOptions.tightGapPerLength = options.lengthScaleTolerance;
  // Stage 2 continues with the tail of the (stage 1 + stage 2)-step schedule.
  const double* continuationWeights =
      continuation > 0
          ? penaltyWeightSchedule(options.newtonIterations + continuation) +
                options.newtonIterations
          : nullptr;
  // Two-stage: stage 1 takes the cheap separating-axis bound only (no feature bounds); a lane
  // it leaves loose continues in stage 2, whose certification has the feature bounds.
  PenaltyOptions stage1Options = penaltyOptions;
  if (continuation > 0) stage1Options.tightGap = std::numeric_limits<double>::infinity();
  HybridStatistics counts;
  counts.pairs = count;
  // The scale-aware path runs the whole (stage 1 + stage 2)-step schedule, with feature bounds.
  const int clippedSteps = options.newtonIterations + continuation;
  const double* clippedWeights = penaltyWeightSchedule(clippedSteps);
  const double clipRatio = kClipSizeRatio * kClipSizeRatio;

  TrianglePairBatch batch;
  PenaltyBatchResult penalty;
  ContinuationQueue queue;
  ClipQueue clipQueue;
  for (std::size_t begin = 0; begin < count; begin += kTrianglePairBatchSize) {
    const int lanes = pairs.loadBatch(batch, begin);
    penaltyTriangleDistanceBatch(batch, stage1Options, penalty);
    // The acceptance tests for the whole batch first (branch-free), then the results.
    int verdict[kTrianglePairBatchSize];
    verdictsOf(penalty, options, verdict);
    // Every lane's penalty result first (a branch-free copy), then the fallbacks over it.
    TriangleDistanceResult* out = results + begin;
    for (int l = 0; l < lanes; ++l) out[l] = penalty.lane(l);
    for (int l = 0; l < lanes; ++l) {
      if (verdict[l] == 0) continue;
      const std::size_t k = begin + std::size_t(l);
      // Very different triangle sizes: the clipped pair instead (LargeTriangleClip.h),
      // certified by the clip's bounds where they meet, else by the kernel on the clipped pair.
      if (verdict[l] == 1 && options.clipLargeTriangles) {
        const double a = penalty.longestSquaredEdge[0][l], b = penalty.longestSquaredEdge[1][l];
        const int large = a > clipRatio * b ? 0 : (b > clipRatio * a ? 1 : -1);
        const Triangle &first = pairs.first(k), &second = pairs.second(k);
        const double h = penalty.lengthScale[l];
        const ClipAcceptance accept{options.relativeTolerance, options.lengthScaleTolerance * h};
        const LargeTriangleClip clip = large == 0   ? clipLargeTriangle(first, second, accept)
                                       : large == 1 ? clipLargeTriangle(second, first, accept)
                                                    : LargeTriangleClip{};
        const int bounds =
            clip.bounded ? verdictOf(clip.upperBound, clip.lowerBound, h, options) : 1;
        if (bounds != 1 || clip.clipped) {
          ++counts.clipped;
          if (bounds == 0) {
            results[k] = clipResult(clip, large);
          } else if (bounds == 2) {
            ++counts.contactBandFallbacks;
            results[k] = triangleDistance(first, second);
          } else {
            clipQueue.push(clip, first, second, large, h, k);
            if (clipQueue.size == kTrianglePairBatchSize)
              runClipped(pairs, clipQueue, clippedWeights, clippedSteps, penaltyOptions, options,
                         results, counts);
          }
          continue;
        }
      }
      if (verdict[l] == 1 && continuation > 0) {
        queue.push(batch, penalty, l, k);
        if (queue.size == kTrianglePairBatchSize)
          continueQueued(pairs, queue, continuationWeights, continuation, penaltyOptions,
                         options, results, counts);
        continue;
      }
      ++(verdict[l] == 2 ? counts.contactBandFallbacks : counts.residualFallbacks);
      results[k] = triangleDistance(pairs.first(k), pairs.second(k));
    }
  }
  continueQueued(pairs, queue, continuationWeights, continuation, penaltyOptions, options,
                 results, counts);
  runClipped(pairs, clipQueue, clippedWeights, clippedSteps, penaltyOptions, options, results,
             counts);
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
