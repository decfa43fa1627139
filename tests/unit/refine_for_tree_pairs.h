// Test helper: what fix spacetree does after its sweep for the reluctant grid: build the tree on
// the grid's levels, collect the pairs within the cut-off, hand them to refineForPairs (which
// refines and then coarsens). The grid's update() for these positions comes first.
#pragma once

#include <vector>

#include "moving_spheres.h"
#include "tree/AdaptiveGrid.h"
#include "tree/Spacetree.h"

inline void refineForTreePairs(spacetree::AdaptiveGrid& grid, spacetree::Spacetree& tree, const MovingSpheres& c) {
  grid.buildSpacetree(tree, c.pos(), c.r.data(), c.size(), c.size());
  std::vector<int> first, second;
  tree.forEachPairWithin([&](int i, int j, double) {
    first.push_back(i);
    second.push_back(j);
  });
  grid.refineForPairs(c.pos(), c.vel(), c.r.data(), c.size(), first.data(), second.data(), first.size());
}
