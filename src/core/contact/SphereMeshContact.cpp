#include "contact/SphereMeshContact.h"

#include <algorithm>
#include <stdexcept>

#include "geometry/PointTriangleDistance.h"

namespace spacetree::contact {

using Eigen::Matrix3d;
using Eigen::Vector3d;

SphereMeshContactFinder::SphereMeshContactFinder(MeshContactOptions options)
    : options_(std::move(options)) {}

std::size_t SphereMeshContactFinder::find(const geometry::RigidShape& body, const Pose& pose,
                                          const Vector3d& centre, double radius,
                                          std::vector<ContactPoint>& contacts,
                                          MeshContactStatistics* statistics) {
  const double eps = options_.epsilon;
  if (!(eps > 0.0)) throw std::invalid_argument("SphereMeshContactFinder: epsilon must be > 0");
  if (!(radius > eps))
    throw std::invalid_argument("SphereMeshContactFinder: the sphere radius must exceed epsilon");
  MeshContactStatistics counts;
  counts.bodyPairs = 1;
  const auto finish = [&](std::size_t appended) {
    counts.contacts = appended;
    if (statistics) *statistics += counts;
    return appended;
  };

  // The centre in the body frame; reach: |c - p| below it is a contact.
  const Matrix3d rotation = pose.orientation.toRotationMatrix();
  const Vector3d c = rotation.transpose() * (centre - pose.position);
  const double reach = radius + eps;
  if (!(c.norm() < body.boundingRadius + reach)) {
    ++counts.boundingSphereRejections;
    return finish(0);
  }
  const Vector3d below = (body.boundingBoxLow - c).cwiseMax(0.0);
  const Vector3d above = (c - body.boundingBoxHigh).cwiseMax(0.0);
  if (options_.triangleCulling && !((below + above).squaredNorm() < reach * reach)) {
    ++counts.boundingBoxRejections;
    return finish(0);
  }

  // Candidate triangles: those whose bounding sphere reaches the sphere.
  candidates_.clear();
  const bool indexed = body.triangleCount() >= kTriangleIndexMinimum ||
                       body.boundingRadius > kTriangleIndexRadiusRatio * reach;
  const auto consider = [&](int t) {
    const double r = body.triangleRadii[std::size_t(t)] + reach;
    if ((body.triangleCentres[std::size_t(t)] - c).squaredNorm() < r * r) candidates_.push_back(t);
  };
  if (options_.triangleIndex && indexed && body.triangleIndex.size() == body.triangleCount()) {
    body.triangleIndex.forEachCandidate(c, reach, consider);
    std::sort(candidates_.begin(), candidates_.end());
  } else {
    for (std::size_t t = 0; t < body.triangleCount(); ++t) consider(int(t));
  }
  counts.trianglePairsChecked = candidates_.size();
  counts.trianglePairsPruned = body.triangleCount() - candidates_.size();

  raw_.clear();
  for (int t : candidates_) {
    const geometry::Triangle& triangle = body.bodyTriangles[std::size_t(t)];
    const geometry::PointTriangleClosest closest = geometry::closestPointOnTriangle(c, triangle);
    const double gap = closest.offset.norm();  // |c - p|
    if (!(gap < reach)) continue;
    const Vector3d p = c - closest.offset;
    const double h = triangle.longestEdge();
    Vector3d normal;
    if (gap > kDirectionTolerance * h) {
      normal = closest.offset / gap;
      if (options_.localMinimaOnly &&
          !isLocalMinimum(body, t, p, normal, Matrix3d::Identity(), Vector3d::Zero(),
                          kDirectionTolerance * h)) {
        ++counts.nonMinimumContacts;
        continue;
      }
    } else {
      normal = (triangle[1] - triangle[0]).cross(triangle[2] - triangle[0]);
      normal = normal.squaredNorm() > 0.0 ? Vector3d(normal.normalized()) : Vector3d(c.normalized());
      if (!(normal.squaredNorm() > 0.0)) normal = Vector3d::UnitX();
    }
    ContactPoint contact;
    contact.distance = gap - (radius - eps);
    contact.penetration = eps - 0.5 * contact.distance;
    contact.point = p + (0.5 * contact.distance) * normal;
    contact.normal = normal;
    contact.firstTriangle = t;
    contact.secondTriangle = -1;
    raw_.push_back(contact);
  }
  counts.rawContacts = raw_.size();

  const std::size_t begin = contacts.size();
  const std::size_t appended = merger_.merge(raw_, body.minimumEdgeLength, options_, contacts);
  for (std::size_t k = begin; k < contacts.size(); ++k) {
    contacts[k].point = rotation * contacts[k].point + pose.position;
    contacts[k].normal = rotation * contacts[k].normal;
  }
  return finish(appended);
}

}  // namespace spacetree::contact
