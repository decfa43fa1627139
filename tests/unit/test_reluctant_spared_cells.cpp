// Reluctant coarsening spares a cool cell that the refinement criterion would refine again at
// once. An approaching pair of small spheres far from everything else keeps the cells it was
// refined for (no refine/coarsen cycle while it approaches: its markers cool below the
// threshold after two updates, so without the rule the cells were removed and refined again
// every few steps); once the pair separates the cells go and the spheres lift.
#include <gtest/gtest.h>

#include <cstdint>

#include "moving_spheres.h"
#include "refine_for_tree_pairs.h"
#include "tree/AdaptiveGrid.h"
#include "tree/Spacetree.h"

using spacetree::AdaptiveGrid;
using spacetree::AdaptiveGridOptions;
using spacetree::GridType;
using spacetree::Spacetree;
using spacetree::SpacetreeOptions;

namespace {

constexpr double kEps = 0.0005;

// One list build as fix spacetree does it: update, tree on the grid, sweep, refineForPairs.
void listBuild(AdaptiveGrid& grid, Spacetree& tree, const MovingSpheres& c) {
  grid.update(c.pos(), c.vel(), c.r.data(), c.size());
  refineForTreePairs(grid, tree, c);
}

struct Phase {
  std::uint64_t refinements = 0, coarsenings = 0, spared = 0;
  bool pairOnAdmissibleLevels = true;  // at the end of every step
};

Phase run(AdaptiveGrid& grid, Spacetree& tree, MovingSpheres& c, int steps, double dt) {
  Phase p;
  for (int step = 0; step < steps; ++step) {
    c.move(dt);
    listBuild(grid, tree, c);
    p.refinements += grid.statistics().refinements;
    p.coarsenings += grid.statistics().coarsenings;
    p.spared += grid.statistics().spared;
    for (int i : {0, 1})
      if (grid.hostLevel(i) != grid.admissibleLevel(i)) p.pairOnAdmissibleLevels = false;
  }
  return p;
}

}  // namespace

TEST(ReluctantSparedCells, AnApproachingPairKeepsItsCellsAndASeparatingOneLosesThem) {
  for (bool incremental : {true, false}) {
    SCOPED_TRACE(incremental ? "incremental" : "full update");
    MovingSpheres c;
    // Two small spheres whose bounding spheres + eps overlap (gap 0.0005 < 2 eps), closing
    // slowly along x; a big sphere far away sets the coarse start-off grid.
    c.add({0.30, 0.31, 0.32}, {0.01, 0.0, 0.0}, 0.003);
    c.add({0.3065, 0.31, 0.32}, {-0.01, 0.0, 0.0}, 0.003);
    c.add({0.80, 0.80, 0.80}, {0.0, 0.0, 0.0}, 0.05);
    AdaptiveGridOptions options;
    options.type = GridType::Reluctant;
    options.epsilon = kEps;
    options.pairsFromCaller = true;
    options.incremental = incremental;
    AdaptiveGrid grid(options);
    Spacetree tree(SpacetreeOptions{kEps, spacetree::kMaxSpacetreeLevel});

    listBuild(grid, tree, c);  // refines for the pair: both drop to their admissible levels
    ASSERT_GT(grid.statistics().refinements, 0u);
    ASSERT_GT(grid.admissibleLevel(0), grid.statistics().regularDepth + 1);
    for (int i : {0, 1}) ASSERT_EQ(grid.hostLevel(i), grid.admissibleLevel(i));
    const std::uint64_t cells = grid.statistics().cells;

    // 40 steps closing in (the gap shrinks by 8e-4 of its 6.5e-3 centre distance): the cells
    // cool but stay, spared; nothing is removed or refined again.
    const Phase approach = run(grid, tree, c, 40, 1e-3);
    EXPECT_EQ(approach.coarsenings, 0u);
    EXPECT_EQ(approach.refinements, 0u);
    EXPECT_GT(approach.spared, 0u);
    EXPECT_TRUE(approach.pairOnAdmissibleLevels);
    EXPECT_EQ(grid.statistics().cells, cells);

    // Moving apart (still within reach of each other: not approaching): the cells are coarsened
    // within a few steps and the spheres lift to the start-off grid.
    c.v[0][0] = -0.01;
    c.v[1][0] = 0.01;
    const Phase separate = run(grid, tree, c, 10, 1e-3);
    EXPECT_GT(separate.coarsenings, 0u);
    EXPECT_EQ(separate.refinements, 0u);
    EXPECT_LT(grid.statistics().cells, cells);
    for (int i : {0, 1}) EXPECT_LT(grid.hostLevel(i), grid.admissibleLevel(i));
  }
}
