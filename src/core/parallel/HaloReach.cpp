#include "parallel/HaloReach.h"

#include <algorithm>
#include <cmath>

namespace spacetree::parallel {

double HaloReach::ownReach(double radius, double classLargest) const {
  const double pair = (radius + classLargest) * rule_.contactFactor + rule_.skin;
  return std::max(pair, radius + rule_.minimumShell) + rule_.slack;
}

void HaloReach::clearPartners() {
  partners_.clear();
  indexes_.clear();
  indexed_ = 0;
}

void HaloReach::addPartner(const Eigen::Vector3d& x, double radius, const HaloSurface* surface) {
  partners_.push_back(Partner{x, radius, surface});
}

// A surface partner: its contact halo is what its radius adds to its surface's extent (the
// eps of a triangulated body); the particle's surface lies within its radius of its centre.
double HaloReach::touchReach(const Partner& b, double radius) const {
  if (!b.surface) return (radius + b.radius) * rule_.contactFactor + rule_.skin;
  const double halo = std::max(0.0, b.radius - b.surface->extent());
  return b.surface->extent() + (radius + 2.0 * halo) * rule_.contactFactor + rule_.skin;
}

void HaloReach::indexPartners(double finerLargest) {
  if (indexed_ == partners_.size()) return;
  Index index;
  // only partners that reach the own box can touch a particle of this rank
  std::vector<int> reaching;
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = Eigen::Vector3d::Constant(-INFINITY);
  for (std::size_t p = indexed_; p < partners_.size(); ++p) {
    const double reach = touchReach(partners_[p], finerLargest) + rule_.slack;
    const Eigen::Vector3d& x = partners_[p].x;
    const double outside = std::max((ownLo_ - x).cwiseMax(x - ownHi_).maxCoeff(), 0.0);
    if (outside > reach) continue;
    reaching.push_back(int(p));
    index.cell = std::max(index.cell, reach);
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  indexed_ = partners_.size();
  if (reaching.empty()) return;
  if (!(index.cell > 0.0)) index.cell = 1.0;  // radius 0 and skin 0: any cell size works
  // at most 64^3 cells: wider cells are as correct, only less selective
  index.cell = std::max(index.cell, (hi - lo).maxCoeff() / 63.0);
  index.lo = lo;
  std::int64_t ncell = 1;
  for (int d = 0; d < 3; ++d) {
    index.dims[std::size_t(d)] = std::int64_t(std::floor((hi[d] - lo[d]) / index.cell)) + 1;
    ncell *= index.dims[std::size_t(d)];
  }
  const auto cellIndex = [&index](const Eigen::Vector3d& x) {
    std::int64_t c[3];
    for (int d = 0; d < 3; ++d)
      c[d] = std::min(index.dims[std::size_t(d)] - 1,
                      std::max<std::int64_t>(0, std::int64_t(std::floor((x[d] - index.lo[d]) / index.cell))));
    return std::size_t((c[2] * index.dims[1] + c[1]) * index.dims[0] + c[0]);
  };
  index.start.assign(std::size_t(ncell) + 1, 0);
  for (int p : reaching) ++index.start[cellIndex(partners_[std::size_t(p)].x) + 1];
  for (std::size_t c = 0; c < std::size_t(ncell); ++c) index.start[c + 1] += index.start[c];
  index.order.resize(reaching.size());
  std::vector<int> fill(index.start.begin(), index.start.end() - 1);
  for (int p : reaching) index.order[std::size_t(fill[cellIndex(partners_[std::size_t(p)].x)]++)] = p;
  indexes_.push_back(std::move(index));
}

std::size_t HaloReach::indexedPartnerCount() const {
  std::size_t n = 0;
  for (const Index& index : indexes_) n += index.order.size();
  return n;
}

bool HaloReach::canTouch(const Eigen::Vector3d& x, double radius, int partner) const {
  const Partner& b = partners_[std::size_t(partner)];
  const double limit = touchReach(b, radius) + rule_.slack;
  if ((x - b.x).squaredNorm() > limit * limit) return false;
  if (!b.surface) return true;
  const double halo = std::max(0.0, b.radius - b.surface->extent());
  return b.surface->within(x, (radius + 2.0 * halo) * rule_.contactFactor + rule_.skin + rule_.slack);
}

double HaloReach::reach(const Eigen::Vector3d& x, double radius, double classLargest,
                        bool* served) const {
  const double own = ownReach(radius, classLargest);
  double reach = own;
  for (const Index& index : indexes_) {
    std::int64_t c[3];
    bool outside = false;
    for (int d = 0; d < 3 && !outside; ++d) {
      const double f = std::floor((x[d] - index.lo[d]) / index.cell);
      // beyond the cells next to the partners' box: no partner within reach
      outside = !(f >= -1.0 && f <= double(index.dims[std::size_t(d)]));
      c[d] = outside ? 0 : std::int64_t(f);
    }
    if (outside) continue;
    const std::int64_t k0 = std::max<std::int64_t>(0, c[2] - 1), k1 = std::min(index.dims[2] - 1, c[2] + 1);
    const std::int64_t j0 = std::max<std::int64_t>(0, c[1] - 1), j1 = std::min(index.dims[1] - 1, c[1] + 1);
    const std::int64_t i0 = std::max<std::int64_t>(0, c[0] - 1), i1 = std::min(index.dims[0] - 1, c[0] + 1);
    for (std::int64_t k = k0; k <= k1; ++k)
      for (std::int64_t j = j0; j <= j1; ++j)
        for (std::int64_t i = i0; i <= i1; ++i) {
          const std::size_t cell = std::size_t((k * index.dims[1] + j) * index.dims[0] + i);
          for (int q = index.start[cell]; q < index.start[cell + 1]; ++q) {
            const int p = index.order[std::size_t(q)];
            if (canTouch(x, radius, p))
              reach = std::max(reach, grid_.distanceToOwner(x, partners_[std::size_t(p)].x) +
                                          rule_.slack);
          }
        }
  }
  if (served) *served = reach > own;
  return reach;
}

}  // namespace spacetree::parallel
