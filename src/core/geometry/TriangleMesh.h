// An indexed triangle surface: shared vertices plus triangles as vertex-index triples. The
// common currency of the mesh module: readMesh() returns one, validateMesh() checks (and
// repairs) one, computeMassProperties() and RigidShape take one. Orientation convention:
// counter-clockwise seen from outside, i.e. (v1 - v0) x (v2 - v0) is the outward normal.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <cstddef>
#include <vector>

#include "geometry/Triangle.h"

namespace spacetree::geometry {

struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;  // indices into vertices

  std::size_t vertexCount() const { return vertices.size(); }
  std::size_t triangleCount() const { return triangles.size(); }
  bool empty() const { return triangles.empty(); }

  // Triangle t as three points (no index check beyond vector::operator[]).
  Triangle triangle(std::size_t t) const {
    const auto& f = triangles[t];
    return Triangle(vertices[f[0]], vertices[f[1]], vertices[f[2]]);
  }
  // All triangles as points, in order: the input of the triangle-distance kernels.
  std::vector<Triangle> triangleSoup() const;

  // Shortest and longest edge over all triangles (0 for an empty mesh).
  double minimumEdgeLength() const;
  double maximumEdgeLength() const;

  // (v1 - v0) x (v2 - v0) of triangle t: outward normal times twice the area.
  Eigen::Vector3d areaVector(std::size_t t) const;
  double surfaceArea() const;

  // Axis-aligned box around all vertices (empty box for no vertices).
  Eigen::AlignedBox3d boundingBox() const;

  // x -> rotation * x + translation for every vertex.
  void transform(const Eigen::Matrix3d& rotation, const Eigen::Vector3d& translation);
  // Reverses every triangle's orientation (swaps two indices).
  void flipOrientation();
};

}  // namespace spacetree::geometry
