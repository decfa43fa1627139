// Contacts between a posed rigid triangulated body and a sphere (spheres beside triangulated
// grains and obstacles in one scene), in the epsilon formalism of MeshContact.h.
//
// A sphere of radius r is a rigid core of radius r - eps plus the halo eps, as a grain's atom
// radius is its bounding radius plus eps: the sphere's outer surface is where contacts start,
// in every interaction (pair_style gran's overlap of two spheres, walls). With c the centre and
// p the closest point of a triangle of the body (first) to c:
//   - surface distance d = |c - p| - (r - eps) (core to rigid surface); a contact when d < 2 eps,
//     i.e. |c - p| < r + eps;
//   - normal = (c - p) / |c - p|, from the body towards the sphere (first -> second);
//   - point = p + (d / 2) normal, halfway between the two rigid surfaces;
//   - penetration = eps - d / 2 in (0, eps], as between two triangulated bodies, so the same
//     force law applies (NormalSpringDashpot: restitution from its damping ratio alone).
// Where c lies on the surface (|c - p| below kDirectionTolerance times the triangle's longest
// edge) the normal is the triangle's outward normal.
//
// Pipeline: (1) the sphere (reach r + eps) against the body's bounding sphere and box; (2) the
// triangles whose bounding sphere reaches it (through the body's TriangleBvh for indexed shapes,
// as MeshContact step 3, else all), (3) the closest point of each (exact, Voronoi regions) and
// the contacts within reach, (4) the local-minimum filter of MeshContact step 5b (a closest point
// on an edge or vertex whose neighbouring triangle descends towards the centre is not a local
// minimum: that neighbour has a closer point), (5) de-duplication as MeshContact step 6 (an edge
// point found by both triangles of the edge is one contact). Contacts in the world frame.
#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <vector>

#include "contact/ContactMerging.h"
#include "contact/MeshContact.h"
#include "geometry/RigidShape.h"

namespace spacetree::contact {

class SphereMeshContactFinder {
 public:
  // Uses epsilon, deduplicate, localMinimaOnly, mergeNormalCosine, triangleIndex and
  // triangleCulling of the options (the triangle-distance method plays no part: the distance
  // of a point to a triangle is exact).
  explicit SphereMeshContactFinder(MeshContactOptions options);
  const MeshContactOptions& options() const { return options_; }

  // Appends the contacts of `body` at `pose` (first) with the sphere of outer radius `radius`
  // centred at `centre` (world frame; second) and returns how many; statistics, if given, are
  // accumulated (trianglePairsChecked counts the triangles whose closest point was computed).
  // Throws std::invalid_argument for epsilon <= 0 or radius <= epsilon (no rigid core).
  std::size_t find(const geometry::RigidShape& body, const Pose& pose,
                   const Eigen::Vector3d& centre, double radius,
                   std::vector<ContactPoint>& contacts, MeshContactStatistics* statistics = nullptr);

 private:
  MeshContactOptions options_;
  std::vector<int> candidates_;
  std::vector<ContactPoint> raw_;
  ContactMerger merger_;
};

}  // namespace spacetree::contact
