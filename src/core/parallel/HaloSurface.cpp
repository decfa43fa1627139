#include "parallel/HaloSurface.h"

#include "geometry/PointTriangleDistance.h"

namespace spacetree::parallel {

bool PosedShapeSurface::within(const Eigen::Vector3d& point, double distance) const {
  if (!(distance >= 0.0)) return false;
  const Eigen::Vector3d local = toBody_ * (point - position_);
  // a rotation and a shift round at ~1e-16 of the magnitudes: widen the test by as much
  const double slack = 1e-12 * (distance + local.norm() + shape_->boundingRadius);
  const double limit = (distance + slack) * (distance + slack);
  bool found = false;
  const auto test = [&](int t) {
    if (!found &&
        geometry::pointTriangleSquaredDistance(local, shape_->bodyTriangles[std::size_t(t)]) <= limit)
      found = true;
  };
  if (shape_->triangleIndex.size() == shape_->triangleCount())
    shape_->triangleIndex.forEachCandidate(local, distance + slack, test);
  else  // a shape built without its hierarchy
    for (std::size_t t = 0; t < shape_->triangleCount() && !found; ++t) test(int(t));
  return found;
}

}  // namespace spacetree::parallel
