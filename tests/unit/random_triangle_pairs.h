// Test helper: random triangle pairs (vertices in [-1,1]^3, the second triangle shifted by up
// to 3 in a random direction), the population of the penalty/hybrid convergence tests.
#pragma once

#include <cstddef>
#include <random>
#include <vector>

#include <Eigen/Core>

#include "geometry/Triangle.h"

inline void randomTrianglePairs(std::size_t count, unsigned seed,
                                std::vector<spacetree::geometry::Triangle>& first,
                                std::vector<spacetree::geometry::Triangle>& second) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0), shift(0.0, 3.0);
  const auto point = [&] { return Eigen::Vector3d(u(rng), u(rng), u(rng)); };
  for (std::size_t k = 0; k < count; ++k) {
    first.push_back({point(), point(), point()});
    const Eigen::Vector3d s = point() * shift(rng);
    second.push_back({point() + s, point() + s, point() + s});
  }
}
