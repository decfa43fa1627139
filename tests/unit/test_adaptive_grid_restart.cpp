// AdaptiveGrid::serialise / deserialise (restart of fix spacetree): a grid restored from its
// words must behave exactly as the original from then on (same leaf cells, host levels and
// statistics on every later update), for adaptive and reluctant grids with moving particles.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <random>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

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

using Scene = MovingSpheres;

// Small grains and a few big ones flying through them: the grid refines ahead of the big ones
// and coarsens behind them, so its state after a few steps is far from the start-off grid.
Scene scene(unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0), w(-1.0, 1.0);
  Scene s;
  for (int i = 0; i < 900; ++i) {
    const bool big = i % 300 == 0;
    s.x.push_back({u(rng), u(rng), u(rng)});
    s.v.push_back({w(rng) * (big ? 3.0 : 1.0), w(rng), w(rng)});
    s.r.push_back(big ? 0.04 : 0.004 * (1.0 + 0.5 * u(rng)));
  }
  return s;
}

using Cell = std::tuple<int, std::int64_t, std::int64_t, std::int64_t>;

std::vector<Cell> leafCells(const AdaptiveGrid& g) {
  std::vector<Cell> cells;
  g.forEachLeafCell([&](int l, std::int64_t i, std::int64_t j, std::int64_t k) { cells.emplace_back(l, i, j, k); });
  std::sort(cells.begin(), cells.end());
  return cells;
}

// One step as fix spacetree does it: update, sweep, report the pairs (reluctant).
void step(AdaptiveGrid& g, Spacetree& tree, const Scene& s) {
  g.update(s.pos(), s.vel(), s.r.data(), s.size());
  refineForTreePairs(g, tree, s);
}

void expectSameStatistics(const AdaptiveGrid& a, const AdaptiveGrid& b) {
  const auto &sa = a.statistics(), &sb = b.statistics();
  EXPECT_EQ(sa.refinements, sb.refinements);
  EXPECT_EQ(sa.coarsenings, sb.coarsenings);
  EXPECT_EQ(sa.cells, sb.cells);
  EXPECT_EQ(sa.deepestLevel, sb.deepestLevel);
  EXPECT_EQ(sa.regularDepth, sb.regularDepth);
  EXPECT_EQ(sa.geometryResets, sb.geometryResets);
  ASSERT_EQ(sa.levels.size(), sb.levels.size());
  for (std::size_t l = 0; l < sa.levels.size(); ++l) {
    EXPECT_EQ(sa.levels[l].cells, sb.levels[l].cells) << "level " << l;
    EXPECT_EQ(sa.levels[l].realParticles, sb.levels[l].realParticles) << "level " << l;
  }
}

AdaptiveGridOptions optionsFor(GridType type, bool pairsFromCaller) {
  AdaptiveGridOptions o;
  o.type = type;
  o.epsilon = 0.001;
  o.shock = 6;
  o.coarseningThreshold = 3;
  o.padding = 0.3;
  o.pairsFromCaller = pairsFromCaller;
  return o;
}

}  // namespace

TEST(AdaptiveGridRestart, RestoredGridContinuesExactlyAsTheOriginal) {
  const std::vector<std::pair<GridType, bool>> kinds = {
      {GridType::Adaptive, false}, {GridType::Reluctant, false}, {GridType::Reluctant, true}};
  for (const auto& kind : kinds) {
    SCOPED_TRACE(std::string(spacetree::gridTypeName(kind.first)) + (kind.second ? " (caller's pairs)" : ""));
    Scene s = scene(5);
    AdaptiveGrid original(optionsFor(kind.first, kind.second));
    Spacetree treeA(SpacetreeOptions{0.001}), treeB(SpacetreeOptions{0.001});
    for (int n = 0; n < 8; ++n) {
      step(original, treeA, s);
      s.move(0.004);
    }
    const std::vector<std::int64_t> words = original.serialise();
    AdaptiveGrid restored = AdaptiveGrid::deserialise(words.data(), words.size());
    EXPECT_EQ(restored.serialise(), words) << "round trip of the words";
    EXPECT_EQ(leafCells(restored), leafCells(original));
    EXPECT_EQ(restored.leafCellCount(), original.leafCellCount());
    EXPECT_EQ(restored.verticesPerLevel(), original.verticesPerLevel());
    EXPECT_EQ(restored.statistics().geometryResets, original.statistics().geometryResets);
    EXPECT_EQ(restored.statistics().cells, original.statistics().cells);
    EXPECT_EQ(restored.options().shock, 6);
    EXPECT_EQ(restored.options().padding, 0.3);

    // A grid started afresh on the same particles: the restored state must matter.
    AdaptiveGrid fresh(optionsFor(kind.first, kind.second));
    Spacetree treeF(SpacetreeOptions{0.001});
    bool freshDiffers = false;
    std::uint64_t refinements = 0, coarsenings = 0;
    for (int n = 0; n < 10; ++n) {
      SCOPED_TRACE("step " + std::to_string(n) + " after the restore");
      step(original, treeA, s);
      step(restored, treeB, s);
      step(fresh, treeF, s);
      EXPECT_EQ(restored.hostLevels(), original.hostLevels());
      EXPECT_EQ(leafCells(restored), leafCells(original));
      expectSameStatistics(restored, original);
      EXPECT_EQ(restored.serialise(), original.serialise());
      freshDiffers |= leafCells(fresh) != leafCells(original) ||
                      fresh.statistics().refinements != original.statistics().refinements ||
                      fresh.statistics().coarsenings != original.statistics().coarsenings;
      refinements += original.statistics().refinements;
      coarsenings += original.statistics().coarsenings;
      s.move(0.004);
    }
    EXPECT_GT(refinements, 0u) << "the scene must keep refining after the restore";
    EXPECT_GT(coarsenings, 0u) << "the scene must keep coarsening after the restore";
    EXPECT_TRUE(freshDiffers) << "a fresh grid behaves the same: the test would not see a lost state";
  }
}

TEST(AdaptiveGridRestart, RestoredGridIgnoresTheParticleOrder) {
  // After read_restart LIGGGHTS hands the particles over in another order: the restored grid
  // fed the permuted particles must have the same cells and statistics as the original.
  for (GridType type : {GridType::Adaptive, GridType::Reluctant}) {
    SCOPED_TRACE(spacetree::gridTypeName(type));
    Scene s = scene(9);
    AdaptiveGrid original(optionsFor(type, true));
    Spacetree treeA(SpacetreeOptions{0.001}), treeB(SpacetreeOptions{0.001});
    for (int n = 0; n < 6; ++n) {
      step(original, treeA, s);
      s.move(0.004);
    }
    const std::vector<std::int64_t> words = original.serialise();
    AdaptiveGrid restored = AdaptiveGrid::deserialise(words.data(), words.size());
    std::vector<int> perm(std::size_t(s.size()));
    for (int i = 0; i < s.size(); ++i) perm[std::size_t(i)] = i;
    std::shuffle(perm.begin(), perm.end(), std::mt19937(3));
    for (int n = 0; n < 6; ++n) {
      SCOPED_TRACE("step " + std::to_string(n) + " after the restore");
      Scene p;
      for (int i : perm) {
        p.x.push_back(s.x[std::size_t(i)]);
        p.v.push_back(s.v[std::size_t(i)]);
        p.r.push_back(s.r[std::size_t(i)]);
      }
      step(original, treeA, s);
      step(restored, treeB, p);
      EXPECT_EQ(leafCells(restored), leafCells(original));
      expectSameStatistics(restored, original);
      for (int k = 0; k < s.size(); ++k)
        ASSERT_EQ(restored.hostLevel(k), original.hostLevel(perm[std::size_t(k)])) << "particle " << k;
      s.move(0.004);
    }
  }
}

TEST(AdaptiveGridRestart, GridWithoutParticlesRoundTrips) {
  const AdaptiveGrid empty(optionsFor(GridType::Reluctant, true));
  const std::vector<std::int64_t> words = empty.serialise();
  const AdaptiveGrid restored = AdaptiveGrid::deserialise(words.data(), words.size());
  EXPECT_EQ(restored.serialise(), words);
  EXPECT_EQ(restored.leafCellCount(), 0u);
  EXPECT_EQ(AdaptiveGrid::serialisedOptions(words.data(), words.size()).type, GridType::Reluctant);
}

TEST(AdaptiveGridRestart, DamagedDataThrows) {
  Scene s = scene(2);
  AdaptiveGrid grid(optionsFor(GridType::Reluctant, false));
  grid.update(s.pos(), s.vel(), s.r.data(), s.size());
  const std::vector<std::int64_t> words = grid.serialise();
  ASSERT_NO_THROW(AdaptiveGrid::deserialise(words.data(), words.size()));
  auto bad = [&](std::vector<std::int64_t> w) {
    EXPECT_THROW(AdaptiveGrid::deserialise(w.data(), w.size()), std::invalid_argument);
  };
  bad({});
  bad(std::vector<std::int64_t>(words.begin(), words.end() - 1));  // truncated
  std::vector<std::int64_t> w = words;
  w[0] ^= 1;  // magic
  bad(w);
  w = words;
  w[1] = 99;  // version
  bad(w);
  w = words;
  w[2] = 7;  // grid type
  bad(w);
  w = words;
  w[6] = w[5];  // threshold = shock
  bad(w);
  w = words;
  w.push_back(0);  // trailing word
  bad(w);
}

TEST(AdaptiveGridRestart, RestoreUnderOtherOptions) {
  // fix spacetree restated with another shock: the stored cells are kept, the new shock steers
  // the next updates. Another type or halo, or a shallower maxlevel, cannot take the state.
  Scene s = scene(4);
  AdaptiveGrid grid(optionsFor(GridType::Reluctant, true));
  Spacetree tree(SpacetreeOptions{0.001});
  for (int n = 0; n < 5; ++n) {
    step(grid, tree, s);
    s.move(0.004);
  }
  const std::vector<std::int64_t> words = grid.serialise();
  AdaptiveGridOptions other = optionsFor(GridType::Reluctant, true);
  other.shock = 11;
  other.padding = 0.5;
  const AdaptiveGrid restored = AdaptiveGrid::deserialise(words.data(), words.size(), other);
  EXPECT_EQ(restored.options().shock, 11);
  EXPECT_EQ(restored.options().padding, 0.5);
  EXPECT_EQ(leafCells(restored), leafCells(grid));
  EXPECT_EQ(restored.statistics().geometryResets, grid.statistics().geometryResets);

  AdaptiveGridOptions wrongType = optionsFor(GridType::Adaptive, true);
  EXPECT_THROW(AdaptiveGrid::deserialise(words.data(), words.size(), wrongType), std::invalid_argument);
  AdaptiveGridOptions wrongHalo = optionsFor(GridType::Reluctant, true);
  wrongHalo.epsilon = 0.002;
  EXPECT_THROW(AdaptiveGrid::deserialise(words.data(), words.size(), wrongHalo), std::invalid_argument);
  AdaptiveGridOptions shallow = optionsFor(GridType::Reluctant, true);
  shallow.maxLevel = 1;
  ASSERT_GT(grid.geometry().depth, 1);
  EXPECT_THROW(AdaptiveGrid::deserialise(words.data(), words.size(), shallow), std::invalid_argument);
  AdaptiveGridOptions badPair = optionsFor(GridType::Reluctant, true);
  badPair.coarseningThreshold = badPair.shock;
  EXPECT_THROW(AdaptiveGrid::deserialise(words.data(), words.size(), badPair), std::invalid_argument);
}
