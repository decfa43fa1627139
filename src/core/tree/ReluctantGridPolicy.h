// The reluctant grid (paper §5.1): refine only for touching, approaching pairs (the criterion
// of ReluctantCriterion.h), coarsen aggressively wherever the heat markers cooled below the
// threshold, sparing cells the criterion would refine again at once (SpareCheck). Coarsening
// follows the refinement pass and uses its pairs: the grid's own search in update(), or the
// caller's sweep in refineForPairs (options.pairsFromCaller). Particles drop into new cells and
// lift out of removed ones at once (hosts re-derived).
//
// Incremental update (options.incremental), the change-driven form of the full one with the
// same result cell for cell, marker for marker, host for host: hosts re-derived only where a
// particle moved past its margin or read a changed cell (TrackedHosts), markers annealed only
// where their input changed (HeatMarkers), cells re-examined only around vertices that stopped
// being kept, cells refined since the last coarsening, parents of removed cells and cells
// spared last time (GridCoarsening). Interface: see RegularGridPolicy.h.
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "tree/AdaptiveGridOptions.h"
#include "tree/GridCoarsening.h"
#include "tree/HeatMarkers.h"
#include "tree/HostedGrid.h"
#include "tree/KeptVertices.h"
#include "tree/SpareCheck.h"
#include "tree/TrackedHosts.h"

namespace spacetree {

class ReluctantGridPolicy {
 public:
  explicit ReluctantGridPolicy(const AdaptiveGridOptions& options)
      : options_(options), heat_(options.shock, options.coarseningThreshold) {}

  int startOffDepth(int coarsestFit, int) const { return coarsestFit; }
  bool tracking() const { return tracking_; }
  bool updateIncrementally(HostedGrid& g, const double (*x)[3], const double (*v)[3], const double* radius, int n);
  void forgetIncrementalState() { tracking_ = false; }
  void newCube(std::size_t levels) { heat_.clear(levels); }
  void adapt(HostedGrid& g, const double (*x)[3], const double (*v)[3], const double* radius, int n);
  bool refineForPairs(HostedGrid& g, const double (*x)[3], const double (*v)[3], const double* radius, int n,
                      const int* first, const int* second, std::size_t count);
  HeatMarkers* heatMarkers() { return &heat_; }
  const HeatMarkers* heatMarkers() const { return &heat_; }

 private:
  AdaptiveGridOptions options_;
  HeatMarkers heat_;
  GridCoarsening coarsening_;
  SpareCheck spare_;
  std::vector<std::pair<int, int>> closePairs_;  // pairs of this pass that may refine
  // Incremental state: hot markers + kept children counted per vertex, the tracked hosts, the
  // cells refined and removed since they were last looked at.
  bool tracking_ = false;
  KeptVertices kept_;
  TrackedHosts hosts_;
  std::size_t trackedEntries_ = 0;  // table entries after the last reset
  std::vector<LevelCell> newRefined_, removedCells_;
  std::vector<int> newAdmissible_;

  std::size_t trackedEntries() const { return heat_.entries() + kept_.entries() + hosts_.entries(); }
  bool refineCell(HostedGrid& g, int level, std::int64_t i, std::int64_t j, std::int64_t k);
  // Close pairs of this step's hosts by the grid's own sweep (bounding spheres + eps, approaching).
  void searchClosePairs(HostedGrid& g, const double (*x)[3], const double (*v)[3], const double* radius, int n);
  void refineForClosePairs(HostedGrid& g, const double (*x)[3], const double* radius, int n);
  // The coarsening of a pass, with its pairs (first == nullptr: closePairs_), then the re-hosts.
  void coarsen(HostedGrid& g, const double (*x)[3], const double (*v)[3], const double* radius, int n,
               const int* first, const int* second, std::size_t count);
  void resetIncrementalState(HostedGrid& g, const double (*x)[3], const double* radius, int n);
};

}  // namespace spacetree
