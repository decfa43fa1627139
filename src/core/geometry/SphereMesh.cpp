#include "geometry/SphereMesh.h"

#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace spacetree::geometry {

std::vector<Triangle> latitudeLongitudeSphere(int slices, int stacks, double radius) {
  if (slices < 3 || stacks < 2)
    throw std::invalid_argument("latitudeLongitudeSphere: need slices >= 3 and stacks >= 2");
  const double pi = std::acos(-1.0);
  const auto vertex = [&](int slice, int stack) {
    const double polar = pi * stack / stacks;
    const double azimuth = 2.0 * pi * (slice % slices) / slices;
    return Eigen::Vector3d(radius * std::sin(polar) * std::cos(azimuth),
                           radius * std::sin(polar) * std::sin(azimuth),
                           radius * std::cos(polar));
  };
  std::vector<Triangle> triangles;
  triangles.reserve(std::size_t(2) * slices * (stacks - 1));
  for (int i = 0; i < slices; ++i) {
    triangles.emplace_back(vertex(i, 0), vertex(i, 1), vertex(i + 1, 1));
    for (int j = 1; j + 1 < stacks; ++j) {
      triangles.emplace_back(vertex(i, j), vertex(i, j + 1), vertex(i + 1, j + 1));
      triangles.emplace_back(vertex(i, j), vertex(i + 1, j + 1), vertex(i + 1, j));
    }
    triangles.emplace_back(vertex(i, stacks - 1), vertex(i, stacks), vertex(i + 1, stacks - 1));
  }
  return triangles;
}

std::vector<Triangle> latitudeLongitudeSphereWithAbout(int triangles, double radius) {
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
  return latitudeLongitudeSphere(bestSlices, bestStacks, radius);
}

}  // namespace spacetree::geometry
