// Pieces of the analytic walls of a DEM deck (LIGGGHTS' primitive walls: planes and cylinders)
// as triangulated surfaces, so that a triangulated grain meets such a wall through the same
// triangle-pair contact search as an obstacle or a mesh wall (contact/MeshContact.h): one
// patch per wall, placed under each grain (WallPatchPlacement), large enough to hold every
// surface point within reach of the grain.
//   - plane: a square of half width h in z = 0, two triangles, normal +z;
//   - cylinder (the convex side: a grain outside a pipe; inside, CylinderWallContact.h is exact
//     and cheaper): the surface at radius R about the z axis, azimuths [-a, a] around +x (the
//     whole circle for a >= pi), z in [-h, h], normals away from the axis; facets narrow enough
//     that the chord stays within `sagitta` of the true surface (angle step
//     2 acos(1 - sagitta / R)); vertices on the surface.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "geometry/TriangleMesh.h"

namespace spacetree::geometry {

// Throws std::invalid_argument unless halfWidth > 0.
TriangleMesh planeWallPatch(double halfWidth);

// Throws std::invalid_argument unless radius, halfAngle, halfLength, sagitta > 0 and
// sagitta < radius.
TriangleMesh cylinderWallPatch(double radius, double halfAngle, double halfLength, double sagitta);

// Where a wall's patch goes for a grain centred at c (the patch's frame: x_world = orientation
// * x_patch + position).
//   plane through `point` with unit normal n: centred at c's foot on the plane, +z towards c's
//   side (n if c is on the plane);
//   cylinder of axis through `point` along unit `axis`: origin at c's foot on the axis, +z
//   along axis, +x towards c (any perpendicular when c is on the axis).
struct WallPatchPlacement {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  static WallPatchPlacement onPlane(const Eigen::Vector3d& point, const Eigen::Vector3d& normal,
                                    const Eigen::Vector3d& c);
  static WallPatchPlacement onCylinder(const Eigen::Vector3d& point, const Eigen::Vector3d& axis,
                                       const Eigen::Vector3d& c);
};

}  // namespace spacetree::geometry
