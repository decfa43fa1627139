// A partner of the multilevel ghost rule that reaches by its surface rather than by its
// bounding sphere: a fixed obstacle (a hopper, a floor) whose bounding sphere spans the box but
// whose triangles touch only the particles next to them. A small particle must be sent to the
// rank that owns such an obstacle only when it comes close to the obstacle's surface.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "geometry/RigidShape.h"

namespace spacetree::parallel {

class HaloSurface {
 public:
  virtual ~HaloSurface() = default;
  // Largest distance of the surface from the partner's centre (its bounding radius).
  virtual double extent() const = 0;
  // True if some point of the surface lies within `distance` of `point` (conservative: may say
  // true a few ulps beyond).
  virtual bool within(const Eigen::Vector3d& point, double distance) const = 0;
};

// The surface of a RigidShape at a pose (x_world = orientation * x_body + position), searched
// through the shape's triangle hierarchy: O(log n + k) per query.
class PosedShapeSurface : public HaloSurface {
 public:
  PosedShapeSurface(const geometry::RigidShape& shape, const Eigen::Vector3d& position,
                    const Eigen::Quaterniond& orientation)
      : shape_(&shape), position_(position), toBody_(orientation.conjugate().normalized()) {}
  double extent() const override { return shape_->boundingRadius; }
  bool within(const Eigen::Vector3d& point, double distance) const override;

 private:
  const geometry::RigidShape* shape_;
  Eigen::Vector3d position_;
  Eigen::Quaterniond toBody_;
};

}  // namespace spacetree::parallel
