#include "tree/HeatMarkers.h"

#include <algorithm>

#include "tree/LevelParents.h"

namespace spacetree {

void HeatMarkers::clear(std::size_t levels) {
  heat_.assign(levels, VertexCounters{});
  for (VertexCounters& markers : heat_) markers.reset(0);
}

void HeatMarkers::anneal(const RefinedCells& cells, const double (*x)[3], const int* host, int n) {
  // Halve, add the particles of the vertex, add the children's markers. Only levels below the
  // start-off grid can be coarsened, so only they keep markers.
  const int depth = cells.depth(), regularDepth = cells.regularDepth();
  std::vector<VertexCounters>& next = heatNext_;
  next.resize(heat_.size());
  for (std::size_t l = 0; l < next.size(); ++l) next[l].reset(heat_[l].size());
  for (int i = 0; i < n; ++i) {
    const int l = host[i];
    if (l <= regularDepth) continue;
    const Index3 v = cells.nearestVertex(l, x[i]);
    ++next[l][packVertexKey(v.i, v.j, v.k)];
  }
  for (int l = depth; l > regularDepth; --l) {
    for (std::size_t s = 0; s < heat_[l].size(); ++s) {
      const std::int64_t m = heat_[l].values[s];
      if (m / 2 > 0) next[l][heat_[l].keys[s]] += m / 2;
    }
    if (l < depth)
      for (std::size_t s = 0; s < next[l + 1].size(); ++s) {
        const std::int64_t m = next[l + 1].values[s];
        const VertexIndex w = unpackVertexKey(next[l + 1].keys[s]);
        forEachParentVertex(l, w.i, w.j, w.k, [&](std::uint64_t u) {
          std::int64_t& h = next[l][u];
          h = std::min(kMaxHeat, h + m);
        });
      }
  }
  heat_.swap(next);
}

std::size_t HeatMarkers::slot(int level, std::uint64_t vertexKey) {
  // The marker's slot in heat_ (created as 0) indexes its input and dirty flag too: one hash
  // look-up per touched vertex.
  VertexCounters& markers = heat_[level];
  const std::size_t slot = std::size_t(&markers[vertexKey] - markers.values.data());
  if (slot >= input_[level].size()) {
    input_[level].resize(markers.size(), 0);
    dirtyFlag_[level].resize(markers.size(), 0);
    parentsAt_[level].resize(markers.size(), kNoParents);
  }
  return slot;
}

std::uint32_t HeatMarkers::parentSlots(int level, std::size_t slot) {
  // The slots of a marker's parents on level - 1, listed once (count, then the slots): a
  // changing marker then updates its parents' inputs without hashing.
  std::uint32_t at = parentsAt_[level][slot];
  if (at != kNoParents) return at;
  std::vector<std::uint32_t>& pool = parentPool_[level];
  at = std::uint32_t(pool.size());
  pool.push_back(0);
  const VertexIndex w = unpackVertexKey(heat_[level].keys[slot]);
  forEachParentVertex(level - 1, w.i, w.j, w.k, [&](std::uint64_t u) {
    pool.push_back(std::uint32_t(this->slot(level - 1, u)));
    ++pool[at];
  });
  parentsAt_[level][slot] = at;
  return at;
}

void HeatMarkers::markDirty(int level, std::size_t slot) {
  if (dirtyFlag_[level][slot]) return;
  dirtyFlag_[level][slot] = 1;
  dirty_[level].push_back(std::uint32_t(slot));
}

void HeatMarkers::addParticle(int level, std::uint64_t vertexKey, std::int64_t delta) {
  const std::size_t s = slot(level, vertexKey);
  input_[level][s] += delta;
  markDirty(level, s);
}

void HeatMarkers::set(int level, std::size_t slot, std::int64_t value, KeptVertices& kept) {
  const std::int64_t old = heat_[level].values[slot];
  if (value == old) return;
  heat_[level].values[slot] = value;
  const std::uint64_t vertexKey = heat_[level].keys[slot];
  if (isHot(old) != isHot(value)) kept.add(level, vertexKey, isHot(value) ? 1 : -1);
  if (level - 1 > regularDepth_) {  // parents anneal on levels below the start-off grid only
    const std::uint32_t at = parentSlots(level, slot);
    const std::vector<std::uint32_t>& pool = parentPool_[level];
    std::vector<std::int64_t>& inputs = input_[level - 1];
    for (std::uint32_t p = at + 1; p <= at + pool[at]; ++p) {
      inputs[pool[p]] += value - old;
      markDirty(level - 1, pool[p]);
    }
  }
}

void HeatMarkers::shockTracked(int level, std::uint64_t vertexKey, KeptVertices& kept) {
  const std::size_t s = slot(level, vertexKey);
  set(level, s, std::min(kMaxHeat, heat_[level].values[s] + shock_), kept);
  markDirty(level, s);  // halved at the next annealing
}

void HeatMarkers::annealChanged(const RefinedCells& cells, KeptVertices& kept) {
  // Finest level first: a vertex's input holds its children's new markers when it is visited
  // (their changes add the parents to dirty_ of the coarser level, not yet taken).
  for (int l = cells.depth(); l > regularDepth_; --l) {
    std::swap(dirty_[l], annealing_[l]);
    dirty_[l].clear();
    for (std::uint32_t slot : annealing_[l]) dirtyFlag_[l][slot] = 0;
    for (std::uint32_t slot : annealing_[l]) {
      const std::int64_t m = heat_[l].values[slot];
      const std::int64_t next = std::min(kMaxHeat, m / 2 + input_[l][slot]);
      if (next == m) continue;     // converged: stays so until its input changes
      set(l, slot, next, kept);    // inserts on level l - 1 only: the slot stays valid
      markDirty(l, slot);          // not converged yet
    }
  }
}

void HeatMarkers::beginTracking(const RefinedCells& cells, const int* host, const std::uint64_t* hostKey, int n,
                                KeptVertices& kept) {
  const int depth = cells.depth();
  const std::size_t levels = std::size_t(depth) + 1;
  regularDepth_ = cells.regularDepth();
  dirty_.resize(levels);
  annealing_.resize(levels);
  dirtyFlag_.resize(levels);
  input_.resize(levels);
  parentsAt_.resize(levels);
  parentPool_.resize(levels);
  for (std::size_t l = 0; l < levels; ++l) {
    dirty_[l].clear();
    dirtyFlag_[l].assign(heat_[l].size(), 0);
    input_[l].assign(heat_[l].size(), 0);
    parentsAt_[l].assign(heat_[l].size(), kNoParents);  // slots of the last full update
    parentPool_[l].clear();
  }
  // Inputs: the particles hosted, then the children's markers as they stand (incl. this
  // update's shocks).
  for (int i = 0; i < n; ++i)
    if (host[i] > regularDepth_) {
      const std::size_t s = slot(host[i], hostKey[i]);
      input_[host[i]][s] += 1;
    }
  for (int l = depth; l - 1 > regularDepth_; --l)
    for (std::size_t s = 0; s < heat_[l].size(); ++s) {
      const std::int64_t m = heat_[l].values[s];
      if (m == 0) continue;
      const VertexIndex w = unpackVertexKey(heat_[l].keys[s]);
      forEachParentVertex(l - 1, w.i, w.j, w.k, [&](std::uint64_t u) {
        const std::size_t parent = slot(l - 1, u);
        input_[l - 1][parent] += m;
      });
    }
  // Hot markers counted as kept, and the vertices not at their fixed point listed. set()
  // keeps both from here on.
  for (int l = depth; l > regularDepth_; --l)
    for (std::size_t s = 0; s < heat_[l].size(); ++s) {
      const std::int64_t m = heat_[l].values[s];
      if (isHot(m)) kept.add(l, heat_[l].keys[s], 1);
      if (std::min(kMaxHeat, m / 2 + input_[l][s]) != m) markDirty(l, s);
    }
}

std::size_t HeatMarkers::entries() const {
  std::size_t entries = 0;
  for (const VertexCounters& m : heat_) entries += m.size();
  return entries;
}

}  // namespace spacetree
