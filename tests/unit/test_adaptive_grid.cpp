// The adaptive grid only moves particles between levels; the Spacetree sweep on its levels
// must still list exactly the brute-force pairs, whatever the grid refines or coarsens.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <set>
#include <stdexcept>
#include <utility>
#include <vector>

#include "moving_spheres.h"
#include "tree/AdaptiveGrid.h"
#include "tree/Spacetree.h"

using spacetree::AdaptiveGrid;
using spacetree::AdaptiveGridOptions;
using spacetree::GridType;
using spacetree::Spacetree;
using spacetree::SpacetreeOptions;

namespace {

using PairSet = std::set<std::pair<int, int>>;

using Scene = MovingSpheres;

bool isPair(const Scene& s, int i, int j, double eps) {
  double d2 = 0.0;
  for (int d = 0; d < 3; ++d) d2 += (s.x[i][d] - s.x[j][d]) * (s.x[i][d] - s.x[j][d]);
  const double cut = s.r[i] + s.r[j] + 2.0 * eps;
  return d2 <= cut * cut;
}

PairSet bruteForce(const Scene& s, double eps) {
  PairSet pairs;
  for (int i = 0; i < s.size(); ++i)
    for (int j = i + 1; j < s.size(); ++j)
      if (isPair(s, i, j, eps)) pairs.insert({i, j});
  return pairs;
}

PairSet gridPairs(const AdaptiveGrid& grid, Spacetree& tree, const Scene& s) {
  grid.buildSpacetree(tree, s.pos(), s.r.data(), s.size(), s.size());
  PairSet pairs;
  bool duplicate = false;
  tree.forEachPairWithin([&](int i, int j, double) {
    if (!pairs.insert(std::minmax(i, j)).second) duplicate = true;
  });
  EXPECT_FALSE(duplicate);
  return pairs;
}

// Small particles plus a few big ones (radius ratio `ratio`), random velocities.
Scene polydisperse(int nSmall, int nBig, double rSmall, double ratio, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0), w(-1.0, 1.0);
  Scene s;
  for (int i = 0; i < nSmall + nBig; ++i) {
    const double r = i < nSmall ? rSmall * (1.0 + 0.5 * u(rng)) : rSmall * ratio;
    s.add({u(rng), u(rng), u(rng)}, {w(rng), w(rng), w(rng)}, r);
  }
  return s;
}

void expectAdmissible(const AdaptiveGrid& grid, const Scene& s, double eps) {
  for (int i = 0; i < s.size(); ++i) {
    const int l = grid.hostLevel(i);
    ASSERT_GE(grid.meshSize(l), 2.0 * (s.r[i] + eps)) << "particle " << i << " on level " << l;
    ASSERT_LE(l, grid.admissibleLevel(i));
  }
}

}  // namespace

TEST(AdaptiveGrid, AllGridTypesMatchBruteForceWhileParticlesMove) {
  const double eps = 0.001;
  for (GridType type : {GridType::Regular, GridType::Adaptive, GridType::Reluctant})
    for (double ratio : {10.0, 100.0}) {
      SCOPED_TRACE(std::string(spacetree::gridTypeName(type)) + " ratio " + std::to_string(ratio));
      Scene s = polydisperse(1200, 4, 0.005, ratio / 1.5, 11);
      AdaptiveGridOptions options;
      options.type = type;
      options.epsilon = eps;
      AdaptiveGrid grid(options);
      Spacetree tree(SpacetreeOptions{eps});
      std::uint64_t refinements = 0, coarsenings = 0, pairsSeen = 0;
      for (int step = 0; step < 25; ++step) {
        grid.update(s.pos(), s.vel(), s.r.data(), s.size());
        expectAdmissible(grid, s, eps);
        const PairSet expected = bruteForce(s, eps);
        ASSERT_EQ(gridPairs(grid, tree, s), expected) << "step " << step;
        pairsSeen += expected.size();
        if (step > 0) {
          refinements += grid.statistics().refinements;
          coarsenings += grid.statistics().coarsenings;
        }
        s.move(0.004);
      }
      EXPECT_GT(pairsSeen, 100u);
      if (type != GridType::Regular) {
        EXPECT_GT(refinements, 0u) << "the grid should follow the particles";
        EXPECT_GT(coarsenings, 0u) << "the grid should coarsen behind the particles";
      }
    }
}

TEST(AdaptiveGrid, RegularHostsEveryParticleOnItsFinestAdmissibleLevel) {
  const Scene s = polydisperse(500, 5, 0.003, 30.0, 12);
  AdaptiveGridOptions options;
  options.type = GridType::Regular;
  AdaptiveGrid grid(options);
  grid.update(s.pos(), s.vel(), s.r.data(), s.size());
  for (int i = 0; i < s.size(); ++i) ASSERT_EQ(grid.hostLevel(i), grid.admissibleLevel(i));
  const auto& st = grid.statistics();
  EXPECT_EQ(st.refinements + st.coarsenings, 0u);
  const std::uint64_t perAxis = std::uint64_t(std::llround(std::pow(3.0, st.regularDepth)));
  EXPECT_EQ(st.levels[st.regularDepth].cells, perAxis * perAxis * perAxis);
}

TEST(AdaptiveGrid, AdaptiveEndsWithParticlesOnTheirAdmissibleLevels) {
  const double eps = 0.0005;
  Scene s = polydisperse(300, 3, 0.002, 100.0, 13);
  AdaptiveGridOptions options;
  options.epsilon = eps;
  AdaptiveGrid grid(options);
  for (int sweep = 0; sweep < 3; ++sweep) grid.update(s.pos(), s.vel(), s.r.data(), s.size());
  for (int i = 0; i < s.size(); ++i) EXPECT_EQ(grid.hostLevel(i), grid.admissibleLevel(i)) << i;
  // Standing still, the grid is in equilibrium.
  EXPECT_EQ(grid.statistics().refinements, 0u);
  EXPECT_EQ(grid.statistics().coarsenings, 0u);
  std::uint64_t real = 0;
  for (const auto& level : grid.statistics().levels) real += level.realParticles;
  EXPECT_EQ(real, std::uint64_t(s.size()));
}

TEST(AdaptiveGrid, ReluctantUsesFewerCellsAndStillFindsTheImpact) {
  // Paper §7.1: two spheres approaching along the diagonal of the unit cube.
  auto scene = [] {
    Scene s;
    s.add({0.2, 0.2, 0.2}, {0.1, 0.1, 0.1}, 0.01);
    s.add({0.8, 0.8, 0.8}, {-0.1, -0.1, -0.1}, 0.1);
    return s;
  };
  const double dt = 0.01;
  std::uint64_t cells[2] = {0, 0};
  int contactStep[2] = {-1, -1};
  int smallLevelBeforeContact[2] = {0, 0}, smallLevelAfterContact[2] = {0, 0};
  for (int g = 0; g < 2; ++g) {
    AdaptiveGridOptions options;
    options.type = g == 0 ? GridType::Adaptive : GridType::Reluctant;
    AdaptiveGrid grid(options);
    Spacetree tree;
    Scene s = scene();
    for (int step = 0; step < 300; ++step) {
      grid.update(s.pos(), s.vel(), s.r.data(), s.size());
      expectAdmissible(grid, s, 0.0);
      const PairSet found = gridPairs(grid, tree, s);
      ASSERT_EQ(found, bruteForce(s, 0.0)) << "step " << step;
      if (!found.empty() && contactStep[g] < 0) contactStep[g] = step;
      cells[g] += grid.statistics().cells;
      int& deepest = contactStep[g] < 0 ? smallLevelBeforeContact[g] : smallLevelAfterContact[g];
      deepest = std::max(deepest, grid.hostLevel(0));
      s.move(dt);
    }
  }
  EXPECT_GT(contactStep[0], 0);
  EXPECT_EQ(contactStep[0], contactStep[1]) << "both grids must see the impact at once";
  EXPECT_LT(cells[1], cells[0]) << "reluctant should traverse fewer cells over the run";
  // Adaptive drops the small sphere at once; reluctant keeps it on the start-off grid until
  // the approaching spheres touch, then refines so that it drops.
  EXPECT_GT(smallLevelBeforeContact[0], smallLevelBeforeContact[1]);
  EXPECT_GT(smallLevelAfterContact[1], smallLevelBeforeContact[1]);
}

TEST(AdaptiveGrid, CoarsensOnceParticlesLeaveARegion) {
  for (GridType type : {GridType::Adaptive, GridType::Reluctant}) {
    SCOPED_TRACE(spacetree::gridTypeName(type));
    // A cloud of small particles drifting across the box, a big still one fixes the cube.
    Scene s;
    std::mt19937_64 rng(14);
    std::uniform_real_distribution<double> u(0.0, 0.08), w(-0.3, 0.3);
    for (int i = 0; i < 200; ++i)  // jitter: the reluctant grid refines only for approaching pairs
      s.add({0.1 + u(rng), 0.1 + u(rng), 0.1 + u(rng)}, {0.6 + w(rng), 0.6 + w(rng), 0.6 + w(rng)}, 0.004);
    s.add({0.0, 0.0, 0.0}, {0, 0, 0}, 0.05);
    s.add({1.0, 1.0, 1.0}, {0, 0, 0}, 0.05);
    AdaptiveGridOptions options;
    options.type = type;
    AdaptiveGrid grid(options);
    Spacetree tree;
    const double start[3] = {0.14, 0.14, 0.14};
    std::uint64_t coarsenings = 0;
    bool refinedAtStart = false;
    for (int step = 0; step < 100; ++step) {
      grid.update(s.pos(), s.vel(), s.r.data(), s.size());
      if (step < 3)
        for (int l = grid.statistics().regularDepth; l < grid.geometry().depth; ++l)
          refinedAtStart |= grid.isRefinedAt(l, start);
      coarsenings += grid.statistics().coarsenings;
      ASSERT_EQ(gridPairs(grid, tree, s), bruteForce(s, 0.0)) << "step " << step;
      s.move(0.01);
    }
    if (type == GridType::Adaptive) { EXPECT_TRUE(refinedAtStart); }
    EXPECT_GT(coarsenings, 0u);
    EXPECT_EQ(grid.statistics().geometryResets, 1u) << "coarsened, not reset";
    for (int l = grid.statistics().regularDepth; l < grid.geometry().depth; ++l)
      EXPECT_FALSE(grid.isRefinedAt(l, start)) << "level " << l << " still refined where the cloud was";
  }
}

TEST(AdaptiveGrid, EmptyGridReportsLevelZeroWithoutVertices) {
  // Before any particle (an empty box at setup, before insertion) and after an update without
  // particles: per-level counts exist for every level the statistics list.
  for (GridType type : {GridType::Regular, GridType::Adaptive, GridType::Reluctant}) {
    AdaptiveGridOptions options;
    options.type = type;
    AdaptiveGrid grid(options);
    for (int pass = 0; pass < 2; ++pass) {
      const std::vector<std::uint64_t> vertices = grid.verticesPerLevel();
      ASSERT_EQ(vertices.size(), grid.statistics().levels.size());
      for (std::uint64_t v : vertices) EXPECT_EQ(v, 0u);
      EXPECT_EQ(grid.leafCellCount(), 0u);
      grid.update(nullptr, nullptr, nullptr, 0);
    }
  }
}

TEST(AdaptiveGrid, BadOptionsThrow) {
  AdaptiveGridOptions options;
  options.shock = 4;
  options.coarseningThreshold = 4;
  EXPECT_THROW(AdaptiveGrid{options}, std::invalid_argument);
  options.coarseningThreshold = 5;
  EXPECT_THROW(AdaptiveGrid{options}, std::invalid_argument);
  options = AdaptiveGridOptions{};
  options.shock = 0;
  options.coarseningThreshold = -1;
  EXPECT_THROW(AdaptiveGrid{options}, std::invalid_argument);
  EXPECT_NO_THROW(AdaptiveGrid{AdaptiveGridOptions{}});
  EXPECT_THROW(spacetree::parseGridType("bogus"), std::invalid_argument);
  EXPECT_EQ(spacetree::parseGridType("reluctant"), GridType::Reluctant);
}

TEST(AdaptiveGrid, SpacetreeOnAGivenCubeClampsHostLevelsAndStaysExact) {
  const double eps = 0.001;
  const Scene s = polydisperse(800, 4, 0.004, 20.0, 15);
  spacetree::GridGeometry geometry;
  geometry.origin = {-0.5, -0.5, -0.5};
  geometry.rootSize = 2.0;
  geometry.depth = 6;
  Spacetree tree(SpacetreeOptions{eps});
  for (int requested : {0, 2, 6}) {
    SCOPED_TRACE(requested);
    const std::vector<int> levels(std::size_t(s.size()), requested);
    tree.build(s.pos(), s.r.data(), s.size(), s.size(), geometry, levels.data());
    PairSet found;
    tree.forEachPairWithin([&](int i, int j, double) { found.insert(std::minmax(i, j)); });
    EXPECT_EQ(found, bruteForce(s, eps));
    for (int i = 0; i < s.size(); ++i) {
      ASSERT_GE(tree.meshSize(tree.levelOf(i)), 2.0 * (s.r[i] + eps));
      ASSERT_LE(tree.levelOf(i), requested);
    }
  }
  geometry.origin = {0.5, 0.5, 0.5};  // cube misses most particles
  EXPECT_THROW(tree.build(s.pos(), s.r.data(), s.size(), s.size(), geometry, nullptr), std::invalid_argument);
}

TEST(AdaptiveGrid, LeafCellsTileTheCubeAndHoldEveryParticleAtItsHostLevelOrFiner) {
  // The leaves of a valid tree partition the root cube: their volumes add up to it, none
  // overlaps another, and the leaf containing a particle is never coarser than its host level.
  for (GridType type : {GridType::Regular, GridType::Adaptive, GridType::Reluctant}) {
    SCOPED_TRACE(spacetree::gridTypeName(type));
    Scene s = polydisperse(400, 3, 0.012, 25.0, 16);
    AdaptiveGridOptions options;
    options.type = type;
    options.epsilon = 0.0005;
    AdaptiveGrid grid(options);
    for (int step = 0; step < 6; ++step) {
      grid.update(s.pos(), s.vel(), s.r.data(), s.size());
      s.move(0.01);
    }
    grid.update(s.pos(), s.vel(), s.r.data(), s.size());
    const double root = grid.geometry().rootSize;
    double volume = 0.0;
    std::uint64_t leaves = 0;
    std::set<std::array<std::int64_t, 4>> seen;
    grid.forEachLeafCell([&](int level, std::int64_t i, std::int64_t j, std::int64_t k) {
      const double h = grid.meshSize(level);
      volume += h * h * h;
      ++leaves;
      EXPECT_TRUE(seen.insert({level, i, j, k}).second) << "leaf listed twice";
    });
    EXPECT_EQ(leaves, grid.leafCellCount());
    EXPECT_NEAR(volume, root * root * root, 1e-9 * root * root * root);
    // Each particle centre lies in exactly one leaf (one level of its chain of containing
    // cells), never above its host level: the host descends only through refined cells.
    for (int p = 0; p < s.size(); ++p) {
      int leafLevel = -1, hits = 0;
      for (int l = 0; l <= grid.geometry().depth; ++l) {
        const double h = grid.meshSize(l);
        std::array<std::int64_t, 4> cell{l, 0, 0, 0};
        for (int d = 0; d < 3; ++d)
          cell[d + 1] = std::int64_t(std::floor((s.x[p][d] - grid.geometry().origin[d]) / h));
        if (seen.count(cell)) {
          leafLevel = l;
          ++hits;
        }
      }
      ASSERT_EQ(hits, 1) << "particle " << p << " is in " << hits << " leaves";
      EXPECT_GE(leafLevel, grid.hostLevel(p)) << "particle " << p;
    }
    if (type != GridType::Regular) {
      EXPECT_GT(grid.statistics().deepestLevel, grid.statistics().regularDepth);
    }
  }
}

TEST(AdaptiveGrid, ReluctantFedByTheCallersSweepStaysExactAndAdapts) {
  // pairsFromCaller: no second sweep inside update(); the pairs of the step's own sweep drive
  // the refinement for the next step. Lists must stay exact; the grid must still refine for
  // approaching pairs and coarsen behind them.
  const double eps = 0.001;
  Scene s = polydisperse(1200, 4, 0.005, 10.0, 17);
  AdaptiveGridOptions options;
  options.type = GridType::Reluctant;
  options.epsilon = eps;
  options.pairsFromCaller = true;
  AdaptiveGrid grid(options);
  Spacetree tree(SpacetreeOptions{eps});
  std::uint64_t refinements = 0, coarsenings = 0;
  int deepestSeen = 0;
  for (int step = 0; step < 25; ++step) {
    grid.update(s.pos(), s.vel(), s.r.data(), s.size());
    expectAdmissible(grid, s, eps);
    const PairSet found = gridPairs(grid, tree, s);
    ASSERT_EQ(found, bruteForce(s, eps)) << "step " << step;
    std::vector<int> first, second;
    for (const auto& p : found) {
      first.push_back(p.first);
      second.push_back(p.second);
    }
    grid.refineForPairs(s.pos(), s.vel(), s.r.data(), s.size(), first.data(), second.data(), first.size());
    refinements += grid.statistics().refinements;
    if (step > 0) coarsenings += grid.statistics().coarsenings;
    deepestSeen = std::max(deepestSeen, grid.statistics().deepestLevel);
    s.move(0.004);
  }
  EXPECT_GT(refinements, 0u);
  EXPECT_GT(coarsenings, 0u);
  EXPECT_GT(deepestSeen, grid.statistics().regularDepth) << "approaching pairs must drop";
}

TEST(AdaptiveGrid, AdaptiveCoarseningNeverMovesAParticle) {
  // update() skips the re-host after adaptive coarsening: the host levels it reports must be
  // what a fresh re-host on the coarsened grid gives. A second update with the particles
  // standing still re-hosts from scratch and must agree, level for level.
  const double eps = 0.0005;
  Scene s = polydisperse(600, 3, 0.003, 40.0, 18);
  AdaptiveGridOptions options;
  options.epsilon = eps;
  AdaptiveGrid grid(options);
  std::uint64_t coarsenings = 0;
  for (int step = 0; step < 12; ++step) {
    grid.update(s.pos(), s.vel(), s.r.data(), s.size());
    coarsenings += step > 0 ? grid.statistics().coarsenings : 0;
    const std::vector<int> hosts = grid.hostLevels();
    AdaptiveGrid copy = grid;
    copy.update(s.pos(), s.vel(), s.r.data(), s.size());
    ASSERT_EQ(copy.hostLevels(), hosts) << "step " << step;
    s.move(0.01);
  }
  EXPECT_GT(coarsenings, 0u);
}

namespace {

// Leaf cells of every level, sorted (a grid is its set of leaves).
std::vector<std::array<std::int64_t, 4>> leafCells(const AdaptiveGrid& grid) {
  std::vector<std::array<std::int64_t, 4>> cells;
  grid.forEachLeafCell([&](int l, std::int64_t i, std::int64_t j, std::int64_t k) { cells.push_back({l, i, j, k}); });
  std::sort(cells.begin(), cells.end());
  return cells;
}

}  // namespace

TEST(AdaptiveGrid, IncrementalAdaptiveUpdateEqualsTheFullUpdateOverManyRandomSteps) {
  // The incremental update re-hosts only moved particles and coarsens only around the
  // vertices they left; it must end each step with the grid (leaf cells), host levels and
  // refinement / coarsening counts of the full update, and the sweep must stay exact.
  const double eps = 0.0004;
  for (unsigned seed : {3u, 11u, 29u}) {
    Scene s = polydisperse(400, 3, 0.004, 12.0, seed);
    std::mt19937_64 rng(seed + 100);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    AdaptiveGridOptions options;
    options.epsilon = eps;
    AdaptiveGrid incremental(options);
    options.incremental = false;
    AdaptiveGrid full(options);
    Spacetree tree(SpacetreeOptions{eps, spacetree::kMaxSpacetreeLevel});
    int incrementalSteps = 0;
    std::uint64_t rehosted = 0, coarsenings = 0;
    for (int step = 0; step < 50; ++step) {
      incremental.update(s.pos(), s.vel(), s.r.data(), s.size());
      full.update(s.pos(), s.vel(), s.r.data(), s.size());
      ASSERT_EQ(incremental.hostLevels(), full.hostLevels()) << "seed " << seed << " step " << step;
      ASSERT_EQ(leafCells(incremental), leafCells(full)) << "seed " << seed << " step " << step;
      ASSERT_EQ(incremental.statistics().refinements, full.statistics().refinements) << "step " << step;
      ASSERT_EQ(incremental.statistics().coarsenings, full.statistics().coarsenings) << "step " << step;
      ASSERT_EQ(incremental.statistics().cells, full.statistics().cells);
      if (step % 10 == 0) {
        ASSERT_EQ(gridPairs(incremental, tree, s), bruteForce(s, eps)) << "step " << step;
      }
      if (incremental.statistics().incremental) {
        ++incrementalSteps;
        rehosted += incremental.statistics().rehosted;
        coarsenings += incremental.statistics().coarsenings;
      }
      // Small steps (a few particles change vertex), now and then a jump; one particle in
      // fifty changes its radius every 15 steps (admissible level changes).
      s.move(step % 7 == 3 ? 0.02 : 0.002);
      for (int i = 0; i < s.size(); ++i)
        for (int d = 0; d < 3; ++d) s.x[i][d] = std::clamp(s.x[i][d], 0.0, 1.0);
      if (step % 15 == 14)
        for (int i = 0; i < 400; i += 50) s.r[i] = 0.004 * (1.0 + 3.0 * u(rng));
    }
    EXPECT_GT(incrementalSteps, 30) << "seed " << seed;
    EXPECT_LT(rehosted, std::uint64_t(incrementalSteps) * s.size());  // not everything re-hosted
    EXPECT_GT(coarsenings, 0u);                                     // the incremental coarsening ran
  }
}
