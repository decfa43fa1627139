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

// De-duplication (paper §3, step 2), appending to `contacts`: a raw contact is averaged into an
// earlier appended one when its point is closer than mergeDistance to that contact's mean point
// and the normals' cosine is at least options.mergeNormalCosine (all appended as they are when
// options.deduplicate is false). Point, unit normal and penetration are means weighted by the
// penetrations; distance = 2 (eps - penetration). Returns how many were appended.
class ContactMerger {
 public:
  std::size_t merge(const std::vector<ContactPoint>& raw, double mergeDistance,
                    const MeshContactOptions& options, std::vector<ContactPoint>& contacts);

 private:
  std::vector<Eigen::Vector3d> normalSums_;  // weighted sums of merged unit normals
  std::vector<double> weights_;              // sums of merged penetrations
};

}  // namespace spacetree::contact
