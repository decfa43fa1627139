#include "contact/ContactMerging.h"

#include "contact/MeshContact.h"

#include <algorithm>
#include <cmath>

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

namespace {

// K_ij of ContactMerging.h: 1 for copies of one contact, 0 from mergeDistance apart or at normals
// beyond the cosine.
double kinship(const ContactPoint& a, const ContactPoint& b, double mergeDistance, double cosine) {
  const double t2 = mergeDistance > 0.0
                        ? (a.point - b.point).squaredNorm() / (mergeDistance * mergeDistance)
                        : 1.0;
  if (!(t2 < 1.0)) return 0.0;
  const double c = a.normal.dot(b.normal);
  if (!(c > cosine)) return 0.0;
  const double u = cosine < 1.0 ? std::min(1.0, (c - cosine) / (1.0 - cosine)) : 1.0;
  // copies up to half the merge length (the kernel's point of a face lying on a face lies anywhere
  // between the face's corners), then smoothly distinct
  const double t = std::sqrt(t2);
  const double v = t < 0.5 ? 0.0 : 2.0 * t - 1.0;
  const double near = 1.0 - v * v;
  return near * near * u * u * (3.0 - 2.0 * u);
}

}  // namespace

std::size_t ContactMerger::merge(const std::vector<ContactPoint>& raw, double mergeDistance,
                                 const MeshContactOptions& options,
                                 std::vector<ContactPoint>& contacts) {
  const double eps = options.epsilon;
  const std::size_t begin = contacts.size();
  if (!options.deduplicate) {
    contacts.insert(contacts.end(), raw.begin(), raw.end());
    return raw.size();
  }
  const std::size_t n = raw.size();
  order_.resize(n);
  for (std::size_t k = 0; k < n; ++k) order_[k] = k;
  // deepest first, ties by point and normal: the same order whatever the triangles' order (the
  // sums below then round alike; exact copies are interchangeable)
  std::sort(order_.begin(), order_.end(), [&raw](std::size_t a, std::size_t b) {
    const ContactPoint &x = raw[a], &y = raw[b];
    if (x.penetration != y.penetration) return x.penetration > y.penetration;
    for (int d = 0; d < 3; ++d)
      if (x.point[d] != y.point[d]) return x.point[d] < y.point[d];
    for (int d = 0; d < 3; ++d)
      if (x.normal[d] != y.normal[d]) return x.normal[d] < y.normal[d];
    return false;
  });
  // exact copies of one contact (found on several triangle pairs) are adjacent now: one group
  groups_.clear();
  for (const std::size_t i : order_) {
    if (!groups_.empty()) {
      const ContactPoint &c = raw[i], &g = raw[groups_.back().raw];
      if (c.penetration == g.penetration && c.point == g.point && c.normal == g.normal) {
        ++groups_.back().count;
        continue;
      }
    }
    groups_.push_back({i, 1, 0});
  }
  // which point each group joins (running means, weighted by the penetrations)
  weights_.clear();
  normalSums_.clear();
  for (Group& group : groups_) {
    const ContactPoint& c = raw[group.raw];
    const double wc = group.count * c.penetration;  // > 0 for every contact (d < 2 eps)
    std::size_t joined = contacts.size() - begin;
    for (std::size_t k = begin; k < contacts.size(); ++k) {
      ContactPoint& m = contacts[k];
      if ((c.point - m.point).squaredNorm() < mergeDistance * mergeDistance &&
          c.normal.dot(m.normal) >= options.mergeNormalCosine) {
        double& w = weights_[k - begin];
        const double total = w + wc;
        const double old = total > 0.0 ? w / total : 0.5, added = 1.0 - old;
        m.point = old * m.point + added * c.point;
        m.penetration = old * m.penetration + added * c.penetration;
        m.distance = 2.0 * (eps - m.penetration);
        Vector3d& sum = normalSums_[k - begin];
        sum += wc * c.normal;
        if (sum.squaredNorm() > 0.0) m.normal = sum.normalized();
        w = total;
        m.mergedCount += group.count;
        joined = k - begin;
        break;
      }
    }
    if (joined == contacts.size() - begin) {
      contacts.push_back(c);
      contacts.back().mergedCount = group.count;
      normalSums_.push_back(wc * c.normal);
      weights_.push_back(wc);
    }
    group.point = joined;
  }
  // the shares s_i p_i of each group's raw contacts, summed per point
  const std::size_t points = contacts.size() - begin;
  loads_.assign(points, 0.0);
  pointSums_.assign(points, Vector3d::Zero());
  normalSums_.assign(points, Vector3d::Zero());
  // K_ij is symmetric: each pair once. Group g's sum still takes its terms in ascending j (those
  // of j < g while j was the outer group), so it rounds as a sum over j in order would.
  const std::size_t nGroups = groups_.size();
  kinSums_.resize(nGroups);
  for (std::size_t g = 0; g < nGroups; ++g)
    kinSums_[g] = groups_[g].count * raw[groups_[g].raw].penetration;
  for (std::size_t g = 0; g < nGroups; ++g) {
    const ContactPoint& c = raw[groups_[g].raw];
    for (std::size_t h = g + 1; h < nGroups; ++h) {
      const ContactPoint& d = raw[groups_[h].raw];
      const double k = kinship(c, d, mergeDistance, options.mergeNormalCosine);
      kinSums_[g] += groups_[h].count * k * d.penetration;
      kinSums_[h] += groups_[g].count * k * c.penetration;
    }
  }
  for (std::size_t gi = 0; gi < nGroups; ++gi) {
    const Group& g = groups_[gi];
    const ContactPoint& c = raw[g.raw];
    const double kin = kinSums_[gi];
    const double share = kin > 0.0 ? g.count * c.penetration * c.penetration / kin : 0.0;
    loads_[g.point] += share;
    pointSums_[g.point] += share * c.point;
    normalSums_[g.point] += share * c.normal;
  }
  for (std::size_t k = 0; k < points; ++k) {
    ContactPoint& m = contacts[begin + k];
    if (!(loads_[k] > 0.0) || !(m.penetration > 0.0)) continue;
    m.weight = loads_[k] / m.penetration;
    m.point = pointSums_[k] / loads_[k];
    if (normalSums_[k].squaredNorm() > 0.0) m.normal = normalSums_[k].normalized();
  }
  return points;
}

}  // namespace spacetree::contact
