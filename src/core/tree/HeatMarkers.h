// The reluctant grid's heat markers (paper §5.1), one integer per vertex below the start-off
// grid, with their full and their incremental update in one place. Annealing: a marker m
// becomes min(kMaxHeat, floor(m / 2) + s), s = particles hosted at the vertex + the children's
// new markers; refining a cell shocks the vertices it creates; a vertex whose marker reaches
// the coarsening threshold is hot (kept from coarsening).
//
// Incremental form (tracking): s is kept per vertex and changed by deltas (a particle arrives
// or leaves, a child's marker changes); m stops changing once s does (fixed point 2s or
// 2s - 1). Only vertices whose s or m changed since they were last annealed are visited,
// finest level first, so a vertex costs nothing once converged. Hot markers are counted in the
// KeptVertices as they come and go. Both forms give the same markers (tested).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "tree/KeptVertices.h"
#include "tree/RefinedCells.h"
#include "tree/VertexCounters.h"

namespace spacetree {

class HeatMarkers {
 public:
  // Markers sum their children's (up to 343 per vertex per level): saturate instead of
  // overflowing; anything this hot vetoes coarsening anyway.
  static constexpr std::int64_t kMaxHeat = std::int64_t(1) << 40;

  HeatMarkers(int shock, int coarseningThreshold) : shock_(shock), threshold_(coarseningThreshold) {}

  // No markers, on `levels` levels (a new cube).
  void clear(std::size_t levels);
  // Markers stored by serialise() (their levels, which restore() does not track).
  void restore(std::vector<VertexCounters> markers) { heat_ = std::move(markers); }
  // Per level: vertex -> marker (0, left behind by the incremental annealing: no marker).
  const std::vector<VertexCounters>& markers() const { return heat_; }
  bool isHot(std::int64_t marker) const { return marker > 0 && marker >= threshold_; }

  // Full update: anneal every marker once from the particles' hosts.
  void anneal(const RefinedCells& cells, const double (*x)[3], const int* host, int n);
  // A refinement created vertex `vertexKey` of `level` (full update).
  void shock(int level, std::uint64_t vertexKey) {
    std::int64_t& h = heat_[level][vertexKey];
    h = std::min(kMaxHeat, h + shock_);
  }

  // Incremental update. Tracking starts from the markers as they stand and the hosts
  // (host level and host vertex key per particle); kept counts the hot markers from here on.
  void beginTracking(const RefinedCells& cells, const int* host, const std::uint64_t* hostKey, int n,
                     KeptVertices& kept);
  // A particle arrived at (delta 1) or left (-1) a vertex below the start-off grid.
  void addParticle(int level, std::uint64_t vertexKey, std::int64_t delta);
  // shock(), tracked.
  void shockTracked(int level, std::uint64_t vertexKey, KeptVertices& kept);
  // Anneals the markers whose input changed or that have not converged yet.
  void annealChanged(const RefinedCells& cells, KeptVertices& kept);
  // Entries of the tracked tables, zeros included (they pile up: the caller rebuilds).
  std::size_t entries() const;

 private:
  int shock_, threshold_;
  std::vector<VertexCounters> heat_;      // per level, markers of vertices (0: none)
  std::vector<VertexCounters> heatNext_;  // scratch of anneal(), swapped with heat_

  // Tracking, per level and indexed by the marker's slot in heat_ (slots are stable, entries
  // are never erased while tracking): input s, whether listed in dirty_, and where the slots
  // of its parent vertices start in parentPool_ (kNoParents: not listed yet).
  static constexpr std::uint32_t kNoParents = ~std::uint32_t(0);
  int regularDepth_ = 0;  // the start-off depth while tracking (a change ends it)
  std::vector<std::vector<std::int64_t>> input_;
  std::vector<std::vector<char>> dirtyFlag_;
  std::vector<std::vector<std::uint32_t>> dirty_, annealing_;  // per level: slots in heat_
  std::vector<std::vector<std::uint32_t>> parentsAt_, parentPool_;

  std::size_t slot(int level, std::uint64_t vertexKey);
  std::uint32_t parentSlots(int level, std::size_t slot);
  void markDirty(int level, std::size_t slot);
  void set(int level, std::size_t slot, std::int64_t value, KeptVertices& kept);
};

}  // namespace spacetree
