#include "geometry/WallPatches.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace spacetree::geometry {

using Eigen::Vector3d;

TriangleMesh planeWallPatch(double halfWidth) {
  if (!(halfWidth > 0.0) || !std::isfinite(halfWidth))
    throw std::invalid_argument("planeWallPatch: halfWidth must be > 0");
  TriangleMesh m;
  const double h = halfWidth;
  m.vertices = {Vector3d(-h, -h, 0), Vector3d(h, -h, 0), Vector3d(h, h, 0), Vector3d(-h, h, 0)};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

TriangleMesh cylinderWallPatch(double radius, double halfAngle, double halfLength, double sagitta) {
  if (!(radius > 0.0) || !(halfAngle > 0.0) || !(halfLength > 0.0) || !(sagitta > 0.0) ||
      !(sagitta < radius) || !std::isfinite(radius) || !std::isfinite(halfLength))
    throw std::invalid_argument(
        "cylinderWallPatch: radius, halfAngle, halfLength and sagitta must be > 0, sagitta < radius");
  const bool closed = halfAngle >= M_PI;
  const double span = closed ? 2.0 * M_PI : 2.0 * halfAngle;
  const double step = 2.0 * std::acos(1.0 - sagitta / radius);
  const int facets = std::max(closed ? 3 : 1, int(std::ceil(span / step)));
  const int columns = closed ? facets : facets + 1;  // vertex columns around the axis
  TriangleMesh m;
  for (int k = 0; k < columns; ++k) {
    const double a = (closed ? 0.0 : -halfAngle) + span * k / facets;
    m.vertices.emplace_back(radius * std::cos(a), radius * std::sin(a), -halfLength);
    m.vertices.emplace_back(radius * std::cos(a), radius * std::sin(a), halfLength);
  }
  for (int k = 0; k < facets; ++k) {
    const int a = 2 * k, b = 2 * ((k + 1) % columns);
    // (a, b, b + 1) has normal +radial: counter-clockwise seen from outside
    m.triangles.push_back({a, b, b + 1});
    m.triangles.push_back({a, b + 1, a + 1});
  }
  return m;
}

WallPatchPlacement WallPatchPlacement::onPlane(const Vector3d& point, const Vector3d& normal,
                                               const Vector3d& c) {
  const double height = (c - point).dot(normal);
  const Vector3d up = height < 0.0 ? Vector3d(-normal) : normal;
  WallPatchPlacement p;
  p.position = c - height * normal;
  p.orientation = Eigen::Quaterniond::FromTwoVectors(Vector3d::UnitZ(), up);
  return p;
}

WallPatchPlacement WallPatchPlacement::onCylinder(const Vector3d& point, const Vector3d& axis,
                                                  const Vector3d& c) {
  WallPatchPlacement p;
  p.position = point + (c - point).dot(axis) * axis;
  Vector3d radial = c - p.position;
  if (!(radial.norm() > 0.0)) radial = axis.unitOrthogonal();
  radial.normalize();
  Eigen::Matrix3d frame;
  frame.col(0) = radial;
  frame.col(1) = axis.cross(radial);
  frame.col(2) = axis;
  p.orientation = Eigen::Quaterniond(frame);
  return p;
}

}  // namespace spacetree::geometry
