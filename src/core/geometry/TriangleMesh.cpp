#include "geometry/TriangleMesh.h"

#include <algorithm>
#include <limits>
#include <utility>

namespace spacetree::geometry {

std::vector<Triangle> TriangleMesh::triangleSoup() const {
  std::vector<Triangle> soup;
  soup.reserve(triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t) soup.push_back(triangle(t));
  return soup;
}

double TriangleMesh::minimumEdgeLength() const {
  if (triangles.empty()) return 0.0;
  double shortest = std::numeric_limits<double>::infinity();
  for (const auto& f : triangles)
    for (int i = 0; i < 3; ++i)
      shortest = std::min(shortest, (vertices[f[(i + 1) % 3]] - vertices[f[i]]).norm());
  return shortest;
}

double TriangleMesh::maximumEdgeLength() const {
  double longest = 0.0;
  for (const auto& f : triangles)
    for (int i = 0; i < 3; ++i)
      longest = std::max(longest, (vertices[f[(i + 1) % 3]] - vertices[f[i]]).norm());
  return longest;
}

Eigen::Vector3d TriangleMesh::areaVector(std::size_t t) const {
  const auto& f = triangles[t];
  return (vertices[f[1]] - vertices[f[0]]).cross(vertices[f[2]] - vertices[f[0]]);
}

double TriangleMesh::surfaceArea() const {
  double area = 0.0;
  for (std::size_t t = 0; t < triangles.size(); ++t) area += 0.5 * areaVector(t).norm();
  return area;
}

Eigen::AlignedBox3d TriangleMesh::boundingBox() const {
  Eigen::AlignedBox3d box;
  for (const auto& v : vertices) box.extend(v);
  return box;
}

void TriangleMesh::transform(const Eigen::Matrix3d& rotation, const Eigen::Vector3d& translation) {
  for (auto& v : vertices) v = rotation * v + translation;
}

void TriangleMesh::flipOrientation() {
  for (auto& f : triangles) std::swap(f[1], f[2]);
}

}  // namespace spacetree::geometry
