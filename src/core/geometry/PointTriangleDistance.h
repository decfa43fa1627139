// Closest point of a triangle to a point (Voronoi regions of the vertices, edges and face;
// Ericson, Real-Time Collision Detection, 5.1.5): the contact search's cull of large triangles
// against a sphere (MeshContact step 3) and the sphere-triangle contacts (SphereMeshContact).
// Rounding: a few ulps of the triangle's extent.
#pragma once

#include <Eigen/Core>

#include "geometry/Triangle.h"

namespace spacetree::geometry {

// Where on the triangle the closest point lies: a vertex k, the edge (k, k+1 mod 3) or inside.
enum class TriangleFeature { Vertex0, Vertex1, Vertex2, Edge01, Edge12, Edge20, Face };

struct PointTriangleClosest {
  Eigen::Vector3d offset;  // p - closest point
  TriangleFeature feature = TriangleFeature::Face;
  bool degenerate = false;  // (nearly) zero-area triangle, no face point (offset set to 0)
};

// The closest point of t to p is p - result.offset. A (nearly) degenerate triangle that reaches
// the face branch (see there) gives offset 0 and degenerate = true (the
// squared distance below is then 0, never more than the true distance; closestPointOnTriangle
// resolves it by the edges).
inline PointTriangleClosest pointTriangleOffset(const Eigen::Vector3d& p, const Triangle& t) {
  PointTriangleClosest r;
  const Eigen::Vector3d ab = t[1] - t[0], ac = t[2] - t[0], ap = p - t[0];
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) {
    r.offset = ap;
    r.feature = TriangleFeature::Vertex0;
    return r;
  }
  const Eigen::Vector3d bp = p - t[1];
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) {
    r.offset = bp;
    r.feature = TriangleFeature::Vertex1;
    return r;
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    const double v = d1 / (d1 - d3);
    r.offset = ap - v * ab;
    r.feature = TriangleFeature::Edge01;
    return r;
  }
  const Eigen::Vector3d cp = p - t[2];
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) {
    r.offset = cp;
    r.feature = TriangleFeature::Vertex2;
    return r;
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    const double w = d2 / (d2 - d6);
    r.offset = ap - w * ac;
    r.feature = TriangleFeature::Edge20;
    return r;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    r.offset = bp - w * (t[2] - t[1]);
    r.feature = TriangleFeature::Edge12;
    return r;
  }
  const double denominator = va + vb + vc;  // face interior
  // A (nearly) degenerate triangle can reach this branch with weights of any sign and relative
  // errors ~ 1e-16 / sin(smallest angle): no reliable face point below sin = 1e-8, where its
  // edges are within 1e-8 of its extent of it.
  const double area2 = ab.cross(ac).squaredNorm();
  if (!(denominator > 0.0) || va < 0.0 || vb < 0.0 || vc < 0.0 ||
      !(area2 > 1e-16 * ab.squaredNorm() * ac.squaredNorm())) {
    r.offset = Eigen::Vector3d::Zero();
    r.degenerate = true;
    return r;
  }
  const double v = vb / denominator, w = vc / denominator;
  r.offset = ap - ab * v - ac * w;
  return r;
}

// Squared distance of p to t (0 for a degenerate triangle without a face point: a lower bound,
// what the culls need).
inline double pointTriangleSquaredDistance(const Eigen::Vector3d& p, const Triangle& t) {
  return pointTriangleOffset(p, t).offset.squaredNorm();
}

// The closest point (p - offset) and its feature; a degenerate triangle is taken as its three
// edges (the closest of them; feature of that edge or its end).
PointTriangleClosest closestPointOnTriangle(const Eigen::Vector3d& p, const Triangle& t);

}  // namespace spacetree::geometry
