#include "contact_model/ContactHistory.h"

#include <algorithm>
#include <stdexcept>

namespace spacetree::contact_model {

ContactHistoryMatcher::ContactHistoryMatcher(int historySize, ContactHistoryMatchOptions options)
    : historySize_(historySize), options_(options) {
  if (historySize < 0) throw std::invalid_argument("ContactHistoryMatcher: historySize must be >= 0");
  if (!(options.distance >= 0.0))
    throw std::invalid_argument("ContactHistoryMatcher: distance must be >= 0");
}

void ContactHistoryMatcher::setDistance(double distance) {
  if (!(distance >= 0.0)) throw std::invalid_argument("ContactHistoryMatcher: distance must be >= 0");
  options_.distance = distance;
}

void ContactHistoryMatcher::matchAnchors(const double* previous, std::size_t previousCount,
                                         std::vector<double>& next,
                                         ContactHistoryMatchStatistics* statistics) {
  const std::size_t stride = std::size_t(recordSize());
  const std::size_t count = points_.size();
  const double limit2 = options_.distance * options_.distance;
  const auto anchorPoint = [&](std::size_t m) {
    const double* r = previous + m * stride;
    return Eigen::Vector3d(r[0], r[1], r[2]);
  };
  const auto anchorNormal = [&](std::size_t m) {
    const double* r = previous + m * stride;
    return Eigen::Vector3d(r[3], r[4], r[5]);
  };
  // every (point, record) pair with close normals, the closest first
  candidates_.clear();
  for (std::size_t k = 0; k < count; ++k)
    for (std::size_t m = 0; m < previousCount; ++m)
      if (normals_[k].dot(anchorNormal(m)) >= options_.normalCosine)
        candidates_.push_back({(points_[k] - anchorPoint(m)).squaredNorm(), int(k), int(m)});
  std::sort(candidates_.begin(), candidates_.end(), [](const Candidate& a, const Candidate& b) {
    if (a.distance != b.distance) return a.distance < b.distance;
    if (a.current != b.current) return a.current < b.current;
    return a.previous < b.previous;
  });
  matchOfCurrent_.assign(count, -1);
  previousTaken_.assign(previousCount, 0);
  std::size_t kept = 0, moved = 0, merged = 0, dropped = 0;
  // passes 1 (within `distance`) and 2 (any distance): the candidates are sorted by distance,
  // so pass 1 is the prefix below the limit
  for (int pass = 1; pass <= 2; ++pass)
    for (const Candidate& c : candidates_) {
      if (pass == 1 && !(c.distance < limit2)) break;
      if (matchOfCurrent_[std::size_t(c.current)] >= 0 || previousTaken_[std::size_t(c.previous)]) continue;
      matchOfCurrent_[std::size_t(c.current)] = c.previous;
      previousTaken_[std::size_t(c.previous)] = 1;
      ++kept;
      if (pass == 2) ++moved;
    }
  next.assign(count * stride, 0.0);
  for (std::size_t k = 0; k < count; ++k) {
    double* r = next.data() + k * stride;
    for (int d = 0; d < 3; ++d) {
      r[d] = points_[k][d];
      r[3 + d] = normals_[k][d];
    }
    const int m = matchOfCurrent_[k];
    if (m >= 0)
      std::copy_n(previous + std::size_t(m) * stride + kContactAnchorDoubles, historySize_,
                  r + kContactAnchorDoubles);
  }
  // pass 3: records left over join the nearest continuing point with a close normal
  for (const Candidate& c : candidates_) {
    if (previousTaken_[std::size_t(c.previous)] || matchOfCurrent_[std::size_t(c.current)] < 0) continue;
    previousTaken_[std::size_t(c.previous)] = 1;
    const double* from = previous + std::size_t(c.previous) * stride + kContactAnchorDoubles;
    double* to = next.data() + std::size_t(c.current) * stride + kContactAnchorDoubles;
    for (int h = 0; h < historySize_; ++h) to[h] += from[h];
    ++merged;
  }
  for (std::size_t m = 0; m < previousCount; ++m) dropped += previousTaken_[m] ? 0 : 1;
  if (statistics) {
    statistics->kept += kept;
    statistics->moved += moved;
    statistics->merged += merged;
    statistics->started += count - kept;
    statistics->dropped += dropped;
  }
}

}  // namespace spacetree::contact_model
