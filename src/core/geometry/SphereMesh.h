// Triangulated spheres (latitude-longitude meshes): the test particles of the triangle-distance
// tests and benchmark, and a simple particle surface for callers.
#pragma once

#include <vector>

#include "geometry/Triangle.h"

namespace spacetree::geometry {

// A sphere of the given radius around the origin with `slices` longitudes (>= 3) and `stacks`
// latitude bands (>= 2): fans at the poles, two triangles per quad in between, so
// 2 * slices * (stacks - 1) triangles, all with outward (counter-clockwise) orientation.
// Throws std::invalid_argument for too few slices or stacks.
std::vector<Triangle> latitudeLongitudeSphere(int slices, int stacks, double radius);

// The latitude-longitude sphere whose triangle count is closest to `triangles` (>= 12), with
// about twice as many slices as stacks (near-equilateral triangles at the equator).
std::vector<Triangle> latitudeLongitudeSphereWithAbout(int triangles, double radius);

}  // namespace spacetree::geometry
