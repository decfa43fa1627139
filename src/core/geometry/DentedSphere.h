// The paper's particles (§7): triangulated spheres whose vertices are dented in or pushed out
// at random. A latitude-longitude sphere with the requested triangle count (or the closest one
// it can make, see latitudeLongitudeSphereMesh) gets every vertex moved along its ray from the
// centre to radius * (1 + amplitude * u), u uniform in [-1, 1) and drawn from a seeded
// 64-bit Mersenne twister (bit-exact on every platform: the conversion to [-1, 1) is ours).
// Radial moves keep the surface closed, consistently outward-oriented and free of
// self-intersections (a radial graph: every tetrahedron (centre, triangle) keeps a positive
// volume) for any amplitude in [0, 1).
#pragma once

#include <cstdint>

#include "geometry/TriangleMesh.h"

namespace spacetree::geometry {

struct DentedSphereOptions {
  int triangles = 80;         // requested count (>= 12)
  double radius = 1.0;        // of the undented sphere
  double amplitude = 0.1;     // relative to the radius, in [0, 1)
  std::uint64_t seed = 1;
};

// Throws std::invalid_argument for triangles outside [12, kMaxSphereMeshTriangles] (10^6,
// SphereMesh.h), radius <= 0 or amplitude outside [0, 1).
TriangleMesh dentedSphere(const DentedSphereOptions& options);

}  // namespace spacetree::geometry
