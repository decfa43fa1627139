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

HaloReach::CellKey HaloReach::cellOf(const Eigen::Vector3d& x, double cell) const {
  return CellKey{std::int64_t(std::floor(x[0] / cell)), std::int64_t(std::floor(x[1] / cell)),
                 std::int64_t(std::floor(x[2] / cell))};
}

void HaloReach::indexPartners(double finerLargest) {
  if (indexed_ == partners_.size()) return;
  Index index;
  for (std::size_t p = indexed_; p < partners_.size(); ++p)
    index.cell = std::max(index.cell, touchReach(partners_[p], finerLargest) + rule_.slack);
  if (!(index.cell > 0.0)) index.cell = 1.0;  // radius 0 and skin 0: any cell size works
  for (std::size_t p = indexed_; p < partners_.size(); ++p)
    index.cells[cellOf(partners_[p].x, index.cell)].push_back(int(p));
  indexes_.push_back(std::move(index));
  indexed_ = partners_.size();
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
    const CellKey c = cellOf(x, index.cell);
    for (std::int64_t i = c.i - 1; i <= c.i + 1; ++i)
      for (std::int64_t j = c.j - 1; j <= c.j + 1; ++j)
        for (std::int64_t k = c.k - 1; k <= c.k + 1; ++k) {
          const auto found = index.cells.find(CellKey{i, j, k});
          if (found == index.cells.end()) continue;
          for (int p : found->second)
            if (canTouch(x, radius, p))
              reach = std::max(reach, grid_.distanceToOwner(x, partners_[std::size_t(p)].x) +
                                          rule_.slack);
        }
  }
  if (served) *served = reach > own;
  return reach;
}

}  // namespace spacetree::parallel
