// The spacetree must list exactly the pairs a brute-force O(N^2) search finds, once each.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <stdexcept>
#include <utility>
#include <vector>

#include "sphere_cloud.h"
#include "tree/Spacetree.h"

using spacetree::Spacetree;
using spacetree::SpacetreeOptions;

namespace {

using Particles = spacetree::testing::SphereCloud;

using spacetree::testing::bruteForce;
using spacetree::testing::isPair;
using spacetree::testing::PairSet;

// Runs the tree, fails the test on a duplicate, a self pair or a ghost-ghost pair, and
// returns the candidates that pass the exact cut-off.
PairSet treePairs(Spacetree& tree, const Particles& p, double eps, int nActive,
                  std::size_t* candidates = nullptr) {
  tree.build(p.positions(), p.r.data(), p.size(), nActive);
  PairSet seen, pairs;
  bool duplicate = false, self = false, inactive = false;
  tree.forEachCandidatePair([&](int i, int j) {
    if (i == j) self = true;
    if (i >= nActive && j >= nActive) inactive = true;
    const auto key = std::minmax(i, j);
    if (!seen.insert(key).second) duplicate = true;
    if (isPair(p, i, j, eps)) pairs.insert(key);
  });
  EXPECT_FALSE(duplicate) << "a pair was visited twice";
  EXPECT_FALSE(self) << "a particle was paired with itself";
  EXPECT_FALSE(inactive) << "a pair of two inactive particles was visited";
  if (candidates) *candidates = seen.size();
  return pairs;
}

Particles randomCloud(int n, double box, double rmin, double rmax, unsigned seed, bool logUniform) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Particles p;
  for (int i = 0; i < n; ++i) {
    const double t = u(rng);
    const double r = logUniform ? rmin * std::pow(rmax / rmin, t) : rmin + (rmax - rmin) * t;
    p.add(box * u(rng), box * u(rng), box * u(rng), r);
  }
  return p;
}

void expectExact(const Particles& p, double eps, int nActive, const char* what) {
  Spacetree tree(SpacetreeOptions{eps});
  const PairSet expected = bruteForce(p, eps, nActive);
  const PairSet found = treePairs(tree, p, eps, nActive);
  EXPECT_EQ(found, expected) << what << ": " << found.size() << " found, " << expected.size()
                             << " expected";
  EXPECT_GT(expected.size(), 0u) << what << ": test scene has no pairs";
}

}  // namespace

TEST(Spacetree, MonodisperseMatchesBruteForce) {
  const Particles p = randomCloud(3000, 1.0, 0.02, 0.02, 1, false);
  expectExact(p, 0.005, p.size(), "monodisperse");
}

TEST(Spacetree, BidisperseRatio10And100MatchBruteForce) {
  for (double ratio : {10.0, 100.0}) {
    Particles p = randomCloud(4000, 1.0, 0.004, 0.004, 2, false);
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int b = 0; b < 6; ++b) p.add(u(rng), u(rng), u(rng), 0.004 * ratio / 2);
    expectExact(p, 0.001, p.size(), ratio == 10.0 ? "ratio 10" : "ratio 100");
  }
}

TEST(Spacetree, ContinuousLogUniformDistributionMatchesBruteForce) {
  const Particles p = randomCloud(4000, 1.0, 0.0005, 0.1, 4, true);
  expectExact(p, 0.0007, p.size(), "log-uniform 1:200");
}

TEST(Spacetree, ClusteredSmallParticlesInBigDomain) {
  Particles p = randomCloud(3000, 0.05, 0.001, 0.003, 5, true);  // cluster in one corner
  p.add(0.9, 0.9, 0.9, 0.05);
  p.add(0.06, 0.02, 0.02, 0.03);  // big one touching the cluster
  expectExact(p, 0.0005, p.size(), "clustered");
}

TEST(Spacetree, GhostsArePairedWithOwnedButNotWithEachOther) {
  const Particles p = randomCloud(3000, 1.0, 0.003, 0.06, 6, true);
  expectExact(p, 0.002, 1000, "1000 owned of 3000");
}

TEST(Spacetree, PairExactlyAtTheCutOffIsFound) {
  // Values exactly representable: distance 0.75 = 0.25 + 0.25 + 2 * 0.125.
  Particles p;
  p.add(0.0, 0.0, 0.0, 0.25);
  p.add(0.75, 0.0, 0.0, 0.25);
  p.add(0.0, 0.75, 0.0, 0.25);
  p.add(0.0, 0.0, 0.75, 0.25);
  p.add(0.75, 0.75, 0.75, 0.25);  // sqrt(3)*0.75 away: not a pair
  expectExact(p, 0.125, p.size(), "touching at the cut-off");
  Spacetree tree(SpacetreeOptions{0.125});
  EXPECT_EQ(treePairs(tree, p, 0.125, p.size()).size(), 3u);
}

TEST(Spacetree, SmallParticlesInsideABigOneAreListed) {
  Particles p;
  p.add(0.5, 0.5, 0.5, 0.4);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.2, 0.8);
  for (int i = 0; i < 500; ++i) p.add(u(rng), u(rng), u(rng), 0.002);
  Spacetree tree(SpacetreeOptions{0.001});
  const PairSet found = treePairs(tree, p, 0.001, p.size());
  int withBig = 0;
  for (const auto& pr : found) withBig += pr.first == 0;
  int inside = 0;
  for (int i = 1; i < p.size(); ++i) inside += isPair(p, 0, i, 0.001);
  EXPECT_EQ(withBig, inside);
  EXPECT_GT(inside, 400);
}

TEST(Spacetree, CoincidentPointParticlesWithoutHalo) {
  Particles p;
  for (int i = 0; i < 5; ++i) p.add(0.3, 0.3, 0.3, 0.0);
  p.add(0.9, 0.3, 0.3, 0.0);
  Spacetree tree(SpacetreeOptions{0.0});
  EXPECT_EQ(treePairs(tree, p, 0.0, p.size()), bruteForce(p, 0.0, p.size()));
  EXPECT_EQ(bruteForce(p, 0.0, p.size()).size(), 10u);
}

TEST(Spacetree, EachParticleLivesOnTheFinestLevelItFits) {
  const Particles p = randomCloud(2000, 1.0, 0.0002, 0.2, 8, true);
  const double eps = 0.0001;
  Spacetree tree(SpacetreeOptions{eps});
  tree.build(p.positions(), p.r.data(), p.size(), p.size());
  std::vector<int> perLevel(tree.levelCount(), 0);
  for (int i = 0; i < p.size(); ++i) {
    const int l = tree.levelOf(i);
    const double need = 2.0 * (p.r[i] + eps);
    ASSERT_GE(tree.meshSize(l), need) << "particle " << i << " does not fit its level";
    if (l + 1 < tree.levelCount()) { EXPECT_LT(tree.meshSize(l + 1), need * (1 + 1e-8)); }
    ++perLevel[l];
  }
  for (int l = 0; l + 1 < tree.levelCount(); ++l)
    EXPECT_NEAR(tree.meshSize(l) / tree.meshSize(l + 1), 3.0, 1e-12);
  const auto& stats = tree.statistics();
  std::uint64_t total = 0;
  int populated = 0;
  for (int l = 0; l < tree.levelCount(); ++l) {
    EXPECT_EQ(stats.levels[l].realParticles, std::uint64_t(perLevel[l]));
    total += stats.levels[l].realParticles;
    populated += perLevel[l] > 0;
  }
  EXPECT_EQ(total, std::uint64_t(p.size()));
  EXPECT_GE(populated, 5) << "a 1:1000 distribution should spread over several levels";
}

TEST(Spacetree, VirtualLinksConnectLevelsAndKeepCandidatesLocal) {
  // Few big particles among many small: the sweep must stay far below N^2 candidates and
  // create virtual links on the small particles' level.
  Particles p = randomCloud(20000, 1.0, 0.003, 0.003, 9, false);
  std::mt19937_64 rng(10);
  std::uniform_real_distribution<double> u(0.1, 0.9);
  for (int b = 0; b < 10; ++b) p.add(u(rng), u(rng), u(rng), 0.06);
  Spacetree tree(SpacetreeOptions{0.0005});
  std::size_t candidates = 0;
  const PairSet found = treePairs(tree, p, 0.0005, p.size(), &candidates);
  EXPECT_EQ(found, bruteForce(p, 0.0005, p.size()));
  EXPECT_LT(candidates, 40u * std::size_t(p.size())) << "candidate count is not local";
  const int smallLevel = tree.levelOf(0), bigLevel = tree.levelOf(p.size() - 1);
  EXPECT_LT(bigLevel, smallLevel);
  EXPECT_GT(tree.statistics().levels[smallLevel].virtualLinks, 0u);
  EXPECT_EQ(tree.statistics().levels[bigLevel].virtualLinks, 0u);
}

TEST(Spacetree, DepthCapStaysExact) {
  const Particles p = randomCloud(3000, 1.0, 0.001, 0.05, 11, true);
  SpacetreeOptions options{0.001};
  options.maxLevel = 2;
  Spacetree tree(options);
  EXPECT_EQ(treePairs(tree, p, 0.001, p.size()), bruteForce(p, 0.001, p.size()));
  EXPECT_LE(tree.levelCount(), 3);
}

TEST(Spacetree, MovingParticlesStayExactOverRebuilds) {
  // Random walk with rebuilds: lift and drop between vertices and levels keep the set exact.
  Particles p = randomCloud(2000, 1.0, 0.002, 0.05, 12, true);
  std::mt19937_64 rng(13);
  std::normal_distribution<double> step(0.0, 0.01);
  Spacetree tree(SpacetreeOptions{0.002});
  for (int sweep = 0; sweep < 10; ++sweep) {
    for (auto& xi : p.x)
      for (double& c : xi) c += step(rng);
    for (double& ri : p.r) ri *= 1.0 + 0.05 * std::abs(step(rng));  // growing radii lift
    ASSERT_EQ(treePairs(tree, p, 0.002, p.size()), bruteForce(p, 0.002, p.size())) << "sweep " << sweep;
  }
}

TEST(Spacetree, RejectsNonFiniteInput) {
  Particles p;
  p.add(0.0, 0.0, 0.0, 0.1);
  p.add(std::nan(""), 0.0, 0.0, 0.1);
  Spacetree tree(SpacetreeOptions{0.01});
  EXPECT_THROW(tree.build(p.positions(), p.r.data(), p.size(), p.size()), std::invalid_argument);
  p.x[1][0] = 1.0;
  p.r[1] = -1.0;
  EXPECT_THROW(tree.build(p.positions(), p.r.data(), p.size(), p.size()), std::invalid_argument);
  EXPECT_THROW(Spacetree(SpacetreeOptions{-1.0}), std::invalid_argument);
}

TEST(Spacetree, EmptyAndSingleParticle) {
  Spacetree tree(SpacetreeOptions{0.1});
  Particles p;
  int calls = 0;
  tree.build(p.positions(), p.r.data(), 0, 0);
  tree.forEachCandidatePair([&](int, int) { ++calls; });
  p.add(1.0, 2.0, 3.0, 0.5);
  tree.build(p.positions(), p.r.data(), 1, 1);
  tree.forEachCandidatePair([&](int, int) { ++calls; });
  EXPECT_EQ(calls, 0);
  EXPECT_EQ(tree.statistics().levels[tree.levelOf(0)].realParticles, 1u);
}

TEST(Spacetree, PairsWithinMatchBruteForceAndAreASubsetOfCandidates) {
  const Particles p = randomCloud(4000, 1.0, 0.001, 0.05, 14, true);
  const double eps = 0.0015;
  Spacetree tree(SpacetreeOptions{eps});
  tree.build(p.positions(), p.r.data(), p.size(), p.size());
  PairSet within, exact;
  bool distanceRight = true;
  tree.forEachPairWithin([&](int i, int j, double d2) {
    within.insert(std::minmax(i, j));
    double expected = 0.0;
    for (int d = 0; d < 3; ++d) expected += (p.x[i][d] - p.x[j][d]) * (p.x[i][d] - p.x[j][d]);
    distanceRight = distanceRight && d2 == expected;
  });
  EXPECT_TRUE(distanceRight) << "the squared distance handed to the visitor is not bit-exact";
  for (const auto& pr : within)
    if (isPair(p, pr.first, pr.second, eps)) exact.insert(pr);
  EXPECT_EQ(exact, bruteForce(p, eps, p.size()));
  // the tolerance admits nothing measurably beyond the cut-off
  for (const auto& pr : within) {
    double d2 = 0.0;
    for (int d = 0; d < 3; ++d) d2 += std::pow(p.x[pr.first][d] - p.x[pr.second][d], 2);
    EXPECT_LE(std::sqrt(d2), (p.r[pr.first] + p.r[pr.second] + 2 * eps) * (1 + 1e-11));
  }
}

TEST(Spacetree, CrowdedVerticesArePrunedAlongXAndStayExact) {
  // All particles forced onto a coarse level: vertices hold dozens of particles and are
  // swept along x. Pairs at exactly the cut-off along x (the pruned axis), a few big spheres
  // (kept apart from the pruning), ghosts among them.
  const double eps = 0.001;
  Particles p;
  std::mt19937_64 rng(78);
  std::uniform_real_distribution<double> u(0.1, 0.9);
  for (int k = 0; k < 60; ++k) {  // active, listed first
    // The biggest particles, so the pruning bounds are tight. The first 30 pairs straddle a
    // boundary x = 0, 0.5 or 1 between two level-1 vertices (y, z < 0.5); the others lie
    // within one vertex (y, z > 0.5, x in (0.1, 0.4)).
    const bool straddles = k < 30;
    const double r1 = 0.016 - 0.0001 * (k % 30), r2 = r1;
    const double y = 0.5 * u(rng) + (straddles ? 0.0 : 0.4), z = 0.5 * u(rng) + (straddles ? 0.0 : 0.4);
    const double x = straddles ? 0.5 * (k % 3) - 0.5 * (r1 + r2 + 2.0 * eps) : 0.5 * u(rng);
    p.add(x, y, z, r1);
    p.add(x + (r1 + r2 + 2.0 * eps), y, z, r2);
  }
  for (int k = 0; k < 6; ++k) p.add(u(rng), u(rng), u(rng), 0.2);  // big ones: unsorted tails
  const Particles cloud = randomCloud(1500, 1.0, 0.004, 0.01, 77, true);
  for (int i = 0; i < cloud.size(); ++i) p.add(cloud.x[i][0], cloud.x[i][1], cloud.x[i][2], cloud.r[i]);
  const int nActive = p.size() - 150;
  spacetree::GridGeometry geometry;
  geometry.origin = {-0.25, -0.25, -0.25};
  geometry.rootSize = 1.5;
  geometry.depth = 4;
  const std::vector<int> levels(std::size_t(p.size()), 1);
  Spacetree tree(SpacetreeOptions{eps});
  tree.build(p.positions(), p.r.data(), p.size(), nActive, geometry, levels.data());
  PairSet candidates, within;
  tree.forEachCandidatePair([&](int i, int j) {
    if (isPair(p, i, j, eps)) candidates.insert(std::minmax(i, j));
  });
  const std::uint64_t tested = tree.statistics().candidatePairs;
  tree.forEachPairWithin([&](int i, int j, double) { within.insert(std::minmax(i, j)); });
  const PairSet expected = bruteForce(p, eps, nActive);
  EXPECT_EQ(candidates, expected);
  EXPECT_EQ(within, expected);
  EXPECT_GE(expected.size(), 30u);  // most of the touching pairs survive the round-off
  // Without pruning each particle would be tested against about 14 x 1620 / 64 = 350 others.
  EXPECT_LT(tested, std::uint64_t(p.size()) * 120);
}

TEST(Spacetree, FinestPopulatedMeshSizeIsTheLevelOfTheSmallestParticle) {
  Spacetree tree(SpacetreeOptions{0.001});
  EXPECT_EQ(tree.finestPopulatedMeshSize(), 0.0) << "no build: no cell a particle lives in";
  const Particles p = randomCloud(500, 1.0, 0.002, 0.2, 21, true);
  tree.build(p.positions(), p.r.data(), p.size(), p.size());
  const int smallest = int(std::min_element(p.r.begin(), p.r.end()) - p.r.begin());
  int finest = 0;
  for (int i = 0; i < p.size(); ++i) finest = std::max(finest, tree.levelOf(i));
  EXPECT_EQ(finest, tree.levelOf(smallest));
  EXPECT_GT(finest, 0) << "the scene must span several levels";
  EXPECT_EQ(tree.finestPopulatedMeshSize(), tree.meshSize(finest));
  EXPECT_GE(tree.finestPopulatedMeshSize(), 2.0 * (p.r[smallest] + 0.001));
  // without its smallest particles the tree's finest populated level is coarser
  Particles big;
  for (int i = 0; i < p.size(); ++i)
    if (p.r[i] > 0.05) big.add(p.x[i][0], p.x[i][1], p.x[i][2], p.r[i]);
  tree.build(big.positions(), big.r.data(), big.size(), big.size());
  EXPECT_GT(tree.finestPopulatedMeshSize(), 2.9 * tree.meshSize(finest));
}
