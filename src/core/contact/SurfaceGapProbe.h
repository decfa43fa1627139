// The surface gap of two posed triangulated bodies that are not in contact, as far as a time-step
// decision needs it (fix adapt/timestep with triangulated particles): whether their surfaces come
// closer than a band, and if so the nearest points. Two bodies the contact search found no contact
// for are at least 2 eps apart (eps: the halo); within one step of length dt their surfaces close
// by at most surfaceClosingSpeedBound() * dt, so a pair whose gap is unknown only needs probing
// when that much closing could matter, and then only within that band.
//
// The probe is MeshContactFinder (same distance method and pruning) with the halo widened to
// band / 2 and without de-duplication, so that the smallest raw distance is the surface distance
// whenever that is below the band (the global minimum of the distance is a local minimum, which
// the local-minimum filter keeps). Widened finders are kept per band class (the band rounded up
// to 2 eps * 1.25^k), so that probes with nearby bands share one finder and its scratch buffers.
#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <memory>
#include <optional>
#include <vector>

#include "contact/MeshContact.h"
#include "geometry/RigidShape.h"

namespace spacetree::contact {

// Upper bound of the speed at which any surface point of body i approaches any surface point of
// body j: |v_j - v_i| + |w_i| r_i + |w_j| r_j (velocities of the centres of mass, angular
// velocities, bounding radii about the centres of mass). Rigorous for rigid bodies: the rate of
// change of the surface distance is at least minus this.
double surfaceClosingSpeedBound(const Eigen::Vector3d& velocityI, const Eigen::Vector3d& angularVelocityI,
                                double boundingRadiusI, const Eigen::Vector3d& velocityJ,
                                const Eigen::Vector3d& angularVelocityJ, double boundingRadiusJ);

class SurfaceGapProbe {
 public:
  // options: those of the contact search (epsilon = the halo eps > 0, distance method, Newton
  // steps); deduplicate and epsilon are set per probe. Throws as MeshContactFinder.
  explicit SurfaceGapProbe(MeshContactOptions options);

  // The nearest points of `first` and `second` if their surfaces are closer than `band`
  // (>= 2 eps): a ContactPoint in the world frame with distance d < band, normal from first to
  // second, penetration eps - d/2 (negative beyond the halo); nullopt when they are at least
  // `band` apart (up to the distance method's certified accuracy). Statistics, if given, are
  // accumulated.
  std::optional<ContactPoint> nearest(const geometry::RigidShape& first, const Pose& firstPose,
                                      const geometry::RigidShape& second, const Pose& secondPose,
                                      double band, MeshContactStatistics* statistics = nullptr);

  double halo() const { return options_.epsilon; }
  std::size_t probes() const { return probes_; }

 private:
  MeshContactFinder& finderFor(double band);

  MeshContactOptions options_;
  std::vector<std::unique_ptr<MeshContactFinder>> finders_;  // by band class k
  std::vector<ContactPoint> found_;
  std::size_t probes_ = 0;
};

}  // namespace spacetree::contact
