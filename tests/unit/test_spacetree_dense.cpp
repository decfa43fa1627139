// The dense one-level path of the spacetree (DenseLevel): packs of one size that fill their box
// must give exactly the brute-force pairs, and exactly the general path's candidates, distances
// and visiting order; packs that miss the density or crowding test, or hold two levels, must
// take the general path.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <tuple>
#include <utility>
#include <vector>

#include "sphere_cloud.h"
#include "tree/Spacetree.h"

using spacetree::GridGeometry;
using spacetree::Spacetree;
using spacetree::SpacetreeOptions;
using Particles = spacetree::testing::SphereCloud;

namespace {

using spacetree::testing::bruteForce;
using spacetree::testing::isPair;
using spacetree::testing::PairSet;

// Spheres of radius r on an nx x ny x nz lattice of spacing s, each coordinate jittered by up to
// +-jitter, listed in lattice order (k fastest).
Particles lattice(int nx, int ny, int nz, double s, double r, double jitter, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-jitter, jitter);
  Particles p;
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j)
      for (int k = 0; k < nz; ++k) p.add(i * s + u(rng), j * s + u(rng), k * s + u(rng), r);
  return p;
}

Particles shuffled(const Particles& p, unsigned seed) {
  std::vector<int> order(std::size_t(p.size()));
  for (int i = 0; i < p.size(); ++i) order[std::size_t(i)] = i;
  std::shuffle(order.begin(), order.end(), std::mt19937_64(seed));
  Particles q;
  for (int i : order) q.add(p.x[i][0], p.x[i][1], p.x[i][2], p.r[i]);
  return q;
}

// Builds the tree on p, checks which path it took, and compares both sweeps with brute force:
// the candidates once each, never a self or ghost-ghost pair; the pairs within the cut-off
// exactly the brute-force ones, with their exact squared distance and radius sum.
void expectExact(const Particles& p, double eps, int nActive, bool dense, const char* what) {
  Spacetree tree(SpacetreeOptions{eps});
  tree.build(p.positions(), p.r.data(), p.size(), nActive);
  EXPECT_EQ(tree.usesDenseLevel(), dense) << what;
  const PairSet expected = bruteForce(p, eps, nActive);
  EXPECT_GT(expected.size(), 0u) << what;

  PairSet seen, candidatesWithin;
  bool duplicate = false, self = false, ghosts = false;
  tree.forEachCandidatePair([&](int i, int j) {
    self = self || i == j;
    ghosts = ghosts || (i >= nActive && j >= nActive);
    duplicate = duplicate || !seen.insert(std::minmax(i, j)).second;
    if (isPair(p, i, j, eps)) candidatesWithin.insert(std::minmax(i, j));
  });
  EXPECT_FALSE(duplicate) << what;
  EXPECT_FALSE(self) << what;
  EXPECT_FALSE(ghosts) << what;
  // the counter also holds the ghost-ghost candidates the sweep tests and drops
  if (nActive == p.size())
    EXPECT_EQ(tree.statistics().candidatePairs, seen.size()) << what;
  else
    EXPECT_GE(tree.statistics().candidatePairs, seen.size()) << what;
  EXPECT_EQ(candidatesWithin, expected) << what;

  PairSet within;
  bool exactValues = true;
  tree.forEachPairWithin([&](int i, int j, double d2, double radiusSum) {
    within.insert(std::minmax(i, j));
    double e2 = 0.0;
    for (int d = 0; d < 3; ++d) e2 += (p.x[i][d] - p.x[j][d]) * (p.x[i][d] - p.x[j][d]);
    exactValues = exactValues && d2 == e2 && radiusSum == p.r[i] + p.r[j];
  });
  EXPECT_TRUE(exactValues) << what;
  EXPECT_EQ(within, expected) << what;
}

// The sequence forEachPairWithin hands out: the same on both paths, bit for bit.
using Visit = std::tuple<int, int, double, double>;
std::vector<Visit> visits(Spacetree& tree) {
  std::vector<Visit> out;
  tree.forEachPairWithin([&](int i, int j, double d2, double radiusSum) { out.emplace_back(i, j, d2, radiusSum); });
  return out;
}

}  // namespace

TEST(SpacetreeDense, LatticePackMatchesBruteForce) {
  // One sphere per vertex (spacing = the mesh size 2 (r + eps)): about half the lattice
  // neighbours are within the cut-off, the others just beyond it.
  const Particles p = lattice(14, 13, 12, 1.1, 0.5, 0.04, 1);
  expectExact(p, 0.05, p.size(), true, "lattice");
}

TEST(SpacetreeDense, ShuffledOrderAndGhostsMatchBruteForce) {
  // Atoms in no spatial order (as exchanges leave them), the last 40 % inactive: ghosts spread
  // over the whole pack, and cells holding only ghosts next to cells with owned ones.
  const Particles p = shuffled(lattice(12, 12, 12, 1.1, 0.5, 0.04, 2), 3);
  expectExact(p, 0.05, p.size(), true, "shuffled");
  expectExact(p, 0.05, p.size() * 6 / 10, true, "shuffled with ghosts");
  expectExact(p, 0.05, 10, true, "ten owned among ghosts");
}

TEST(SpacetreeDense, SeveralParticlesPerVertexAndRandomPacks) {
  // One to seven small spheres per lattice site (mesh 1.1 for r = 0.25 and eps = 0.3), and a
  // random pack at about 0.7 particles per vertex: runs longer than the short-run slots, many
  // boundary cells.
  const Particles sites = lattice(12, 10, 9, 1.1, 0.25, 0.05, 4);
  Particles several;
  for (int s = 0; s < sites.size(); ++s)
    for (int t = 0; t < 1 + s % 7; ++t)
      several.add(sites.x[s][0] + 0.05 * (t - 3), sites.x[s][1] + 0.07 * (t - 3), sites.x[s][2] + 0.1 * (t - 3), 0.25);
  expectExact(several, 0.3, several.size() - 300, true, "several per vertex");
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 9.0);
  Particles cloud;
  for (int i = 0; i < 700; ++i) cloud.add(u(rng), u(rng), u(rng), 0.4);
  expectExact(cloud, 0.1, 500, true, "random pack with ghosts");
}

TEST(SpacetreeDense, RadiiOfSeveralSizesOnOneCappedLevel) {
  // With its depth capped (maxLevel 2), the tree puts radii 0.15 .. 0.35 all on its finest
  // level (mesh ~1.0): the dense path then tests each candidate with its own radius sum.
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(0.0, 9.0), r(0.15, 0.35);
  Particles p;
  for (int i = 0; i < 700; ++i) p.add(u(rng), u(rng), u(rng), r(rng));
  SpacetreeOptions options{0.1};
  options.maxLevel = 2;
  Spacetree tree(options);
  tree.build(p.positions(), p.r.data(), p.size(), 600);
  ASSERT_TRUE(tree.usesDenseLevel());
  PairSet within;
  bool exactValues = true;
  tree.forEachPairWithin([&](int i, int j, double d2, double radiusSum) {
    within.insert(std::minmax(i, j));
    exactValues = exactValues && d2 == p.distanceSquared(std::min(i, j), std::max(i, j)) && radiusSum == p.r[i] + p.r[j];
  });
  EXPECT_TRUE(exactValues);
  const PairSet expected = bruteForce(p, 0.1, 600);
  EXPECT_GT(expected.size(), 100u);
  EXPECT_EQ(within, expected);
}

TEST(SpacetreeDense, FlatAndThinBoxesStayExact) {
  // The box's margin weighs most in a flat or thin box: 20 x 6 x 5 vertices (600 occupied of
  // 21 x 8 x 7 cells with the margin) and a single plane of 25 x 25 (625 of 26 x 27 x 3) pass
  // the density test; a single row of 40 (of 41 x 3 x 3) does not.
  const Particles slab = lattice(20, 6, 5, 1.1, 0.5, 0.03, 6);
  expectExact(slab, 0.05, slab.size(), true, "slab");
  const Particles plane = lattice(25, 25, 1, 1.1, 0.5, 0.03, 7);
  expectExact(plane, 0.05, plane.size(), true, "plane");
  const Particles row = lattice(40, 1, 1, 1.1, 0.5, 0.03, 8);
  expectExact(row, 0.05, row.size(), false, "row");
}

TEST(SpacetreeDense, DensityTestAtItsThreshold) {
  // A 10 x 10 x 10 lattice has 11 x 12 x 12 = 1584 cells with the margin: dense with at least
  // 396 occupied vertices. Keep the corner spheres (the box stays the same) and fill a band of
  // lattice sites up to 396 and up to 395.
  const Particles full = lattice(10, 10, 10, 1.1, 0.5, 0.0, 9);
  for (int kept : {396, 395}) {
    Particles p;
    for (int s = 0; s < full.size(); ++s) {
      const int i = s / 100, j = (s / 10) % 10, k = s % 10;
      const bool corner = (i == 0 || i == 9) && (j == 0 || j == 9) && (k == 0 || k == 9);
      if (corner || s < kept - 4) p.add(full.x[s][0], full.x[s][1], full.x[s][2], full.r[s]);
    }
    ASSERT_EQ(p.size(), kept);
    expectExact(p, 0.05, p.size(), kept >= 396, kept >= 396 ? "396 of 1584" : "395 of 1584");
  }
}

TEST(SpacetreeDense, CrowdedVertexOrTwoLevelsTakeTheGeneralPath) {
  // Eight particles on one vertex are crowded (sweep and prune); seven are not.
  for (int extra : {7, 6}) {
    Particles p = lattice(8, 8, 8, 1.1, 0.5, 0.0, 10);
    for (int e = 0; e < extra; ++e) p.add(3.3 + 0.05 * e, 3.3, 3.3 - 0.05 * e, 0.5);
    expectExact(p, 0.05, p.size(), extra < 7, extra < 7 ? "seven on a vertex" : "eight on a vertex");
  }
  // A sphere too big for the finest level: two populated levels.
  Particles two = lattice(8, 8, 8, 1.1, 0.5, 0.0, 11);
  two.add(4.0, 4.0, 4.0, 1.2);
  expectExact(two, 0.05, two.size(), false, "two levels");
}

TEST(SpacetreeDense, SameCandidatesDistancesAndOrderAsTheGeneralPath) {
  // The general path on the same cube and level (a caller's geometry always takes it) visits
  // the same vertices in the same order: the pairs, their squared distances and radius sums
  // must come out identical, in the same sequence.
  for (const Particles& p : {lattice(15, 11, 13, 1.1, 0.5, 0.04, 12), shuffled(lattice(9, 9, 9, 1.1, 0.5, 0.04, 13), 14)}) {
    const double eps = 0.05;
    Spacetree dense(SpacetreeOptions{eps}), general(SpacetreeOptions{eps});
    dense.build(p.positions(), p.r.data(), p.size(), p.size());
    ASSERT_TRUE(dense.usesDenseLevel());
    GridGeometry geometry;
    geometry.origin = dense.origin();
    geometry.rootSize = dense.rootSize();
    geometry.depth = dense.levelCount() - 1;
    general.build(p.positions(), p.r.data(), p.size(), p.size(), geometry, nullptr);
    ASSERT_FALSE(general.usesDenseLevel());
    const std::vector<Visit> a = visits(dense), b = visits(general);
    EXPECT_EQ(a, b);
    EXPECT_EQ(dense.statistics().candidatePairs, general.statistics().candidatePairs);
    // statistics of the build: one level, its vertices and particles, as the general path counts them
    const int l = geometry.depth;
    EXPECT_EQ(dense.statistics().deepestPopulatedLevel, l);
    EXPECT_EQ(dense.statistics().levels[l].vertices, general.statistics().levels[l].vertices);
    EXPECT_EQ(dense.statistics().levels[l].realParticles, std::uint64_t(p.size()));
    for (int i = 0; i < p.size(); ++i) ASSERT_EQ(dense.levelOf(i), general.levelOf(i));
    // the dense path holds 4 bytes per particle and per cell; the general one over 60 per particle
    EXPECT_LT(dense.statistics().memoryBytes, 20u * std::uint64_t(p.size()));
    EXPECT_GT(general.statistics().memoryBytes, 60u * std::uint64_t(p.size()));
  }
}

TEST(SpacetreeDense, SwitchingPathsBetweenBuildsStaysExact) {
  // One tree, rebuilt: dense, then two levels (general), then dense again with fewer particles.
  const double eps = 0.05;
  Spacetree tree(SpacetreeOptions{eps});
  Particles p = lattice(9, 9, 9, 1.1, 0.5, 0.04, 15);
  Particles two = p;
  two.add(5.0, 5.0, 5.0, 1.5);
  const Particles smaller = lattice(6, 7, 5, 1.1, 0.5, 0.04, 16);
  for (const Particles* q : std::vector<const Particles*>{&p, &two, &smaller}) {
    tree.build(q->positions(), q->r.data(), q->size(), q->size());
    EXPECT_EQ(tree.usesDenseLevel(), q != &two);
    PairSet within;
    tree.forEachPairWithin([&](int i, int j, double) { within.insert(std::minmax(i, j)); });
    EXPECT_EQ(within, bruteForce(*q, eps, q->size()));
    EXPECT_EQ(tree.particleCount(), q->size());
  }
}
