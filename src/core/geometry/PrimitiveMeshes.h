// Closed, outward-oriented meshes of simple solids: boxes (cubes, floors, walls) and tori (the
// genus-1 test shape). Spheres: SphereMesh.h; the paper's dented spheres: DentedSphere.h.
#pragma once

#include <Eigen/Core>

#include "geometry/TriangleMesh.h"

namespace spacetree::geometry {

// Axis-aligned box with edge lengths `size`, centred at the origin: 8 vertices, 12 triangles.
// Throws std::invalid_argument unless every edge length is > 0.
TriangleMesh boxMesh(const Eigen::Vector3d& size);

// The same box with each face a grid of cells[axis] x cells[other axis] squares (two
// triangles each, shared vertices along the box edges): a fine mesh of the same surface,
// 4 (nx ny + ny nz + nz nx) triangles. Throws std::invalid_argument for edge lengths <= 0 or
// cell counts < 1.
TriangleMesh gridBoxMesh(const Eigen::Vector3d& size, const Eigen::Vector3i& cells);

// Torus around the z axis through the origin: tube centre-line radius `majorRadius`, tube
// radius `minorRadius` < majorRadius, `majorSegments` x `minorSegments` (>= 3 each) quads of
// two triangles. Vertices lie on the true torus; its volume converges to 2 pi^2 R r^2 as the
// segments grow. Throws std::invalid_argument for bad arguments.
TriangleMesh torusMesh(double majorRadius, double minorRadius, int majorSegments,
                       int minorSegments);

}  // namespace spacetree::geometry
