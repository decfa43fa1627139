// The paper's branch-free triangle-to-triangle distance (§6.2, after Krestenitis et al.): the
// closest points x = A0 + u1 (A1 - A0) + u2 (A2 - A0) and y = B0 + v1 (B1 - B0) + v2 (B2 - B0)
// minimise |x - y|^2 over the barycentric parameters z = (u1, u2, v1, v2); the six admissibility
// constraints (u1, u2 >= 0, u1 + u2 <= 1, same for v) enter as a quadratic penalty, and a fixed
// number of (semi-smooth) Newton steps runs on a batch of pairs in lock step, without branches,
// so that the compiler maps the loop over the batch onto SIMD lanes.
//
// The penalty weight grows from step to step (continuation): small weights keep the first steps
// well conditioned while the active constraints are found, the final weight (1e12 relative to
// the mean squared edge length) leaves a constraint violation of ~1e-12 of the distance. The
// result is then made admissible (clamped into both triangles), so `distance` is the distance
// of two true points of the triangles: an upper bound of the true distance. `lowerBound`
// certifies it from below: for the unit direction n of the two points, every point of A lies
// at least min_i n.A_i and every point of B at most max_j n.B_j along n (separating axis), so
// dist(A, B) >= min_i n.A_i - max_j n.B_j. At the exact minimiser the two bounds coincide; the
// gap distance - lowerBound is the residual the hybrid method accepts or falls back on.
// Both bounds hold up to a few ulps of the pair's extent (floating-point rounding).
#pragma once

#include <cstddef>

#include "geometry/TrianglePairBatch.h"

namespace spacetree::geometry {

constexpr int kMaxNewtonIterations = 32;

struct PenaltyOptions {
  int newtonIterations = 8;  // fixed count in [1, kMaxNewtonIterations]; the paper uses 4 or 8
  // The cheap separating-axis bound along the points' direction is enough for the batch when
  // in every lane distance - bound <= tightGap * distance + tightGapPerLength * h; otherwise
  // three more (feature) bounds are computed for the whole batch. Only the tightness of
  // lowerBound depends on these (it is rigorous either way); the hybrid passes its acceptance
  // tolerances so that it gets the feature bounds exactly when the cheap one would fail it.
  double tightGap = 1e-13;
  double tightGapPerLength = 0.0;
};

struct PenaltyBatchResult {
  alignas(64) double distance[kTrianglePairBatchSize];     // |pointOnFirst - pointOnSecond|
  alignas(64) double lowerBound[kTrianglePairBatchSize];   // >= 0, <= the true distance
  alignas(64) double lengthScale[kTrianglePairBatchSize];  // longest edge of the two triangles
  // Longest squared edge of the first (0) and of the second (1) triangle: the size ratio the
  // hybrid's scale-aware path tests (LargeTriangleClip.h).
  alignas(64) double longestSquaredEdge[2][kTrianglePairBatchSize];
  alignas(64) double pointOnFirst[3][kTrianglePairBatchSize];
  alignas(64) double pointOnSecond[3][kTrianglePairBatchSize];
  // The last Newton iterate (u1, u2, v1, v2) before it is made admissible: the state a
  // continuation (penaltyTriangleDistanceBatchContinued) starts from.
  alignas(64) double iterate[4][kTrianglePairBatchSize];

  TriangleDistanceResult lane(int l) const {
    TriangleDistanceResult r;
    r.distance = distance[l];
    r.pointOnFirst = {pointOnFirst[0][l], pointOnFirst[1][l], pointOnFirst[2][l]};
    r.pointOnSecond = {pointOnSecond[0][l], pointOnSecond[1][l], pointOnSecond[2][l]};
    return r;
  }
};

// The kernel: all kTrianglePairBatchSize lanes of the batch. Throws std::invalid_argument for an
// iteration count outside [1, kMaxNewtonIterations].
void penaltyTriangleDistanceBatch(const TrianglePairBatch& batch, const PenaltyOptions& options,
                                  PenaltyBatchResult& result);

// The penalty weights of the `steps`-step schedule (steps values, relative to the mean squared
// edge length), the ones penaltyTriangleDistanceBatch uses. Throws std::invalid_argument for
// steps outside [1, kMaxNewtonIterations].
const double* penaltyWeightSchedule(int steps);

// The kernel from a given iterate: `steps` Newton steps with weights[0, steps) starting from
// start[0..3][lane] = (u1, u2, v1, v2) (the centroids when start is null). Running a schedule
// in two calls, the second from the first's result.iterate, gives bit for bit the result of one
// call with the concatenated schedule (each lane's arithmetic does not depend on the others;
// only lowerBound may come out tighter where another lane of the batch needed feature bounds).
void penaltyTriangleDistanceBatchContinued(const TrianglePairBatch& batch, const double* weights,
                                           int steps,
                                           const double (*start)[kTrianglePairBatchSize],
                                           const PenaltyOptions& options,
                                           PenaltyBatchResult& result);

// Penalty distances (no certification, no fallback) of first[k] and second[k], k < count; of
// one triangle against each of second[0, count); and of every pair of two meshes (results in
// row-major order, results[i * secondCount + j] for first[i] and second[j]).
void penaltyTriangleDistances(const Triangle* first, const Triangle* second, std::size_t count,
                              const PenaltyOptions& options, TriangleDistanceResult* results);
void penaltyTriangleDistances(const Triangle& first, const Triangle* second, std::size_t count,
                              const PenaltyOptions& options, TriangleDistanceResult* results);
void penaltyTriangleDistancesOfAllPairs(const Triangle* first, std::size_t firstCount,
                                        const Triangle* second, std::size_t secondCount,
                                        const PenaltyOptions& options,
                                        TriangleDistanceResult* results);

}  // namespace spacetree::geometry
