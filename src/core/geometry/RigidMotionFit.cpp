#include "geometry/RigidMotionFit.h"

#include <cmath>

namespace spacetree::geometry {

using Eigen::Matrix3d;
using Eigen::Vector3d;

namespace {

// Orthonormal frame (columns) of three points: e1 along p1 - p0, e3 normal to their plane.
Matrix3d frameOf(const Vector3d& p0, const Vector3d& p1, const Vector3d& p2) {
  const Vector3d e1 = (p1 - p0).normalized();
  const Vector3d e3 = e1.cross(p2 - p0).normalized();
  Matrix3d f;
  f.col(0) = e1;
  f.col(1) = e3.cross(e1);
  f.col(2) = e3;
  return f;
}

}  // namespace

RigidMotionFit::RigidMotionFit(const std::vector<Vector3d>& reference) {
  if (reference.size() < 3) return;
  const Vector3d& p0 = reference[0];
  std::size_t far = 0, wide = 0;
  double farthest = 0.0, widest = 0.0;
  for (std::size_t i = 1; i < reference.size(); ++i) {
    const double d = (reference[i] - p0).squaredNorm();
    if (d > farthest) { farthest = d; far = i; }
  }
  if (!(farthest > 0.0)) return;
  const Vector3d axis = reference[far] - p0;
  for (std::size_t i = 1; i < reference.size(); ++i) {
    const double a = axis.cross(reference[i] - p0).squaredNorm();
    if (a > widest) { widest = a; wide = i; }
  }
  // on one line (to rounding of the points' extent): no frame
  if (!(widest > 1e-20 * farthest * farthest)) return;
  frame_ = {0, far, wide};
  valid_ = true;
}

bool RigidMotionFit::fit(const std::vector<Vector3d>& reference, const std::vector<Vector3d>& current,
                         double tolerance, Matrix3d& rotation, Vector3d& translation) const {
  if (!valid_ || reference.size() != current.size()) return false;
  const auto& [a, b, c] = frame_;
  rotation = frameOf(current[a], current[b], current[c]) *
             frameOf(reference[a], reference[b], reference[c]).transpose();
  translation = current[a] - rotation * reference[a];
  const double limit = tolerance * tolerance;
  for (std::size_t i = 0; i < reference.size(); ++i)
    if (!((rotation * reference[i] + translation - current[i]).squaredNorm() <= limit)) return false;
  return true;
}

}  // namespace spacetree::geometry
