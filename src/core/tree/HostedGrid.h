// What every grid type works on: the refined cells, and per particle the finest level it fits
// (admissible) and the level it is hosted on, with the statistics of the last update. The grid
// types (RegularGridPolicy, AdaptiveGridPolicy, ReluctantGridPolicy) change the cells and keep
// the hosts in step; AdaptiveGrid owns one HostedGrid and hands it to its policy.
#pragma once

#include <cstdint>
#include <vector>

#include "tree/AdaptiveGridStatistics.h"
#include "tree/RefinedCells.h"
#include "tree/Spacetree.h"

namespace spacetree {

struct HostedGrid {
  explicit HostedGrid(const SpacetreeOptions& treeOptions) : tree(treeOptions) {}

  RefinedCells cells;
  std::vector<int> host, admissible;
  AdaptiveGridStatistics stats;
  // The tree's own mesh-size rule decides which levels a particle fits, so grid and tree agree
  // (requiredMeshSize); the reluctant grid also searches its close pairs with this tree.
  Spacetree tree;

  double requiredMeshSize(double radius) const { return tree.requiredMeshSize(radius); }
  // The finest level of the cube a particle of this radius fits.
  int admissibleFor(double radius) {
    if (radius != lastRadius_) {  // radii repeat (species): skip the level search
      lastRadius_ = radius;
      lastAdmissible_ = cells.finestFit(requiredMeshSize(radius));
    }
    return lastAdmissible_;
  }
  void cubeChanged() { lastRadius_ = -1.0; }  // admissible levels depend on the cube

  // Re-derives every host on the current cells. Same positions (within one update, and
  // refineForPairs after it) on unchanged cells: the hosts are already those.
  void rehostAll(const double (*x)[3], int n);
  // The particles moved, or their hosts were set otherwise than by rehostAll().
  void hostsChanged() { hostsCurrent_ = false; }

  // stats: cells and particles per level, from the cells and the hosts.
  void collectStatistics();

 private:
  bool hostsCurrent_ = false;
  std::uint64_t hostsVersion_ = 0;
  double lastRadius_ = -1.0;
  int lastAdmissible_ = 0;
};

}  // namespace spacetree
