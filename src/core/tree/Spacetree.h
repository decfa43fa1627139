// Multilevel spacetree neighbour search (paper §4): a cascade of 3-way refined Cartesian
// grids. Each particle is a *real* particle of the finest level whose mesh size h still
// satisfies h >= 2(r + eps), hosted by the vertex nearest its centre. Coarser (bigger)
// particles appear on finer vertices as *virtual links*, so every pair is found bottom-up on
// the level of its smaller particle:
//   - same level: a vertex against itself and its 13 "forward" neighbours (symmetry);
//   - across levels: a vertex against its virtual links, i.e. the coarser real particles whose
//     centre lies within linkRadius(r, h) of the vertex (r + 2 eps + h (1 + sqrt(3)) / 2: the
//     farthest a partner on that vertex can reach, tighter than the paper's projection radius
//     r + 2 eps + h sqrt(3)) and whose vertex is one of the 3x3x3 around the finer vertex's
//     nearest coarse vertex.
// Levels are sparse: only vertices that host particles exist, so the memory is per particle,
// not per domain volume. The tree is rebuilt from scratch by build(); drop (to the finest
// admissible level) and lift (to a coarser one when a particle grows) happen there.
//
// No look-up tables: each level keeps its vertices sorted by (i, j, k) and grouped in rows of
// equal (i, j). The forward neighbours of the vertices are found by walking the sorted list
// with one cursor per neighbouring row (a fixed offset keeps the key order, so the cursors only
// move forward), and the virtual links by each coarse particle visiting the finer vertices
// inside its link ball, row by row (a binary search per row for the ball's k interval): the
// cost of a big particle follows the vertices near its surface, not its volume, and vertices
// far from every coarse particle cost nothing. Where the coarse level is sparse and the finer
// one holds many vertices (a dilute cloud of continuous sizes: thousands of balls each
// crossing dozens of rows to find a vertex or two), each finer vertex instead reads the coarse
// level's occupancy bitmap around its nearest coarse vertex (VertexBitmap: one bit read for
// most), whichever a cost estimate finds cheaper (linkFromFineVertices); the links are the same.
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
#include <type_traits>
#include <vector>

#include "tree/DenseLevel.h"
#include "tree/GridGeometry.h"
#include "tree/RadixSort.h"
#include "tree/RunTest.h"
#include "tree/SpacetreeStatistics.h"
#include "tree/VertexBitmap.h"
#include "tree/VertexKey.h"

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
    if (dense_.built()) {
      stats_.candidatePairs = dense_.forEachCandidatePair(visit);
      return;
    }
    sweep(CandidateVisitor<Visitor>{*this, visit}, 1.0 + kPruneMargin);
  }

  // Like forEachCandidatePair, but only pairs with
  //   dx^2 + dy^2 + dz^2 <= ((r_i + r_j + 2 eps) (1 + relativeTolerance))^2
  // reach the visitor, as visit(i, j, squaredDistance), evaluated in that order on the tree's own sorted copies (streaming
  // access); a visitor taking visit(i, j, squaredDistance, radiusSum) also gets r_i + r_j. With tolerance 0 this is bit for bit the cut-off of LIGGGHTS' granular builders
  // (contact_distance_factor 1); a small tolerance makes it a superset of other roundings.
  template <class Visitor>
  void forEachPairWithin(Visitor&& visit, double relativeTolerance = 0.0) {
    const double scale = 1.0 + relativeTolerance;
    if (dense_.built()) {
      stats_.candidatePairs = dense_.forEachPairWithin(visit, 2.0 * options_.epsilon, scale);
      return;
    }
    sweep(WithinVisitor<Visitor>(*this, visit, 2.0 * options_.epsilon, scale), scale * (1.0 + kPruneMargin));
  }

  int levelOf(int particle) const { return dense_.built() ? levelCount() - 1 : particleLevel_[particle]; }
  int particleCount() const { return particleCount_; }  // of the last build
  // Whether the last build took the dense one-level path (DenseLevel.h): every particle on the
  // finest level, its occupied vertices at least a quarter of their box, none crowded. Only a
  // build on a cube of the tree's own (not on a caller's grid) takes it.
  bool usesDenseLevel() const { return dense_.built(); }
  int levelCount() const { return int(levels_.size()); }
  double meshSize(int level) const { return levels_[level].meshSize; }
  // Virtual-link radius of a coarser particle of radius r on the vertices of a level of mesh
  // size h: a particle p hosted there lies within h sqrt(3) / 2 of its (nearest) vertex and has
  // r_p <= h / 2 - eps (h >= 2 (r_p + eps)), so a pair within the cut-off r + r_p + 2 eps has
  // the vertex within r + eps + h (1 + sqrt(3)) / 2 of the coarse centre. One more eps and a
  // relative margin cover the round-off of the vertex coordinates and the caller's tolerance.
  double linkRadius(double r, double h) const {
    return (r + 2.0 * options_.epsilon + kLinkMeshFactor * h) * (1.0 + kPruneMargin);
  }
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
  // 20 bytes: a dense level holds about one vertex per particle. The (i, j, k) index is in
  // Level::keys (indexOf); what only crowded vertices need is in Level::crowds.
  struct Vertex {
    std::int32_t begin, end;  // range of hosted particles in the sorted arrays
    std::int32_t active;      // how many of them are active
    std::int32_t bigBegin;    // crowded: [bigBegin, end) holds the much bigger ones, unsorted; else end
    std::int32_t box;         // crowded: its entry in Level::crowds, else -1
    // Crowded: [begin, bigBegin) is ordered by x (sweep and prune).
    bool sortedByX() const { return box >= 0; }
  };
  // Bounding box of particle centres.
  struct Box {
    double lo[3], hi[3];
  };
  // A crowded vertex's [begin, bigBegin): the box of the centres and the largest radius.
  struct Crowd {
    Box box;
    double maxSmallRadius;
  };
  // Vertices holding at least this many particles are crowded (see the top of this file).
  // Regular levels rarely reach it; coarse levels holding a lifted cloud (reluctant grid) do.
  static constexpr std::int32_t kSweepAndPruneMinParticles = 8;
  static constexpr double kBigRadiusOverMedian = 4.0;
  // Whether sweep and prune pays on a vertex of mesh size h holding the particles [begin, end):
  // when even its smallest pair reach 2 r_min + 2 eps is a quarter of the cell or more (a dense
  // pack at its finest level, several particles per cell) an x window keeps most of a
  // neighbour's particles, and the branch-free block test of the plain path is cheaper, up to
  // kDenseCrowdMinParticles (beyond that the plain path's pairs grow too fast).
  bool worthPruning(std::int32_t begin, std::int32_t end, double h) const {
    if (end - begin >= kDenseCrowdMinParticles) return true;
    double smallest = sr_[begin];
    for (std::int32_t q = begin + 1; q < end; ++q) smallest = std::min(smallest, sr_[q]);
    return 4.0 * (2.0 * smallest + 2.0 * options_.epsilon) < h;
  }
  static constexpr std::int32_t kDenseCrowdMinParticles = 24;
  // The vertices of one level sharing (i, j): [begin, end) in Level::vertices, ordered by k;
  // the rows sharing i form a slice, [firstRow, next slice's firstRow) in Level::rows.
  struct Row {
    std::int32_t j, begin, end;
  };
  struct Slice {
    std::int32_t i, firstRow;
  };
  struct Level {
    double meshSize = 0.0;
    std::vector<Vertex> vertices;         // sorted by key: (i, j, k) lexicographically
    std::vector<std::uint64_t> keys;      // their packed keys (the walks read only these)
    std::vector<Row> rows;                // sorted by (i, j)
    std::vector<Slice> slices;            // sorted by i, and a last one past the end
    std::vector<Crowd> crowds;            // of the crowded vertices
    double radiusSum = 0.0, radiusSquaredSum = 0.0;  // of its particles (link cost estimates)
    VertexBitmap occupancy;               // built by the sweep when finer vertices look up this level
    bool occupancyBuilt = false;          // in this build
  };
  static VertexIndex indexOf(const Level& level, std::size_t slot) { return unpackVertexKey(level.keys[slot]); }
  // Largest radius of [begin, bigBegin): stored for crowded vertices, computed otherwise.
  double maxSmallRadius(const Level& level, const Vertex& v) const {
    if (v.box >= 0) return level.crowds[std::size_t(v.box)].maxSmallRadius;
    double r = 0.0;
    for (std::int32_t q = v.begin; q < v.bigBegin; ++q) r = std::max(r, sr_[q]);
    return r;
  }

  // What the traversal calls (positions in the sorted arrays): onPair(a, b) for one candidate
  // pair, onPair.runs(aBegin, aEnd, from, to, triangle) for each a of [aBegin, aEnd), in
  // order, against each of the contiguous positions [from, to) (triangle: [a + 1, to)) in
  // order, skipping the pairs of two inactive particles, and onPair.vertexRuns(aBegin, aEnd,
  // runs, nRuns) for the same on each run in turn, the first a triangle (the runs of one
  // vertex); onPair.finish() once at the end of the sweep. Candidates go to the visitor as they
  // are; pairs within the cut-off are selected in blocks (see WithinVisitor).
  template <class Visit>
  struct CandidateVisitor {
    const Spacetree& tree;
    Visit& visit;
    void operator()(std::int32_t a, std::int32_t b) const { visit(tree.sortedId_[a], tree.sortedId_[b]); }
    void runs(std::int32_t aBegin, std::int32_t aEnd, std::int32_t from, std::int32_t to, bool triangle) const {
      for (std::int32_t a = aBegin; a < aEnd; ++a) {
        const bool aActive = tree.isActive(a);
        for (std::int32_t b = triangle ? a + 1 : from; b < to; ++b)
          if (aActive || tree.isActive(b)) (*this)(a, b);
      }
    }
    void vertexRuns(std::int32_t aBegin, std::int32_t aEnd, const CandidateRun* list, int nRuns) const {
      for (int run = 0; run < nRuns; ++run) runs(aBegin, aEnd, list[run].from, list[run].to, run == 0);
    }
    void finish() const {}
  };
  // Candidates are queued (in sweep order) and tested a block at a time: one branch-free pass
  // computes every distance and keeps the positions within the cut-off, then the hits are
  // visited in order. On a dense level most candidates miss and most runs are short (one
  // particle per vertex against the 2-3 of a neighbouring row), so testing them as they come
  // would pay a mispredicted branch per run; the block pass pays none. On a level of several
  // particles per vertex the runs of a vertex are pre-tested where they are found (RunTest.h),
  // so only the pairs near or within the cut-off are queued.
  template <class Visit>
  struct WithinVisitor {
    const Spacetree& tree;
    Visit& visit;
    double halo, scale;
    bool allActive;  // no inactive particle: no activity test per hit
    static constexpr std::int32_t kBlock = 1024, kShortRun = 4;
    static constexpr std::int32_t kSlack = std::max(kShortRun, kRunTestSlack);
    static constexpr std::int32_t kQueuedRun = 16;  // see testRun
    std::int32_t queued = 0;
    // not initialised: filled before read; slack for the short-run and run-test writes
    std::int32_t first[kBlock + kSlack], second[kBlock + kSlack], hit[kBlock + kSlack];
    const RunTest testCandidates = selectedRunTest();
    const RunTestParticles particles;

    WithinVisitor(const Spacetree& t, Visit& v, double h, double s)
        : tree(t), visit(v), halo(h), scale(s), allActive(t.nActive_ >= t.particleCount()),
          particles{t.sx_.data(), t.sy_.data(), t.sz_.data(), t.sr_.data(), h, s} {}
    double distanceSquared(std::int32_t a, std::int32_t b) const {
      const double dx = tree.sx_[a] - tree.sx_[b], dy = tree.sy_[a] - tree.sy_[b], dz = tree.sz_[a] - tree.sz_[b];
      return dx * dx + dy * dy + dz * dz;
    }
    double cut(std::int32_t a, std::int32_t b) const { return (tree.sr_[a] + tree.sr_[b] + halo) * scale; }
    // The visitor gets (i, j, squaredDistance), or with a fourth parameter also r_i + r_j as
    // the tree holds them (the caller's radii: no look-up of its arrays per pair).
    void emit(std::int32_t a, std::int32_t b, double d2) const {
      if constexpr (std::is_invocable_v<Visit&, int, int, double, double>)
        visit(tree.sortedId_[a], tree.sortedId_[b], d2, tree.sr_[a] + tree.sr_[b]);
      else
        visit(tree.sortedId_[a], tree.sortedId_[b], d2);
    }
    // The callers queue only pairs with an active particle, except runs() for an inactive a,
    // whose pairs with inactive particles the flush drops.
    void operator()(std::int32_t a, std::int32_t b) {
      first[queued] = a;
      second[queued] = b;
      if (++queued == kBlock) flush();
    }
    void runs(std::int32_t aBegin, std::int32_t aEnd, std::int32_t from, std::int32_t to, bool triangle) {
      if (to - (triangle ? aBegin + 1 : from) > kShortRun) {
        testRun(aBegin, aEnd, from, to, triangle);
        return;
      }
      // Short runs (a dense level: the 0-3 particles of a forward row's k - 1 .. k + 1) are
      // each written as kShortRun slots whatever their length, and counted by their length:
      // no branch on the length, which varies from run to run.
      for (std::int32_t a = aBegin; a < aEnd; ++a) {
        const std::int32_t b0 = triangle ? a + 1 : from;
        for (std::int32_t t = 0; t < kShortRun; ++t) {
          first[queued + t] = a;
          second[queued + t] = b0 + t;
        }
        queued += std::max(to - b0, 0);
        if (queued >= kBlock) flush();
      }
    }
    void vertexRuns(std::int32_t aBegin, std::int32_t aEnd, const CandidateRun* list, int nRuns) {
      testRuns(aBegin, aEnd, list, nRuns, true);
    }
    // A longer run of a level of about one particle per vertex (a few are): queued whole up to
    // kQueuedRun candidates per particle (the pre-test, called now and then, costs more there),
    // else pre-tested.
    [[gnu::noinline]] void testRun(std::int32_t aBegin, std::int32_t aEnd, std::int32_t from, std::int32_t to,
                                   bool triangle) {
      if (to - (triangle ? aBegin + 1 : from) > kQueuedRun) {
        const CandidateRun run{from, to};
        testRuns(aBegin, aEnd, &run, 1, triangle);
        return;
      }
      for (std::int32_t a = aBegin; a < aEnd; ++a)
        for (std::int32_t b = triangle ? a + 1 : from; b < to;) {
          const std::int32_t take = std::min(to - b, kBlock - queued);
          for (std::int32_t t = 0; t < take; ++t) {
            first[queued + t] = a;
            second[queued + t] = b + t;
          }
          queued += take;
          b += take;
          if (queued == kBlock) flush();
        }
    }
    // Pre-tests the runs, all at once when they fit in a block. Out of line: a dense pack of
    // one particle per vertex never comes here.
    [[gnu::noinline]] void testRuns(std::int32_t aBegin, std::int32_t aEnd, const CandidateRun* list, int nRuns,
                                    bool triangle) {
      const std::int64_t n = aEnd - aBegin;
      std::int64_t count = 0;
      for (int run = 0; run < nRuns; ++run)
        count += run == 0 && triangle ? n * (list[0].to - aBegin - 1) - n * (n - 1) / 2
                                      : n * (list[run].to - list[run].from);
      if (count <= kBlock) {
        if (queued + count > kBlock) flush();
        queued = testCandidates(particles, aBegin, aEnd, list, nRuns, triangle, first, second, queued);
      } else {
        for (int run = 0; run < nRuns; ++run)
          for (std::int32_t a = aBegin; a < aEnd; ++a)
            for (std::int32_t b = run == 0 && triangle ? a + 1 : list[run].from; b < list[run].to;) {
              if (queued == kBlock) flush();
              const CandidateRun chunk{b, std::min(list[run].to, b + kBlock - queued)};
              queued = testCandidates(particles, a, a + 1, &chunk, 1, false, first, second, queued);
              b = chunk.to;
            }
      }
      if (queued >= kBlock) flush();
    }
    void flush() {
      std::int32_t hits = 0;
      for (std::int32_t t = 0; t < queued; ++t) {
        const std::int32_t a = first[t], b = second[t];
        const double d2 = distanceSquared(a, b), c = cut(a, b);
        hit[hits] = t;
        hits += d2 <= c * c ? 1 : 0;
      }
      for (std::int32_t h = 0; h < hits; ++h) {
        const std::int32_t a = first[hit[h]], b = second[hit[h]];
        if (allActive || tree.isActive(a) || tree.isActive(b)) emit(a, b, distanceSquared(a, b));
      }
      queued = 0;
    }
    void finish() { flush(); }
  };
  // The traversal, calling onPair as above.
  // pruneScale: pairs of crowded vertices are skipped when a coordinate difference exceeds
  // (r_max + r_max' + 2 eps) pruneScale, a bound at or above the visitor's cut-off.
  template <class PairFunction>
  void sweep(PairFunction&& onPair, double pruneScale);
  // Pairs within the vertices of level l and between forward neighbours. kCrowded: the level
  // holds crowded vertices (else their branches are compiled out).
  // kByVertex: a level of several particles per vertex, whose runs (mostly longer than the
  // visitor's short ones) go to it a vertex at a time.
  template <bool kCrowded, bool kByVertex, class PairFunction>
  void sweepLevel(int l, PairFunction& onPair, double pruneScale, std::uint64_t& comparisons);
  // Particles per vertex from which a level is swept kByVertex.
  static constexpr double kByVertexParticlesPerVertex = 1.5;
  // Whether the virtual links of coarse level m on finer level l are found from the fine
  // vertices (each looking up the 3x3x3 coarse vertices around it) rather than from the coarse
  // particles (link balls), by the estimated cost of each; `around` is then the coarse level's
  // bitmap when that is the cheaper look-up (built here), else nullptr.
  bool linkFromFineVertices(int m, int l, const VertexBitmap*& around);
  // Virtual links of the particles of coarse level m on the vertices of finer level l, and
  // their pairs; returns the links. kCrowded: level l or m holds crowded vertices.
  template <bool kCrowded, class PairFunction>
  std::uint64_t linkLevels(int m, int l, PairFunction& onPair, double pruneScale, std::uint64_t& comparisons,
                           std::uint64_t& tests);
  // The rows of `level` with (i, j) in [lo, hi], slice by slice: sliceRange(i, jLo, jHi) may
  // narrow the j range of a slice (false: skip it); then onRow(i, row) for each occupied row.
  template <class SliceRange, class OnRow>
  void forEachRowIn(const Level& level, const std::int64_t lo[2], const std::int64_t hi[2], SliceRange&& sliceRange,
                    OnRow&& onRow) const;
  // f(slot) for the vertices of the row with k in [k0, k1], in order.
  template <class F>
  static void forEachVertexInRow(const Level& level, const Row& row, std::int64_t k0, std::int64_t k1, F&& f);
  // f(slot) for the vertices of `level` with index in [lo, hi] per axis, in key order.
  template <class F>
  void forEachVertexIn(const Level& level, const std::int64_t lo[3], const std::int64_t hi[3], F&& f) const;
  // Pairs of two vertex-connected vertices of one level, at least one of them crowded: only
  // particles within reach of the other vertex's bounding box take part (a slab along the
  // shared face, edge or corner), then a sweep along x; without the slabs when the pair reach
  // is not small against the mesh size (dense crowded vertices: they would keep everything).
  // Returns the comparisons made. Out of line, so that the plain path of the sweep stays small.
  template <class PairFunction>
  [[gnu::noinline]] std::uint64_t sweepCrowdedPair(const Level& level, const Vertex& v, const Vertex& nb,
                                                   double halo, double pruneScale, PairFunction& onPair);
  // Vertex index bounds of a coordinate range, t = (x - origin) / h, padded by one vertex
  // (conversion truncates: for t < 0 it rounds up, which the padding still covers).
  static std::int64_t indexBelow(double t) { return std::int64_t(t) - 1; }
  static std::int64_t indexAbove(double t) { return std::int64_t(t) + 1; }
  // Relative margin of that bound over the cut-off (round-off of the x difference).
  static constexpr double kPruneMargin = 1e-9;
  // (1 + sqrt(3)) / 2: a level's mesh sizes in the virtual-link radius (linkRadius).
  static constexpr double kLinkMeshFactor = 1.3660254037844386;
  // Rows of at most this many vertices are tested whole, in one branch-free pass (a link ball).
  static constexpr std::int32_t kShortRow = 8;
  int hostLevel(double required) const;
  // Checks positions and radii; returns the bounding box and the radius range.
  static void validate(const double (*x)[3], const double* radius, int n, double lo[3],
                       double hi[3], double& minRadius, double& maxRadius);
  void clear(int n, int nActive);  // forget the last build
  void resetLevels(const std::array<double, 3>& origin, double rootSize, int depth);
  void placeParticles(const double (*x)[3], const double* radius, int n, const int* hostLevel);
  // The dense one-level path (DenseLevel.h) when the particles fit it; false: they do not.
  bool placeDense(const double (*x)[3], const double* radius, int n, const double hi[3], double minRadius,
                  double maxRadius);
  void releaseGeneralStorage();  // the dense path holds none of the general path's arrays
  // Its steps: the level and sort key of every particle, and, after the sort, the sorted arrays
  // and the levels' vertices; countMemory() sums the storage held.
  template <class Record>
  void keyParticles(const double (*x)[3], const double* radius, int n, const int* hostLevel,
                    const SortKeyPacking& packing, std::vector<Record>& records);
  template <class Record>
  void placeSorted(const std::vector<Record>& sorted, const SortKeyPacking& packing, const double (*x)[3],
                   const double* radius, int n);
  void countMemory();
  // Orders the particles [begin, end) of one crowded vertex; returns its bigBegin.
  std::int32_t orderCrowdedVertex(std::int32_t begin, std::int32_t end, const double (*x)[3], const double* radius);
  bool isActive(std::int32_t sorted) const { return sortedId_[sorted] < nActive_; }
  // Virtual link: coarse particle q lies within linkRadius(r_q, h) = (r_q + linkReach)
  // (1 + kPruneMargin) of the vertex at (vx, vy, vz).
  bool linksTo(std::int32_t q, double vx, double vy, double vz, double linkReach) const {
    const double dx = sx_[q] - vx, dy = sy_[q] - vy, dz = sz_[q] - vz;
    const double reach = (sr_[q] + linkReach) * (1.0 + kPruneMargin);
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
  // Of levels_, contiguous (hostLevel, keyParticles).
  double meshSizes_[kMaxSpacetreeLevel + 1] = {}, inverseMeshSizes_[kMaxSpacetreeLevel + 1] = {};
  int nActive_ = 0, particleCount_ = 0;

  // Particles sorted by (level, vertex key), structure of arrays for streaming access.
  std::vector<double> sx_, sy_, sz_, sr_;
  std::vector<std::int32_t> sortedId_;
  std::vector<std::int8_t> particleLevel_;  // by original index (levels 0..kMaxSpacetreeLevel)
  DenseLevel dense_;  // else: the dense one-level path

  // Scratch, kept to avoid allocation on every build.
  std::vector<KeyedIndex> sortKeys_, sortScratch_;        // keys of more than 32 bits
  std::vector<KeyedIndex32> sortKeys32_, sortScratch32_;  // else
  std::vector<int> populated_;  // levels hosting particles
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

}  // namespace spacetree

#include "tree/SpacetreeSweep.h"  // the traversal templates
