// Triangulated spheres (latitude-longitude meshes): the test particles of the triangle-distance
// tests and benchmark, the base of the dented spheres (DentedSphere.h), and a simple particle
// surface for callers.
#pragma once

#include <vector>

#include "geometry/Triangle.h"
#include "geometry/TriangleMesh.h"

namespace spacetree::geometry {

// The most triangles a generated sphere may have: 10^6 (a LIGGGHTS particle template of that
// size takes about 0.5 GB and 4 s to build).
inline constexpr int kMaxSphereMeshTriangles = 1000000;

// A sphere of the given radius around the origin with `slices` longitudes (>= 3) and `stacks`
// latitude bands (>= 2): fans at the poles, two triangles per quad in between, so
// 2 * slices * (stacks - 1) triangles and slices * (stacks - 1) + 2 shared vertices, closed
// and outward (counter-clockwise) oriented. Throws std::invalid_argument for too few slices
// or stacks, or more than kMaxSphereMeshTriangles triangles.
TriangleMesh latitudeLongitudeSphereMesh(int slices, int stacks, double radius);

// The latitude-longitude sphere whose triangle count is closest to `triangles` (>= 12), with
// about twice as many slices as stacks (near-equilateral triangles at the equator). Every
// even count >= 12 that is 2 * slices * (stacks - 1) for some admissible pair is met exactly
// (e.g. 12, 20, 40, 80, 160, 320, 640, 1000). Linear in `triangles`; throws
// std::invalid_argument above kMaxSphereMeshTriangles.
TriangleMesh latitudeLongitudeSphereMeshWithAbout(int triangles, double radius);

// The same two as triangle soups (the triangles' points, no shared indices).
std::vector<Triangle> latitudeLongitudeSphere(int slices, int stacks, double radius);
std::vector<Triangle> latitudeLongitudeSphereWithAbout(int triangles, double radius);

}  // namespace spacetree::geometry
