// Exact geometric triangle-to-triangle distance (the reference "brute force" of the paper, §6.2):
// the minimum over the 9 edge-edge and 6 vertex-face sub-checks, plus detection of intersecting
// triangles (an edge of one piercing the other: distance 0). Robust for parallel, coplanar and
// degenerate (zero-area, zero-length-edge) triangles. "Exact" means geometrically complete, in
// double precision: the error is a few ulps of the pair's extent (see docs/triangle_distance.md).
#pragma once

#include <cstddef>

#include "geometry/Triangle.h"

namespace spacetree::geometry {

TriangleDistanceResult triangleDistance(const Triangle& first, const Triangle& second);

// The same for first[k] and second[k], k < count; for one triangle against each of
// second[0, count); and for every pair of two meshes (results[i * secondCount + j]): the array
// forms of the penalty and hybrid methods, for like-for-like use.
void triangleDistances(const Triangle* first, const Triangle* second, std::size_t count,
                       TriangleDistanceResult* results);
void triangleDistances(const Triangle& first, const Triangle* second, std::size_t count,
                       TriangleDistanceResult* results);
void triangleDistancesOfAllPairs(const Triangle* first, std::size_t firstCount,
                                 const Triangle* second, std::size_t secondCount,
                                 TriangleDistanceResult* results);

}  // namespace spacetree::geometry
