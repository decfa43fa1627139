// Coarsening of the adaptive and reluctant grids by the analysed tree grammar (paper §5.1):
// the 3^d children of a refined cell are removed when none of them is refined and none of
// their non-hanging vertices is kept; a vertex is kept if it is hot (adaptive: hosts a
// particle; reluctant: its heat marker reaches the threshold) or one of its children is kept.
// Two forms with the same result: the full one derives the kept vertices of every level anew;
// the incremental one re-examines only cells that may have lost their last blocker (around
// vertices that stopped being kept, cells refined since the last coarsening, parents of
// removed cells, cells spared last time). The reluctant grid spares cool cells its refinement
// criterion would refine again at once (SpareCheck).
#pragma once

#include <cstdint>
#include <vector>

#include "tree/AdaptiveGridStatistics.h"
#include "tree/HeatMarkers.h"
#include "tree/KeptVertices.h"
#include "tree/RefinedCells.h"
#include "tree/SpareCheck.h"
#include "tree/VertexKeySet.h"

namespace spacetree {

class GridCoarsening {
 public:
  // Full, adaptive: hot vertices are the host vertices of the particles.
  void keepingHosts(RefinedCells& cells, const double (*x)[3], const int* host, int n, AdaptiveGridStatistics& stats);
  // Full, reluctant: hot vertices are those with hot markers; `spare` (nullable) may keep a
  // removable cell.
  void keepingHotMarkers(RefinedCells& cells, const HeatMarkers& heat, SpareCheck* spare,
                         AdaptiveGridStatistics& stats);
  // Incremental: re-examines the cells around the vertices `kept` lists as lost, the cells of
  // `refinedSince` and, with a spare check, the cells it spared last time. Removed cells are
  // appended to `removed` (nullable).
  void aroundLostVertices(RefinedCells& cells, const KeptVertices& kept, const std::vector<LevelCell>& refinedSince,
                          SpareCheck* spare, std::vector<LevelCell>* removed, AdaptiveGridStatistics& stats);

 private:
  // Scratch, kept between updates (no reallocation and page faults per update).
  std::vector<VertexKeySet> keep_;       // full: kept vertices per level
  VertexKeySet blocked_;                 // full: cells of one level that may not be removed
  std::vector<std::uint64_t> removals_;  // cells of one level to remove
  std::vector<VertexKeySet> candidates_; // incremental: cells per level to re-examine

  void removeUnblocked(RefinedCells& cells, SpareCheck* spare, AdaptiveGridStatistics& stats);
  // A refined child, or a kept non-hanging vertex of the children's patch (as in the full form).
  bool isBlocked(const RefinedCells& cells, const KeptVertices& kept, int level, std::int64_t i, std::int64_t j,
                 std::int64_t k) const;
};

}  // namespace spacetree
