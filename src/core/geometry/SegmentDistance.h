// Closest points of two 3D segments: the edge-edge sub-check of the exact triangle distance.
// Header-only so that it inlines into the (ISA-dispatched) triangle routine.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>

#include "geometry/IsaDispatch.h"

namespace spacetree::geometry {

struct SegmentClosestPoints {
  double squaredDistance;
  Eigen::Vector3d pointOnFirst;
  Eigen::Vector3d pointOnSecond;
};

// Segments p + s pDir and q + t qDir, s, t in [0, 1]; inverseSquaredLengthP = 1 / |pDir|^2
// (0 for a zero-length segment), likewise for q, so that callers checking many edge pairs
// divide once per edge. Robust for parallel, collinear and zero-length segments.
//
// The textbook form s = (b f - c e) / (a e - b^2) cancels catastrophically for nearly parallel
// segments, and a wrong s of order one costs an error of order sqrt(eps) in the distance of
// nearly touching, nearly parallel edges. The line-line parameter is computed instead from the
// common normal n = pDir x qDir as s = ((q - p) x qDir) . n / |n|^2: its error is ~eps / sin(angle),
// and along the nearly flat valley of |P(s) - Q(t)|^2 this changes the squared distance only by
// |n|^2 ds^2 ~ eps^2 |pDir|^2 |qDir|^2, i.e. the distance by ~eps times the edge length.
//
// Clamping is branch-free and follows the convex structure: s is the clamped line-line
// parameter, t the clamped best partner of s, and s is then re-optimised for that t. If t needed
// no clamping the re-optimisation leaves s unchanged (a clamped s stays clamped: the objective
// along the valley t(s) is convex), otherwise it is the textbook correction; either way the KKT
// conditions of the box [0, 1]^2 hold. Parallel segments (n = 0) start from s = 0.
SPACETREE_INLINE_INTO_CLONES SegmentClosestPoints closestPointsOfSegments(
    const Eigen::Vector3d& p, const Eigen::Vector3d& pDir, double inverseSquaredLengthP,
    const Eigen::Vector3d& q, const Eigen::Vector3d& qDir, double inverseSquaredLengthQ) {
  const auto clamp01 = [](double x) { return std::min(1.0, std::max(0.0, x)); };
  const Eigen::Vector3d qToP = p - q;
  const double pq = pDir.dot(qDir);
  const double pDirDotQToP = pDir.dot(qToP);
  const double qDirDotQToP = qDir.dot(qToP);
  const Eigen::Vector3d n = pDir.cross(qDir);
  const double nn = n.squaredNorm();
  const double lineLineS = nn > 0.0 ? (-qToP).cross(qDir).dot(n) / nn : 0.0;

  double s = clamp01(lineLineS);
  const double t = clamp01((pq * s + qDirDotQToP) * inverseSquaredLengthQ);
  s = clamp01((pq * t - pDirDotQToP) * inverseSquaredLengthP);

  SegmentClosestPoints result;
  result.pointOnFirst = p + s * pDir;
  result.pointOnSecond = q + t * qDir;
  result.squaredDistance = (result.pointOnFirst - result.pointOnSecond).squaredNorm();
  return result;
}

// 1 / |d|^2, or 0 for a zero vector (the segment is a point; its parameter stays 0).
SPACETREE_INLINE_INTO_CLONES double inverseSquaredLengthOrZero(const Eigen::Vector3d& d) {
  const double dd = d.squaredNorm();
  return dd > 0.0 ? 1.0 / dd : 0.0;
}

}  // namespace spacetree::geometry
