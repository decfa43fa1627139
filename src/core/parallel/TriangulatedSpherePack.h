// A dense pack of triangulated spheres, the scene of the task-parallel tests and benchmark: a
// jittered cubic lattice of latitude-longitude spheres with spacing `spacing` r, radii varied by
// +-radiusJitter, centres moved by up to +-positionJitter r per axis and every sphere randomly
// rotated. The meshes are inscribed in their spheres (coarse meshes are up to ~15 % of r inside
// between the vertices), so a spacing a little below 2 makes neighbouring meshes touch and
// overlap slightly in random orientations.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "parallel/PosedMeshes.h"

namespace spacetree::parallel {

struct TriangulatedSpherePackOptions {
  int particles = 1000;
  int trianglesPerParticle = 48;  // closest latitude-longitude sphere is used
  double radius = 1e-3;           // nominal radius
  double radiusJitter = 0.05;     // relative
  double positionJitter = 0.05;   // relative to the radius, per axis
  double spacing = 1.8;           // lattice spacing relative to the radius
  std::uint32_t seed = 1;
};

struct TriangulatedSpherePack {
  PosedMeshes meshes;
  std::vector<std::array<double, 3>> centre;
  std::vector<double> radius;  // bounding radius (the mesh vertices lie on this sphere)
};

// Throws std::invalid_argument for particles < 1, trianglesPerParticle < 12 or spacing <= 0.
TriangulatedSpherePack makeTriangulatedSpherePack(const TriangulatedSpherePackOptions& options);

}  // namespace spacetree::parallel
