// Contacts of a posed rigid triangulated body inside a cylinder wall (a drum, a pipe: the
// concave side of LIGGGHTS' primitive x/y/zcylinder), in the epsilon formalism of
// MeshContact.h with the wall as the second body (its halo eps like any body's).
//
// Inside the cylinder, the gap of a surface point p to the wall, g(p) = R - rho(p) (rho: the
// distance from the axis, a convex function), is concave, so over each triangle it is smallest
// at a vertex: the contacts are exactly the body's vertices v with g(v) < 2 eps that are local
// minima of g over the surface (no neighbouring vertex strictly closer to the wall). Each gives
//   normal = radial unit vector at v (from the body towards the wall),
//   point = v + (g / 2) normal, distance = g, penetration = eps - g / 2,
// then de-duplication as MeshContact step 6. Exact (no facets of the cylinder) and cheap: one
// pass over the vertices after a bounding-sphere check. Contacts in the world frame.
#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <vector>

#include "contact/ContactMerging.h"
#include "contact/MeshContact.h"
#include "geometry/RigidShape.h"

namespace spacetree::contact {

class CylinderWallContactFinder {
 public:
  // Uses epsilon, deduplicate and mergeNormalCosine of the options.
  explicit CylinderWallContactFinder(MeshContactOptions options);

  // Appends the contacts of `body` at `pose` (first) with the inner side of the cylinder of
  // radius `radius` about the axis through `axisPoint` along unit `axis` (second); returns how
  // many. Throws std::invalid_argument for epsilon <= 0 or radius <= 0.
  std::size_t find(const geometry::RigidShape& body, const Pose& pose,
                   const Eigen::Vector3d& axisPoint, const Eigen::Vector3d& axis, double radius,
                   std::vector<ContactPoint>& contacts, MeshContactStatistics* statistics = nullptr);

 private:
  MeshContactOptions options_;
  std::vector<double> gaps_;
  std::vector<ContactPoint> raw_;
  ContactMerger merger_;
};

}  // namespace spacetree::contact
