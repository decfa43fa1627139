// Test and benchmark helper: a 40-triangle dented grain (radius 1) in the halo of a slab's top
// face, the scenes of test_mesh_contact_culling.cpp and bench/size_ratio_fallbacks.cpp.
#pragma once

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "contact/MeshContact.h"
#include "geometry/DentedSphere.h"
#include "geometry/RigidShape.h"

namespace grain_on_slab {

inline spacetree::geometry::RigidShape grain() {
  spacetree::geometry::DentedSphereOptions d;
  d.triangles = 40;
  d.amplitude = 0.2;
  d.seed = 7;
  return spacetree::geometry::RigidShape::fromMesh(spacetree::geometry::dentedSphere(d));
}

struct Scene {
  spacetree::contact::Pose slab, grain;
};

// The grain at random orientations over the top face of a slab of edge lengths `size` (the
// slab's pose a fixed rotation and shift): over the face's interior (50 %), near an edge (30 %)
// or a corner (20 %), its lowest vertex 0.02 .. 2.5 eps above the face (in the halo; rigid
// surfaces that intersect have no unique closest points).
inline std::vector<Scene> scenes(const spacetree::geometry::RigidShape& g,
                                 const Eigen::Vector3d& size, double eps, int count,
                                 unsigned seed) {
  using Eigen::Quaterniond;
  using Eigen::Vector3d;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> n;
  const Quaterniond slabTurn(Eigen::AngleAxisd(0.3, Vector3d(1, 2, 3).normalized()));
  std::vector<Scene> out;
  for (int s = 0; s < count; ++s) {
    const Quaterniond turn = Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized();
    double lowest = INFINITY;
    for (const Vector3d& v : g.bodyMesh.vertices) lowest = std::min(lowest, (turn * v).z());
    Vector3d at((u(rng) - 0.5) * size.x(), (u(rng) - 0.5) * size.y(), 0.0);
    const double kind = u(rng);
    if (kind > 0.8) {  // near a corner
      at.x() = std::copysign(0.5 * size.x() + 0.6 * (u(rng) - 0.7), at.x());
      at.y() = std::copysign(0.5 * size.y() + 0.6 * (u(rng) - 0.7), at.y());
    } else if (kind > 0.5) {  // near an edge
      at.x() = std::copysign(0.5 * size.x() + 0.6 * (u(rng) - 0.7), at.x());
    }
    at.z() = 0.5 * size.z() - lowest + (0.02 + 2.48 * u(rng)) * eps;
    Scene scene;
    scene.slab = spacetree::contact::Pose{Vector3d(0.2, -0.1, 0.3), slabTurn};
    scene.grain = spacetree::contact::Pose{slabTurn * at + scene.slab.position, slabTurn * turn};
    out.push_back(scene);
  }
  return out;
}

}  // namespace grain_on_slab
