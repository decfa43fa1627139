#include "tree/GridCoarsening.h"

#include "tree/LevelParents.h"

namespace spacetree {

void GridCoarsening::keepingHosts(RefinedCells& cells, const double (*x)[3], const int* host, int n,
                                  AdaptiveGridStatistics& stats) {
  const int depth = cells.depth(), regularDepth = cells.regularDepth();
  if (depth <= regularDepth) return;
  if (keep_.size() < std::size_t(depth) + 1) keep_.resize(std::size_t(depth) + 1);
  std::vector<std::size_t> perLevel(std::size_t(depth) + 1, 0);
  for (int i = 0; i < n; ++i) ++perLevel[host[i]];
  for (int l = regularDepth + 1; l <= depth; ++l) keep_[l].reset(perLevel[l]);
  for (int i = 0; i < n; ++i) {
    const int l = host[i];
    if (l <= regularDepth) continue;
    const Index3 v = cells.nearestVertex(l, x[i]);
    keep_[l].insert(packVertexKey(v.i, v.j, v.k));
  }
  removeUnblocked(cells, nullptr, stats);
}

void GridCoarsening::keepingHotMarkers(RefinedCells& cells, const HeatMarkers& heat, SpareCheck* spare,
                                       AdaptiveGridStatistics& stats) {
  const int depth = cells.depth(), regularDepth = cells.regularDepth();
  if (depth <= regularDepth) return;
  if (keep_.size() < std::size_t(depth) + 1) keep_.resize(std::size_t(depth) + 1);
  const std::vector<VertexCounters>& markers = heat.markers();
  for (int l = regularDepth + 1; l <= depth; ++l) {
    keep_[l].reset(markers[l].size());
    for (std::size_t s = 0; s < markers[l].size(); ++s)
      if (heat.isHot(markers[l].values[s])) keep_[l].insert(markers[l].keys[s]);  // (the incremental annealing leaves zeros behind)
  }
  removeUnblocked(cells, spare, stats);
}

void GridCoarsening::removeUnblocked(RefinedCells& cells, SpareCheck* spare, AdaptiveGridStatistics& stats) {
  const int depth = cells.depth(), regularDepth = cells.regularDepth();
  std::vector<VertexKeySet>& keep = keep_;
  // Kept children keep their parents, bottom-up. Open-addressing sets (plus key lists) per
  // level: the parent propagation inserts up to 27 keys per kept vertex, which dominated the
  // update with node-based hash sets.
  for (int l = depth - 1; l > regularDepth; --l) {
    // Grows the table for this level's own hot vertices plus all parents of the finer ones.
    keep[l].reserveMore(27 * keep[l + 1].keys.size());
    // Children 3m+1 and 3m+2 have the same parents: skip a vertex whose parent range equals
    // the previous one's (keys come in spatially coherent order, so this saves many inserts).
    std::int64_t last[3] = {-1, -1, -1};
    for (std::uint64_t k : keep[l + 1].keys) {
      const VertexIndex w = unpackVertexKey(k);
      const std::int64_t range[3] = {w.i % 3 == 0 ? w.i : w.i - w.i % 3 + 1, w.j % 3 == 0 ? w.j : w.j - w.j % 3 + 1,
                                     w.k % 3 == 0 ? w.k : w.k - w.k % 3 + 1};
      if (range[0] == last[0] && range[1] == last[1] && range[2] == last[2]) continue;
      last[0] = range[0];
      last[1] = range[1];
      last[2] = range[2];
      forEachParentVertex(l, w.i, w.j, w.k, [&](std::uint64_t u) { keep[l].insert(u); });
    }
  }
  // Finest first, so whole empty subtrees collapse in one update. Decisions of one level are
  // taken before its removals change hanging status. Driven from the few blockers, not from
  // the many cells: each refined child and each kept non-hanging child vertex marks the parent
  // cells it blocks (a vertex on a parent boundary blocks up to 2^d of them), instead of 64
  // vertex tests per refined cell.
  std::vector<std::uint64_t>& removals = removals_;
  for (int l = depth - 1; l >= regularDepth; --l) {
    removals.clear();
    VertexKeySet& blocked = blocked_;
    blocked.reset((l + 1 < depth ? cells.refinedOn(l + 1).size() : 0) + 2 * keep[l + 1].keys.size());
    if (l + 1 < depth)
      for (std::uint64_t childKey : cells.refinedOn(l + 1).keys) {
        const VertexIndex c = unpackVertexKey(childKey);
        blocked.insert(packVertexKey(c.i / 3, c.j / 3, c.k / 3));
      }
    for (std::uint64_t vertexKey : keep[l + 1].keys) {
      const VertexIndex w = unpackVertexKey(vertexKey);
      if (w.i < 0 || w.j < 0 || w.k < 0 || cells.isHanging(l + 1, w.i, w.j, w.k)) continue;
      forEachParentCell(w.i, w.j, w.k, [&](std::uint64_t cellKey) { blocked.insert(cellKey); });
    }
    for (std::uint64_t cellKey : cells.refinedOn(l).keys) {
      if (blocked.contains(cellKey)) continue;
      if (spare && spare->wouldRefineAgain(l, cellKey)) {
        ++stats.spared;
        continue;
      }
      removals.push_back(cellKey);
    }
    cells.coarsen(l, removals);
    stats.coarsenings += removals.size();
  }
}

bool GridCoarsening::isBlocked(const RefinedCells& cells, const KeptVertices& kept, int level, std::int64_t i,
                               std::int64_t j, std::int64_t k) const {
  if (level + 1 < cells.depth())
    for (std::int64_t a = 3 * i; a < 3 * i + 3; ++a)
      for (std::int64_t b = 3 * j; b < 3 * j + 3; ++b)
        for (std::int64_t c = 3 * k; c < 3 * k + 3; ++c)
          if (cells.refinedOn(level + 1).contains(packVertexKey(a, b, c))) return true;
  for (std::int64_t a = 3 * i; a <= 3 * i + 3; ++a)
    for (std::int64_t b = 3 * j; b <= 3 * j + 3; ++b)
      for (std::int64_t c = 3 * k; c <= 3 * k + 3; ++c)
        if (kept.isKept(level + 1, packVertexKey(a, b, c)) && !cells.isHanging(level + 1, a, b, c)) return true;
  return false;
}

void GridCoarsening::aroundLostVertices(RefinedCells& cells, const KeptVertices& kept,
                                        const std::vector<LevelCell>& refinedSince, SpareCheck* spare,
                                        std::vector<LevelCell>* removed, AdaptiveGridStatistics& stats) {
  const int depth = cells.depth(), regularDepth = cells.regularDepth();
  if (depth <= regularDepth) return;
  if (candidates_.size() < std::size_t(depth) + 1) candidates_.resize(std::size_t(depth) + 1);
  for (int m = regularDepth; m < depth; ++m) candidates_[m].reset(0);
  for (int l = regularDepth + 1; l <= depth; ++l)
    for (std::uint64_t vertexKey : kept.lost(l)) {
      if (kept.isKept(l, vertexKey)) continue;  // lost and regained within this update
      const VertexIndex w = unpackVertexKey(vertexKey);
      // The parent cells this vertex blocked.
      forEachParentCell(w.i, w.j, w.k, [&](std::uint64_t cellKey) {
        if (cells.refinedOn(l - 1).contains(cellKey)) candidates_[l - 1].insert(cellKey);
      });
    }
  for (const LevelCell& cell : refinedSince)
    if (cell.first >= regularDepth && cell.first < depth) candidates_[cell.first].insert(cell.second);
  if (spare) {
    std::vector<LevelCell>& spared = spare->sparedCells();
    for (const LevelCell& cell : spared)  // spared last time: the criterion may no longer hold
      if (cell.first >= regularDepth && cell.first < depth) candidates_[cell.first].insert(cell.second);
    spared.clear();
  }
  std::vector<std::uint64_t>& removals = removals_;
  for (int m = depth - 1; m >= regularDepth; --m) {
    removals.clear();
    for (std::uint64_t cellKey : candidates_[m].keys) {  // decide the whole level first
      if (!cells.refinedOn(m).contains(cellKey)) continue;
      const VertexIndex c = unpackVertexKey(cellKey);
      if (isBlocked(cells, kept, m, c.i, c.j, c.k)) continue;
      if (spare && spare->wouldRefineAgain(m, cellKey)) {
        spare->sparedCells().emplace_back(m, cellKey);
        ++stats.spared;
        continue;
      }
      removals.push_back(cellKey);
    }
    if (removals.empty()) continue;
    cells.coarsen(m, removals);
    stats.coarsenings += removals.size();
    if (removed)
      for (std::uint64_t cellKey : removals) removed->emplace_back(m, cellKey);
    if (m - 1 >= regularDepth)
      for (std::uint64_t cellKey : removals) {  // the parent lost a refined child
        const VertexIndex c = unpackVertexKey(cellKey);
        candidates_[m - 1].insert(packVertexKey(c.i / 3, c.j / 3, c.k / 3));
      }
  }
}

}  // namespace spacetree
