// The naive adaptive grid (paper §5.1): refine wherever a particle would drop to a finer level,
// coarsen by the analysed tree grammar with the host vertices as the hot ones. After an update
// every particle is hosted on its admissible level, on a non-hanging vertex that the
// coarsening keeps (so the coarsening never moves a particle).
//
// Incremental update: a particle whose admissible level and nearest vertex there are unchanged
// keeps its host without a single look-up, and its refinement needs nothing. Only the others
// are re-hosted and refined for, in index order, exactly as the full update treats them.
// Coarsening can only remove cells that lost a blocker: around vertices that stopped being
// kept, cells refined in this update, and parents of removed cells (cascading up). Kept
// vertices are counted (KeptVertices: particles hosted + kept children), so the tree grammar
// is updated along the changed paths instead of being re-derived from every particle.
// Interface: see RegularGridPolicy.h.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "tree/AdaptiveGridOptions.h"
#include "tree/GridCoarsening.h"
#include "tree/HeatMarkers.h"
#include "tree/HostedGrid.h"
#include "tree/KeptVertices.h"

namespace spacetree {

class AdaptiveGridPolicy {
 public:
  explicit AdaptiveGridPolicy(const AdaptiveGridOptions& options) : options_(options) {}

  int startOffDepth(int coarsestFit, int) const { return coarsestFit; }
  bool tracking() const { return tracking_; }
  bool updateIncrementally(HostedGrid& g, const double (*x)[3], const double (*v)[3], const double* radius, int n);
  void forgetIncrementalState() { tracking_ = false; }
  void newCube(std::size_t) {}
  void adapt(HostedGrid& g, const double (*x)[3], const double (*v)[3], const double* radius, int n);
  bool refineForPairs(HostedGrid&, const double (*)[3], const double (*)[3], const double*, int, const int*,
                      const int*, std::size_t) {
    return false;
  }
  HeatMarkers* heatMarkers() { return nullptr; }
  const HeatMarkers* heatMarkers() const { return nullptr; }

 private:
  AdaptiveGridOptions options_;
  GridCoarsening coarsening_;
  // Incremental state: host vertex key per particle, the kept-vertex counters, the cells
  // refined in this update and the particles whose host may have changed.
  bool tracking_ = false;
  std::vector<std::uint64_t> hostKey_;
  KeptVertices kept_;
  std::size_t keptEntries_ = 0;  // counter entries after the last reset
  std::vector<LevelCell> newRefined_;
  std::vector<int> moved_;

  bool refineCell(HostedGrid& g, int level, std::int64_t i, std::int64_t j, std::int64_t k);
  // Refines the 2^d cells around particle i's host vertex until it is hosted on its
  // admissible level.
  void dropByRefining(HostedGrid& g, const double (*x)[3], int i);
  void resetIncrementalState(HostedGrid& g, const double (*x)[3], int n);
};

}  // namespace spacetree
