// Mass properties from closed surfaces against analytic values: cube, box (rotated and
// translated), sphere (converging with refinement), torus (genus 1, converging), an
// inward-oriented cube (repaired by validateMesh, rejected by computeMassProperties), and the
// RigidShape built from them (principal frame, bounding sphere, edge lengths).
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <random>
#include <vector>

#include "geometry/DentedSphere.h"
#include "geometry/MassProperties.h"
#include "geometry/MeshValidation.h"
#include "geometry/PrimitiveMeshes.h"
#include "geometry/RigidShape.h"
#include "geometry/SphereMesh.h"

using namespace spacetree::geometry;
using Eigen::Matrix3d;
using Eigen::Vector3d;

namespace {

const double pi = std::acos(-1.0);

Matrix3d boxInertiaPerDensity(const Vector3d& s) {
  const double v = s.prod();
  return Vector3d(v * (s.y() * s.y() + s.z() * s.z()) / 12.0,
                  v * (s.x() * s.x() + s.z() * s.z()) / 12.0,
                  v * (s.x() * s.x() + s.y() * s.y()) / 12.0)
      .asDiagonal();
}

TEST(MassProperties, UnitCube) {
  const MassProperties p = computeMassProperties(boxMesh(Vector3d(1, 1, 1)));
  EXPECT_NEAR(p.volume, 1.0, 1e-15);
  EXPECT_LE(p.centreOfMass.norm(), 1e-15);
  EXPECT_LE((p.inertiaPerUnitDensity - Matrix3d::Identity() / 6.0).norm(), 1e-15);
  EXPECT_LE((p.principalMomentsPerUnitDensity - Vector3d::Constant(1.0 / 6.0)).norm(), 1e-15);
  EXPECT_NEAR(p.principalAxes.determinant(), 1.0, 1e-14);
  // Density and mass forms.
  EXPECT_NEAR(p.mass(2500.0), 2500.0, 1e-10);
  EXPECT_NEAR(p.inertia(2500.0)(0, 0), 2500.0 / 6.0, 1e-10);
  EXPECT_NEAR(p.inertiaForMass(3.0)(1, 1), 0.5, 1e-15);
}

TEST(MassProperties, RotatedTranslatedBox) {
  const Vector3d size(0.2, 0.5, 1.3);
  const Matrix3d rotation =
      Eigen::AngleAxisd(1.1, Vector3d(0.3, -0.4, 0.8).normalized()).toRotationMatrix();
  const Vector3d shift(1e3, -7.25, 3.5);
  TriangleMesh mesh = boxMesh(size);
  mesh.transform(rotation, shift);
  const MassProperties p = computeMassProperties(mesh);
  const double volume = size.prod();
  EXPECT_NEAR(p.volume, volume, 1e-13 * volume);
  EXPECT_LE((p.centreOfMass - shift).norm(), 1e-12);
  const Matrix3d expected = rotation * boxInertiaPerDensity(size) * rotation.transpose();
  EXPECT_LE((p.inertiaPerUnitDensity - expected).norm(), 1e-12 * expected.norm());
  // Distinct moments: ascending, axes equal to the box's rotated axes up to sign.
  const Vector3d moments = boxInertiaPerDensity(size).diagonal().reverse();  // x: largest
  ASSERT_LT(moments[0], moments[1]);
  ASSERT_LT(moments[1], moments[2]);
  EXPECT_LE((p.principalMomentsPerUnitDensity - moments).norm(), 1e-12 * moments.norm());
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(std::abs(p.principalAxes.col(k).dot(rotation.col(2 - k))), 1.0, 1e-10) << k;
  EXPECT_NEAR(p.principalAxes.determinant(), 1.0, 1e-12);
}

TEST(MassProperties, SphereConvergesToAnalyticValues) {
  const double r = 0.3;
  const double volume = 4.0 / 3.0 * pi * r * r * r;
  const double moment = 0.4 * volume * r * r;
  double previousVolumeError = 1.0, previousMomentError = 1.0;
  for (int stacks : {8, 16, 32, 64, 128}) {
    const MassProperties p = computeMassProperties(latitudeLongitudeSphereMesh(2 * stacks, stacks, r));
    const double volumeError = std::abs(p.volume - volume) / volume;
    double momentError = 0.0;
    for (int k = 0; k < 3; ++k)
      momentError = std::max(momentError,
                             std::abs(p.principalMomentsPerUnitDensity[k] - moment) / moment);
    EXPECT_LE(p.centreOfMass.norm(), 1e-14);
    // Inscribed mesh: second-order convergence (error / 4 per refinement; allow / 3).
    EXPECT_LT(volumeError, previousVolumeError / 3.0) << stacks;
    EXPECT_LT(momentError, previousMomentError / 3.0) << stacks;
    previousVolumeError = volumeError;
    previousMomentError = momentError;
  }
  EXPECT_LT(previousVolumeError, 5e-4);
  EXPECT_LT(previousMomentError, 1e-3);
}

TEST(MassProperties, TorusIsAcceptedAndConverges) {
  const double R = 1.0, r = 0.25;
  const double volume = 2.0 * pi * pi * R * r * r;
  const double izz = volume * (R * R + 0.75 * r * r);         // about the symmetry axis
  const double ixx = volume * (0.5 * R * R + 0.625 * r * r);  // about a diameter
  double previousError = 1.0;
  for (int n : {12, 24, 48, 96}) {
    TriangleMesh torus = torusMesh(R, r, 2 * n, n);
    ASSERT_NO_THROW(validateMesh(torus, "torus"));
    const MassProperties p = computeMassProperties(torus);
    const double error = std::max({std::abs(p.volume - volume) / volume,
                                   std::abs(p.inertiaPerUnitDensity(2, 2) - izz) / izz,
                                   std::abs(p.inertiaPerUnitDensity(0, 0) - ixx) / ixx,
                                   std::abs(p.inertiaPerUnitDensity(1, 1) - ixx) / ixx});
    EXPECT_LE(p.centreOfMass.norm(), 1e-13);
    EXPECT_LT(error, previousError / 3.0) << n;
    previousError = error;
  }
  EXPECT_LT(previousError, 2e-3);
}

TEST(MassProperties, ConcaveShapeEqualsSumOfParts) {
  // An L-shaped solid from the union of two boxes is not available as one mesh here, but a box
  // with a box-shaped cavity (inner surface oriented inward) is: volume and inertia subtract.
  TriangleMesh outer = boxMesh(Vector3d(2, 2, 2));
  TriangleMesh inner = boxMesh(Vector3d(1, 1, 1));
  inner.transform(Matrix3d::Identity(), Vector3d(0.25, 0, 0));
  inner.flipOrientation();
  const int offset = int(outer.vertexCount());
  for (const auto& v : inner.vertices) outer.vertices.push_back(v);
  for (auto f : inner.triangles) outer.triangles.push_back({f[0] + offset, f[1] + offset, f[2] + offset});
  ASSERT_NO_THROW(validateMesh(outer, "hollow"));
  const MassProperties p = computeMassProperties(outer);
  EXPECT_NEAR(p.volume, 7.0, 1e-14);
  EXPECT_NEAR(p.centreOfMass.x(), -0.25 / 7.0, 1e-15);  // (8*0 - 1*0.25) / 7
  // I_yy about the centre of mass: big box minus cavity, parallel-axis terms included.
  const double c = p.centreOfMass.x();
  const double iyy = (8.0 * 8.0 / 12.0 + 8.0 * c * c) - (2.0 / 12.0 + 1.0 * (0.25 - c) * (0.25 - c));
  EXPECT_NEAR(p.inertiaPerUnitDensity(1, 1), iyy, 1e-13);
}

TEST(MassProperties, InwardCubeIsRejectedUntilRepaired) {
  TriangleMesh cube = boxMesh(Vector3d(1, 1, 1));
  cube.flipOrientation();
  EXPECT_THROW(computeMassProperties(cube), std::invalid_argument);
  validateMesh(cube, "inward cube");  // documented repair: flip all
  const MassProperties p = computeMassProperties(cube);
  EXPECT_NEAR(p.volume, 1.0, 1e-15);
  EXPECT_NEAR(p.principalMomentsPerUnitDensity[0], 1.0 / 6.0, 1e-15);
}

TEST(RigidShape, BoxIsMovedIntoItsPrincipalFrame) {
  const Vector3d size(0.2, 0.5, 1.3);
  const Matrix3d rotation =
      Eigen::AngleAxisd(-0.6, Vector3d(1, 1, 0).normalized()).toRotationMatrix();
  const Vector3d shift(4, 5, 6);
  TriangleMesh mesh = boxMesh(size);
  mesh.transform(rotation, shift);
  const RigidShape shape = RigidShape::fromMesh(mesh);
  // In the body frame the inertia tensor is diagonal with the principal moments.
  const MassProperties body = computeMassProperties(shape.bodyMesh);
  EXPECT_LE(body.centreOfMass.norm(), 1e-13);
  const Matrix3d diagonal = shape.principalInertiaPerUnitDensity.asDiagonal();
  EXPECT_LE((body.inertiaPerUnitDensity - diagonal).norm(), 1e-13 * diagonal.norm());
  EXPECT_LE((shape.principalInertiaPerUnitDensity - boxInertiaPerDensity(size).diagonal().reverse()).norm(),
            1e-13);
  EXPECT_NEAR(shape.volume, size.prod(), 1e-15);
  EXPECT_NEAR(shape.boundingRadius, 0.5 * size.norm(), 1e-14);
  EXPECT_NEAR(shape.minimumEdgeLength, 0.2, 1e-14);
  EXPECT_NEAR(shape.mass(1000.0), 130.0, 1e-10);
  EXPECT_NEAR(shape.meshRotation.determinant(), 1.0, 1e-13);
  // The body frame maps back onto the source mesh.
  const Eigen::Quaterniond q = shape.bodyOrientationFor();
  for (std::size_t v = 0; v < mesh.vertexCount(); ++v)
    EXPECT_LE((q * shape.bodyMesh.vertices[v] + shape.centreOfMassInMesh - mesh.vertices[v]).norm(),
              1e-13);
  // Adjacency: the apex across each edge belongs to the triangle on the other side, which
  // traverses the edge the other way; every vertex of a box mesh has 3 to 6 neighbours.
  ASSERT_EQ(shape.edgeApex.size(), shape.triangleCount());
  const auto& tris = shape.bodyMesh.triangles;
  for (std::size_t t = 0; t < tris.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = tris[t][k], b = tris[t][(k + 1) % 3], apex = shape.edgeApex[t][k];
      bool found = false;
      for (const auto& f : tris)
        for (int m = 0; m < 3; ++m)
          found |= f[m] == b && f[(m + 1) % 3] == a && f[(m + 2) % 3] == apex;
      EXPECT_TRUE(found) << t << " " << k;
    }
  ASSERT_EQ(shape.vertexNeighbourOffsets.size(), shape.bodyMesh.vertexCount() + 1);
  for (std::size_t v = 0; v < shape.bodyMesh.vertexCount(); ++v) {
    const int count = shape.vertexNeighbourOffsets[v + 1] - shape.vertexNeighbourOffsets[v];
    EXPECT_GE(count, 3);
    EXPECT_LE(count, 6);
  }
  // Triangle bounding spheres contain their triangles.
  ASSERT_EQ(shape.triangleCentres.size(), shape.triangleCount());
  for (std::size_t t = 0; t < shape.triangleCount(); ++t)
    for (int k = 0; k < 3; ++k)
      EXPECT_LE((shape.bodyTriangles[t][k] - shape.triangleCentres[t]).norm(),
                shape.triangleRadii[t] + 1e-15);
}

TEST(RigidShape, DentedSphereHasConsistentMassProperties) {
  DentedSphereOptions options;
  options.triangles = 160;
  options.radius = 0.01;
  options.amplitude = 0.2;
  TriangleMesh mesh = dentedSphere(options);
  validateMesh(mesh, "dented");
  const RigidShape shape = RigidShape::fromMesh(mesh);
  EXPECT_GT(shape.volume, 4.0 / 3.0 * pi * std::pow(0.008, 3) * 0.9);
  EXPECT_LT(shape.volume, 4.0 / 3.0 * pi * std::pow(0.012, 3));
  EXPECT_LE(shape.boundingRadius, 0.012 + 0.01);  // radius plus centre-of-mass shift bound
  const Vector3d I = shape.principalInertiaPerUnitDensity;
  EXPECT_LE(I[0], I[1]);
  EXPECT_LE(I[1], I[2]);
  EXPECT_LE(I[2], I[0] + I[1] + 1e-20);  // triangle inequality of principal moments
  EXPECT_GT(shape.minimumEdgeLength, 0.0);
}

}  // namespace
