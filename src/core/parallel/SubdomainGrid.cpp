#include "parallel/SubdomainGrid.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace spacetree::parallel {

namespace {

double intervalDistance(double p, double a, double b) { return std::max({0.0, a - p, p - b}); }

}  // namespace

SubdomainGrid::SubdomainGrid(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                             const std::array<bool, 3>& periodic,
                             const std::array<std::vector<double>, 3>& splits)
    : lo_(lo), hi_(hi), periodic_(periodic), splits_(splits) {
  for (int d = 0; d < 3; ++d) {
    if (!(hi[d] > lo[d])) throw std::invalid_argument("subdomain grid: hi must exceed lo");
    const std::vector<double>& s = splits_[std::size_t(d)];
    if (s.size() < 2 || s.front() != 0.0 || s.back() != 1.0)
      throw std::invalid_argument("subdomain grid: splits must run from 0 to 1");
    for (std::size_t i = 1; i < s.size(); ++i)
      if (!(s[i] > s[i - 1])) throw std::invalid_argument("subdomain grid: splits must ascend");
  }
}

double SubdomainGrid::cut(int d, int i) const {
  const std::vector<double>& s = splits_[std::size_t(d)];
  if (std::size_t(i) + 1 == s.size()) return hi_[d];  // as LIGGGHTS: the last box ends at hi
  return lo_[d] + (hi_[d] - lo_[d]) * s[std::size_t(i)];
}

double SubdomainGrid::axisDistance(int d, double p, double q) const {
  const double length = hi_[d] - lo_[d];
  const double tolerance =
      kRelativeTolerance * std::max({length, std::abs(lo_[d]), std::abs(hi_[d])});
  const int n = boxes(d);
  double shift = 0.0;
  if (periodic_[std::size_t(d)]) shift = std::floor((q - lo_[d]) / length) * length;
  const double inside = q - shift;
  int box = 0;
  while (box + 1 < n && cut(d, box + 1) <= inside) ++box;

  double distance = intervalDistance(p, cut(d, box) + shift, cut(d, box + 1) + shift);
  // q within rounding of a cut or a periodic face: the neighbouring box may own it
  if (inside - cut(d, box) <= tolerance) {
    if (box > 0)
      distance = std::max(distance, intervalDistance(p, cut(d, box - 1) + shift, cut(d, box) + shift));
    else if (periodic_[std::size_t(d)])
      distance = std::max(distance, intervalDistance(p, cut(d, n - 1) + shift - length,
                                                     cut(d, n) + shift - length));
  }
  if (cut(d, box + 1) - inside <= tolerance) {
    if (box + 1 < n)
      distance = std::max(distance, intervalDistance(p, cut(d, box + 1) + shift, cut(d, box + 2) + shift));
    else if (periodic_[std::size_t(d)])
      distance = std::max(distance, intervalDistance(p, cut(d, 0) + shift + length,
                                                     cut(d, 1) + shift + length));
  }
  return distance;
}

double SubdomainGrid::distanceToOwner(const Eigen::Vector3d& p, const Eigen::Vector3d& q) const {
  return std::max({axisDistance(0, p[0], q[0]), axisDistance(1, p[1], q[1]),
                   axisDistance(2, p[2], q[2])});
}

double SubdomainGrid::distanceToBox(const Eigen::Vector3d& p, const std::array<int, 3>& box,
                                    const std::array<int, 3>& shift) const {
  double distance = 0.0;
  for (int d = 0; d < 3; ++d) {
    const double s = shift[std::size_t(d)] * (hi_[d] - lo_[d]);
    const int b = box[std::size_t(d)];
    distance = std::max(distance, intervalDistance(p[d], cut(d, b) + s, cut(d, b + 1) + s));
  }
  return distance;
}

}  // namespace spacetree::parallel
