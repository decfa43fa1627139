#include "tree/ReluctantGridPolicy.h"

#include <algorithm>

#include "tree/ReluctantCriterion.h"

namespace spacetree {

bool ReluctantGridPolicy::refineCell(HostedGrid& g, int level, std::int64_t i, std::int64_t j, std::int64_t k) {
  if (!g.cells.canRefine(level, i, j, k)) return false;
  // Vertices of the new patch that did not exist as full vertices before get the heat shock.
  std::vector<std::uint64_t> created;
  for (std::int64_t a = 3 * i; a <= 3 * i + 3; ++a)
    for (std::int64_t b = 3 * j; b <= 3 * j + 3; ++b)
      for (std::int64_t c = 3 * k; c <= 3 * k + 3; ++c)
        if (g.cells.isHanging(level + 1, a, b, c)) created.push_back(packVertexKey(a, b, c));
  const std::uint64_t cellKey = packVertexKey(i, j, k);
  g.cells.refine(level, cellKey);
  if (tracking_) newRefined_.emplace_back(level, cellKey);
  for (std::uint64_t vertexKey : created) {
    if (tracking_)
      heat_.shockTracked(level + 1, vertexKey, kept_);  // also the parents' inputs, kept counters
    else
      heat_.shock(level + 1, vertexKey);
  }
  ++g.stats.refinements;
  return true;
}

void ReluctantGridPolicy::searchClosePairs(HostedGrid& g, const double (*x)[3], const double (*v)[3],
                                           const double* radius, int n) {
  closePairs_.clear();
  g.tree.build(x, radius, n, n, g.cells.geometry(), g.host.data());
  g.tree.forEachPairWithin([&](int a, int b, double) {
    if (approaching(x, v, a, b)) closePairs_.emplace_back(a, b);
  });
}

void ReluctantGridPolicy::refineForClosePairs(HostedGrid& g, const double (*x)[3], const double* radius, int n) {
  // Refine the cell containing particle p if p would drop and q is held by the cell. The
  // neighbours p's next finer vertex needs are refined with it, so that p really drops.
  // Repeated while drops happen: one sweep may cascade over several levels.
  const RefinedCells& cells = g.cells;
  for (int round = 0; round <= cells.depth(); ++round) {
    bool refined = false;
    const std::size_t firstRefined = newRefined_.size();
    for (const auto& pair : closePairs_) {
      for (int side = 0; side < 2; ++side) {
        const int p = side ? pair.second : pair.first, q = side ? pair.first : pair.second;
        const int l = g.host[p];
        if (l >= g.admissible[p] || g.host[q] > l) continue;
        const Index3 c = cells.cellOf(l, x[p]);
        if (!heldByCell(cells, options_.epsilon, l, c, x[q], g.host[q], radius[q])) continue;
        const Index3 w = cells.nearestVertex(l + 1, x[p]);
        for (std::int64_t a = w.i - 1; a <= w.i; ++a)
          for (std::int64_t b = w.j - 1; b <= w.j; ++b)
            for (std::int64_t e = w.k - 1; e <= w.k; ++e)
              if (a >= 0 && b >= 0 && e >= 0) refined |= refineCell(g, l, a / 3, b / 3, e / 3);
      }
    }
    if (!refined) break;
    if (tracking_)
      hosts_.rehostAroundRefined(g, heat_, x, newRefined_, firstRefined);  // only particles that read a refined cell
    else
      g.rehostAll(x, n);
  }
}

void ReluctantGridPolicy::coarsen(HostedGrid& g, const double (*x)[3], const double (*v)[3], const double* radius,
                                  int n, const int* first, const int* second, std::size_t count) {
  SpareCheck::Pass pass;
  pass.cells = &g.cells;
  pass.epsilon = options_.epsilon;
  pass.x = x;
  pass.v = v;
  pass.radius = radius;
  pass.host = g.host.data();
  pass.admissible = g.admissible.data();
  pass.n = n;
  pass.first = first;
  pass.second = second;
  pass.count = count;
  pass.closePairs = &closePairs_;
  if (tracking_) {
    pass.firstAtVertex = &hosts_.firstAtVertex();
    pass.nextAtVertex = &hosts_.nextAtVertex();
  }
  spare_.begin(pass);
  if (tracking_) {
    coarsening_.aroundLostVertices(g.cells, kept_, newRefined_, &spare_, &removedCells_, g.stats);
    kept_.clearLost();
    newRefined_.clear();
    hosts_.rehostAroundRemoved(g, heat_, x, removedCells_);  // particles under removed cells lift
  } else {
    coarsening_.keepingHotMarkers(g.cells, heat_, &spare_, g.stats);
    g.rehostAll(x, n);
  }
  spare_.end();  // no check outside a pass
}

bool ReluctantGridPolicy::refineForPairs(HostedGrid& g, const double (*x)[3], const double (*v)[3],
                                         const double* radius, int n, const int* first, const int* second,
                                         std::size_t count) {
  if (!g.cells.hasCube() || n != int(g.host.size())) return false;
  closePairs_.clear();
  for (std::size_t k = 0; k < count; ++k) {
    const int a = first[k], b = second[k];
    if (a < 0 || b < 0 || a >= n || b >= n) continue;
    // Refinement only drops particles, so a pair of two particles already on their admissible
    // levels never triggers one (in any round of refineForClosePairs): skip it before the
    // approach test (random loads of x and v).
    if (g.host[a] >= g.admissible[a] && g.host[b] >= g.admissible[b]) continue;
    if (!approaching(x, v, a, b)) continue;
    closePairs_.emplace_back(a, b);
  }
  refineForClosePairs(g, x, radius, n);
  coarsen(g, x, v, radius, n, first, second, count);
  return true;
}

void ReluctantGridPolicy::adapt(HostedGrid& g, const double (*x)[3], const double (*v)[3], const double* radius,
                                int n) {
  heat_.anneal(g.cells, x, g.host.data(), n);
  if (!options_.pairsFromCaller) {
    searchClosePairs(g, x, v, radius, n);
    refineForClosePairs(g, x, radius, n);
  }
  g.rehostAll(x, n);
  // Coarsening follows the refinement pass (here, or refineForPairs after the caller's sweep),
  // with its pairs; particles under removed cells lift.
  if (!options_.pairsFromCaller) coarsen(g, x, v, radius, n, nullptr, nullptr, 0);
  if (options_.incremental) resetIncrementalState(g, x, radius, n);
}

void ReluctantGridPolicy::resetIncrementalState(HostedGrid& g, const double (*x)[3], const double* radius, int n) {
  const int depth = g.cells.depth(), regularDepth = g.cells.regularDepth();
  kept_.reset(std::size_t(depth) + 1, regularDepth);
  hosts_.reset(g, x, radius, n);
  heat_.beginTracking(g.cells, g.host.data(), hosts_.hostKeys().data(), n, kept_);
  kept_.clearLost();
  newRefined_.clear();
  removedCells_.clear();
  // The next coarsening examines every refined cell once, as the full one does (which cells
  // the criterion spares depends on that pass's pairs).
  std::vector<LevelCell>& spared = spare_.sparedCells();
  spared.clear();
  for (int l = regularDepth; l < depth; ++l)
    for (std::uint64_t cellKey : g.cells.refinedOn(l).keys) spared.emplace_back(l, cellKey);
  trackedEntries_ = trackedEntries();
  tracking_ = true;
}

bool ReluctantGridPolicy::updateIncrementally(HostedGrid& g, const double (*x)[3], const double (*v)[3],
                                              const double* radius, int n) {
  const int depth = g.cells.depth();
  // Zeros left behind (markers cooled off, vertices left) pile up: rebuild now and then.
  if (trackedEntries() > 2 * trackedEntries_ + 8 * std::size_t(n) + 4096 * std::size_t(depth + 1)) return false;
  int coarsestFit = depth;
  newAdmissible_.resize(std::size_t(n));
  for (int i = 0; i < n; ++i) {
    newAdmissible_[i] = hosts_.sameRadius(i, radius[i]) ? g.admissible[i] : g.admissibleFor(radius[i]);
    coarsestFit = std::min(coarsestFit, newAdmissible_[i]);
  }
  if (coarsestFit != g.cells.regularDepth()) return false;  // the start-off grid changes: full update

  // 1. Particles that moved past their margin (or changed their admissible level), on the
  //    grid of the last update (the full update's first rehostAll).
  hosts_.rehostMoved(g, heat_, x, radius, newAdmissible_);
  // 2. Heat markers.
  heat_.annealChanged(g.cells, kept_);
  // 3. Refinement for the close pairs found here (else the caller's refineForPairs, after the
  //    tree is built); it re-hosts the particles that read a refined cell.
  // 4. Coarsening around vertices that stopped being kept (and cells spared last time), with
  //    the pass's pairs; then the particles under removed cells lift. With the caller's pairs
  //    both follow its sweep, in refineForPairs.
  if (!options_.pairsFromCaller) {
    searchClosePairs(g, x, v, radius, n);
    refineForClosePairs(g, x, radius, n);
    coarsen(g, x, v, radius, n, nullptr, nullptr, 0);
  }
  g.stats.incremental = true;
  g.stats.rehosted = hosts_.rehostCount();
  g.hostsChanged();
  return true;
}

}  // namespace spacetree
