// The hybrid triangle-to-triangle distance (paper §6.2): the batched penalty-Newton kernel for
// every pair, the exact geometric method for the pairs the penalty result cannot be trusted on.
//
// A penalty result is accepted only when two checks pass, both from rigorous bounds: the kernel
// returns an upper bound U (distance of two admissible points) and a lower bound L (separating
// axis) of the true distance d, each up to floating-point rounding.
//   1. Residual: U - L <= relativeTolerance * U + lengthScaleTolerance * h, h the longest edge
//      of the pair. The returned distance U is then within that tolerance of d: relative to d
//      for separated pairs, relative to the triangle size for touching ones.
//   2. Contact band: with contactDistance T > 0 (the paper's 2 eps) the pair must not straddle
//      T: either U + s < T (surely in contact) or L - s >= T (surely not), where the slack
//      s = kRoundingSlack * (U + 2h) exceeds the rounding error of both L and the exact method.
//      Whenever the exact method decides d < T, so does the hybrid, and vice versa: the
//      decisions are identical by construction, not just on the pairs tested.
// Everything else falls back to triangleDistance(). See docs/triangle_distance.md for numbers.
#pragma once

#include <cstddef>

#include "geometry/Triangle.h"

namespace spacetree::geometry {

struct HybridOptions {
  double contactDistance = 0.0;         // T = 2 eps; 0 (or less) switches the band check off
  double relativeTolerance = 1e-11;     // accepted certified gap: this times the distance ...
  double lengthScaleTolerance = 1e-14;  // ... plus this times the longest edge h
  int newtonIterations = 5;             // penalty Newton steps of stage 1 (the paper: 4 or 8)
  // Two-stage hybrid when > 0: the pairs that stage 1 (newtonIterations steps) leaves with a
  // too large residual are gathered into new batches and continue from their last iterate for
  // this many steps, with the last continuationIterations weights of the
  // (newtonIterations + continuationIterations)-step schedule; they are certified by the same
  // rule, the rest falls back. Stage 1 then computes only the cheap lower bound (no feature
  // bounds): a pair it leaves loose continues, and stage 2 has the feature bounds.
  // newtonIterations + continuationIterations <= 32.
  // Default 5+4: the fastest combination measured (docs/triangle_distance.md); 0 gives the
  // single-stage hybrid.
  int continuationIterations = 4;
  // Scale-aware path: a pair whose triangles differ in size by more than kClipSizeRatio and
  // that stage 1 leaves uncertified is recomputed with the large triangle clipped to the small
  // one's neighbourhood (same distance, LargeTriangleClip.h), from the centroids with all
  // newtonIterations + continuationIterations steps, and certified by the same rule (with
  // the original pair's h and the clip's vertex-face bounds); what still fails falls back.
  bool clipLargeTriangles = true;
};

// Rounding slack of the contact band, relative to the pair's extent U + 2h. The bounds and the
// exact method are computed relative to a vertex of the first triangle, in a few dozen
// operations on coordinates of magnitude <= U + 2h; their errors are ~1e-15 of that (a few
// ulps), the slack allows a thousand times more.
constexpr double kRoundingSlack = 1e-12;

struct HybridStatistics {
  std::size_t pairs = 0;
  std::size_t residualFallbacks = 0;     // certified gap above the tolerance
  std::size_t contactBandFallbacks = 0;  // accurate, but within rounding of the contact distance
  std::size_t continued = 0;             // pairs that ran stage 2 (two-stage hybrid only)
  std::size_t clipped = 0;               // pairs that took the scale-aware path

  std::size_t fallbacks() const { return residualFallbacks + contactBandFallbacks; }
  double fallbackFraction() const { return pairs ? double(fallbacks()) / double(pairs) : 0.0; }
  HybridStatistics& operator+=(const HybridStatistics& other) {
    pairs += other.pairs;
    residualFallbacks += other.residualFallbacks;
    contactBandFallbacks += other.contactBandFallbacks;
    continued += other.continued;
    clipped += other.clipped;
    return *this;
  }
};

// Hybrid distances of first[k] and second[k], k < count; of one triangle against each of
// second[0, count); and of every pair of two meshes (results[i * secondCount + j] for first[i]
// and second[j]). Statistics, if given, are accumulated.
void hybridTriangleDistances(const Triangle* first, const Triangle* second, std::size_t count,
                             const HybridOptions& options, TriangleDistanceResult* results,
                             HybridStatistics* statistics = nullptr);
void hybridTriangleDistances(const Triangle& first, const Triangle* second, std::size_t count,
                             const HybridOptions& options, TriangleDistanceResult* results,
                             HybridStatistics* statistics = nullptr);
void hybridTriangleDistancesOfAllPairs(const Triangle* first, std::size_t firstCount,
                                       const Triangle* second, std::size_t secondCount,
                                       const HybridOptions& options,
                                       TriangleDistanceResult* results,
                                       HybridStatistics* statistics = nullptr);

}  // namespace spacetree::geometry
