// Triangulated particles in world coordinates: the triangles of all particles in one flat array,
// particle p owning triangles [offset[p], offset[p + 1]). Built by posing reference meshes
// (rotation + translation per particle), e.g. latitude-longitude spheres.
#pragma once

#include <Eigen/Geometry>

#include <cstddef>
#include <vector>

#include "geometry/Triangle.h"

namespace spacetree::parallel {

struct PosedMeshes {
  std::vector<geometry::Triangle> triangles;
  std::vector<std::size_t> offset{0};

  int particleCount() const { return int(offset.size()) - 1; }
  std::size_t triangleCount(int p) const { return offset[p + 1] - offset[p]; }
  const geometry::Triangle* trianglesOf(int p) const { return triangles.data() + offset[p]; }

  // Appends a particle: `reference` rotated by `rotation`, then moved to `position`.
  void add(const std::vector<geometry::Triangle>& reference, const Eigen::Matrix3d& rotation,
           const Eigen::Vector3d& position) {
    for (const geometry::Triangle& t : reference)
      triangles.emplace_back(rotation * t[0] + position, rotation * t[1] + position,
                             rotation * t[2] + position);
    offset.push_back(triangles.size());
  }
};

}  // namespace spacetree::parallel
