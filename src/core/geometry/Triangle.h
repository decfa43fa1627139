// Small value types of the triangle-distance module: a triangle as three vertices and the result
// of a triangle-to-triangle distance query (distance plus one pair of closest points).
#pragma once

#include <Eigen/Core>

#include <algorithm>
#include <array>

namespace spacetree::geometry {

struct Triangle {
  std::array<Eigen::Vector3d, 3> vertex;

  Triangle() = default;
  Triangle(const Eigen::Vector3d& v0, const Eigen::Vector3d& v1, const Eigen::Vector3d& v2)
      : vertex{v0, v1, v2} {}

  const Eigen::Vector3d& operator[](int i) const { return vertex[i]; }
  Eigen::Vector3d& operator[](int i) { return vertex[i]; }

  // Longest edge: the length scale tolerances of a pair are measured against.
  double longestEdge() const {
    return std::max({(vertex[1] - vertex[0]).norm(), (vertex[2] - vertex[1]).norm(),
                     (vertex[0] - vertex[2]).norm()});
  }
};

struct TriangleDistanceResult {
  double distance = 0.0;          // Euclidean distance between the two triangles (0 if they meet)
  Eigen::Vector3d pointOnFirst;   // closest point on the first triangle
  Eigen::Vector3d pointOnSecond;  // closest point on the second triangle; equal if distance is 0
};

}  // namespace spacetree::geometry
