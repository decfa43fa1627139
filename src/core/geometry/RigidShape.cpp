#include "geometry/RigidShape.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

namespace spacetree::geometry {

Eigen::Quaterniond RigidShape::bodyOrientationFor(const Eigen::Quaterniond& meshOrientation) const {
  return (meshOrientation * Eigen::Quaterniond(meshRotation)).normalized();
}

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
  shape.bodyTriangles = shape.bodyMesh.triangleSoup();
  shape.minimumEdgeLength = shape.bodyMesh.minimumEdgeLength();

  shape.boundingBoxLow = Eigen::Vector3d::Constant(INFINITY);
  shape.boundingBoxHigh = Eigen::Vector3d::Constant(-INFINITY);
  for (const auto& f : shape.bodyMesh.triangles)
    for (int v : f) {
      const Eigen::Vector3d& x = shape.bodyMesh.vertices[v];
      shape.boundingRadius = std::max(shape.boundingRadius, x.norm());
      shape.boundingBoxLow = shape.boundingBoxLow.cwiseMin(x);
      shape.boundingBoxHigh = shape.boundingBoxHigh.cwiseMax(x);
    }
  shape.triangleCentres.reserve(shape.bodyTriangles.size());
  shape.triangleRadii.reserve(shape.bodyTriangles.size());
  for (const Triangle& t : shape.bodyTriangles) {
    const Eigen::Vector3d centre = (t[0] + t[1] + t[2]) / 3.0;
    shape.triangleCentres.push_back(centre);
    shape.triangleRadii.push_back(std::max({(t[0] - centre).norm(), (t[1] - centre).norm(),
                                            (t[2] - centre).norm()}));
  }
  shape.triangleIndex = TriangleBvh(shape.triangleCentres, shape.triangleRadii);
  // Adjacency: directed edge (a, b) -> apex of its triangle; the neighbour across (a, b) of
  // a triangle is the triangle with the directed edge (b, a).
  std::map<std::pair<int, int>, int> apexOfDirectedEdge;
  const auto& triangles = shape.bodyMesh.triangles;
  for (const auto& f : triangles)
    for (int k = 0; k < 3; ++k) apexOfDirectedEdge[{f[k], f[(k + 1) % 3]}] = f[(k + 2) % 3];
  shape.edgeApex.resize(triangles.size());
  std::vector<std::vector<int>> neighbours(shape.bodyMesh.vertices.size());
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = triangles[t][k], b = triangles[t][(k + 1) % 3];
      const auto it = apexOfDirectedEdge.find({b, a});
      shape.edgeApex[t][k] = it == apexOfDirectedEdge.end() ? -1 : it->second;
      neighbours[a].push_back(b);
      neighbours[b].push_back(a);
    }
  shape.vertexNeighbourOffsets.assign(1, 0);
  for (auto& list : neighbours) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
    shape.vertexNeighbours.insert(shape.vertexNeighbours.end(), list.begin(), list.end());
    shape.vertexNeighbourOffsets.push_back(int(shape.vertexNeighbours.size()));
  }
  return shape;
}

}  // namespace spacetree::geometry
