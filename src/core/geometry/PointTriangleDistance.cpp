#include "geometry/PointTriangleDistance.h"

#include <algorithm>

namespace spacetree::geometry {

PointTriangleClosest closestPointOnTriangle(const Eigen::Vector3d& p, const Triangle& t) {
  PointTriangleClosest r = pointTriangleOffset(p, t);
  if (!r.degenerate) return r;
  // Zero area: the closest point of the three edges (segment k from vertex k to k + 1).
  static constexpr TriangleFeature kEdge[3] = {TriangleFeature::Edge01, TriangleFeature::Edge12,
                                               TriangleFeature::Edge20};
  static constexpr TriangleFeature kVertex[3] = {
      TriangleFeature::Vertex0, TriangleFeature::Vertex1, TriangleFeature::Vertex2};
  double best = -1.0;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d& a = t[k];
    const Eigen::Vector3d e = t[(k + 1) % 3] - a;
    const double ee = e.squaredNorm();
    const double s = ee > 0.0 ? std::clamp((p - a).dot(e) / ee, 0.0, 1.0) : 0.0;
    const Eigen::Vector3d offset = p - (a + s * e);
    const double d2 = offset.squaredNorm();
    if (best < 0.0 || d2 < best) {
      best = d2;
      r.offset = offset;
      r.feature = s <= 0.0 ? kVertex[k] : s >= 1.0 ? kVertex[(k + 1) % 3] : kEdge[k];
    }
  }
  return r;
}

}  // namespace spacetree::geometry
