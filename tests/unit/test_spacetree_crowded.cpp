// Crowded vertices (many particles on one coarse vertex, as the reluctant grid leaves them):
// the slab filters, x windows and pruned virtual links of the sweep must not change a thing.
// Randomised scenes against brute force: the same pairs, each once, with bit-identical
// squared distances, and the same number of virtual links per level.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "tree/Spacetree.h"

using spacetree::GridGeometry;
using spacetree::Spacetree;
using spacetree::SpacetreeOptions;

namespace {

struct Scene {
  std::vector<std::array<double, 3>> x;
  std::vector<double> r;
  std::vector<int> level;  // requested host level (the tree clamps it to the admissible one)
  int nActive = 0;
  const double (*positions() const)[3] { return reinterpret_cast<const double(*)[3]>(x.data()); }
  int size() const { return int(r.size()); }
  void add(double px, double py, double pz, double pr, int l) {
    x.push_back({px, py, pz});
    r.push_back(pr);
    level.push_back(l);
  }
};

constexpr double kEps = 0.001;
constexpr double kRMin = 0.002, kRMax = 0.02;  // log-uniform: max / median = sqrt(10) < 4, not "big"

GridGeometry sceneGeometry() {
  GridGeometry g;
  g.origin = {-0.1, -0.1, -0.1};
  g.rootSize = 1.2;  // levels 0..4: h = 1.2, 0.4, 0.133, 0.044, 0.0148
  g.depth = 4;
  return g;
}

// Clustered cloud on coarse levels, with pairs exactly at the cut-off (along an axis, across
// the boundary between two vertices of their level), groups sharing one x coordinate, much
// bigger particles inside crowded vertices, and ghosts among all of them.
Scene randomScene(unsigned seed, int coarsestLevel) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  auto radius = [&] { return kRMin * std::pow(kRMax / kRMin, u(rng)); };
  auto level = [&] { return coarsestLevel + int(u(rng) * (5 - coarsestLevel)); };  // clamped to admissible
  const GridGeometry g = sceneGeometry();
  Scene s;
  // Clusters (crowded vertices on several levels) and a uniform background.
  for (int c = 0; c < 6; ++c) {
    const double cx = 0.1 + 0.8 * u(rng), cy = 0.1 + 0.8 * u(rng), cz = 0.1 + 0.8 * u(rng);
    const double spread = 0.02 + 0.08 * u(rng);
    std::normal_distribution<double> n(0.0, spread);
    for (int k = 0; k < 180; ++k)
      s.add(std::clamp(cx + n(rng), 0.0, 1.0), std::clamp(cy + n(rng), 0.0, 1.0), std::clamp(cz + n(rng), 0.0, 1.0),
            radius(), level());
  }
  for (int k = 0; k < 500; ++k) s.add(u(rng), u(rng), u(rng), radius(), level());
  // Pairs at exactly the cut-off along one axis, both of the biggest ordinary radius (so the
  // pruning bounds, built from the vertices' largest radii, are tight), across the boundary
  // between two vertex cells of their level; some of either sign, on every axis.
  for (int k = 0; k < 120; ++k) {
    const int l = coarsestLevel + k % (4 - coarsestLevel);  // levels where kRMax is admissible
    const double h = g.rootSize / std::pow(3.0, l);
    const double cut = kRMax + kRMax + 2.0 * kEps;
    const int axis = k % 3;
    double p[3] = {0.1 + 0.8 * u(rng), 0.1 + 0.8 * u(rng), 0.1 + 0.8 * u(rng)};
    const double boundary = g.origin[axis] + (std::floor((p[axis] - g.origin[axis]) / h) + 0.5) * h;
    p[axis] = boundary - 0.5 * cut + (k % 2 ? 0.2 : -0.2) * cut * u(rng);
    double q[3] = {p[0], p[1], p[2]};
    q[axis] = p[axis] + cut;
    if (k % 4 == 3) std::swap(p, q);  // the pair in the other order of the particle list
    s.add(p[0], p[1], p[2], kRMax, l);
    s.add(q[0], q[1], q[2], kRMax, l);
  }
  // Two crowded neighbours (10 particles each side of a vertex-cell boundary) with a pair at
  // the cut-off across it, on level 1 (reach small against h: slabs) and level 2 (not).
  for (int k = 0; k < 12; ++k) {
    const int l = 1 + k % 2;
    const double h = g.rootSize / std::pow(3.0, l);
    const double cut = kRMax + kRMax + 2.0 * kEps;
    const int axis = k / 2 % 3;
    double p[3] = {0.2 + 0.6 * u(rng), 0.2 + 0.6 * u(rng), 0.2 + 0.6 * u(rng)};
    p[axis] = g.origin[axis] + (std::floor((p[axis] - g.origin[axis]) / h) + 0.5) * h - 0.5 * cut;
    for (int m = 0; m < 20; ++m) {
      double q[3] = {p[0] + 0.3 * h * (u(rng) - 0.5), p[1] + 0.3 * h * (u(rng) - 0.5), p[2] + 0.3 * h * (u(rng) - 0.5)};
      q[axis] = p[axis] + 0.5 * cut + (m % 2 ? 1.0 : -1.0) * (0.05 + 0.3 * u(rng)) * h;
      s.add(q[0], q[1], q[2], kRMin * std::pow(0.9 * kRMax / kRMin, u(rng)), l);
    }
    double q[3] = {p[0], p[1], p[2]};
    q[axis] += cut;
    s.add(p[0], p[1], p[2], kRMax, l);
    s.add(q[0], q[1], q[2], kRMax, l);
  }
  // Groups on one x coordinate (ties in the x order, zero-width windows), some touching along y.
  for (int grp = 0; grp < 4; ++grp) {
    const double x0 = 0.1 + 0.8 * u(rng), y0 = 0.1 + 0.8 * u(rng), z0 = 0.1 + 0.8 * u(rng);
    const int l = coarsestLevel;
    for (int k = 0; k < 25; ++k) {
      const double y = y0 + 0.05 * (u(rng) - 0.5), z = z0 + 0.05 * (u(rng) - 0.5);
      s.add(x0, y, z, kRMax, l);
      if (k % 5 == 0) s.add(x0, y + 2.0 * kRMax + 2.0 * kEps, z, kRMax, l);
    }
    s.add(x0, y0, z0, kRMax, l);  // coincident centres
    s.add(x0, y0, z0, kRMin, l);
  }
  // Across levels: crowded level-3 vertices whose biggest particle touches a coarse one at
  // exactly the cut-off along x (the pruned axis of the link's pairs), and coarse particles
  // just inside the virtual-link reach of a level-3 or level-4 vertex (the pruned link bound).
  for (int k = 0; k < 24; ++k) {
    const int fine = 3 + k % 2;
    const double h = g.rootSize / std::pow(3.0, fine);
    const double vx = g.origin[0] + std::floor((0.2 + 0.6 * u(rng) - g.origin[0]) / h) * h;
    const double vy = g.origin[1] + std::floor((0.2 + 0.6 * u(rng) - g.origin[1]) / h) * h;
    const double vz = g.origin[2] + std::floor((0.2 + 0.6 * u(rng) - g.origin[2]) / h) * h;
    const double side = k % 4 < 2 ? 1.0 : -1.0;
    if (fine == 3) {
      for (int m = 0; m < 10; ++m)
        s.add(vx + h * (u(rng) - 0.5) / 3, vy + h * (u(rng) - 0.5) / 3, vz + h * (u(rng) - 0.5) / 3,
              kRMin * std::pow(0.9 * kRMax / kRMin, u(rng)), fine);
      const double ax = vx + side * h / 4;
      s.add(ax, vy, vz, kRMax, fine);
      s.add(ax + side * (kRMax + kRMax + 2.0 * kEps), vy, vz, kRMax, 1 + k % 4 / 2);
    } else {
      s.add(vx, vy, vz, kRMin, fine);
      const double linkReach = 2.0 * kEps + 0.5 * (1.0 + std::sqrt(3.0)) * h;
      s.add(vx + side * (kRMax + linkReach) * (1.0 - 1e-12), vy, vz, kRMax, 1 + k % 4 / 2);
    }
  }
  // Much bigger particles (> 4 x the median) among the small ones of crowded vertices.
  for (int k = 0; k < 8; ++k) s.add(u(rng), u(rng), u(rng), k % 2 ? 0.1 : 0.05, coarsestLevel);
  // Ghosts: a random tenth, listed last.
  std::vector<int> order(std::size_t(s.size()));
  for (int i = 0; i < s.size(); ++i) order[std::size_t(i)] = i;
  std::shuffle(order.begin(), order.end(), rng);
  Scene shuffled;
  for (int i : order) shuffled.add(s.x[i][0], s.x[i][1], s.x[i][2], s.r[i], s.level[i]);
  shuffled.nActive = s.size() - s.size() / 10;
  return shuffled;
}

using PairDistances = std::map<std::pair<int, int>, double>;

// The squared distance exactly as a visitor gets it: (x_i - x_j)^2 summed over x, y, z.
double squaredDistance(const Scene& s, int i, int j) {
  const double dx = s.x[i][0] - s.x[j][0], dy = s.x[i][1] - s.x[j][1], dz = s.x[i][2] - s.x[j][2];
  return dx * dx + dy * dy + dz * dz;
}

PairDistances bruteForce(const Scene& s, double scale) {
  PairDistances pairs;
  for (int i = 0; i < s.size(); ++i)
    for (int j = i + 1; j < s.size(); ++j) {
      if (i >= s.nActive && j >= s.nActive) continue;
      const double cut = (s.r[i] + s.r[j] + 2.0 * kEps) * scale;
      const double d2 = squaredDistance(s, i, j);
      if (d2 <= cut * cut) pairs[{i, j}] = d2;
    }
  return pairs;
}

// Virtual links as the tree defines them (vertex v of level l, coarser particle q within
// (r_q + 2 eps + h (1 + sqrt(3)) / 2) (1 + 1e-9) of it), limited to the 3x3x3 neighbourhood of v's nearest vertex on
// q's level, where the tree looks for them.
std::vector<std::uint64_t> bruteForceLinks(const Scene& s, const Spacetree& tree) {
  const int nLevels = tree.levelCount();
  const auto& o = tree.origin();
  auto vertexOf = [&](int i, int l) {
    const double inv = 1.0 / tree.meshSize(l);
    return std::array<std::int64_t, 3>{std::int64_t((s.x[i][0] - o[0]) * inv + 0.5),
                                       std::int64_t((s.x[i][1] - o[1]) * inv + 0.5),
                                       std::int64_t((s.x[i][2] - o[2]) * inv + 0.5)};
  };
  std::vector<std::set<std::array<std::int64_t, 3>>> vertices{std::size_t(nLevels)};
  for (int i = 0; i < s.size(); ++i) vertices[std::size_t(tree.levelOf(i))].insert(vertexOf(i, tree.levelOf(i)));
  std::vector<std::uint64_t> links(std::size_t(nLevels), 0);
  for (int l = 0; l < nLevels; ++l) {
    const double h = tree.meshSize(l);
    const double linkReach = 2.0 * kEps + 0.5 * (1.0 + std::sqrt(3.0)) * h;
    for (const auto& v : vertices[std::size_t(l)]) {
      const double vx = o[0] + v[0] * h, vy = o[1] + v[1] * h, vz = o[2] + v[2] * h;
      for (int q = 0; q < s.size(); ++q) {
        const int m = tree.levelOf(q);
        if (m >= l) continue;
        const std::int64_t step = std::int64_t(std::llround(std::pow(3.0, l - m))), half = (step - 1) / 2;
        const auto u = vertexOf(q, m);
        bool near = true;
        for (int d = 0; d < 3; ++d) near = near && std::llabs(u[d] - (v[d] + half) / step) <= 1;
        if (!near) continue;
        const double dx = s.x[q][0] - vx, dy = s.x[q][1] - vy, dz = s.x[q][2] - vz;
        const double reach = (s.r[q] + linkReach) * (1.0 + 1e-9);
        if (dx * dx + dy * dy + dz * dz < reach * reach) ++links[std::size_t(l)];
      }
    }
  }
  return links;
}

void expectExact(const Scene& s, const char* what) {
  Spacetree tree(SpacetreeOptions{kEps});
  tree.build(s.positions(), s.r.data(), s.size(), s.nActive, sceneGeometry(), s.level.data());
  // The scene must exercise what it is for: many vertices holding 8 particles or more.
  std::map<std::array<std::int64_t, 4>, int> population;
  for (int i = 0; i < s.size(); ++i) {
    const int l = tree.levelOf(i);
    const double inv = 1.0 / tree.meshSize(l);
    ++population[{l, std::int64_t((s.x[i][0] - tree.origin()[0]) * inv + 0.5),
                  std::int64_t((s.x[i][1] - tree.origin()[1]) * inv + 0.5),
                  std::int64_t((s.x[i][2] - tree.origin()[2]) * inv + 0.5)}];
  }
  int crowded = 0;
  for (const auto& entry : population) crowded += entry.second >= 8;
  EXPECT_GE(crowded, 10) << what;

  for (const double tolerance : {0.0, 1e-6}) {
    const PairDistances expected = bruteForce(s, 1.0 + tolerance);
    PairDistances found;
    bool duplicate = false, distanceWrong = false;
    tree.forEachPairWithin(
        [&](int i, int j, double d2) {
          if (!found.emplace(std::minmax(i, j), d2).second) duplicate = true;
          if (d2 != squaredDistance(s, i, j)) distanceWrong = true;
        },
        tolerance);
    EXPECT_FALSE(duplicate) << what << ": a pair was reported twice";
    EXPECT_FALSE(distanceWrong) << what << ": a squared distance differs from (x_i - x_j)^2 summed";
    EXPECT_EQ(found.size(), expected.size()) << what << ", tolerance " << tolerance;
    EXPECT_TRUE(found == expected) << what << ", tolerance " << tolerance;
    int missing = 0;
    for (const auto& [pair, d2] : expected)
      if (!found.count(pair)) ++missing;
    EXPECT_EQ(missing, 0) << what << ", tolerance " << tolerance;
  }
  // Pairs exactly at the cut-off survive the round-off in most cases: the scene tests them.
  int atCutOff = 0;
  for (const auto& [pair, d2] : bruteForce(s, 1.0)) {
    const double cut = s.r[pair.first] + s.r[pair.second] + 2.0 * kEps;
    if (d2 >= cut * cut * (1.0 - 1e-12)) ++atCutOff;
  }
  EXPECT_GE(atCutOff, 30) << what;

  // Candidates: a superset, once each, never two ghosts.
  std::set<std::pair<int, int>> candidates;
  bool duplicate = false, ghosts = false;
  tree.forEachCandidatePair([&](int i, int j) {
    if (!candidates.insert(std::minmax(i, j)).second) duplicate = true;
    if (i >= s.nActive && j >= s.nActive) ghosts = true;
  });
  EXPECT_FALSE(duplicate) << what;
  EXPECT_FALSE(ghosts) << what;
  for (const auto& [pair, d2] : bruteForce(s, 1.0)) EXPECT_TRUE(candidates.count(pair)) << what;
  // The candidates handed to the exact test are few: pruning works on crowded vertices.
  EXPECT_LT(tree.statistics().candidatePairs, std::uint64_t(s.size()) * 60) << what;

  // Same virtual links per level as the plain definition.
  const std::vector<std::uint64_t> links = bruteForceLinks(s, tree);
  for (int l = 0; l < tree.levelCount(); ++l)
    EXPECT_EQ(tree.statistics().levels[std::size_t(l)].virtualLinks, links[std::size_t(l)])
        << what << ", level " << l;
}

}  // namespace

TEST(SpacetreeCrowded, RandomCoarseScenesMatchBruteForce) {
  for (unsigned seed = 1; seed <= 6; ++seed) {
    const Scene s = randomScene(seed, seed % 2 ? 1 : 2);
    expectExact(s, seed % 2 ? "coarsest host level 1" : "coarsest host level 2");
  }
}

TEST(SpacetreeCrowded, EverythingOnOneCoarseLevel) {
  // One level only: no virtual links, all pairs among and between crowded vertices.
  Scene s = randomScene(11, 1);
  std::fill(s.level.begin(), s.level.end(), 1);
  expectExact(s, "all on level 1");
}

TEST(SpacetreeCrowded, FewFineVerticesGatherCoarseCandidatesOnDemand) {
  // A crowded coarse level with few finer vertices: their virtual-link candidates are gathered
  // per ancestor (not precomputed), crowded coarse vertices pruned by position as well.
  Scene s = randomScene(21, 1);
  for (std::size_t i = 0; i < s.level.size(); ++i) s.level[i] = i % 40 == 0 ? 4 : 1;
  expectExact(s, "few fine vertices");
}
