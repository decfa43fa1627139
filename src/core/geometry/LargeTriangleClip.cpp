#include "geometry/LargeTriangleClip.h"

#include <algorithm>
#include <cmath>

#include "geometry/SegmentDistance.h"

namespace spacetree::geometry {

using Eigen::Vector3d;

namespace {

double longestSquaredEdge(const Triangle& t) {
  return std::max({(t[1] - t[0]).squaredNorm(), (t[2] - t[1]).squaredNorm(),
                   (t[0] - t[2]).squaredNorm()});
}

// Separating-axis bound along m (any length, 0 gives 0) of the large triangle {0, e1, e2} and
// the small one {q0, q1, q2}, both relative to the large triangle's vertex 0: rigorous for the
// direction as computed.
double separationAlong(const Vector3d& m, const Vector3d& e1, const Vector3d& e2,
                       const Vector3d (&q)[3]) {
  const double norm = m.norm();
  if (!(norm > 0.0)) return 0.0;
  const double l1 = m.dot(e1) / norm, l2 = m.dot(e2) / norm;
  const double minL = std::min({0.0, l1, l2}), maxL = std::max({0.0, l1, l2});
  double minS = INFINITY, maxS = -INFINITY;
  for (const Vector3d& p : q) {
    const double s = m.dot(p) / norm;
    minS = std::min(minS, s);
    maxS = std::max(maxS, s);
  }
  return std::max({minS - maxL, minL - maxS, 0.0});
}

}  // namespace

int largeTriangleOfPair(const Triangle& first, const Triangle& second) {
  const double a = longestSquaredEdge(first), b = longestSquaredEdge(second);
  const double ratio = kClipSizeRatio * kClipSizeRatio;
  if (a > ratio * b) return 0;
  if (b > ratio * a) return 1;
  return -1;
}

LargeTriangleClip clipLargeTriangle(const Triangle& large, const Triangle& small,
                                    const ClipAcceptance& accept) {
  LargeTriangleClip out;
  // Everything relative to the large triangle's vertex 0 (rounding scales with the pair).
  const Vector3d e1 = large[1] - large[0], e2 = large[2] - large[0];
  const Vector3d n = e1.cross(e2);
  const double nn = n.squaredNorm();
  if (!(nn > 0.0) || !std::isfinite(nn)) return out;
  const double area = std::sqrt(nn);  // |e1 x e2|
  // Dual basis of the large triangle's plane: the parameters of the projection of q are
  // (q . d1, q . d2) (area coordinates: d1 = e2 x n / |n|^2, d2 = n x e1 / |n|^2).
  const Vector3d d1 = e2.cross(n) / nn, d2 = n.cross(e1) / nn;
  const Vector3d unit = n / area;
  const Vector3d q[3] = {small[0] - large[0], small[1] - large[0], small[2] - large[0]};
  const double height[3] = {unit.dot(q[0]), unit.dot(q[1]), unit.dot(q[2])};

  // The best pair of points found (relative coordinates): x on the large triangle, y on the
  // small one; first each small vertex against its projection clamped into the large triangle.
  double best = INFINITY;  // squared distance
  Vector3d x = Vector3d::Zero(), y = Vector3d::Zero();
  int vertex = -1;         // the small triangle's vertex y is, or -1
  const auto offer = [&](const Vector3d& onLarge, const Vector3d& onSmall, int j) {
    const double d = (onSmall - onLarge).squaredNorm();
    if (d < best) {
      best = d;
      x = onLarge;
      y = onSmall;
      vertex = j;
      return true;
    }
    return false;
  };
  for (int j = 0; j < 3; ++j) {
    double u1 = std::max(q[j].dot(d1), 0.0), u2 = std::max(q[j].dot(d2), 0.0);
    const double sum = u1 + u2;
    if (sum > 1.0) {
      u1 /= sum;
      u2 /= sum;
    }
    offer(e1 * u1 + e2 * u2, q[j], j);
  }
  if (!std::isfinite(best)) return out;
  // Lower bound along the large triangle's normal (vertex over the face: the large triangle's
  // own heights along the rounded normal are kept, so the bound is rigorous for that direction).
  {
    const double l1 = unit.dot(e1), l2 = unit.dot(e2);
    const double minL = std::min({0.0, l1, l2}), maxL = std::max({0.0, l1, l2});
    const double minS = std::min({height[0], height[1], height[2]});
    const double maxS = std::max({height[0], height[1], height[2]});
    out.lowerBound = std::max({minS - maxL, minL - maxS, 0.0});
  }
  const auto finishBounds = [&] {
    out.upperBound = std::sqrt(best);
    out.pointOnLarge = large[0] + x;
    out.pointOnSmall = vertex >= 0 ? small[vertex] : Vector3d(large[0] + y);
    out.bounded = true;
  };
  const auto accepted = [&] {
    return accept.relative >= 0.0 &&
           out.upperBound - out.lowerBound <= accept.relative * out.upperBound + accept.absolute;
  };
  finishBounds();
  if (accepted()) return out;

  // The ball B(c, D + r) around the small triangle's centroid as an ellipse in the large
  // triangle's parameters, and the sub-triangle bounding its part inside the triangle.
  const Vector3d c = (q[0] + q[1] + q[2]) / 3.0;
  const double r = std::sqrt(std::max({(q[0] - c).squaredNorm(), (q[1] - c).squaredNorm(),
                                       (q[2] - c).squaredNorm()}));
  // The relative margin only widens the part (rounding of the extent below is ~1e-16).
  const double reach = (std::sqrt(best) + r) * (1.0 + 1e-9);
  const double h = (height[0] + height[1] + height[2]) / 3.0;
  const double kappaSquared = reach * reach - h * h;
  if (!(kappaSquared > 0.0)) return out;
  const double kappa = std::sqrt(kappaSquared) / area;
  const double c1 = c.dot(d1), c2 = c.dot(d2);
  const double w1 = kappa * e2.norm(), w2 = kappa * e1.norm(), w3 = kappa * (e2 - e1).norm();
  const double a1 = std::max(0.0, c1 - w1), a2 = std::max(0.0, c2 - w2);
  const double b = std::min(1.0, c1 + c2 + w3);
  const double scale = b - a1 - a2;
  if (!(scale > 0.0) || !(scale <= kClipMaximumScale)) return out;
  const Vector3d part[3] = {e1 * a1 + e2 * a2, e1 * (b - a2) + e2 * a2, e1 * a1 + e2 * (b - a1)};

  // Edges of the part that lie on the large triangle's own edges (where the clamps bit: a
  // closest point there may be on the edge, not over the face): each against the small
  // triangle's edges (segment distances, their end points covering its vertices).
  Vector3d edgeOfLarge = Vector3d::Zero(), edgeOfSmall = Vector3d::Zero();
  bool edgeEdgeBest = false;
  const int sides[3][2] = {{0, 1}, {0, 2}, {1, 2}};  // on u2 = 0, u1 = 0, u1 + u2 = 1
  const bool onEdge[3] = {a2 == 0.0, a1 == 0.0, b == 1.0};
  for (int s = 0; s < 3; ++s) {
    if (!onEdge[s]) continue;
    const Vector3d& from = part[sides[s][0]];
    const Vector3d along = part[sides[s][1]] - from;
    const double inverse = inverseSquaredLengthOrZero(along);
    for (int j = 0; j < 3; ++j) {
      const Vector3d smallEdge = q[(j + 1) % 3] - q[j];
      const SegmentClosestPoints ee = closestPointsOfSegments(
          from, along, inverse, q[j], smallEdge, inverseSquaredLengthOrZero(smallEdge));
      if (offer(ee.pointOnFirst, ee.pointOnSecond, -1)) {
        edgeEdgeBest = true;
        edgeOfLarge = along;
        edgeOfSmall = smallEdge;
      }
    }
  }
  finishBounds();

  // Lower bound, beyond the normal's: separating axes along the best pair's direction (exact at
  // a minimum of any kind) and, for an edge-edge candidate, along the two edges' cross product.
  if (out.upperBound > out.lowerBound)
    out.lowerBound = std::max(out.lowerBound, separationAlong(y - x, e1, e2, q));
  if (edgeEdgeBest && out.upperBound > out.lowerBound)
    out.lowerBound = std::max(out.lowerBound,
                              separationAlong(edgeOfLarge.cross(edgeOfSmall), e1, e2, q));
  out.part = Triangle(large[0] + part[0], large[0] + part[1], large[0] + part[2]);
  out.clipped = true;
  return out;
}

}  // namespace spacetree::geometry
