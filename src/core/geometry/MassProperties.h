// Mass properties of the solid bounded by a closed, outward-oriented triangle surface
// (validateMesh()): volume, centre of mass and inertia tensor, by the divergence theorem. Each
// triangle spans a signed tetrahedron with a reference point; the exact integrals of 1, x and
// x x^T over these tetrahedra sum to those of the solid, for any shape: concave, several
// components, holes (genus 1, a torus). Uniform density.
#pragma once

#include <Eigen/Core>

#include "geometry/TriangleMesh.h"

namespace spacetree::geometry {

constexpr double kDegenerateMomentTolerance = 1e-9;

struct MassProperties {
  double volume = 0.0;
  Eigen::Vector3d centreOfMass = Eigen::Vector3d::Zero();
  // Inertia tensor about the centre of mass, in the mesh's axes, per unit density:
  // I = integral (|r|^2 Id - r r^T) dV, r = x - centreOfMass.
  Eigen::Matrix3d inertiaPerUnitDensity = Eigen::Matrix3d::Zero();
  // Eigen-decomposition I = axes * diag(moments) * axes^T: moments ascending, axes as columns,
  // orthonormal and right-handed (det = +1). The choice is deterministic: each axis with a
  // distinct moment is signed so that its largest component is positive; moments equal within
  // kDegenerateMomentTolerance (relative) share an eigenspace, where the basis closest to the
  // mesh axes is taken - all three equal (cube, regular sphere mesh): the identity, so such a
  // shape keeps the mesh's axes as body axes; two equal (cylinder): the mesh axis with the
  // largest projection onto the plane, then its completion.
  Eigen::Vector3d principalMomentsPerUnitDensity = Eigen::Vector3d::Zero();
  Eigen::Matrix3d principalAxes = Eigen::Matrix3d::Identity();

  double mass(double density) const { return density * volume; }
  Eigen::Matrix3d inertia(double density) const { return density * inertiaPerUnitDensity; }
  Eigen::Matrix3d inertiaForMass(double mass) const {
    return (mass / volume) * inertiaPerUnitDensity;
  }
  Eigen::Vector3d principalMoments(double density) const {
    return density * principalMomentsPerUnitDensity;
  }
};

// Throws std::invalid_argument when the enclosed volume is not positive (open or inward mesh:
// run validateMesh() first).
MassProperties computeMassProperties(const TriangleMesh& mesh);

}  // namespace spacetree::geometry
