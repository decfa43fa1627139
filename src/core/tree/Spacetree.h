// Multilevel spacetree neighbour search (paper §4): a cascade of 3-way refined Cartesian
// grids. Each particle is a *real* particle of the finest level whose mesh size h still
// satisfies h >= 2(r + eps), hosted by the vertex nearest its centre. Coarser (bigger)
// particles appear on finer vertices as *virtual links*, so every pair is found bottom-up on
// the level of its smaller particle:
//   - same level: a vertex against itself and its 13 "forward" neighbours (symmetry);
//   - across levels: a vertex against its virtual links, i.e. the coarser real particles whose
//     centre lies within r + 2 eps + h sqrt(3) of the vertex (the paper's projection radius).
// Levels are sparse: only vertices that host particles exist, so the memory is per particle,
// not per domain volume. The tree is rebuilt from scratch by build(); drop (to the finest
// admissible level) and lift (to a coarser one when a particle grows) happen there.
//
// Crowded vertices (>= 8 particles: a lifted cloud on a coarse level of the reluctant grid)
// keep their particles ordered by x with a bounding box, and are pruned instead of paired in
// full: within a vertex by an x window then |dy|, |dz|; between two vertices only the
// particles within reach of the other's box (a slab along the shared face, edge or corner)
// take part; a finer vertex scans only the x window of a crowded coarse vertex for virtual
// links (and nothing when it is beyond reach of the box). Bounds are the vertices' largest
// radii with a 1e-9 margin, tested on coordinate differences as the visitor's distance is, so
// the pairs, their distances and the virtual links are those of the unpruned sweep.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "tree/CoarseNeighbourhoods.h"
#include "tree/GridGeometry.h"
#include "tree/RadixSort.h"
#include "tree/SpacetreeStatistics.h"
#include "tree/VertexKey.h"
#include "tree/VertexLookup.h"

namespace spacetree {

struct SpacetreeOptions {
  double epsilon = 0.0;                 // halo: pairs closer than r_i + r_j + 2 eps are found
  int maxLevel = kMaxSpacetreeLevel;    // deepest level below the root cube
};

class Spacetree {
 public:
  explicit Spacetree(SpacetreeOptions options = {});

  void setOptions(const SpacetreeOptions& options);
  const SpacetreeOptions& options() const { return options_; }

  // Sorts the particles into the tree. Particles [0, nActive) are active (owned); a pair of two
  // inactive particles (ghosts) is never reported. Throws std::invalid_argument for a
  // non-finite position or radius, or a negative radius.
  void build(const double (*x)[3], const double* radius, int n, int nActive);

  // Same, on a given cube with the host level of every particle chosen by the caller (an
  // adaptive grid). The sweep is exact for any level at or coarser than the finest one a
  // particle fits, so a too fine hostLevel[i] is clamped to that; hostLevel == nullptr means
  // the finest admissible level. Throws std::invalid_argument as build() does, and for a
  // particle centre outside the cube or a geometry with depth outside [0, maxLevel].
  void build(const double (*x)[3], const double* radius, int n, int nActive,
             const GridGeometry& geometry, const int* hostLevel);

  // Calls visit(i, j) (original indices, i != j) once for every unordered candidate pair with
  // at least one active particle. The candidates are a superset of the pairs with
  // |x_i - x_j| <= r_i + r_j + 2 eps; the visitor applies the exact cut-off.
  template <class Visitor>
  void forEachCandidatePair(Visitor&& visit) {
    sweep([&](std::int32_t a, std::int32_t b) { visit(sortedId_[a], sortedId_[b]); }, 1.0 + kPruneMargin);
  }

  // Like forEachCandidatePair, but only pairs with
  //   dx^2 + dy^2 + dz^2 <= ((r_i + r_j + 2 eps) (1 + relativeTolerance))^2
  // reach the visitor, as visit(i, j, squaredDistance), evaluated in that order on the tree's own sorted copies (streaming
  // access). With tolerance 0 this is bit for bit the cut-off of LIGGGHTS' granular builders
  // (contact_distance_factor 1); a small tolerance makes it a superset of other roundings.
  template <class Visitor>
  void forEachPairWithin(Visitor&& visit, double relativeTolerance = 0.0) {
    const double halo = 2.0 * options_.epsilon;
    const double scale = 1.0 + relativeTolerance;
    sweep([&](std::int32_t a, std::int32_t b) {
      const double dx = sx_[a] - sx_[b], dy = sy_[a] - sy_[b], dz = sz_[a] - sz_[b];
      const double cut = (sr_[a] + sr_[b] + halo) * scale;
      const double distanceSquared = dx * dx + dy * dy + dz * dz;
      if (distanceSquared <= cut * cut) visit(sortedId_[a], sortedId_[b], distanceSquared);
    }, scale * (1.0 + kPruneMargin));
  }

  int levelOf(int particle) const { return particleLevel_[particle]; }
  int particleCount() const { return int(particleLevel_.size()); }  // of the last build
  int levelCount() const { return int(levels_.size()); }
  double meshSize(int level) const { return levels_[level].meshSize; }
  double rootSize() const { return rootSize_; }
  const std::array<double, 3>& origin() const { return origin_; }
  // Mesh size a particle of this radius needs: h >= 2 (r + eps), with a relative safety margin
  // so that touching-at-the-cut-off pairs land on adjacent vertices despite round-off.
  double requiredMeshSize(double radius) const;

  // Counters of the last build() and forEachCandidatePair().
  const SpacetreeStatistics& statistics() const { return stats_; }
  // Mesh size of the finest level that hosts a particle in the last build (0 when none does):
  // the smallest cell a particle may cross in one time step.
  double finestPopulatedMeshSize() const {
    return stats_.deepestPopulatedLevel >= 0 ? meshSize(stats_.deepestPopulatedLevel) : 0.0;
  }

 private:
  struct Vertex {
    VertexIndex index;
    std::int32_t begin, end;  // range of hosted particles in the sorted arrays
    std::int32_t active;      // how many of them are active
    double maxRadius;         // of the hosted particles
    std::int32_t bigBegin;    // crowded: [bigBegin, end) holds the much bigger ones, unsorted
    std::int32_t box;         // crowded: its entry in Level::boxes, else -1
    double maxSmallRadius;    // of [begin, bigBegin)
    // Crowded: [begin, bigBegin) is ordered by x (sweep and prune).
    bool sortedByX() const { return box >= 0; }
  };
  // Bounding box of particle centres.
  struct Box {
    double lo[3], hi[3];
  };
  // Vertices holding at least this many particles are crowded (see the top of this file).
  // Regular levels rarely reach it; coarse levels holding a lifted cloud (reluctant grid) do.
  static constexpr std::int32_t kSweepAndPruneMinParticles = 8;
  static constexpr double kBigRadiusOverMedian = 4.0;
  struct Level {
    double meshSize = 0.0;
    std::vector<Vertex> vertices;         // sorted by key
    std::vector<Box> boxes;               // of the crowded vertices' [begin, bigBegin)
    VertexLookup lookup;                  // coordinates -> position in `vertices`
    // Virtual-link candidates for finer vertices: precomputed per coarse vertex when many
    // finer vertices will ask (dense fine levels), else gathered on demand and cached.
    bool precomputedNeighbourhoods = false;
    CoarseNeighbourhoods neighbourhoods;
  };
  // Coarse particles near the last ancestor vertex gathered on one coarser level: those of
  // plain vertices, and the crowded vertices (slots), whose particles are pruned by position.
  struct AncestorCache {
    std::uint64_t ancestorKey = ~std::uint64_t(0);
    std::vector<std::int32_t> candidates;
    std::vector<std::int32_t> crowdedVertices;
  };

  // The traversal; onPair(a, b) receives positions in the sorted arrays.
  // pruneScale: pairs of crowded vertices are skipped when a coordinate difference exceeds
  // (r_max + r_max' + 2 eps) pruneScale, a bound at or above the visitor's cut-off.
  template <class PairFunction>
  void sweep(PairFunction&& onPair, double pruneScale);
  // One level of the sweep; returns its virtual links. kCrowded: the level or a coarser one
  // holds crowded vertices (else their branches are compiled out).
  template <bool kCrowded, class PairFunction>
  std::uint64_t sweepLevel(int l, PairFunction& onPair, double pruneScale, std::uint64_t& comparisons);
  // Pairs of two vertex-connected vertices of one level, at least one of them crowded: only
  // particles within reach of the other vertex's bounding box take part (a slab along the
  // shared face, edge or corner), then a sweep along x; without the slabs when the pair reach
  // is not small against the mesh size (dense crowded vertices: they would keep everything).
  // Returns the comparisons made. Out of line, so that the plain path of the sweep stays small.
  template <class PairFunction>
  [[gnu::noinline]] std::uint64_t sweepCrowdedPair(const Level& level, const Vertex& v, const Vertex& nb,
                                                   double halo, double pruneScale, PairFunction& onPair);
  // Relative margin of that bound over the cut-off (round-off of the x difference).
  static constexpr double kPruneMargin = 1e-9;
  int hostLevel(double required) const;
  // Checks positions and radii; returns the bounding box and the radius range.
  static void validate(const double (*x)[3], const double* radius, int n, double lo[3],
                       double hi[3], double& minRadius, double& maxRadius);
  void clear(int n, int nActive);  // forget the last build
  void resetLevels(const std::array<double, 3>& origin, double rootSize, int depth);
  void placeParticles(const double (*x)[3], const double* radius, int n, const int* hostLevel);
  // Orders the particles [begin, end) of one crowded vertex; returns its bigBegin.
  std::int32_t orderCrowdedVertex(std::int32_t begin, std::int32_t end, const double (*x)[3], const double* radius);
  void gatherAncestorNeighbourhood(int coarseLevel, std::int64_t ai, std::int64_t aj,
                                   std::int64_t ak, AncestorCache& out) const;
  bool isActive(std::int32_t sorted) const { return sortedId_[sorted] < nActive_; }
  // Virtual link: coarse particle q lies within r_q + linkReach of the vertex at (vx, vy, vz).
  bool linksTo(std::int32_t q, double vx, double vy, double vz, double linkReach) const {
    const double dx = sx_[q] - vx, dy = sy_[q] - vy, dz = sz_[q] - vz;
    const double reach = sr_[q] + linkReach;
    return dx * dx + dy * dy + dz * dz < reach * reach;
  }
  // The positions q in [first, last) that link to the vertex, into linkHits_ (branch-free: in
  // a crowded vertex's window most candidates miss); returns their count.
  std::int32_t collectLinks(std::int32_t first, std::int32_t last, double vx, double vy, double vz,
                            double linkReach) {
    if (linkHits_.size() < std::size_t(last - first)) linkHits_.resize(std::size_t(last - first));
    std::int32_t* out = linkHits_.data();
    std::int32_t count = 0;
    for (std::int32_t q = first; q < last; ++q) {
      out[count] = q;
      count += linksTo(q, vx, vy, vz, linkReach) ? 1 : 0;
    }
    return count;
  }

  // Second and third pruned axes of a pair already within reach along x (y, z differences as
  // the visitor computes them, up to sign).
  bool withinYZ(std::int32_t a, std::int32_t b, double reach) const {
    return std::abs(sy_[a] - sy_[b]) <= reach && std::abs(sz_[a] - sz_[b]) <= reach;
  }
  Box boxOf(std::int32_t begin, std::int32_t end) const;  // of the centres in [begin, end)
  // Box of the vertex's [begin, bigBegin): stored for crowded vertices, computed otherwise.
  Box smallBox(const Level& level, const Vertex& v) const;
  // Positions [begin, end) ordered by x: the first one with x - x_q <= reach, and the first
  // one after it with x_q - x > reach. Bounds are tested on coordinate differences, as the
  // visitor's distance is, so rounding cannot drop a pair the visitor would accept.
  std::int32_t firstWithinX(std::int32_t begin, std::int32_t end, double x, double reach) const {
    return std::int32_t(std::partition_point(sx_.data() + begin, sx_.data() + end,
                                             [&](double xq) { return x - xq > reach; }) -
                        sx_.data());
  }
  std::int32_t endWithinX(std::int32_t begin, std::int32_t end, double x, double reach) const {
    return std::int32_t(std::partition_point(sx_.data() + begin, sx_.data() + end,
                                             [&](double xq) { return xq - x <= reach; }) -
                        sx_.data());
  }
  // Positions in [begin, end) (ordered by x when sorted) whose centre lies within `reach` of
  // the box on every axis, in order; their own bounding box goes to `near`.
  void particlesNearBox(std::int32_t begin, std::int32_t end, bool sorted, const Box& box, double reach,
                        std::vector<std::int32_t>& out, Box& near) const;

  SpacetreeOptions options_;
  double rootSize_ = 0.0;
  std::array<double, 3> origin_{0.0, 0.0, 0.0};
  std::vector<Level> levels_;
  int nActive_ = 0;

  // Particles sorted by (level, vertex key), structure of arrays for streaming access.
  std::vector<double> sx_, sy_, sz_, sr_;
  std::vector<std::int32_t> sortedId_;
  std::vector<std::int32_t> particleLevel_;  // by original index

  // Scratch, kept to avoid allocation on every build.
  std::vector<KeyedIndex> sortKeys_, sortScratch_;
  std::vector<AncestorCache> ancestorCaches_;
  std::vector<int> populatedCoarser_;
  struct XAndId {
    double x;
    std::int32_t id;
  };
  void sortByXThenId(std::vector<XAndId>& records);
  static constexpr std::int32_t kLargestBucket = 16;  // else std::sort
  std::vector<XAndId> byX_, byXScratch_;
  std::vector<std::int32_t> bucketFirst_;
  std::vector<std::int32_t> bigIds_;
  std::vector<double> scratchValues_;
  std::vector<std::int32_t> nearA_, nearB_;  // sweepCrowdedPair
  std::vector<std::int32_t> linkHits_;       // collectLinks

  SpacetreeStatistics stats_;
};

// The 13 neighbour offsets that are lexicographically positive: each unordered pair of
// vertex-connected vertices is visited from exactly one side.
inline constexpr std::array<std::array<int, 3>, 13> kForwardNeighbourOffsets{{
    {1, -1, -1}, {1, -1, 0}, {1, -1, 1}, {1, 0, -1}, {1, 0, 0}, {1, 0, 1}, {1, 1, -1},
    {1, 1, 0}, {1, 1, 1}, {0, 1, -1}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}}};

template <class PairFunction>
void Spacetree::sweep(PairFunction&& onPair, double pruneScale) {
  std::uint64_t candidatePairs = 0;
  const int nLevels = int(levels_.size());
  for (auto& level : stats_.levels) level.virtualLinks = 0;
  ancestorCaches_.resize(nLevels);
  for (auto& cache : ancestorCaches_) cache.ancestorKey = ~std::uint64_t(0);

  for (int l = 0; l < nLevels; ++l) {
    const Level& level = levels_[l];
    if (level.vertices.empty()) continue;
    populatedCoarser_.clear();
    bool crowded = !level.boxes.empty();
    for (int m = 0; m < l; ++m) {
      if (levels_[m].vertices.empty()) continue;
      populatedCoarser_.push_back(m);
      crowded = crowded || !levels_[m].boxes.empty();
    }
    // A level without crowded vertices, below none, runs the plain loop (its own code).
    stats_.levels[l].virtualLinks = crowded ? sweepLevel<true>(l, onPair, pruneScale, candidatePairs)
                                            : sweepLevel<false>(l, onPair, pruneScale, candidatePairs);
  }
  stats_.candidatePairs = candidatePairs;
}

template <bool kCrowded, class PairFunction>
std::uint64_t Spacetree::sweepLevel(int l, PairFunction& onPair, double pruneScale, std::uint64_t& comparisons) {
  std::uint64_t candidatePairs = 0;  // local: kept in a register
  const double halo = 2.0 * options_.epsilon;
  const double sqrt3 = std::sqrt(3.0);
  const Level& level = levels_[l];
  const double h = level.meshSize;
  // Virtual-link radius beyond the coarse particle's own radius (paper: r + 2 eps + h sqrt(d)).
  const double linkReach = 2.0 * options_.epsilon + sqrt3 * h;
  std::uint64_t virtualLinks = 0;
  const bool dense = level.lookup.dense();
  std::array<std::int64_t, kForwardNeighbourOffsets.size()> denseOffsets{};
  if (dense)
    for (std::size_t n = 0; n < denseOffsets.size(); ++n)
      denseOffsets[n] = level.lookup.denseOffset(kForwardNeighbourOffsets[n][0],
                                                 kForwardNeighbourOffsets[n][1],
                                                 kForwardNeighbourOffsets[n][2]);

  for (const Vertex& v : level.vertices) {
    // 1. Real particles of this vertex among themselves.
    const bool allActive = v.active == v.end - v.begin;  // no ghost: skip per-pair checks
    if (kCrowded && v.sortedByX()) {
      const double reach = (2.0 * v.maxSmallRadius + halo) * pruneScale;
      for (std::int32_t a = v.begin; a < v.bigBegin; ++a)
        for (std::int32_t b = a + 1; b < v.bigBegin && sx_[b] - sx_[a] <= reach; ++b) {
          if (!withinYZ(a, b, reach)) continue;
          if (allActive || isActive(a) || isActive(b)) onPair(a, b);
          ++candidatePairs;
        }
      for (std::int32_t b = v.bigBegin; b < v.end; ++b)  // the big ones against all before them
        for (std::int32_t a = v.begin; a < b; ++a)
          if (allActive || isActive(a) || isActive(b)) onPair(a, b);
      candidatePairs += std::uint64_t(v.end - v.bigBegin) * (v.end - v.bigBegin - 1) / 2 +
                        std::uint64_t(v.end - v.bigBegin) * (v.bigBegin - v.begin);
    } else {
      for (std::int32_t a = v.begin; a < v.end; ++a)
        for (std::int32_t b = a + 1; b < v.end; ++b)
          if (allActive || isActive(a) || isActive(b)) onPair(a, b);
      candidatePairs += std::uint64_t(v.end - v.begin) * (v.end - v.begin - 1) / 2;
    }

    // 2. Against the real particles of the forward vertex-connected neighbours.
    const std::int64_t position =
        dense ? level.lookup.densePosition(v.index.i, v.index.j, v.index.k) : 0;
    for (int n = 0; n < int(kForwardNeighbourOffsets.size()); ++n) {
      const auto& o = kForwardNeighbourOffsets[n];
      const std::int32_t w =
          dense ? level.lookup.atDensePosition(position + denseOffsets[n])
                : level.lookup.find(std::int64_t(v.index.i) + o[0], std::int64_t(v.index.j) + o[1],
                                    std::int64_t(v.index.k) + o[2]);
      if (w == VertexLookup::kAbsent) continue;
      const Vertex& nb = level.vertices[w];
      if (v.active == 0 && nb.active == 0) continue;
      if constexpr (kCrowded) {
        if (v.sortedByX() || nb.sortedByX()) {
          candidatePairs += sweepCrowdedPair(level, v, nb, halo, pruneScale, onPair);
          continue;
        }
      }
      if (allActive || nb.active == nb.end - nb.begin) {
        for (std::int32_t a = v.begin; a < v.end; ++a)
          for (std::int32_t b = nb.begin; b < nb.end; ++b) onPair(a, b);
      } else {
        for (std::int32_t a = v.begin; a < v.end; ++a)
          for (std::int32_t b = nb.begin; b < nb.end; ++b)
            if (isActive(a) || isActive(b)) onPair(a, b);
      }
      candidatePairs += std::uint64_t(v.end - v.begin) * (nb.end - nb.begin);
    }

    // 3. Against virtual links: real particles of coarser levels near this vertex. They are
    //    found through the nearest vertex (ancestor) on each coarser populated level, whose
    //    3x3x3 neighbourhood holds every coarse particle that can reach this vertex.
    const double vx = origin_[0] + v.index.i * h;
    const double vy = origin_[1] + v.index.j * h;
    const double vz = origin_[2] + v.index.k * h;
    // A link to coarse particle q pairs it with this vertex's particles; on a crowded vertex
    // only with those whose x lies within reach of q's.
    auto linked = [&](std::int32_t q) {
      ++virtualLinks;
      const bool qActive = isActive(q);
      if (!qActive && v.active == 0) return;
      std::int32_t smallBegin = v.begin, smallEnd = v.bigBegin;  // the whole vertex if plain
      if (kCrowded && v.sortedByX()) {
        const double pairReach = (sr_[q] + v.maxSmallRadius + halo) * pruneScale;
        smallBegin = firstWithinX(v.begin, v.bigBegin, sx_[q], pairReach);
        smallEnd = endWithinX(smallBegin, v.bigBegin, sx_[q], pairReach);
      }
      for (std::int32_t a = smallBegin; a < smallEnd; ++a)
        if (qActive || allActive || isActive(a)) onPair(a, q);
      for (std::int32_t a = v.bigBegin; a < v.end; ++a)
        if (qActive || allActive || isActive(a)) onPair(a, q);
      candidatePairs += std::uint64_t(smallEnd - smallBegin) + std::uint64_t(v.end - v.bigBegin);
    };
    auto link = [&](std::int32_t q) {
      if (linksTo(q, vx, vy, vz, linkReach)) linked(q);
    };
    for (int m : populatedCoarser_) {
      const Level& coarse = levels_[m];
      const std::int64_t s = kPowersOfThree[l - m];
      const std::int64_t half = (s - 1) / 2;  // s is odd: nearest coarse vertex, no ties
      const std::int64_t ai = (std::int64_t(v.index.i) + half) / s;
      const std::int64_t aj = (std::int64_t(v.index.j) + half) / s;
      const std::int64_t ak = (std::int64_t(v.index.k) + half) / s;
      CoarseNeighbourhoods::Neighbourhood candidates;
      if (coarse.precomputedNeighbourhoods) {
        candidates = coarse.neighbourhoods.near(ai, aj, ak);
      } else {
        AncestorCache& cache = ancestorCaches_[m];
        const std::uint64_t ancestorKey = packVertexKey(ai, aj, ak);
        if (cache.ancestorKey != ancestorKey) {
          cache.ancestorKey = ancestorKey;
          gatherAncestorNeighbourhood(m, ai, aj, ak, cache);
        }
        candidates.particles = {cache.candidates.data(), cache.candidates.data() + cache.candidates.size()};
        candidates.crowdedVertices = {cache.crowdedVertices.data(),
                                      cache.crowdedVertices.data() + cache.crowdedVertices.size()};
      }
      for (const std::int32_t* c = candidates.particles.begin; c != candidates.particles.end; ++c) link(*c);
      if constexpr (kCrowded) {
        // Crowded coarse vertices: only particles whose x lies within reach of the vertex can
        // link (and none when the vertex is beyond reach of the box on any axis).
        for (const std::int32_t* c = candidates.crowdedVertices.begin; c != candidates.crowdedVertices.end; ++c) {
          const Vertex& u = coarse.vertices[*c];
          const Box& box = coarse.boxes[u.box];
          const double reach = (u.maxSmallRadius + linkReach) * (1.0 + kPruneMargin);
          if (box.lo[0] - vx <= reach && vx - box.hi[0] <= reach && box.lo[1] - vy <= reach &&
              vy - box.hi[1] <= reach && box.lo[2] - vz <= reach && vz - box.hi[2] <= reach) {
            const std::int32_t first = firstWithinX(u.begin, u.bigBegin, vx, reach);
            const std::int32_t count =
                collectLinks(first, endWithinX(first, u.bigBegin, vx, reach), vx, vy, vz, linkReach);
            for (std::int32_t t = 0; t < count; ++t) linked(linkHits_[std::size_t(t)]);
          }
          for (std::int32_t q = u.bigBegin; q < u.end; ++q) link(q);
        }
      }
    }
  }
  comparisons += candidatePairs;
  return virtualLinks;
}

template <class PairFunction>
std::uint64_t Spacetree::sweepCrowdedPair(const Level& level, const Vertex& v, const Vertex& nb, double halo,
                                          double pruneScale, PairFunction& onPair) {
  const bool bothActive = v.active == v.end - v.begin && nb.active == nb.end - nb.begin;
  std::uint64_t comparisons = 0;
  // The ordinary particles: those of v near nb's box, and those of nb near theirs.
  const double reach = (v.maxSmallRadius + nb.maxSmallRadius + halo) * pruneScale;
  if (4.0 * reach >= level.meshSize) {
    if (v.sortedByX() && nb.sortedByX()) {
      // Both in x order: a window of nb's per particle of v.
      std::int32_t start = nb.begin;
      for (std::int32_t a = v.begin; a < v.bigBegin; ++a) {
        const double xa = sx_[a];
        while (start < nb.bigBegin && xa - sx_[start] > reach) ++start;
        for (std::int32_t b = start; b < nb.bigBegin && sx_[b] - xa <= reach; ++b) {
          if (!withinYZ(a, b, reach)) continue;
          if (bothActive || isActive(a) || isActive(b)) onPair(a, b);
          ++comparisons;
        }
      }
    } else {
      for (std::int32_t a = v.begin; a < v.bigBegin; ++a)
        for (std::int32_t b = nb.begin; b < nb.bigBegin; ++b)
          if (bothActive || isActive(a) || isActive(b)) onPair(a, b);
      comparisons += std::uint64_t(v.bigBegin - v.begin) * (nb.bigBegin - nb.begin);
    }
  } else {
    Box nearV, nearNb;
    particlesNearBox(v.begin, v.bigBegin, v.sortedByX(), smallBox(level, nb), reach, nearA_, nearV);
    if (!nearA_.empty()) {
      particlesNearBox(nb.begin, nb.bigBegin, nb.sortedByX(), nearV, reach, nearB_, nearNb);
      if (v.sortedByX() && nb.sortedByX()) {
        // Both in x order: a window of nb's per particle of v.
        std::size_t start = 0;
        for (const std::int32_t a : nearA_) {
          const double xa = sx_[a];
          while (start < nearB_.size() && xa - sx_[nearB_[start]] > reach) ++start;
          for (std::size_t t = start; t < nearB_.size() && sx_[nearB_[t]] - xa <= reach; ++t) {
            const std::int32_t b = nearB_[t];
            if (!withinYZ(a, b, reach)) continue;
            if (bothActive || isActive(a) || isActive(b)) onPair(a, b);
            ++comparisons;
          }
        }
      } else {
        for (const std::int32_t a : nearA_)
          for (const std::int32_t b : nearB_)
            if (bothActive || isActive(a) || isActive(b)) onPair(a, b);
        comparisons += std::uint64_t(nearA_.size()) * nearB_.size();
      }
    }
  }
  // The big ones of either vertex against everything of the other, unpruned.
  if (nb.bigBegin < nb.end)
    for (std::int32_t a = v.begin; a < v.bigBegin; ++a)
      for (std::int32_t b = nb.bigBegin; b < nb.end; ++b)
        if (bothActive || isActive(a) || isActive(b)) onPair(a, b);
  for (std::int32_t a = v.bigBegin; a < v.end; ++a)
    for (std::int32_t b = nb.begin; b < nb.end; ++b)
      if (bothActive || isActive(a) || isActive(b)) onPair(a, b);
  comparisons += std::uint64_t(v.bigBegin - v.begin) * (nb.end - nb.bigBegin) +
                 std::uint64_t(v.end - v.bigBegin) * (nb.end - nb.begin);
  return comparisons;
}

}  // namespace spacetree
