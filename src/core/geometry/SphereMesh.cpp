#include "geometry/SphereMesh.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace spacetree::geometry {

TriangleMesh latitudeLongitudeSphereMesh(int slices, int stacks, double radius) {
  if (slices < 3 || stacks < 2)
    throw std::invalid_argument("latitudeLongitudeSphere: need slices >= 3 and stacks >= 2");
  if (std::int64_t(2) * slices * (stacks - 1) > kMaxSphereMeshTriangles)
    throw std::invalid_argument("latitudeLongitudeSphere: more than " +
                                std::to_string(kMaxSphereMeshTriangles) + " triangles");
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
  if (triangles > kMaxSphereMeshTriangles)
    throw std::invalid_argument("latitudeLongitudeSphereWithAbout: more than " +
                                std::to_string(kMaxSphereMeshTriangles) + " triangles");
  // Closest count first, then slices closest to twice the stacks, then the fewest stacks and
  // slices. For given stacks the miss is V-shaped in the slices, so only the two slice counts
  // around triangles / (2 (stacks - 1)) (clamped to [3, 3 stacks]) can win: O(triangles) work.
  // 64-bit products: 2 * slices * (stacks - 1) overflows int near 10^5 requested triangles.
  const std::int64_t wanted = std::max(triangles, 0);
  int bestSlices = 3, bestStacks = 2;
  const auto miss = [wanted](std::int64_t slices, std::int64_t stacks) {
    return std::llabs(2 * slices * (stacks - 1) - wanted);
  };
  for (std::int64_t stacks = 2; 6 * (stacks - 1) <= wanted + 6; ++stacks) {
    const std::int64_t below = std::clamp<std::int64_t>(wanted / (2 * (stacks - 1)), 3, 3 * stacks);
    const std::int64_t above = std::min<std::int64_t>(below + 1, 3 * stacks);
    for (const std::int64_t slices : {below, above}) {
      const std::int64_t m = miss(slices, stacks), bestMiss = miss(bestSlices, bestStacks);
      if (m < bestMiss || (m == bestMiss && std::llabs(slices - 2 * stacks) <
                                                std::llabs(bestSlices - 2 * bestStacks))) {
        bestSlices = int(slices);
        bestStacks = int(stacks);
      }
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
