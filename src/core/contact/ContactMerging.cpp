#include "contact/ContactMerging.h"

#include "contact/MeshContact.h"

#include <algorithm>

namespace spacetree::contact {

using Eigen::Matrix3d;
using Eigen::Vector3d;

namespace {

double distanceToSegment(const Vector3d& p, const Vector3d& a, const Vector3d& b) {
  const Vector3d e = b - a;
  const double ee = e.squaredNorm();
  const double s = ee > 0.0 ? std::clamp((p - a).dot(e) / ee, 0.0, 1.0) : 0.0;
  return (p - (a + s * e)).norm();
}

}  // namespace

bool isLocalMinimum(const geometry::RigidShape& shape, int t, const Vector3d& p, const Vector3d& u,
                    const Matrix3d& rotation, const Vector3d& shift, double tolerance) {
  const auto& f = shape.bodyMesh.triangles[std::size_t(t)];
  const auto world = [&](int v) { return Vector3d(rotation * shape.bodyMesh.vertices[std::size_t(v)] + shift); };
  const auto descends = [&](int w) {
    const Vector3d step = world(w) - p;
    return u.dot(step) > kFeatureTolerance * step.norm();
  };
  const Vector3d corner[3] = {world(f[0]), world(f[1]), world(f[2])};
  for (int k = 0; k < 3; ++k)
    if ((p - corner[k]).norm() <= tolerance) {
      for (int n = shape.vertexNeighbourOffsets[std::size_t(f[k])];
           n < shape.vertexNeighbourOffsets[std::size_t(f[k]) + 1]; ++n)
        if (descends(shape.vertexNeighbours[std::size_t(n)])) return false;
      return true;
    }
  for (int k = 0; k < 3; ++k)
    if (distanceToSegment(p, corner[k], corner[(k + 1) % 3]) <= tolerance) {
      const int apex = shape.edgeApex[std::size_t(t)][k];
      return apex < 0 || !descends(apex);
    }
  return true;  // inside the face: u is its normal
}

std::size_t ContactMerger::merge(const std::vector<ContactPoint>& raw, double mergeDistance,
                                 const MeshContactOptions& options,
                                 std::vector<ContactPoint>& contacts) {
  const double eps = options.epsilon;
  const std::size_t begin = contacts.size();
  normalSums_.clear();
  weights_.clear();
  for (const ContactPoint& c : raw) {
    bool merged = false;
    if (options.deduplicate)
      for (std::size_t k = begin; k < contacts.size(); ++k) {
        ContactPoint& m = contacts[k];
        if ((c.point - m.point).squaredNorm() < mergeDistance * mergeDistance &&
            c.normal.dot(m.normal) >= options.mergeNormalCosine) {
          double& w = weights_[k - begin];
          const double wc = c.penetration;  // > 0 for every contact (d < 2 eps)
          const double total = w + wc;
          const double old = total > 0.0 ? w / total : 0.5, added = 1.0 - old;
          m.point = old * m.point + added * c.point;
          m.penetration = old * m.penetration + added * c.penetration;
          m.distance = 2.0 * (eps - m.penetration);
          Vector3d& sum = normalSums_[k - begin];
          sum += wc * c.normal;
          if (sum.squaredNorm() > 0.0) m.normal = sum.normalized();
          w = total;
          ++m.mergedCount;
          merged = true;
          break;
        }
      }
    if (!merged) {
      contacts.push_back(c);
      normalSums_.push_back(c.penetration * c.normal);
      weights_.push_back(c.penetration);
    }
  }
  return contacts.size() - begin;
}

}  // namespace spacetree::contact
