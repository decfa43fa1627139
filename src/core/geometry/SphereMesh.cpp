#include "geometry/SphereMesh.h"

#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace spacetree::geometry {

TriangleMesh latitudeLongitudeSphereMesh(int slices, int stacks, double radius) {
  if (slices < 3 || stacks < 2)
    throw std::invalid_argument("latitudeLongitudeSphere: need slices >= 3 and stacks >= 2");
  const double pi = std::acos(-1.0);
  TriangleMesh mesh;
  // Vertex 0: north pole; then ring j = 1 .. stacks-1 with `slices` vertices; last: south pole.
  mesh.vertices.emplace_back(0.0, 0.0, radius);
  for (int stack = 1; stack < stacks; ++stack) {
    const double polar = pi * stack / stacks;
    for (int slice = 0; slice < slices; ++slice) {
      const double azimuth = 2.0 * pi * slice / slices;
      mesh.vertices.emplace_back(radius * std::sin(polar) * std::cos(azimuth),
                                 radius * std::sin(polar) * std::sin(azimuth),
                                 radius * std::cos(polar));
    }
  }
  mesh.vertices.emplace_back(0.0, 0.0, -radius);
  const int southPole = int(mesh.vertices.size()) - 1;
  const auto ring = [slices](int slice, int stack) { return 1 + (stack - 1) * slices + slice % slices; };
  mesh.triangles.reserve(std::size_t(2) * slices * (stacks - 1));
  for (int i = 0; i < slices; ++i) {
    mesh.triangles.push_back({0, ring(i, 1), ring(i + 1, 1)});
    for (int j = 1; j + 1 < stacks; ++j) {
      mesh.triangles.push_back({ring(i, j), ring(i, j + 1), ring(i + 1, j + 1)});
      mesh.triangles.push_back({ring(i, j), ring(i + 1, j + 1), ring(i + 1, j)});
    }
    mesh.triangles.push_back({ring(i, stacks - 1), southPole, ring(i + 1, stacks - 1)});
  }
  return mesh;
}

TriangleMesh latitudeLongitudeSphereMeshWithAbout(int triangles, double radius) {
  // Closest count first, then slices closest to twice the stacks.
  int bestSlices = 3, bestStacks = 2;
  const auto miss = [triangles](int slices, int stacks) {
    return std::abs(2 * slices * (stacks - 1) - triangles);
  };
  for (int stacks = 2; 2 * 3 * (stacks - 1) <= triangles + 6; ++stacks)
    for (int slices = 3; slices <= 3 * stacks; ++slices) {
      const int m = miss(slices, stacks), bestMiss = miss(bestSlices, bestStacks);
      if (m < bestMiss || (m == bestMiss && std::abs(slices - 2 * stacks) <
                                                std::abs(bestSlices - 2 * bestStacks))) {
        bestSlices = slices;
        bestStacks = stacks;
      }
    }
  return latitudeLongitudeSphereMesh(bestSlices, bestStacks, radius);
}

std::vector<Triangle> latitudeLongitudeSphere(int slices, int stacks, double radius) {
  return latitudeLongitudeSphereMesh(slices, stacks, radius).triangleSoup();
}

std::vector<Triangle> latitudeLongitudeSphereWithAbout(int triangles, double radius) {
  return latitudeLongitudeSphereMeshWithAbout(triangles, radius).triangleSoup();
}

}  // namespace spacetree::geometry
