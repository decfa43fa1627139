#include "tree/AdaptiveGridPolicy.h"

#include <algorithm>

namespace spacetree {

bool AdaptiveGridPolicy::refineCell(HostedGrid& g, int level, std::int64_t i, std::int64_t j, std::int64_t k) {
  if (!g.cells.canRefine(level, i, j, k)) return false;
  const std::uint64_t cellKey = packVertexKey(i, j, k);
  g.cells.refine(level, cellKey);
  if (tracking_) newRefined_.emplace_back(level, cellKey);
  ++g.stats.refinements;
  return true;
}

void AdaptiveGridPolicy::dropByRefining(HostedGrid& g, const double (*x)[3], int i) {
  // The 2^d cells around the host vertex hold every cell its next nearest vertex needs, so
  // each round drops the particle by one level (the paper cascades within one top-down sweep,
  // too).
  while (g.host[i] < g.admissible[i]) {
    const int l = g.host[i];
    const Index3 v = g.cells.nearestVertex(l, x[i]);
    for (std::int64_t a = v.i - 1; a <= v.i; ++a)
      for (std::int64_t b = v.j - 1; b <= v.j; ++b)
        for (std::int64_t c = v.k - 1; c <= v.k; ++c) refineCell(g, l, a, b, c);
    g.host[i] = g.cells.hostOf(x[i], g.admissible[i]);
    if (g.host[i] <= l) break;  // defensive: no progress (re-examined next update)
  }
}

void AdaptiveGridPolicy::adapt(HostedGrid& g, const double (*x)[3], const double (*)[3], const double*, int n) {
  g.hostsChanged();  // hosts are set here, not by rehostAll
  for (int i = 0; i < n; ++i) dropByRefining(g, x, i);
  // Every host vertex is kept, so the cells around it and (having refined children) all their
  // ancestors stay: no host changes, no re-host needed.
  coarsening_.keepingHosts(g.cells, x, g.host.data(), n, g.stats);
  if (options_.incremental) resetIncrementalState(g, x, n);
}

void AdaptiveGridPolicy::resetIncrementalState(HostedGrid& g, const double (*x)[3], int n) {
  const int regularDepth = g.cells.regularDepth();
  hostKey_.resize(std::size_t(n));
  kept_.reset(std::size_t(g.cells.depth()) + 1, regularDepth);
  for (int i = 0; i < n; ++i) {
    const Index3 v = g.cells.nearestVertex(g.host[i], x[i]);
    hostKey_[i] = packVertexKey(v.i, v.j, v.k);
    if (g.host[i] > regularDepth) kept_.add(g.host[i], hostKey_[i], 1);
  }
  keptEntries_ = kept_.entries();
  tracking_ = true;
}

bool AdaptiveGridPolicy::updateIncrementally(HostedGrid& g, const double (*x)[3], const double (*)[3],
                                             const double* radius, int n) {
  // Counters of vertices that are no longer kept stay as zeros: rebuild when they pile up.
  if (kept_.entries() > 2 * keptEntries_ + 4096) return false;
  const int regularDepth = g.cells.regularDepth();
  int coarsestFit = g.cells.depth();
  moved_.clear();
  for (int i = 0; i < n; ++i) {
    const int admissible = g.admissibleFor(radius[i]);
    coarsestFit = std::min(coarsestFit, admissible);
    bool moved = admissible != g.admissible[i] || g.host[i] != admissible;
    g.admissible[i] = admissible;
    if (!moved) {
      const Index3 v = g.cells.nearestVertex(admissible, x[i]);
      moved = packVertexKey(v.i, v.j, v.k) != hostKey_[i];
    }
    if (moved) moved_.push_back(i);
  }
  if (coarsestFit != regularDepth) return false;  // the start-off grid changes: full update

  kept_.clearLost();
  newRefined_.clear();
  // Re-host the moved particles on the grid of the last update, then refine for them.
  for (int i : moved_) {
    if (g.host[i] > regularDepth) kept_.add(g.host[i], hostKey_[i], -1);
    g.host[i] = g.cells.hostOf(x[i], g.admissible[i]);
  }
  for (int i : moved_) dropByRefining(g, x, i);
  for (int i : moved_) {
    const Index3 v = g.cells.nearestVertex(g.host[i], x[i]);
    hostKey_[i] = packVertexKey(v.i, v.j, v.k);
    if (g.host[i] > regularDepth) kept_.add(g.host[i], hostKey_[i], 1);
  }
  coarsening_.aroundLostVertices(g.cells, kept_, newRefined_, nullptr, nullptr, g.stats);
  g.stats.incremental = true;
  g.stats.rehosted = moved_.size();
  g.hostsChanged();
  return true;
}

}  // namespace spacetree
