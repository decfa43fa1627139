#include "geometry/TriangleDistance.h"

#include <Eigen/Geometry>

#include <cmath>
#include <limits>

#include "geometry/AccurateCrossProduct.h"
#include "geometry/IsaDispatch.h"
#include "geometry/SegmentDistance.h"

namespace spacetree::geometry {
namespace {

using Eigen::Vector3d;

// A triangle relative to the pair's local origin, with its edges and (unnormalised) normal.
// Working relative to a vertex of the first triangle keeps rounding errors proportional to the
// pair's extent instead of to the absolute coordinates (particles far from the origin).
struct LocalTriangle {
  Vector3d vertex[3];
  Vector3d edge[3];  // edge[i] = vertex[i+1] - vertex[i]
  double inverseSquaredEdgeLength[3];  // 0 for a zero-length edge
  Vector3d normal;   // edge[0] x (vertex[2] - vertex[0]), compensated: accurate for slivers
  double normalSquaredNorm;

  SPACETREE_INLINE_INTO_CLONES LocalTriangle(const Triangle& t, const Vector3d& origin) {
    for (int i = 0; i < 3; ++i) vertex[i] = t[i] - origin;
    for (int i = 0; i < 3; ++i) edge[i] = vertex[(i + 1) % 3] - vertex[i];
    for (int i = 0; i < 3; ++i) inverseSquaredEdgeLength[i] = inverseSquaredLengthOrZero(edge[i]);
    normal = accurateCross(edge[0], vertex[2] - vertex[0]);
    normalSquaredNorm = normal.squaredNorm();
  }

  // Whether x (anywhere along the normal) projects into the closed triangle. The sign of each
  // edge function is only wrong within a few ulps of the edge, where the edge-edge sub-checks
  // find the same distance anyway.
  SPACETREE_INLINE_INTO_CLONES bool projectsInside(const Vector3d& x) const {
    for (int i = 0; i < 3; ++i)
      if (edge[i].cross(x - vertex[i]).dot(normal) < 0.0) return false;
    return true;
  }
};

struct Candidate {
  double squaredDistance = std::numeric_limits<double>::infinity();
  Vector3d onFirst = Vector3d::Zero();
  Vector3d onSecond = Vector3d::Zero();
};

// An edge of `edges` crossing the plane of `face` strictly inside the face: the triangles
// intersect. Edges lying in the plane (coplanar triangles) do not count here; their contacts
// are edge-edge or vertex-face contacts at distance 0.
SPACETREE_INLINE_INTO_CLONES bool findPiercingEdge(const LocalTriangle& edges, const double heightAboveFace[3],
                      const LocalTriangle& face, Vector3d& crossing) {
  if (face.normalSquaredNorm == 0.0) return false;
  for (int i = 0; i < 3; ++i) {
    const double h0 = heightAboveFace[i];
    const double h1 = heightAboveFace[(i + 1) % 3];
    if ((h0 < 0.0 && h1 > 0.0) || (h0 > 0.0 && h1 < 0.0)) {
      const Vector3d x = edges.vertex[i] + (h0 / (h0 - h1)) * edges.edge[i];
      if (face.projectsInside(x)) {
        crossing = x;
        return true;
      }
    }
  }
  return false;
}

// Vertices of `vertices` whose projection falls into `face`: the vertex-face sub-checks.
// firstIsFace says which side of the result the face point belongs to.
SPACETREE_INLINE_INTO_CLONES void improveByVertexFace(const LocalTriangle& vertices, const double heightAboveFace[3],
                         const LocalTriangle& face, bool firstIsFace, Candidate& best) {
  if (face.normalSquaredNorm == 0.0) return;  // degenerate face: its edges cover it
  for (int i = 0; i < 3; ++i) {
    const double h = heightAboveFace[i];
    const double squaredDistance = h * h / face.normalSquaredNorm;
    if (squaredDistance >= best.squaredDistance) continue;
    if (!face.projectsInside(vertices.vertex[i])) continue;
    const Vector3d foot = vertices.vertex[i] - (h / face.normalSquaredNorm) * face.normal;
    best.squaredDistance = squaredDistance;
    best.onFirst = firstIsFace ? foot : vertices.vertex[i];
    best.onSecond = firstIsFace ? vertices.vertex[i] : foot;
  }
}

}  // namespace

SPACETREE_DISPATCH_BY_ISA
TriangleDistanceResult triangleDistance(const Triangle& first, const Triangle& second) {
  const Vector3d origin = first[0];
  const LocalTriangle a(first, origin);
  const LocalTriangle b(second, origin);

  double bAboveA[3], aAboveB[3];  // heights above the other plane, scaled by |normal|
  for (int i = 0; i < 3; ++i) {
    bAboveA[i] = a.normal.dot(b.vertex[i] - a.vertex[0]);
    aAboveB[i] = b.normal.dot(a.vertex[i] - b.vertex[0]);
  }

  TriangleDistanceResult result;
  Vector3d crossing;
  if (findPiercingEdge(b, bAboveA, a, crossing) || findPiercingEdge(a, aAboveB, b, crossing)) {
    result.distance = 0.0;
    result.pointOnFirst = result.pointOnSecond = crossing + origin;
    return result;
  }

  Candidate best;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const SegmentClosestPoints s =
          closestPointsOfSegments(a.vertex[i], a.edge[i], a.inverseSquaredEdgeLength[i],
                                  b.vertex[j], b.edge[j], b.inverseSquaredEdgeLength[j]);
      if (s.squaredDistance < best.squaredDistance) {
        best.squaredDistance = s.squaredDistance;
        best.onFirst = s.pointOnFirst;
        best.onSecond = s.pointOnSecond;
      }
    }
  improveByVertexFace(b, bAboveA, a, /*firstIsFace=*/true, best);
  improveByVertexFace(a, aAboveB, b, /*firstIsFace=*/false, best);

  result.distance = std::sqrt(best.squaredDistance);
  result.pointOnFirst = best.onFirst + origin;
  result.pointOnSecond = best.onSecond + origin;
  return result;
}

void triangleDistances(const Triangle* first, const Triangle* second, std::size_t count,
                       TriangleDistanceResult* results) {
  for (std::size_t k = 0; k < count; ++k) results[k] = triangleDistance(first[k], second[k]);
}

void triangleDistances(const Triangle& first, const Triangle* second, std::size_t count,
                       TriangleDistanceResult* results) {
  for (std::size_t k = 0; k < count; ++k) results[k] = triangleDistance(first, second[k]);
}

void triangleDistancesOfAllPairs(const Triangle* first, std::size_t firstCount,
                                 const Triangle* second, std::size_t secondCount,
                                 TriangleDistanceResult* results) {
  for (std::size_t i = 0; i < firstCount; ++i)
    triangleDistances(first[i], second, secondCount, results + i * secondCount);
}

}  // namespace spacetree::geometry
