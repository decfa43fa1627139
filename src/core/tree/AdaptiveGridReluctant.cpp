// Incremental reluctant update: the change-driven form of the full update (AdaptiveGrid.cpp),
// with the same result cell for cell, marker for marker, host for host.
//
// * Hosts. A host is derived from the cells containing the particle (descent) and its nearest
//   vertices (lifts) on a few levels. Each particle remembers the position of its last
//   derivation and the distance to the nearest cell face or vertex rounding plane it read
//   there (its margin): while it moves less, it reads the same cells and vertices, so only a
//   grid change there can change its host. Grid changes re-derive just the particles that
//   read the changed cell: found through per-vertex particle lists (a refined cell's readers
//   are hosted on the corners of its ancestors, a removed cell's on its children's vertices).
// * Heat markers. m <- min(kMaxHeat, floor(m / 2) + s) with s = particles hosted at the vertex
//   + the children's new markers. s is kept per vertex and changed by deltas (a particle
//   arrives or leaves, a child's marker changes); m stops changing once s does (fixed point 2s
//   or 2s - 1). Only vertices whose s or m changed since they were last annealed are visited,
//   finest level first, so a vertex costs nothing once converged.
// * Coarsening. Hot markers (>= threshold) and kept children are counted per vertex (as the
//   adaptive grid counts particles); only cells around vertices that stopped being kept, cells
//   refined since the last coarsening, parents of removed cells and cells spared last time
//   are re-examined.
// * Spared cells. Coarsening follows the refinement pass and uses its pairs: a cool cell that
//   the criterion would refine again at once (a partner hosted at its children's vertices
//   would drop from the cell's level, the other is held there, they approach) stays. Without
//   this an approaching pair far from others had its cells removed and refined again every
//   two or three updates (markers of 1-particle vertices settle at 1-2 < threshold 4).
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>

#include "tree/AdaptiveGrid.h"

namespace spacetree {

namespace {
std::uint64_t key(std::int64_t i, std::int64_t j, std::int64_t k) { return packVertexKey(i, j, k); }
}  // namespace

double AdaptiveGrid::hostMargin(const double p[3], int admissible, int host, int descent) const {
  // How far p may move (per axis) before cellOf() on a descent level or nearestVertex() on a
  // lift level could change: distance to the nearest floor boundary of the scaled coordinate,
  // less a bound on the rounding of (p - origin) * (1 / h).
  const double scale = std::max({std::abs(p[0]), std::abs(p[1]), std::abs(p[2])}) +
                       std::max({std::abs(geometry_.origin[0]), std::abs(geometry_.origin[1]),
                                 std::abs(geometry_.origin[2])}) +
                       geometry_.rootSize;
  const double rounding = 64.0 * DBL_EPSILON * scale;
  double margin = std::numeric_limits<double>::infinity();
  auto limit = [&](int level, double shift) {
    const double inv = inverseMeshSize_[level];
    for (int d = 0; d < 3; ++d) {
      const double y = (p[d] - geometry_.origin[d]) * inv + shift;
      const double f = y - std::floor(y);
      margin = std::min(margin, (std::min(f, 1.0 - f) - 1e-9) * meshSize_[level]);
    }
  };
  const int first = std::max(0, std::min(regularDepth_, admissible));
  for (int l = first; l <= std::min(descent, admissible - 1); ++l) limit(l, 0.0);  // cellOf
  for (int l = host; l <= descent; ++l) limit(l, 0.5);                           // nearestVertex
  return margin - rounding;
}

void AdaptiveGrid::linkHost(int i) {
  std::int64_t& first = firstAtVertex_[host_[i]][hostKey_[i]];
  previousAtVertex_[i] = -1;
  nextAtVertex_[i] = int(first) - 1;
  if (first > 0) previousAtVertex_[first - 1] = i;
  first = i + 1;
}

void AdaptiveGrid::unlinkHost(int i) {
  const int before = previousAtVertex_[i], after = nextAtVertex_[i];
  if (before >= 0)
    nextAtVertex_[before] = after;
  else
    firstAtVertex_[host_[i]][hostKey_[i]] = after + 1;
  if (after >= 0) previousAtVertex_[after] = before;
}

std::size_t AdaptiveGrid::heatSlot(int level, std::uint64_t vertexKey) {
  // The marker's slot in heat_ (created as 0; slots are stable, entries are never erased)
  // indexes its input and dirty flag too: one hash look-up per touched vertex.
  Markers& markers = heat_[level];
  const std::size_t slot = std::size_t(&markers[vertexKey] - markers.values.data());
  if (slot >= heatInput_[level].size()) {
    heatInput_[level].resize(markers.size(), 0);
    dirtyFlag_[level].resize(markers.size(), 0);
    parentsAt_[level].resize(markers.size(), kNoParents);
  }
  return slot;
}

std::uint32_t AdaptiveGrid::parentSlots(int level, std::size_t slot) {
  // The slots of a marker's parents on level - 1, listed once (count, then the slots): a
  // changing marker then updates its parents' inputs without hashing.
  std::uint32_t at = parentsAt_[level][slot];
  if (at != kNoParents) return at;
  std::vector<std::uint32_t>& pool = parentPool_[level];
  at = std::uint32_t(pool.size());
  pool.push_back(0);
  const VertexIndex w = unpackVertexKey(heat_[level].keys[slot]);
  forEachParentVertex(level - 1, w.i, w.j, w.k, [&](std::uint64_t u) {
    pool.push_back(std::uint32_t(heatSlot(level - 1, u)));
    ++pool[at];
  });
  parentsAt_[level][slot] = at;
  return at;
}

void AdaptiveGrid::markDirty(int level, std::size_t slot) {
  if (dirtyFlag_[level][slot]) return;
  dirtyFlag_[level][slot] = 1;
  dirty_[level].push_back(std::uint32_t(slot));
}

void AdaptiveGrid::addHeatInput(int level, std::uint64_t vertexKey, std::int64_t delta) {
  const std::size_t slot = heatSlot(level, vertexKey);
  heatInput_[level][slot] += delta;
  markDirty(level, slot);
}

void AdaptiveGrid::setHeat(int level, std::size_t slot, std::int64_t value) {
  const std::int64_t old = heat_[level].values[slot];
  if (value == old) return;
  heat_[level].values[slot] = value;
  const std::uint64_t vertexKey = heat_[level].keys[slot];
  const std::int64_t threshold = options_.coarseningThreshold;
  const bool wasHot = old > 0 && old >= threshold, hot = value > 0 && value >= threshold;
  if (wasHot != hot) addKept(level, vertexKey, hot ? 1 : -1);
  if (level - 1 > regularDepth_) {  // parents anneal on levels below the start-off grid only
    const std::uint32_t at = parentSlots(level, slot);
    const std::vector<std::uint32_t>& pool = parentPool_[level];
    std::vector<std::int64_t>& inputs = heatInput_[level - 1];
    for (std::uint32_t p = at + 1; p <= at + pool[at]; ++p) {
      inputs[pool[p]] += value - old;
      markDirty(level - 1, pool[p]);
    }
  }
}

void AdaptiveGrid::addShock(int level, std::uint64_t vertexKey) {
  const std::size_t slot = heatSlot(level, vertexKey);
  setHeat(level, slot, std::min(kMaxHeat, heat_[level].values[slot] + options_.shock));
  markDirty(level, slot);  // halved at the next annealing
}

void AdaptiveGrid::annealDirtyMarkers() {
  // Finest level first: a vertex's input holds its children's new markers when it is visited
  // (their changes add the parents to dirty_ of the coarser level, not yet taken).
  for (int l = geometry_.depth; l > regularDepth_; --l) {
    std::swap(dirty_[l], annealing_[l]);
    dirty_[l].clear();
    for (std::uint32_t slot : annealing_[l]) dirtyFlag_[l][slot] = 0;
    for (std::uint32_t slot : annealing_[l]) {
      const std::int64_t m = heat_[l].values[slot];
      const std::int64_t next = std::min(kMaxHeat, m / 2 + heatInput_[l][slot]);
      if (next == m) continue;  // converged: stays so until its input changes
      setHeat(l, slot, next);   // inserts on level l - 1 only: the slot stays valid
      markDirty(l, slot);       // not converged yet
    }
  }
}

void AdaptiveGrid::rehostParticle(const double (*x)[3], int i) {
  int descent;
  const int host = hostPath(x[i], admissible_[i], descent);
  const Index3 v = nearestVertex(host, x[i]);
  const std::uint64_t hostKey = key(v.i, v.j, v.k);
  if (host != host_[i] || hostKey != hostKey_[i]) {
    unlinkHost(i);
    if (host_[i] > regularDepth_) addHeatInput(host_[i], hostKey_[i], -1);
    host_[i] = host;
    hostKey_[i] = hostKey;
    linkHost(i);
    if (host > regularDepth_) addHeatInput(host, hostKey, 1);
  }
  for (int d = 0; d < 3; ++d) referencePosition_[i][d] = x[i][d];
  margin_[i] = hostMargin(x[i], admissible_[i], host, descent);
  if (!(margin_[i] > 0.0)) fragile_.push_back(i);
  ++rehostCount_;
}

void AdaptiveGrid::rehostCandidates(const double (*x)[3]) {
  // A particle whose derivation reads a cell only up to rounding (margin <= 0) may not be
  // found through the lists: re-derive it at every grid change.
  // They are listed again by rehostParticle() if still fragile.
  for (int i : fragile_)
    if (!queued_[i]) {
      queued_[i] = 1;
      rehostQueue_.push_back(i);
    }
  fragile_.clear();
  for (int i : rehostQueue_) {
    queued_[i] = 0;
    rehostParticle(x, i);
  }
  rehostQueue_.clear();
}

void AdaptiveGrid::rehostAroundRefined(const double (*x)[3], std::size_t firstRefined) {
  // Refining cell C of level l changes what computeHost reads for particles whose descent
  // stopped at C or whose nearest vertex on level l + 1 has C among its parent cells; both are
  // hosted on a level L <= l, at a corner of C's ancestor on level L (they lie within h(l)/6
  // of C).
  for (std::size_t r = firstRefined; r < newRefined_.size(); ++r) {
    const int l = newRefined_[r].first;
    const VertexIndex c = unpackVertexKey(newRefined_[r].second);
    const std::int64_t last = cellsPerAxis(l + 1) - 1;
    // Readers lie within half a child cell of C: a box test first (0.6 for the rounding).
    const double child = meshSize_[l + 1];
    double lo[3], hi[3];
    const std::int64_t corner[3] = {c.i, c.j, c.k};
    for (int d = 0; d < 3; ++d) {
      lo[d] = geometry_.origin[d] + (3.0 * double(corner[d]) - 0.6) * child;
      hi[d] = geometry_.origin[d] + (3.0 * double(corner[d]) + 3.6) * child;
    }
    auto reads = [&](const double p[3]) {
      if (p[0] < lo[0] || p[0] > hi[0] || p[1] < lo[1] || p[1] > hi[1] || p[2] < lo[2] || p[2] > hi[2])
        return false;
      const Index3 cell = cellOf(l, p);
      if (cell.i == c.i && cell.j == c.j && cell.k == c.k) return true;
      const Index3 w = nearestVertex(l + 1, p);
      auto parent = [last](std::int64_t wd, std::int64_t cd) {
        return std::max<std::int64_t>(wd - 1, 0) / 3 <= cd && cd <= std::min(wd, last) / 3;
      };
      return parent(w.i, c.i) && parent(w.j, c.j) && parent(w.k, c.k);
    };
    std::int64_t ai = c.i, aj = c.j, ak = c.k;
    for (int level = l; level >= regularDepth_; --level) {
      for (std::int64_t a = ai; a <= ai + 1; ++a)
        for (std::int64_t b = aj; b <= aj + 1; ++b)
          for (std::int64_t e = ak; e <= ak + 1; ++e)
            for (int i = int(firstAtVertex_[level].get(key(a, b, e))) - 1; i >= 0; i = nextAtVertex_[i])
              if (!queued_[i] && reads(x[i])) {
                queued_[i] = 1;
                rehostQueue_.push_back(i);
              }
      ai /= 3;
      aj /= 3;
      ak /= 3;
    }
  }
  rehostCandidates(x);
}

void AdaptiveGrid::rehostAroundRemoved(const double (*x)[3]) {
  // Removing cell C of level l changes hosts only of particles hosted on level l + 1 at a
  // vertex of C's children (that vertex becomes hanging, or the descent stops at C); particles
  // that lifted above C keep their host and read a subset of what they read before.
  for (const auto& cell : removedCells_) {
    const int l = cell.first + 1;
    const VertexIndex c = unpackVertexKey(cell.second);
    for (std::int64_t a = 3 * c.i; a <= 3 * c.i + 3; ++a)
      for (std::int64_t b = 3 * c.j; b <= 3 * c.j + 3; ++b)
        for (std::int64_t e = 3 * c.k; e <= 3 * c.k + 3; ++e)
          for (int i = int(firstAtVertex_[l].get(key(a, b, e))) - 1; i >= 0; i = nextAtVertex_[i])
            if (!queued_[i]) {
              queued_[i] = 1;
              rehostQueue_.push_back(i);
            }
  }
  removedCells_.clear();
  rehostCandidates(x);
}

std::size_t AdaptiveGrid::reluctantEntries() const {
  std::size_t entries = 0;
  for (const auto* list : {&heat_, &keepCount_, &firstAtVertex_})
    for (const Markers& m : *list) entries += m.size();
  return entries;
}

void AdaptiveGrid::resetReluctantState(const double (*x)[3], const double* radius, int n) {
  const std::size_t levels = std::size_t(geometry_.depth) + 1;
  const int depth = geometry_.depth;
  hostKey_.resize(std::size_t(n));
  hostRadius_.assign(radius, radius + n);
  referencePosition_.resize(std::size_t(n));
  margin_.resize(std::size_t(n));
  nextAtVertex_.resize(std::size_t(n));
  previousAtVertex_.resize(std::size_t(n));
  queued_.assign(std::size_t(n), 0);
  rehostQueue_.clear();
  fragile_.clear();
  for (auto* list : {&firstAtVertex_, &keepCount_}) {
    list->resize(levels);
    for (Markers& m : *list) m.reset(0);
  }
  dirty_.resize(levels);
  annealing_.resize(levels);
  dirtyFlag_.resize(levels);
  heatInput_.resize(levels);
  parentsAt_.resize(levels);
  parentPool_.resize(levels);
  for (std::size_t l = 0; l < levels; ++l) {
    dirty_[l].clear();
    dirtyFlag_[l].assign(heat_[l].size(), 0);
    heatInput_[l].assign(heat_[l].size(), 0);
    parentsAt_[l].assign(heat_[l].size(), kNoParents);  // slots of the last full update
    parentPool_[l].clear();
  }
  lostKept_.assign(levels, {});
  candidates_.resize(levels);
  newRefined_.clear();
  removedCells_.clear();
  // Hosts as the full update left them; the margins need the descent levels.
  for (int i = 0; i < n; ++i) {
    int descent;
    hostPath(x[i], admissible_[i], descent);
    const Index3 v = nearestVertex(host_[i], x[i]);
    hostKey_[i] = key(v.i, v.j, v.k);
    linkHost(i);
    if (host_[i] > regularDepth_) {
      const std::size_t slot = heatSlot(host_[i], hostKey_[i]);
      heatInput_[host_[i]][slot] += 1;
    }
    for (int d = 0; d < 3; ++d) referencePosition_[i][d] = x[i][d];
    margin_[i] = hostMargin(x[i], admissible_[i], host_[i], descent);
    if (!(margin_[i] > 0.0)) fragile_.push_back(i);
  }
  // Inputs: the children's markers, as they stand (incl. this update's shocks).
  for (int l = depth; l - 1 > regularDepth_; --l)
    for (std::size_t s = 0; s < heat_[l].size(); ++s) {
      const std::int64_t m = heat_[l].values[s];
      if (m == 0) continue;
      const VertexIndex w = unpackVertexKey(heat_[l].keys[s]);
      forEachParentVertex(l - 1, w.i, w.j, w.k,
                          [&](std::uint64_t u) {
                            const std::size_t slot = heatSlot(l - 1, u);
                            heatInput_[l - 1][slot] += m;
                          });
    }
  // Kept counters (hot markers and kept children) and the vertices not at their fixed point.
  // setHeat() keeps both from here on.
  for (int l = depth; l > regularDepth_; --l)
    for (std::size_t s = 0; s < heat_[l].size(); ++s) {
      const std::int64_t m = heat_[l].values[s];
      if (m > 0 && m >= options_.coarseningThreshold) addKept(l, heat_[l].keys[s], 1);
      if (std::min(kMaxHeat, m / 2 + heatInput_[l][s]) != m) markDirty(l, s);
    }
  for (auto& lost : lostKept_) lost.clear();
  // The next coarsening examines every refined cell once, as the full one does (which cells
  // the criterion spares depends on that pass's pairs).
  spared_.clear();
  for (int l = regularDepth_; l < depth; ++l)
    for (std::uint64_t cellKey : refined_[l].keys) spared_.emplace_back(l, cellKey);
  keepEntries_ = reluctantEntries();
  incrementalValid_ = true;
}

void AdaptiveGrid::coarsenReluctant(const double (*x)[3], int n) {
  if (reluctantTracking()) {
    coarsenAroundLostVertices();
    for (auto& lost : lostKept_) lost.clear();
    newRefined_.clear();
    rehostAroundRemoved(x);
  } else {
    coarsen(x, n);
    rehostAll(x, n);
  }
  spare_ = SpareCheck{};  // no check outside a pass
}

void AdaptiveGrid::beginSpareCheck(const double (*x)[3], const double (*v)[3], const double* radius, int n,
                                   const int* first, const int* second, std::size_t count) {
  spare_ = SpareCheck{};
  spare_.x = x;
  spare_.v = v;
  spare_.radius = radius;
  spare_.n = n;
  spare_.first = first;
  spare_.second = second;
  spare_.count = first && second ? count : 0;
}

bool AdaptiveGrid::wouldRefineAgain(int m, std::uint64_t cellKey) {
  if (!spare_.x || m + 1 > geometry_.depth) return false;  // outside a pass: no spare check
  SpareCheck& s = spare_;
  const int n = s.n;
  const double (*x)[3] = s.x;
  if (!s.indexed) {  // partners per particle (CSR), both directions
    partnerStart_.assign(std::size_t(n) + 1, 0);
    auto forEachPair = [&](auto f) {
      if (s.first) {
        for (std::size_t k = 0; k < s.count; ++k) f(s.first[k], s.second[k]);
      } else {
        for (const auto& pair : closePairs_) f(pair.first, pair.second);
      }
    };
    auto valid = [n](int a, int b) { return a >= 0 && b >= 0 && a < n && b < n && a != b; };
    forEachPair([&](int a, int b) {
      if (!valid(a, b)) return;
      ++partnerStart_[std::size_t(a) + 1];
      ++partnerStart_[std::size_t(b) + 1];
    });
    for (int i = 0; i < n; ++i) partnerStart_[std::size_t(i) + 1] += partnerStart_[std::size_t(i)];
    partners_.resize(std::size_t(partnerStart_[std::size_t(n)]));
    std::vector<int>& fill = scratchNextAt_;  // borrowed: the host lists are built after this
    fill.assign(partnerStart_.begin(), partnerStart_.end() - 1);
    forEachPair([&](int a, int b) {
      if (!valid(a, b)) return;
      partners_[std::size_t(fill[std::size_t(a)]++)] = b;
      partners_[std::size_t(fill[std::size_t(b)]++)] = a;
    });
    s.indexed = true;
  }
  const bool tracked = reluctantTracking();
  if (!tracked && !s.hostsIndexed) {  // particles per host vertex, from the hosts
    scratchFirstAt_.resize(std::size_t(geometry_.depth) + 1);
    for (Markers& m : scratchFirstAt_) m.reset(0);
    scratchNextAt_.assign(std::size_t(n), -1);
    for (int i = 0; i < n; ++i) {
      const int l = host_[i];
      if (l <= regularDepth_) continue;
      const Index3 w = nearestVertex(l, x[i]);
      std::int64_t& head = scratchFirstAt_[std::size_t(l)][key(w.i, w.j, w.k)];
      scratchNextAt_[std::size_t(i)] = int(head) - 1;
      head = i + 1;
    }
    s.hostsIndexed = true;
  }
  const VertexIndex c = unpackVertexKey(cellKey);
  // p, hosted at a vertex of C's children, sits on level m (or coarser) once C is removed; the
  // criterion of refineForClosePairs there refines the parents of the 2^d cells around p's
  // nearest vertex on level m + 1 (its present host vertex, in C's closed patch): C among them.
  auto criterionHolds = [&](int p) {
    if (admissible_[p] <= m) return false;  // would not drop
    const Index3 pc = cellOf(m, x[p]);
    for (int t = partnerStart_[std::size_t(p)]; t < partnerStart_[std::size_t(p) + 1]; ++t) {
      const int q = partners_[std::size_t(t)];
      bool held = false;
      // A finer q is taken on level m too: under C it lifts with p; elsewhere that can only
      // spare more (a cell kept longer costs comparisons, never pairs).
      if (std::min(host_[q], m) == m) {
        const Index3 w = nearestVertex(m, x[q]);
        held = w.i >= pc.i && w.i <= pc.i + 1 && w.j >= pc.j && w.j <= pc.j + 1 && w.k >= pc.k && w.k <= pc.k + 1;
      } else {  // coarser q: virtual on p's cell's vertices within the link radius
        held = linksToCell(m, pc, x[q], s.radius[q]);
      }
      if (!held) continue;
      if (s.v) {
        double approach = 0.0;
        for (int d = 0; d < 3; ++d) approach += (x[q][d] - x[p][d]) * (s.v[q][d] - s.v[p][d]);
        if (!(approach < 0.0)) continue;
      }
      return true;
    }
    return false;
  };
  const std::vector<Markers>& firstAt = tracked ? firstAtVertex_ : scratchFirstAt_;
  const std::vector<int>& nextAt = tracked ? nextAtVertex_ : scratchNextAt_;
  for (std::int64_t a = 3 * c.i; a <= 3 * c.i + 3; ++a)
    for (std::int64_t b = 3 * c.j; b <= 3 * c.j + 3; ++b)
      for (std::int64_t e = 3 * c.k; e <= 3 * c.k + 3; ++e)
        for (int p = int(firstAt[std::size_t(m) + 1].get(key(a, b, e))) - 1; p >= 0; p = nextAt[std::size_t(p)])
          if (criterionHolds(p)) return true;
  return false;
}

bool AdaptiveGrid::updateReluctantIncrementally(const double (*x)[3], const double (*v)[3], const double* radius,
                                                int n) {
  // Zeros left behind (markers cooled off, vertices left) pile up: rebuild now and then.
  if (reluctantEntries() > 2 * keepEntries_ + 8 * std::size_t(n) + 4096 * std::size_t(geometry_.depth + 1))
    return false;
  int coarsestFit = geometry_.depth;
  newAdmissible_.resize(std::size_t(n));
  for (int i = 0; i < n; ++i) {
    newAdmissible_[i] = radius[i] == hostRadius_[i] ? admissible_[i] : admissibleFor(radius[i]);
    coarsestFit = std::min(coarsestFit, newAdmissible_[i]);
  }
  if (coarsestFit != regularDepth_) return false;  // the start-off grid changes: full update

  rehostCount_ = 0;
  // 1. Particles that moved past their margin (or changed their admissible level) on the grid
  //    of the last update (the full update's first rehostAll).
  fragile_.clear();
  for (int i = 0; i < n; ++i) {
    const double moved = std::max({std::abs(x[i][0] - referencePosition_[i][0]),
                                   std::abs(x[i][1] - referencePosition_[i][1]),
                                   std::abs(x[i][2] - referencePosition_[i][2])});
    hostRadius_[i] = radius[i];
    if (newAdmissible_[i] == admissible_[i] && moved < margin_[i]) continue;
    admissible_[i] = newAdmissible_[i];
    rehostParticle(x, i);
  }
  // 2. Heat markers (updateHeatMarkers).
  annealDirtyMarkers();
  // 3. Refinement for close pairs found here (else the caller's refineForPairs, after the
  //    tree is built); it re-hosts the particles that read a refined cell.
  // 4. Coarsening around vertices that stopped being kept (and cells spared last time), with
  //    the pass's pairs; then the particles under removed cells lift. With the caller's pairs
  //    both follow its sweep, in refineForPairs.
  if (!options_.pairsFromCaller) {
    searchClosePairs(x, v, radius, n);
    refineForClosePairs(x, radius, n);
    beginSpareCheck(x, v, radius, n, nullptr, nullptr, 0);
    coarsenReluctant(x, n);
  }
  stats_.incremental = true;
  stats_.rehosted = rehostCount_;
  hostsCurrent_ = false;
  return true;
}

}  // namespace spacetree
