// The pre-test of candidate runs (tree/RunTest.h) and the sweep that uses it: every version
// keeps, in order, every pair the exact cut-off accepts and nothing beyond the margin; the
// spacetree with several particles per vertex (long runs, with ghosts, pairs exactly at the
// cut-off, runs of more candidates than one queue block) lists exactly the brute-force pairs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "sphere_cloud.h"
#include "tree/RunTest.h"
#include "tree/Spacetree.h"

using spacetree::RunTest;
using spacetree::RunTestParticles;
using spacetree::Spacetree;
using spacetree::SpacetreeOptions;

namespace {

struct SoA {
  std::vector<double> x, y, z, r;
};

// The flush's exact decision, in its arithmetic.
bool exactlyWithin(const SoA& s, double halo, double scale, int a, int b) {
  const double dx = s.x[a] - s.x[b], dy = s.y[a] - s.y[b], dz = s.z[a] - s.z[b];
  const double c = (s.r[a] + s.r[b] + halo) * scale;
  return dx * dx + dy * dy + dz * dz <= c * c;
}

double relativeExcess(const SoA& s, double halo, double scale, int a, int b) {
  const double dx = s.x[a] - s.x[b], dy = s.y[a] - s.y[b], dz = s.z[a] - s.z[b];
  const double c = (s.r[a] + s.r[b] + halo) * scale;
  return (dx * dx + dy * dy + dz * dz) / (c * c) - 1.0;
}

std::vector<std::pair<RunTest, const char*>> versions() {
  std::vector<std::pair<RunTest, const char*>> v{{spacetree::portableRunTest(), "portable"}};
  if (RunTest avx2 = spacetree::avx2RunTest()) v.push_back({avx2, "avx2"});
  if (RunTest fast = spacetree::avx512RunTest()) v.push_back({fast, "avx512"});
  return v;
}

// Random centres with a few pairs placed exactly at the cut-off (binary fractions).
SoA runParticles(int n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  SoA s;
  for (int i = 0; i < n; ++i) {
    if (i % 7 == 3) {  // 0.375 from the previous one along an axis: 0.125 + 0.125 + 0.125
      s.x.push_back(s.x.back() + 0.375);
      s.y.push_back(s.y.back());
      s.z.push_back(s.z.back());
      s.r.push_back(0.125);
      s.r[std::size_t(i - 1)] = 0.125;
      continue;
    }
    s.x.push_back(std::ldexp(std::floor(u(rng) * 1024.0), -10));
    s.y.push_back(std::ldexp(std::floor(u(rng) * 1024.0), -10));
    s.z.push_back(std::ldexp(std::floor(u(rng) * 1024.0), -10));
    s.r.push_back(0.05 + 0.2 * u(rng));
  }
  return s;
}

}  // namespace

TEST(RunTest, KeepsTheExactPairsInOrderAndNothingBeyondTheMargin) {
  const SoA s = runParticles(160, 11);
  const double halo = 0.125;
  std::mt19937_64 rng(12);
  for (const auto& [test, name] : versions()) {
    for (const double scale : {1.0, 1.0 + 1e-9}) {
      const RunTestParticles p{s.x.data(), s.y.data(), s.z.data(), s.r.data(), halo, scale};
      std::size_t exactAtCut = 0, kept = 0;
      for (int trial = 0; trial < 4000; ++trial) {
        // A vertex [aBegin, aEnd) against 1-5 runs of 0-34 positions, the first maybe its own
        // particles after a (triangle).
        const bool triangle = trial % 3 == 0;
        const int aBegin = int(rng() % 100), aEnd = aBegin + 1 + int(rng() % 6);
        std::vector<spacetree::CandidateRun> runs(1 + rng() % 5);
        for (auto& run : runs) {
          run.from = int(rng() % 120);
          run.to = run.from + int(rng() % 35);
        }
        if (triangle) runs[0] = {aBegin, std::min(160, aEnd + int(rng() % 25))};
        std::vector<std::pair<int, int>> expected, all;
        for (std::size_t r = 0; r < runs.size(); ++r)
          for (int a = aBegin; a < aEnd; ++a)
            for (int b = r == 0 && triangle ? a + 1 : runs[r].from; b < runs[r].to; ++b) {
              all.push_back({a, b});
              if (exactlyWithin(s, halo, scale, a, b)) expected.push_back({a, b});
              if (relativeExcess(s, halo, scale, a, b) == 0.0) ++exactAtCut;
            }
        const int start = int(rng() % 5);  // slot the queue is at
        std::vector<std::int32_t> first(start + all.size() + spacetree::kRunTestSlack + 4, -7),
            second(first.size(), -7);
        const int end =
            test(p, aBegin, aEnd, runs.data(), int(runs.size()), triangle, first.data(), second.data(), start);
        ASSERT_GE(end, start) << name;
        // Nothing written past the candidates' slots plus the slack, nor before the start.
        for (std::size_t t = start + all.size() + spacetree::kRunTestSlack; t < first.size(); ++t)
          ASSERT_TRUE(first[t] == -7 && second[t] == -7) << name << ": slot " << t << " written";
        for (int t = 0; t < start; ++t) ASSERT_TRUE(first[t] == -7 && second[t] == -7) << name;
        // Kept: a subsequence of the candidates in sweep order (runs, then a, then position),
        // each within the margin, holding every exact pair.
        std::vector<std::pair<int, int>> got;
        for (int t = start; t < end; ++t) got.push_back({first[t], second[t]});
        kept += got.size();
        std::size_t next = 0, nextExact = 0;
        for (const auto& pair : got) {
          while (next < all.size() && all[next] != pair) {
            ASSERT_FALSE(nextExact < expected.size() && all[next] == expected[nextExact])
                << name << ": exact pair (" << all[next].first << ", " << all[next].second << ") dropped";
            ++next;
          }
          ASSERT_LT(next, all.size()) << name << ": (" << pair.first << ", " << pair.second << ") out of order";
          if (nextExact < expected.size() && expected[nextExact] == pair) ++nextExact;
          ++next;
          EXPECT_LE(relativeExcess(s, halo, scale, pair.first, pair.second), 2e-12) << name;
        }
        ASSERT_EQ(nextExact, expected.size()) << name << ": an exact pair was dropped (trial " << trial << ")";
      }
      if (scale == 1.0) {
        EXPECT_GT(exactAtCut, 100u) << "the scene should hold pairs exactly at the cut-off";
      }
      EXPECT_GT(kept, 1000u);
    }
  }
}

namespace {

using Particles = spacetree::testing::SphereCloud;
using spacetree::testing::bruteForce;
using spacetree::testing::PairSet;

// The pairs of forEachPairWithin (tolerance 0), failing on a duplicate or a wrong distance;
// forEachCandidatePair must visit each of them once, and no pair twice.
PairSet within(const Particles& p, double eps, int nActive) {
  Spacetree tree(SpacetreeOptions{eps});
  tree.build(p.positions(), p.r.data(), p.size(), nActive);
  EXPECT_FALSE(tree.usesDenseLevel()) << "the scenes hold a big sphere: the multilevel sweep runs";
  PairSet found, candidates;
  tree.forEachPairWithin([&](int i, int j, double d2) {
    EXPECT_TRUE(found.insert(std::minmax(i, j)).second) << "pair visited twice";
    EXPECT_EQ(d2, p.distanceSquared(i, j));
  });
  bool twice = false;
  tree.forEachCandidatePair([&](int i, int j) { twice |= !candidates.insert(std::minmax(i, j)).second; });
  EXPECT_FALSE(twice) << "candidate visited twice";
  EXPECT_TRUE(std::includes(candidates.begin(), candidates.end(), found.begin(), found.end()));
  return found;
}

void expectBruteForce(const Particles& p, double eps, int nActive, const char* what) {
  const PairSet expected = bruteForce(p, eps, nActive);
  if (nActive > 0) {
    EXPECT_FALSE(expected.empty()) << what;
  }
  EXPECT_EQ(within(p, eps, nActive), expected) << what;
}

}  // namespace

TEST(RunTest, SeveralParticlesPerVertexWithGhostsMatchBruteForce) {
  // About 4 and 12 particles per vertex (cells = cut-off = 0.05): a vertex against the
  // 12-40 of a forward row; the denser one has rows of more candidates than a queue block.
  // Each with a big sphere (a second level: the multilevel sweep, not the dense one-level path).
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (const int n : {4000, 12000}) {
    Particles p;
    for (int i = 0; i < n; ++i) p.add(0.5 * u(rng), 0.5 * u(rng), 0.5 * u(rng), 0.02);
    p.add(0.25, 0.25, -0.1, 0.12);  // a big one touching the cloud: two levels
    expectBruteForce(p, 0.005, n, "all owned");
    expectBruteForce(p, 0.005, n * 3 / 5, "ghosts");
    expectBruteForce(p, 0.005, 0, "only ghosts");
  }
}

TEST(RunTest, RunsOfMoreCandidatesThanAQueueBlockMatchBruteForce) {
  // 10-22 particles around each site of a lattice of the cell size (0.05, the cut-off):
  // vertices of that many (still paired in full: dense), so a vertex against a forward row is
  // up to 22 x 66 candidates, more than a queue block, and the queue fills in the middle of
  // such runs at varying places. (More than 8 per vertex: the multilevel sweep, not the dense
  // one-level path.)
  std::mt19937_64 rng(22);
  std::uniform_real_distribution<double> u(-0.012, 0.012);
  Particles p;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      for (int k = 0; k < 6; ++k) {
        const int count = 10 + int(rng() % 13);
        for (int t = 0; t < count; ++t) p.add(0.05 * i + u(rng), 0.05 * j + u(rng), 0.05 * k + u(rng), 0.02);
      }
  expectBruteForce(p, 0.005, p.size(), "clumps");
  expectBruteForce(p, 0.005, p.size() / 2, "clumps with ghosts");
}

TEST(RunTest, LatticePairsExactlyAtTheCutOffAreListed) {
  // Spacing 0.375 with cut-off 0.125 + 0.125 + 2 * 0.25 = 0.75: about eight particles per
  // vertex, and every second neighbour along an axis exactly at the cut-off (binary fractions:
  // no rounding anywhere).
  Particles p;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j)
      for (int k = 0; k < 10; ++k) p.add(0.375 * i, 0.375 * j, 0.375 * k, 0.125);
  p.add(1.5, 1.5, -2.0, 1.5);  // a big one touching the lattice: two levels
  const PairSet all = bruteForce(p, 0.25, p.size());
  std::size_t atCut = 0;
  for (const auto& [i, j] : all) atCut += p.distanceSquared(i, j) == 0.5625 ? 1 : 0;
  EXPECT_EQ(atCut, 3u * 8 * 10 * 10);  // (i, i + 2) along each axis (the big one: none)
  expectBruteForce(p, 0.25, p.size(), "lattice");
  expectBruteForce(p, 0.25, 400, "lattice with ghosts");
}
