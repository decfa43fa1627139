#include "tree/AdaptiveGrid.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace spacetree {

AdaptiveGrid::Policy AdaptiveGrid::policyFor(const AdaptiveGridOptions& options) {
  switch (options.type) {
    case GridType::Regular: return RegularGridPolicy(options);
    case GridType::Adaptive: return AdaptiveGridPolicy(options);
    case GridType::Reluctant: return ReluctantGridPolicy(options);
  }
  throw std::invalid_argument("adaptive grid: unknown grid type");
}

AdaptiveGrid::AdaptiveGrid(AdaptiveGridOptions options)
    : options_(options), grid_(SpacetreeOptions{options.epsilon, options.maxLevel}), policy_(policyFor(options)) {
  if (options.shock <= 0) throw std::invalid_argument("adaptive grid: shock must be > 0");
  if (options.coarseningThreshold < 0)
    throw std::invalid_argument("adaptive grid: coarsening threshold must be >= 0");
  if (options.coarseningThreshold >= options.shock)
    throw std::invalid_argument(
        "adaptive grid: coarsening threshold must be below the refinement shock, else fresh "
        "refinements are coarsened at once");
  if (!(options.padding >= 0.0) || !std::isfinite(options.padding))
    throw std::invalid_argument("adaptive grid: padding must be finite and >= 0");
}

bool AdaptiveGrid::needsNewCube(const double (*x)[3], const double* radius, int n) const {
  const RefinedCells& cells = grid_.cells;
  if (!cells.hasCube()) return true;
  const GridGeometry& geometry = cells.geometry();
  // requiredMeshSize() grows with the radius: the extreme radii decide.
  double minRadius = std::numeric_limits<double>::infinity(), maxRadius = -minRadius;
  for (int i = 0; i < n; ++i) {
    for (int d = 0; d < 3; ++d)
      if (!(x[i][d] >= geometry.origin[d] && x[i][d] <= geometry.origin[d] + geometry.rootSize)) return true;
    minRadius = std::min(minRadius, radius[i]);
    maxRadius = std::max(maxRadius, radius[i]);
  }
  if (n > 0 && grid_.requiredMeshSize(maxRadius) > geometry.rootSize) return true;
  const double minNeed = n > 0 ? grid_.requiredMeshSize(minRadius) : std::numeric_limits<double>::infinity();
  // A smaller particle than the finest level was made for: go deeper.
  return geometry.depth < options_.maxLevel && minNeed > 0.0 && cells.meshSize(geometry.depth) / 3.0 >= minNeed;
}

GridGeometry AdaptiveGrid::chooseCube(const double (*x)[3], const double* radius, int n) const {
  double lo[3], hi[3];
  double minNeed = std::numeric_limits<double>::infinity(), maxNeed = 0.0;
  for (int d = 0; d < 3; ++d) {
    lo[d] = std::numeric_limits<double>::infinity();
    hi[d] = -lo[d];
  }
  for (int i = 0; i < n; ++i) {
    for (int d = 0; d < 3; ++d) {
      if (!std::isfinite(x[i][d])) throw std::invalid_argument("adaptive grid: a particle has a non-finite position");
      lo[d] = std::min(lo[d], x[i][d]);
      hi[d] = std::max(hi[d], x[i][d]);
    }
    if (!(radius[i] >= 0.0) || !std::isfinite(radius[i]))
      throw std::invalid_argument("adaptive grid: a particle has a negative or non-finite radius");
    const double need = grid_.requiredMeshSize(radius[i]);
    minNeed = std::min(minNeed, need);
    maxNeed = std::max(maxNeed, need);
  }
  // Padded cube: particles may move a while before it has to be re-chosen (which resets the
  // refinement). Levels as in Spacetree::build: the finest one fits the smallest particle.
  const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  const double margin = options_.padding * std::max(extent, minNeed > 0.0 ? minNeed : 0.0);
  const double rootNeed = std::max(extent + 2.0 * margin, maxNeed);
  GridGeometry geometry;
  chooseRootCube(minNeed, rootNeed, options_.maxLevel, geometry);
  if (!(geometry.rootSize > 0.0)) geometry.rootSize = 1.0;
  for (int d = 0; d < 3; ++d) geometry.origin[d] = 0.5 * (lo[d] + hi[d]) - 0.5 * geometry.rootSize;
  return geometry;
}

template <class GridPolicy>
void AdaptiveGrid::fullUpdate(GridPolicy& policy, const double (*x)[3], const double (*v)[3], const double* radius,
                              int n) {
  HostedGrid& g = grid_;
  policy.forgetIncrementalState();
  g.stats.incremental = false;
  g.stats.rehosted = std::uint64_t(n);
  g.hostsChanged();  // particles moved
  g.host.assign(std::size_t(n), 0);
  g.admissible.resize(std::size_t(n));
  if (n == 0) return;
  if (needsNewCube(x, radius, n)) {
    g.cells.resetCube(chooseCube(x, radius, n));
    policy.newCube(std::size_t(g.cells.depth()) + 1);
    ++g.stats.geometryResets;
    g.cubeChanged();
  }
  int coarsestFit = g.cells.depth(), finestFitAll = 0;
  for (int i = 0; i < n; ++i) {
    g.admissible[i] = g.admissibleFor(radius[i]);
    coarsestFit = std::min(coarsestFit, g.admissible[i]);
    finestFitAll = std::max(finestFitAll, g.admissible[i]);
  }
  g.cells.setRegularDepth(policy.startOffDepth(coarsestFit, finestFitAll));
  g.rehostAll(x, n);  // particles moved: drops and lifts on the current grid
  policy.adapt(g, x, v, radius, n);
}

void AdaptiveGrid::update(const double (*x)[3], const double (*v)[3], const double* radius, int n) {
  HostedGrid& g = grid_;
  g.stats.refinements = 0;
  g.stats.coarsenings = 0;
  g.stats.spared = 0;
  n = std::max(n, 0);
  std::visit(
      [&](auto& policy) {
        const bool incremental = options_.incremental && policy.tracking() && n > 0 && n == int(g.host.size()) &&
                                 !needsNewCube(x, radius, n) && policy.updateIncrementally(g, x, v, radius, n);
        if (!incremental) fullUpdate(policy, x, v, radius, n);
      },
      policy_);
  g.collectStatistics();
}

void AdaptiveGrid::refineForPairs(const double (*x)[3], const double (*v)[3], const double* radius, int n,
                                  const int* first, const int* second, std::size_t count) {
  const bool refined = std::visit(
      [&](auto& policy) { return policy.refineForPairs(grid_, x, v, radius, n, first, second, count); }, policy_);
  if (refined) grid_.collectStatistics();
}

void AdaptiveGrid::buildSpacetree(Spacetree& tree, const double (*x)[3], const double* radius, int n,
                                  int nActive) const {
  if (n <= 0 || !grid_.cells.hasCube()) {
    tree.build(x, radius, n, nActive);  // nothing to place (e.g. an MPI rank without atoms)
    return;
  }
  tree.build(x, radius, n, nActive, grid_.cells.geometry(), grid_.host.data());
}

}  // namespace spacetree
