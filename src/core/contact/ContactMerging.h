// The last two steps of every contact search of a triangulated body (MeshContact.h steps 5b and
// 6; SphereMeshContact.h): the local-minimum filter of a closest point on a triangle, and the
// de-duplication of raw contacts into the contacts a force law acts on.
#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <vector>

#include "geometry/RigidShape.h"

namespace spacetree::contact {

struct ContactPoint;        // contact/MeshContact.h
struct MeshContactOptions;  // contact/MeshContact.h

// Whether moving the closest point p of triangle t of `shape` onto a neighbouring triangle can
// shorten the distance along direction u (unit, from p towards the other body): if p lies
// within `tolerance` of a vertex (an edge) of t and some neighbour vertex w around that vertex
// (across that edge) has u . (w - p) > kFeatureTolerance |w - p|, the closest points are not a
// local minimum of the surface distance and a neighbouring triangle is strictly closer. The
// points of the shape are mapped by x -> rotation * x + shift (the frame p and u are given in).
bool isLocalMinimum(const geometry::RigidShape& shape, int t, const Eigen::Vector3d& p,
                    const Eigen::Vector3d& u, const Eigen::Matrix3d& rotation,
                    const Eigen::Vector3d& shift, double tolerance);

// De-duplication (paper §3, step 2), appending to `contacts` (all raw contacts as they are when
// options.deduplicate is false). Which raw contacts form one contact point: taken deepest first,
// a raw contact joins the first point whose mean point is closer than mergeDistance and whose
// normal has a cosine of at least options.mergeNormalCosine with its own, else it starts a point.
// The penetration of a point is the mean of its raw contacts' weighted by their penetrations
// (distance = 2 (eps - penetration)).
//
// What force a point carries must not jump when a raw contact changes points (a mean point moved
// past mergeDistance, a raw contact entered the halo; a resting grain rocked on for ever with a
// jump of its force as large as its weight, bench/heap_repose.py): each raw contact i counts with
// the share s_i = p_i / sum_j K_ij p_j of itself (K_ii = 1), K_ij = phi(|x_i - x_j| / mergeDistance)
// psi(n_i . n_j), phi(t) = 1 up to t = 1/2 (the kernel's point of a face lying on a face lies
// anywhere between the face's corners: within half a merge length of a corner's contact it is
// that contact again), then (1 - (2t - 1)^2)^2, 0 from t = 1; psi rising smoothly from 0 at
// mergeNormalCosine to 1 at parallel normals: copies of one contact (K = 1) share one contact's
// force, raw contacts a merge length apart or with normals beyond the cosine count in full, and in
// between the count changes smoothly. A point's weight is sum over its raw contacts of s_i p_i
// over its penetration, its point and normal the means weighted by s_i p_i: the sum of the
// points' springs and their moment change continuously with the raw contacts whichever point each
// joins. Returns how many were appended.
class ContactMerger {
 public:
  std::size_t merge(const std::vector<ContactPoint>& raw, double mergeDistance,
                    const MeshContactOptions& options, std::vector<ContactPoint>& contacts);

 private:
  std::vector<std::size_t> order_;           // raw contacts, deepest first
  struct Group {       // exact copies of one raw contact
    std::size_t raw;    // the first (index into raw)
    int count;
    std::size_t point;  // the point it joined (from the first appended)
  };
  std::vector<Group> groups_;
  std::vector<double> weights_;              // per point: sum of its raw penetrations
  // per point: sum of its raw p_i n_i while joining, then of s_i p_i n_i
  std::vector<double> loads_;                // per point: sum of s_i p_i
  std::vector<double> kinSums_;              // per group: sum over groups of count K_ij p_j
  std::vector<Eigen::Vector3d> pointSums_;   // per point: sum of s_i p_i x_i
  std::vector<Eigen::Vector3d> normalSums_;
};

}  // namespace spacetree::contact
