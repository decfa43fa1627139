#include "geometry/TriangleBvh.h"

#include <algorithm>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace spacetree::geometry {

using Eigen::Vector3d;

TriangleBvh::TriangleBvh(const std::vector<Vector3d>& centres, const std::vector<double>& radii)
    : centres_(centres), radii_(radii) {
  if (centres.size() != radii.size())
    throw std::invalid_argument("TriangleBvh: centres and radii differ in size");
  if (centres.empty()) return;
  order_.resize(centres.size());
  std::iota(order_.begin(), order_.end(), 0);
  for (std::size_t i = 0; i < centres.size(); ++i)
    extent_ = std::max(extent_, centres[i].norm() + radii[i]);
  nodes_.reserve(2 * centres.size() / kLeafSize + 2);
  build(0, int(order_.size()), centres, radii);
}

int TriangleBvh::build(int begin, int end, const std::vector<Vector3d>& centres,
                       const std::vector<double>& radii) {
  const int index = int(nodes_.size());
  nodes_.emplace_back();
  Vector3d lo = Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  Vector3d clo = lo, chi = hi;  // box of the centres (split axis)
  for (int k = begin; k < end; ++k) {
    const int i = order_[std::size_t(k)];
    const Vector3d r = Vector3d::Constant(radii[std::size_t(i)]);
    lo = lo.cwiseMin(centres[std::size_t(i)] - r);
    hi = hi.cwiseMax(centres[std::size_t(i)] + r);
    clo = clo.cwiseMin(centres[std::size_t(i)]);
    chi = chi.cwiseMax(centres[std::size_t(i)]);
  }
  nodes_[std::size_t(index)].lo = lo;
  nodes_[std::size_t(index)].hi = hi;
  // Depth is O(log n) (median split), far below the query's fixed stack of 64.
  if (end - begin <= kLeafSize) {
    nodes_[std::size_t(index)].begin = begin;
    nodes_[std::size_t(index)].count = end - begin;
    return index;
  }
  int axis = 0;
  (chi - clo).maxCoeff(&axis);
  const int middle = begin + (end - begin) / 2;
  std::nth_element(order_.begin() + begin, order_.begin() + middle, order_.begin() + end,
                   [&](int a, int b) {
                     const double ca = centres[std::size_t(a)][axis], cb = centres[std::size_t(b)][axis];
                     return ca < cb || (ca == cb && a < b);
                   });
  build(begin, middle, centres, radii);
  const int right = build(middle, end, centres, radii);
  nodes_[std::size_t(index)].right = right;
  return index;
}

void TriangleBvh::query(const Vector3d& q, double radius, std::vector<int>& out) const {
  out.clear();
  forEachCandidate(q, radius, [&](int i) {
    const double reach = radii_[std::size_t(i)] + radius;
    if ((centres_[std::size_t(i)] - q).squaredNorm() < reach * reach) out.push_back(i);
  });
  std::sort(out.begin(), out.end());
}

}  // namespace spacetree::geometry
