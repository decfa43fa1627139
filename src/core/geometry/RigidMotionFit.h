// The rigid motion x -> R x + t that carries a set of reference points onto their current
// positions (a mesh wall moved by LIGGGHTS' fix move/mesh), so that a surface built once in the
// reference configuration can follow the wall by its pose instead of being rebuilt every step.
// The motion comes from three well-spread reference points (chosen once: the first point, the
// one farthest from it, the one farthest from their line) and is accepted only if it carries
// every point to within `tolerance` of its current position (a deforming or rearranged set is
// not a rigid motion: the caller rebuilds). O(n) per fit.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <vector>

namespace spacetree::geometry {

class RigidMotionFit {
 public:
  RigidMotionFit() = default;
  // Chooses the three frame points of `reference`; fails (valid() false) for fewer than three
  // points or points on one line.
  explicit RigidMotionFit(const std::vector<Eigen::Vector3d>& reference);
  bool valid() const { return valid_; }

  // rotation, translation with rotation * reference[i] + translation = current[i] for every i
  // within tolerance; false (outputs unspecified) otherwise, or for a size mismatch.
  bool fit(const std::vector<Eigen::Vector3d>& reference, const std::vector<Eigen::Vector3d>& current,
           double tolerance, Eigen::Matrix3d& rotation, Eigen::Vector3d& translation) const;

 private:
  std::array<std::size_t, 3> frame_{};
  bool valid_ = false;
};

}  // namespace spacetree::geometry
