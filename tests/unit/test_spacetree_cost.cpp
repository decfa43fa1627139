// The sweep's cost follows its output: a big particle's virtual links cost the finer vertices
// near its surface (not every vertex its reach box covers), and a dilute continuous cloud tests
// links only near coarse particles. The pair sets stay exactly brute force's, and the links
// exactly the paper's (vertex within r + 2 eps + h sqrt(3) of the coarser particle).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "sphere_cloud.h"
#include "tree/Spacetree.h"

using spacetree::Spacetree;
using spacetree::SpacetreeOptions;

namespace {

using Cloud = spacetree::testing::SphereCloud;

using PairSet = std::set<std::pair<int, int>>;

PairSet bruteForce(const Cloud& c, double eps) {
  PairSet pairs;
  for (int i = 0; i < c.size(); ++i)
    for (int j = i + 1; j < c.size(); ++j) {
      const double cut = c.r[i] + c.r[j] + 2.0 * eps;
      if (c.distanceSquared(i, j) <= cut * cut) pairs.insert({i, j});
    }
  return pairs;
}

PairSet treePairs(Spacetree& tree, const Cloud& c) {
  tree.build(c.positions(), c.r.data(), c.size(), c.size());
  PairSet pairs;
  tree.forEachPairWithin([&](int i, int j, double) { EXPECT_TRUE(pairs.insert(std::minmax(i, j)).second); });
  return pairs;
}

// Vertices of level l hosting a particle, and how many of them lie within
// (r + 2 eps + h (1 + sqrt(3)) / 2) (1 + 1e-9) of particle q (its virtual links on that level).
std::uint64_t linksOf(const Spacetree& tree, const Cloud& c, int q, int l, double eps) {
  std::set<std::array<std::int64_t, 3>> vertices;
  const double h = tree.meshSize(l);
  for (int i = 0; i < c.size(); ++i)
    if (tree.levelOf(i) == l) {
      std::array<std::int64_t, 3> v;
      for (int d = 0; d < 3; ++d) v[d] = std::int64_t((c.x[i][d] - tree.origin()[d]) / h + 0.5);
      vertices.insert(v);
    }
  const double reach = (c.r[q] + 2.0 * eps + 0.5 * (1.0 + std::sqrt(3.0)) * h) * (1.0 + 1e-9);
  std::uint64_t links = 0;
  for (const auto& v : vertices) {
    double d2 = 0.0;
    for (int d = 0; d < 3; ++d) {
      const double dx = c.x[q][d] - (tree.origin()[d] + double(v[d]) * h);
      d2 += dx * dx;
    }
    links += d2 < reach * reach ? 1 : 0;
  }
  return links;
}

}  // namespace

// One sphere of 30 small diameters, touched within the skin by ~3 000 small spheres on a shell
// and surrounded by a jittered lattice of them (the crowded scene of bench/neighbor_vs_lammps).
TEST(SpacetreeCost, BigParticleTouchedByThousandsCostsItsSurface) {
  const double rSmall = 0.5, rBig = 15.0, eps = 0.25;  // skin = half a small diameter
  Cloud c;
  c.add(0.0, 0.0, 0.0, rBig);
  const double shell = rBig + rSmall + 0.05;
  const int nShell = 3000;
  for (int k = 0; k < nShell; ++k) {  // Fibonacci sphere
    const double z = 1.0 - 2.0 * (k + 0.5) / nShell, rho = std::sqrt(1.0 - z * z), phi = 2.399963229728653 * k;
    c.add(shell * rho * std::cos(phi), shell * rho * std::sin(phi), shell * z, rSmall);
  }
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> jitter(-0.04, 0.04);
  const double spacing = 1.1, half = 18.0;
  for (double px = -half; px <= half; px += spacing)
    for (double py = -half; py <= half; py += spacing)
      for (double pz = -half; pz <= half; pz += spacing)
        if (px * px + py * py + pz * pz > (shell + 1.0) * (shell + 1.0))
          c.add(px + jitter(rng), py + jitter(rng), pz + jitter(rng), rSmall);

  Spacetree tree(SpacetreeOptions{eps});
  const PairSet expected = bruteForce(c, eps);
  ASSERT_EQ(treePairs(tree, c), expected);
  std::size_t touching = 0;
  for (const auto& p : expected) touching += p.first == 0 ? 1 : 0;
  EXPECT_GT(touching, 2500u) << "the big sphere should be touched by thousands";

  const int small = tree.levelOf(1), big = tree.levelOf(0);
  ASSERT_LT(big, small);
  const auto& level = tree.statistics().levels[std::size_t(small)];
  const std::uint64_t links = linksOf(tree, c, 0, small, eps);
  EXPECT_EQ(level.virtualLinks, links);
  // Surface, not volume: the small vertices inside the big sphere's reach box number about
  // (2 (15 + reach) / 1.1)^3 - (sphere) ~ 14 000; only those near its surface are tested.
  EXPECT_LE(level.linkTests, 2 * links) << links << " links";
  EXPECT_LT(level.linkTests, level.vertices / 2) << "every small vertex near the big one tested";
}

// Number of spheres ~ d^-3, d in [1, 100], solid fraction 0.05, random centres: every level
// holds some, and coarse particles are few and far between.
TEST(SpacetreeCost, DiluteContinuousCloudTestsLinksOnlyNearCoarseParticles) {
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double dMin = 1.0, dMax = 100.0, eps = 0.05;
  Cloud c;
  double volume = 0.0;
  std::vector<double> diameters;
  for (int k = 0; k < 6000; ++k) {
    const double e = -2.0;  // inverse of the cumulative distribution of d^-3
    const double d = k == 0 ? dMax : std::pow(std::pow(dMin, e) + u(rng) * (std::pow(dMax, e) - std::pow(dMin, e)), 1.0 / e);
    diameters.push_back(d);
    volume += M_PI / 6.0 * d * d * d;
  }
  const double box = std::cbrt(volume / 0.05);
  for (double d : diameters) c.add(box * u(rng), box * u(rng), box * u(rng), 0.5 * d);

  Spacetree tree(SpacetreeOptions{eps});
  const PairSet expected = bruteForce(c, eps);
  ASSERT_EQ(treePairs(tree, c), expected);
  EXPECT_GT(expected.size(), 100u);

  std::uint64_t links = 0, tests = 0, lookups = 0, coarse = 0;
  int populated = 0;
  for (int l = 0; l < tree.levelCount(); ++l) {
    const auto& level = tree.statistics().levels[std::size_t(l)];
    links += level.virtualLinks;
    tests += level.linkTests;
    lookups += level.linkLookups;
    populated += level.realParticles > 0 ? 1 : 0;
    // the links are exactly the paper's, whichever way they were found
    std::uint64_t expected = 0;
    for (int q = 0; q < c.size(); ++q)
      if (tree.levelOf(q) < l && level.realParticles > 0) expected += linksOf(tree, c, q, l, eps);
    EXPECT_EQ(level.virtualLinks, expected) << "level " << l;
  }
  for (int l = 0; l + 1 < tree.levelCount(); ++l) coarse += tree.statistics().levels[std::size_t(l)].realParticles;
  EXPECT_GE(populated, 4);
  EXPECT_GT(links, 100u);
  // Each test is a (finer vertex, coarser particle) pair near that particle: about the links,
  // not (finer vertices) x (coarser particles in their neighbourhood). A finer vertex that
  // looks up the coarse vertices around it (a sparse coarse level) tests the few particles
  // there: on average at most two that it does not link.
  EXPECT_LE(tests, 2 * links + 2 * lookups + 100)
      << links << " links, " << lookups << " look-ups, " << coarse << " particles above the finest level";
  EXPECT_GT(lookups, 0u) << "a sparse coarse level should be looked up from the finer vertices";
}

// A dense pack of one size (bench/neighbor_vs_lammps' bidisperse_R1: spheres of d = 1 on a
// jittered lattice of spacing 1.1, skin 0.1): one particle per vertex, so the per-vertex
// records weigh as much as the particles. The tree holds at most 88 bytes per particle (sorted
// copies 36, 8-byte sort records and their scratch 16, vertex record and key 28, level 1), and
// the pairs with an active particle are brute force's, in blocks of candidates far more than
// one (half the particles inactive, as ghosts).
TEST(SpacetreeCost, DenseOneSizePackHoldsFewBytesPerParticle) {
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> jitter(-0.04, 0.04);
  const int side = 20;
  const double eps = 0.05;
  Cloud c;
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j)
      for (int k = 0; k < side; ++k) c.add(1.1 * i + jitter(rng), 1.1 * j + jitter(rng), 1.1 * k + jitter(rng), 0.5);
  // inactive particles: a random half, moved to the end (the tree takes [0, nActive) as active)
  std::shuffle(c.x.begin(), c.x.end(), rng);
  const int nActive = c.size() / 2;

  Spacetree tree(SpacetreeOptions{eps});
  tree.build(c.positions(), c.r.data(), c.size(), nActive);
  PairSet found;
  tree.forEachPairWithin([&](int i, int j, double) { EXPECT_TRUE(found.insert(std::minmax(i, j)).second); });
  PairSet expected;
  for (const auto& pr : bruteForce(c, eps))
    if (pr.first < nActive || pr.second < nActive) expected.insert(pr);
  EXPECT_EQ(found, expected);
  EXPECT_GT(expected.size(), std::size_t(c.size()));

  const auto& s = tree.statistics();
  ASSERT_GE(s.deepestPopulatedLevel, 0);
  EXPECT_EQ(s.levels[std::size_t(s.deepestPopulatedLevel)].vertices, std::uint64_t(c.size()))
      << "not one particle per vertex: the scene does not test what it should";
  EXPECT_LE(double(s.memoryBytes) / c.size(), 88.0) << s.memoryBytes << " bytes";
}
