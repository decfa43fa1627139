// Persistent dynamically adaptive spacetree grid (paper §5.1). It keeps the refined cells of
// every level from step to step and decides on which level each particle is hosted; the
// Spacetree sweep then runs on those levels (Spacetree::build with geometry() and
// hostLevels()). The sweep is exact for any host level at or coarser than the finest one a
// particle fits, so adaptivity only trades cells against comparisons, never correctness.
//
// Levels above regularDepth are refined everywhere and never stored: for Regular that is the
// finest level any particle fits (today's placement); for Adaptive and Reluctant it is the
// paper's start-off grid, the finest level the biggest particle fits. Below it refined cells
// are kept sparsely in one hash set per level.
//
// This class chooses the cube and runs the steps every grid type shares; the cells and the
// host derivation are RefinedCells, what differs per type is its policy (RegularGridPolicy,
// AdaptiveGridPolicy, ReluctantGridPolicy), serialisation is AdaptiveGridSerialisation.cpp.
#pragma once

#include <cstddef>
#include <cstdint>
#include <variant>
#include <vector>

#include "tree/AdaptiveGridOptions.h"
#include "tree/AdaptiveGridPolicy.h"
#include "tree/AdaptiveGridStatistics.h"
#include "tree/GridGeometry.h"
#include "tree/GridType.h"
#include "tree/HostedGrid.h"
#include "tree/RegularGridPolicy.h"
#include "tree/ReluctantGridPolicy.h"
#include "tree/Spacetree.h"

namespace spacetree {

class AdaptiveGrid {
 public:
  // Throws std::invalid_argument for inconsistent options (threshold >= shock, ...).
  explicit AdaptiveGrid(AdaptiveGridOptions options = {});

  // One step: re-host the moved particles, refine, coarsen, re-host (reluctant with
  // pairsFromCaller: re-host and anneal; refineForPairs refines and coarsens). Velocities drive the
  // reluctant approach test (v may be nullptr: every close pair then counts as approaching).
  // The cube is re-chosen (grid reset to the start-off grid) when a particle leaves it or no
  // longer fits the root cell.
  void update(const double (*x)[3], const double (*v)[3], const double* radius, int n);

  // Reluctant grid with pairsFromCaller: refines for the pairs (first[k], second[k]) that the
  // sweep on this step's tree found (bounding spheres + eps overlap), keeping those that
  // approach (v may be nullptr), then coarsens (cool cells, except those the criterion would
  // refine again at once for these pairs). This is what the paper triggers from inside the
  // traversal; particles drop into the new cells and lift out of the removed ones at once
  // (hosts re-derived). x must be the positions of the last update(). With pairsFromCaller,
  // update() does not coarsen: call this after every update().
  void refineForPairs(const double (*x)[3], const double (*v)[3], const double* radius, int n,
                      const int* first, const int* second, std::size_t count);

  // Builds `tree` on this grid's cube with this grid's host levels (tree options must use the
  // same epsilon). Particles must be those of the last update().
  void buildSpacetree(Spacetree& tree, const double (*x)[3], const double* radius, int n,
                      int nActive) const;

  const AdaptiveGridOptions& options() const { return options_; }
  const GridGeometry& geometry() const { return grid_.cells.geometry(); }
  const std::vector<int>& hostLevels() const { return grid_.host; }
  int hostLevel(int particle) const { return grid_.host[particle]; }
  int admissibleLevel(int particle) const { return grid_.admissible[particle]; }
  double meshSize(int level) const { return grid_.cells.meshSize(level); }
  // Whether the cell of `level` containing point p is refined.
  bool isRefinedAt(int level, const double p[3]) const { return grid_.cells.isRefinedAt(level, p); }
  const AdaptiveGridStatistics& statistics() const { return grid_.stats; }

  // Leaf cells (cells that exist and are not refined), for output: f(level, i, j, k) with the
  // cell's integer coordinates on its level (lower corner origin + (i, j, k) h(level)).
  template <class F>
  void forEachLeafCell(F&& f) const {
    grid_.cells.forEachLeafCell(f);
  }
  std::uint64_t leafCellCount() const { return grid_.cells.leafCellCount(); }
  // Non-hanging vertices per level (index = level, as statistics().levels; zeros before the
  // grid has a cube, e.g. an empty box before insertion); computed on request, not per update.
  std::vector<std::uint64_t> verticesPerLevel() const {
    std::vector<std::uint64_t> vertices = grid_.cells.verticesPerLevel();
    if (vertices.empty()) vertices.assign(statistics().levels.size(), 0);
    return vertices;
  }

  // Restart: everything the grid keeps between updates that changes later updates (options,
  // cube, refined cells per level, reluctant heat markers, the cumulative reset count) as a
  // flat word list; doubles are stored bit-exact, sets in ascending key order, so a restored
  // grid's next updates equal the original's. Per-particle hosts are not stored: they are
  // recomputed by update(), which must come before the next buildSpacetree().
  std::vector<std::int64_t> serialise() const;
  // Inverse of serialise(). Throws std::invalid_argument for data that serialise() cannot
  // have written (wrong magic/version, truncated, inconsistent sizes or levels).
  static AdaptiveGrid deserialise(const std::int64_t* words, std::size_t count);
  // The stored state under other options: shock, threshold, padding and pairsFromCaller only
  // steer later updates and may differ; the type and epsilon must equal the stored ones and
  // the stored depth must not exceed options.maxLevel (else std::invalid_argument).
  static AdaptiveGrid deserialise(const std::int64_t* words, std::size_t count,
                                  const AdaptiveGridOptions& options);
  // The options stored in serialised data (same checks on the header as deserialise()).
  static AdaptiveGridOptions serialisedOptions(const std::int64_t* words, std::size_t count);

 private:
  // What differs per grid type (the interface is described in RegularGridPolicy.h). A variant,
  // not a base class: grids are values (copied, returned by deserialise) and the dispatch is
  // one branch per call.
  using Policy = std::variant<RegularGridPolicy, AdaptiveGridPolicy, ReluctantGridPolicy>;
  static Policy policyFor(const AdaptiveGridOptions& options);

  AdaptiveGridOptions options_;
  HostedGrid grid_;
  Policy policy_;

  bool needsNewCube(const double (*x)[3], const double* radius, int n) const;
  GridGeometry chooseCube(const double (*x)[3], const double* radius, int n) const;
  template <class GridPolicy>
  void fullUpdate(GridPolicy& policy, const double (*x)[3], const double (*v)[3], const double* radius, int n);
};

}  // namespace spacetree
