#include "geometry/RigidShape.h"

#include <algorithm>

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

  for (const auto& f : shape.bodyMesh.triangles)
    for (int v : f)
      shape.boundingRadius = std::max(shape.boundingRadius, shape.bodyMesh.vertices[v].norm());
  shape.triangleCentres.reserve(shape.bodyTriangles.size());
  shape.triangleRadii.reserve(shape.bodyTriangles.size());
  for (const Triangle& t : shape.bodyTriangles) {
    const Eigen::Vector3d centre = (t[0] + t[1] + t[2]) / 3.0;
    shape.triangleCentres.push_back(centre);
    shape.triangleRadii.push_back(std::max({(t[0] - centre).norm(), (t[1] - centre).norm(),
                                            (t[2] - centre).norm()}));
  }
  return shape;
}

}  // namespace spacetree::geometry
