#include "geometry/RigidShape.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <utility>

namespace spacetree::geometry {

Eigen::Quaterniond RigidShape::bodyOrientationFor(const Eigen::Quaterniond& meshOrientation) const {
  return (meshOrientation * Eigen::Quaterniond(meshRotation)).normalized();
}

namespace {

// Everything but the frame and the mass properties, from shape.bodyMesh: triangles, extent,
// triangle spheres and their index, and the adjacency. Adjacency over undirected edges: the
// neighbour across an edge is the other triangle of that edge when exactly two share it (a
// closed, consistently oriented mesh: always); a boundary or non-manifold edge has none (-1).
void completeShape(RigidShape& shape) {
  shape.bodyTriangles = shape.bodyMesh.triangleSoup();
  shape.minimumEdgeLength = shape.bodyMesh.minimumEdgeLength();

  shape.boundingRadius = 0.0;
  shape.boundingBoxLow = Eigen::Vector3d::Constant(INFINITY);
  shape.boundingBoxHigh = Eigen::Vector3d::Constant(-INFINITY);
  for (const auto& f : shape.bodyMesh.triangles)
    for (int v : f) {
      const Eigen::Vector3d& x = shape.bodyMesh.vertices[v];
      shape.boundingRadius = std::max(shape.boundingRadius, x.norm());
      shape.boundingBoxLow = shape.boundingBoxLow.cwiseMin(x);
      shape.boundingBoxHigh = shape.boundingBoxHigh.cwiseMax(x);
    }
  shape.triangleCentres.clear();
  shape.triangleRadii.clear();
  shape.triangleCentres.reserve(shape.bodyTriangles.size());
  shape.triangleRadii.reserve(shape.bodyTriangles.size());
  for (const Triangle& t : shape.bodyTriangles) {
    const Eigen::Vector3d centre = (t[0] + t[1] + t[2]) / 3.0;
    shape.triangleCentres.push_back(centre);
    shape.triangleRadii.push_back(std::max({(t[0] - centre).norm(), (t[1] - centre).norm(),
                                            (t[2] - centre).norm()}));
  }
  shape.triangleIndex = TriangleBvh(shape.triangleCentres, shape.triangleRadii);
  // Undirected edge (a < b) -> (triangle, apex) of the triangles that have it.
  std::map<std::pair<int, int>, std::vector<std::pair<std::size_t, int>>> apexesOfEdge;
  const auto& triangles = shape.bodyMesh.triangles;
  const auto key = [](int a, int b) { return a < b ? std::make_pair(a, b) : std::make_pair(b, a); };
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (int k = 0; k < 3; ++k)
      apexesOfEdge[key(triangles[t][k], triangles[t][(k + 1) % 3])].push_back(
          {t, triangles[t][(k + 2) % 3]});
  shape.edgeApex.assign(triangles.size(), {-1, -1, -1});
  std::vector<std::vector<int>> neighbours(shape.bodyMesh.vertices.size());
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = triangles[t][k], b = triangles[t][(k + 1) % 3];
      const auto& sharing = apexesOfEdge[key(a, b)];
      if (sharing.size() == 2) shape.edgeApex[t][k] = sharing[sharing[0].first == t ? 1 : 0].second;
      neighbours[a].push_back(b);
      neighbours[b].push_back(a);
    }
  shape.vertexNeighbourOffsets.assign(1, 0);
  shape.vertexNeighbours.clear();
  for (auto& list : neighbours) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
    shape.vertexNeighbours.insert(shape.vertexNeighbours.end(), list.begin(), list.end());
    shape.vertexNeighbourOffsets.push_back(int(shape.vertexNeighbours.size()));
  }
}

}  // namespace

RigidShape RigidShape::fromMesh(const TriangleMesh& mesh) {
  const MassProperties properties = computeMassProperties(mesh);
  RigidShape shape;
  shape.meshRotation = properties.principalAxes;
  shape.centreOfMassInMesh = properties.centreOfMass;
  shape.volume = properties.volume;
  shape.principalInertiaPerUnitDensity = properties.principalMomentsPerUnitDensity;

  shape.bodyMesh = mesh;
  // x_body = R^T (x_mesh - c)
  const Eigen::Matrix3d toBody = properties.principalAxes.transpose();
  shape.bodyMesh.transform(toBody, -toBody * properties.centreOfMass);
  completeShape(shape);
  return shape;
}

RigidShape RigidShape::fromSurface(const TriangleMesh& mesh) {
  if (mesh.empty()) throw std::invalid_argument("RigidShape::fromSurface: no triangles");
  RigidShape shape;
  const Eigen::AlignedBox3d box = mesh.boundingBox();
  shape.centreOfMassInMesh = box.center();
  shape.bodyMesh = mesh;
  shape.bodyMesh.transform(Eigen::Matrix3d::Identity(), -shape.centreOfMassInMesh);
  completeShape(shape);
  return shape;
}

}  // namespace spacetree::geometry
