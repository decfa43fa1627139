#include "contact/CylinderWallContact.h"

#include <cmath>
#include <stdexcept>

namespace spacetree::contact {

using Eigen::Matrix3d;
using Eigen::Vector3d;

CylinderWallContactFinder::CylinderWallContactFinder(MeshContactOptions options)
    : options_(std::move(options)) {}

std::size_t CylinderWallContactFinder::find(const geometry::RigidShape& body, const Pose& pose,
                                            const Vector3d& axisPoint, const Vector3d& axis,
                                            double radius, std::vector<ContactPoint>& contacts,
                                            MeshContactStatistics* statistics) {
  const double eps = options_.epsilon;
  if (!(eps > 0.0)) throw std::invalid_argument("CylinderWallContactFinder: epsilon must be > 0");
  if (!(radius > 0.0)) throw std::invalid_argument("CylinderWallContactFinder: radius must be > 0");
  MeshContactStatistics counts;
  counts.bodyPairs = 1;
  const auto radialOf = [&](const Vector3d& p) {
    const Vector3d r = p - axisPoint;
    return Vector3d(r - r.dot(axis) * axis);
  };
  const double contactDistance = 2.0 * eps;
  // the bounding sphere stays farther than 2 eps from the wall: nothing to do
  if (!(radius - radialOf(pose.position).norm() - body.boundingRadius < contactDistance)) {
    ++counts.boundingSphereRejections;
    if (statistics) *statistics += counts;
    return 0;
  }
  const Matrix3d rotation = pose.orientation.toRotationMatrix();
  const std::vector<Vector3d>& vertices = body.bodyMesh.vertices;
  gaps_.resize(vertices.size());
  for (std::size_t v = 0; v < vertices.size(); ++v)
    gaps_[v] = radius - radialOf(rotation * vertices[v] + pose.position).norm();
  counts.trianglePairsChecked = vertices.size();
  // a strictly closer neighbour (beyond rounding of the gaps) makes a vertex no local minimum
  const double tolerance = 1e-12 * (radius + body.boundingRadius);
  raw_.clear();
  for (std::size_t v = 0; v < vertices.size(); ++v) {
    const double g = gaps_[v];
    if (!(g < contactDistance)) continue;
    bool minimum = true;
    for (int n = body.vertexNeighbourOffsets[v]; n < body.vertexNeighbourOffsets[v + 1] && minimum; ++n)
      minimum = !(gaps_[std::size_t(body.vertexNeighbours[std::size_t(n)])] < g - tolerance);
    if (!minimum) {
      ++counts.nonMinimumContacts;
      continue;
    }
    const Vector3d p = rotation * vertices[v] + pose.position;
    const Vector3d radial = radialOf(p);
    const double rho = radial.norm();
    ContactPoint c;
    c.normal = rho > 0.0 ? Vector3d(radial / rho) : Vector3d(axis.unitOrthogonal());
    c.distance = g;
    c.penetration = eps - 0.5 * g;
    c.point = p + (0.5 * g) * c.normal;
    raw_.push_back(c);
  }
  counts.rawContacts = raw_.size();
  const std::size_t appended = merger_.merge(raw_, body.minimumEdgeLength, options_, contacts);
  counts.contacts = appended;
  if (statistics) *statistics += counts;
  return appended;
}

}  // namespace spacetree::contact
