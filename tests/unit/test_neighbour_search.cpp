// NeighbourSearch: one build (grid update, tree, sweep, refinement) must list exactly the pairs
// within r_i + r_j + skin, with the judge's verdicts, for every grid type, and drive the
// reluctant grid exactly as an explicit update / build / sweep / refineForPairs sequence does.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <stdexcept>
#include <utility>
#include <vector>

#include "moving_spheres.h"
#include "tree/AdaptiveGrid.h"
#include "tree/NeighbourSearch.h"

using spacetree::AdaptiveGrid;
using spacetree::AdaptiveGridOptions;
using spacetree::GridType;
using spacetree::NeighbourSearch;

namespace {

MovingSpheres cloud(unsigned seed, int n) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  MovingSpheres c;
  for (int i = 0; i < n; ++i)
    c.add({u(rng), u(rng), u(rng)}, {u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5}, 0.004 * std::pow(10.0, 1.5 * u(rng)));
  return c;
}

using PairSet = std::set<std::pair<int, int>>;

PairSet bruteForce(const MovingSpheres& c, double skin, int nActive) {
  PairSet pairs;
  for (int i = 0; i < c.size(); ++i)
    for (int j = i + 1; j < c.size(); ++j) {
      if (i >= nActive && j >= nActive) continue;
      double d2 = 0.0;
      for (int d = 0; d < 3; ++d) d2 += (c.x[i][d] - c.x[j][d]) * (c.x[i][d] - c.x[j][d]);
      const double cut = c.r[i] + c.r[j] + skin;
      if (d2 <= cut * cut) pairs.insert({i, j});
    }
  return pairs;
}

// The search's listed pairs as a set, checking order (first < second) and marks on the way.
PairSet listed(const NeighbourSearch::ListedPairs& pairs, const MovingSpheres& c, bool marksTouching) {
  PairSet out;
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const int i = pairs.first[k], j = pairs.second[k] < 0 ? ~pairs.second[k] : pairs.second[k];
    EXPECT_LT(i, j);
    EXPECT_TRUE(out.insert({i, j}).second) << "pair listed twice";
    if (marksTouching) {
      double d2 = 0.0;
      for (int d = 0; d < 3; ++d) d2 += (c.x[i][d] - c.x[j][d]) * (c.x[i][d] - c.x[j][d]);
      EXPECT_EQ(pairs.second[k] < 0, d2 < (c.r[i] + c.r[j]) * (c.r[i] + c.r[j]));
    }
  }
  return out;
}

}  // namespace

TEST(NeighbourSearch, ListsThePairsWithinTheSkinForEveryGrid) {
  const double skin = 0.01;
  for (int grid = 0; grid < 4; ++grid) {
    NeighbourSearch search;
    search.setSkin(skin);
    EXPECT_EQ(search.epsilon(), 0.5 * skin);
    if (grid > 0) {
      AdaptiveGridOptions o;
      o.type = grid == 1 ? GridType::Regular : grid == 2 ? GridType::Adaptive : GridType::Reluctant;
      search.useNewGrid(o);
      ASSERT_NE(search.grid(), nullptr);
      EXPECT_EQ(search.grid()->options().epsilon, 0.5 * skin);
      EXPECT_TRUE(search.grid()->options().pairsFromCaller);
    }
    MovingSpheres c = cloud(7 + grid, 600);
    const int nActive = 450;
    NeighbourSearch::ListedPairs pairs;
    for (int step = 0; step < 4; ++step) {
      auto touching = [&](int i, int j, double d2) {
        return d2 < (c.r[i] + c.r[j]) * (c.r[i] + c.r[j]) ? NeighbourSearch::Verdict::KeepMarked
                                                           : NeighbourSearch::Verdict::Keep;
      };
      search.findPairs(c.pos(), c.vel(), c.r.data(), c.size(), nActive, 0.0, touching, pairs);
      EXPECT_EQ(listed(pairs, c, true), bruteForce(c, skin, nActive)) << "grid " << grid << " step " << step;
      c.move(0.002);
    }
  }
}

TEST(NeighbourSearch, SkippedPairsAreNotListed) {
  NeighbourSearch search;
  search.setSkin(0.02);
  const MovingSpheres c = cloud(3, 400);
  NeighbourSearch::ListedPairs pairs;
  search.findPairs(c.pos(), nullptr, c.r.data(), c.size(), c.size(), 0.0,
                   [](int i, int j, double) {
                     return (i + j) % 2 ? NeighbourSearch::Verdict::Skip : NeighbourSearch::Verdict::Keep;
                   },
                   pairs);
  PairSet expected;
  for (const auto& p : bruteForce(c, 0.02, c.size()))
    if ((p.first + p.second) % 2 == 0) expected.insert(p);
  EXPECT_EQ(listed(pairs, c, false), expected);
  EXPECT_GT(expected.size(), 10u);
}

TEST(NeighbourSearch, AJudgeWithFourParametersGetsTheRadiusSumOfEachPair) {
  // The LIGGGHTS judge takes r_i + r_j from the search instead of its radius array: it must be
  // the sum of exactly those two radii (either order adds alike), for every grid, and the
  // listed pairs those of a three-parameter judge.
  for (int grid = 0; grid < 2; ++grid) {
    NeighbourSearch search;
    search.setSkin(0.01);
    if (grid) {
      AdaptiveGridOptions o;
      o.type = GridType::Reluctant;
      search.useNewGrid(o);
    }
    const MovingSpheres c = cloud(21 + grid, 500);
    NeighbourSearch::ListedPairs pairs;
    std::size_t judged = 0;
    search.findPairs(c.pos(), c.vel(), c.r.data(), c.size(), 400, 0.0,
                     [&](int i, int j, double, double radiusSum) {
                       ++judged;
                       EXPECT_EQ(radiusSum, c.r[i] + c.r[j]) << i << " " << j;
                       return NeighbourSearch::Verdict::Keep;
                     },
                     pairs);
    EXPECT_EQ(listed(pairs, c, false), bruteForce(c, 0.01, 400));
    EXPECT_EQ(judged, pairs.size());
    EXPECT_GT(judged, 100u);
  }
}

// The reluctant grid after findPairs is the grid of the explicit sequence a caller would write.
TEST(NeighbourSearch, DrivesTheReluctantGridAsTheExplicitSequence) {
  const double skin = 0.01;
  AdaptiveGridOptions o;
  o.type = GridType::Reluctant;
  NeighbourSearch search;
  search.setSkin(skin);
  search.useNewGrid(o);
  AdaptiveGrid reference(search.gridOptions(o));
  spacetree::Spacetree tree(spacetree::SpacetreeOptions{0.5 * skin});
  MovingSpheres c = cloud(11, 500);
  NeighbourSearch::ListedPairs pairs;
  std::uint64_t refinements = 0;
  for (int step = 0; step < 6; ++step) {
    search.findPairs(c.pos(), c.vel(), c.r.data(), c.size(), c.size(), 0.0,
                     [](int, int, double) { return NeighbourSearch::Verdict::KeepMarked; }, pairs);
    reference.update(c.pos(), c.vel(), c.r.data(), c.size());
    reference.buildSpacetree(tree, c.pos(), c.r.data(), c.size(), c.size());
    std::vector<int> first, second;
    tree.forEachPairWithin([&](int i, int j, double) {
      first.push_back(std::min(i, j));
      second.push_back(std::max(i, j));
    });
    reference.refineForPairs(c.pos(), c.vel(), c.r.data(), c.size(), first.data(), second.data(), first.size());
    EXPECT_EQ(search.grid()->serialise(), reference.serialise()) << "step " << step;
    EXPECT_EQ(search.grid()->hostLevels(), reference.hostLevels()) << "step " << step;
    refinements += search.grid()->statistics().refinements;
    c.move(0.003);
  }
  EXPECT_GT(refinements, 0u) << "the grid never refined: the test would not see a wrong refinement";
}

TEST(NeighbourSearch, GridFollowsTheSkinAndIsKeptOrRenewed) {
  NeighbourSearch search;
  search.setSkin(0.01);
  search.setMaxLevel(6);
  AdaptiveGridOptions o;
  o.type = GridType::Adaptive;
  o.maxLevel = 9;
  search.useNewGrid(o);
  const AdaptiveGrid* first = search.grid();
  EXPECT_EQ(first->options().maxLevel, 6) << "the grid's depth is capped to the search's";
  search.useGrid(o);
  EXPECT_EQ(search.grid(), first) << "same options: the grid is kept";
  search.useNewGrid(o);
  EXPECT_NE(search.grid(), nullptr);
  search.setSkin(0.02);
  EXPECT_EQ(search.grid()->options().epsilon, 0.01) << "a new skin gives a new grid with the new halo";
  EXPECT_EQ(search.grid()->options().type, GridType::Adaptive);
  // A restored grid must have this search's halo.
  AdaptiveGridOptions other = search.gridOptions(o);
  other.epsilon = 0.5;
  EXPECT_THROW(search.useGrid(AdaptiveGrid(other)), std::invalid_argument);
  search.useGrid(AdaptiveGrid(search.gridOptions(o)));
  search.dropGrid();
  EXPECT_EQ(search.grid(), nullptr);
  EXPECT_THROW(search.setSkin(-1.0), std::invalid_argument);
}
