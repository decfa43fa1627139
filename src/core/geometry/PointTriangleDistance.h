// Squared distance of a point to a triangle (closest point by Voronoi regions of the vertices,
// edges and face; Ericson, Real-Time Collision Detection, 5.1.5): the contact search's cull of
// large triangles against a sphere (MeshContact step 3). Rounding: a few ulps of the
// triangle's extent; a degenerate triangle that reaches the face branch gives 0 (never more
// than the true distance).
#pragma once

#include <Eigen/Core>

#include "geometry/Triangle.h"

namespace spacetree::geometry {

inline double pointTriangleSquaredDistance(const Eigen::Vector3d& p, const Triangle& t) {
  const Eigen::Vector3d ab = t[1] - t[0], ac = t[2] - t[0], ap = p - t[0];
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return ap.squaredNorm();  // vertex 0
  const Eigen::Vector3d bp = p - t[1];
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return bp.squaredNorm();  // vertex 1
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {  // edge 01
    const double v = d1 / (d1 - d3);
    return (ap - v * ab).squaredNorm();
  }
  const Eigen::Vector3d cp = p - t[2];
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return cp.squaredNorm();  // vertex 2
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {  // edge 02
    const double w = d2 / (d2 - d6);
    return (ap - w * ac).squaredNorm();
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {  // edge 12
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return (bp - w * (t[2] - t[1])).squaredNorm();
  }
  const double denominator = va + vb + vc;  // face interior
  if (!(denominator > 0.0)) return 0.0;  // degenerate (zero area): no bound (callers cull on it)
  const double v = vb / denominator, w = vc / denominator;
  return (ap - ab * v - ac * w).squaredNorm();
}

}  // namespace spacetree::geometry
