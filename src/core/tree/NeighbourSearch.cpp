#include "tree/NeighbourSearch.h"

#include <cmath>
#include <stdexcept>
#include <utility>

namespace spacetree {

void NeighbourSearch::setSkin(double skin) {
  if (!(skin >= 0.0) || !std::isfinite(skin)) throw std::invalid_argument("neighbour search: skin must be finite and >= 0");
  SpacetreeOptions options = treeOptions_;
  options.epsilon = 0.5 * skin;
  tree_.setOptions(options);
  treeOptions_ = options;
  if (grid_ && grid_->options().epsilon != options.epsilon) useGrid(grid_->options());
}

void NeighbourSearch::setMaxLevel(int maxLevel) {
  SpacetreeOptions options = treeOptions_;
  options.maxLevel = maxLevel;
  tree_.setOptions(options);  // throws for a level outside [0, kMaxSpacetreeLevel]
  treeOptions_ = options;
  if (grid_ && grid_->options().maxLevel > maxLevel) useGrid(grid_->options());
}

AdaptiveGridOptions NeighbourSearch::gridOptions(AdaptiveGridOptions requested) const {
  requested.epsilon = treeOptions_.epsilon;
  if (requested.maxLevel > treeOptions_.maxLevel) requested.maxLevel = treeOptions_.maxLevel;
  requested.pairsFromCaller = true;  // findPairs reports its sweep's pairs (refineAfterSweep)
  return requested;
}

void NeighbourSearch::useNewGrid(const AdaptiveGridOptions& requested) {
  grid_ = std::make_unique<AdaptiveGrid>(gridOptions(requested));
}

void NeighbourSearch::useGrid(const AdaptiveGridOptions& requested) {
  const AdaptiveGridOptions wanted = gridOptions(requested);
  if (grid_) {
    const AdaptiveGridOptions& o = grid_->options();
    if (o.type == wanted.type && o.epsilon == wanted.epsilon && o.maxLevel == wanted.maxLevel &&
        o.shock == wanted.shock && o.coarseningThreshold == wanted.coarseningThreshold &&
        o.padding == wanted.padding && o.incremental == wanted.incremental)
      return;
  }
  useNewGrid(requested);
}

void NeighbourSearch::useGrid(AdaptiveGrid grid) {
  const AdaptiveGridOptions& o = grid.options();
  const AdaptiveGridOptions wanted = gridOptions(o);
  if (o.epsilon != wanted.epsilon || o.maxLevel != wanted.maxLevel || !o.pairsFromCaller)
    throw std::invalid_argument("neighbour search: the grid's halo, depth or pair source is not this search's");
  grid_ = std::make_unique<AdaptiveGrid>(std::move(grid));
}

void NeighbourSearch::buildTree(const double (*x)[3], const double (*v)[3], const double* radius, int n,
                                int nActive) {
  gridSeconds_ = 0.0;
  if (!grid_) {
    tree_.build(x, radius, n, nActive);
    return;
  }
  const Clock::time_point start = Clock::now();
  grid_->update(x, v, radius, n);
  gridSeconds_ = std::chrono::duration<double>(Clock::now() - start).count();
  grid_->buildSpacetree(tree_, x, radius, n, nActive);
}

void NeighbourSearch::refineAfterSweep(const double (*x)[3], const double (*v)[3], const double* radius, int n,
                                       const ListedPairs& pairs) {
  // The reluctant grid refines for the pairs this sweep found (used from the next build on).
  if (!grid_ || grid_->options().type != GridType::Reluctant) return;
  const Clock::time_point start = Clock::now();
  unmarked_.resize(pairs.size());
  for (std::size_t k = 0; k < pairs.size(); ++k) unmarked_[k] = pairs.second[k] < 0 ? ~pairs.second[k] : pairs.second[k];
  grid_->refineForPairs(x, v, radius, n, pairs.first.data(), unmarked_.data(), pairs.size());
  gridSeconds_ += std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace spacetree
