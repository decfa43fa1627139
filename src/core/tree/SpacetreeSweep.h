// The traversal of a built Spacetree (its member templates, included by Spacetree.h): per
// populated level the pairs within and between forward-neighbour vertices (sorted-key walk),
// then the virtual links of every coarser level's particles on its vertices (link balls, or,
// where that is estimated cheaper, each finer vertex looking up its coarse neighbourhood, in the
// coarse level's occupancy bitmap when it has one), and the pruned pairs of crowded vertices.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "tree/BranchlessSearch.h"
#include "tree/Spacetree.h"

namespace spacetree {

template <class PairFunction>
void Spacetree::sweep(PairFunction&& onPair, double pruneScale) {
  std::uint64_t candidatePairs = 0;
  const int nLevels = int(levels_.size());
  for (auto& level : stats_.levels) level.virtualLinks = level.linkTests = level.linkLookups = 0;
  populated_.clear();
  for (int l = 0; l < nLevels; ++l)
    if (!levels_[l].vertices.empty()) populated_.push_back(l);
  for (std::size_t f = 0; f < populated_.size(); ++f) {
    const int l = populated_[f];
    const bool crowded = !levels_[l].crowds.empty();
    // A level without crowded vertices runs the plain loop (its own code), a vertex at a time
    // when it holds several particles per vertex. That one out of line: inlined beside the
    // plain loop it costs the dense one-size packs 5-15 % of their LIGGGHTS list build.
    const Level& level = levels_[l];
    if (crowded)
      sweepLevel<true, false>(l, onPair, pruneScale, candidatePairs);
    else if (double(level.vertices.back().end - level.vertices.front().begin) >=
             kByVertexParticlesPerVertex * double(level.vertices.size()))
      [&]() __attribute__((noinline)) { sweepLevel<false, true>(l, onPair, pruneScale, candidatePairs); }();
    else
      sweepLevel<false, false>(l, onPair, pruneScale, candidatePairs);
    for (std::size_t c = 0; c < f; ++c) {
      const int m = populated_[c];
      stats_.levels[l].virtualLinks +=
          crowded || !levels_[m].crowds.empty()
              ? linkLevels<true>(m, l, onPair, pruneScale, candidatePairs, stats_.levels[l].linkTests)
              : linkLevels<false>(m, l, onPair, pruneScale, candidatePairs, stats_.levels[l].linkTests);
    }
  }
  onPair.finish();
  stats_.candidatePairs = candidatePairs;
}

template <bool kCrowded, bool kByVertex, class PairFunction>
void Spacetree::sweepLevel(int l, PairFunction& onPair, double pruneScale, std::uint64_t& comparisons) {
  std::uint64_t candidatePairs = 0;  // local: kept in a register
  const double halo = 2.0 * options_.epsilon;
  const Level& level = levels_[l];
  const std::size_t nv = level.vertices.size();
  const std::uint64_t* keys = level.keys.data();
  // Forward neighbours of vertex (i, j, k): (i, j, k + 1), and the rows (i, j + 1),
  // (i + 1, j - 1), (i + 1, j), (i + 1, j + 1) at k - 1 .. k + 1. Each row has a cursor at its
  // first vertex at or after k - 1: key + offset, with no carry between the fields (indices
  // are >= 0 and biased).
  constexpr std::uint64_t kJ = std::uint64_t(1) << kVertexKeyBits, kI = kJ << kVertexKeyBits;
  constexpr std::uint64_t kRowOffsets[4] = {kJ - 1, kI - kJ - 1, kI - 1, kI + kJ - 1};
  std::size_t cursor[4] = {0, 0, 0, 0};

  for (std::size_t p = 0; p < nv; ++p) {
    const Vertex& v = level.vertices[p];
    const std::uint64_t key = keys[p];
    const bool allActive = v.active == v.end - v.begin;  // no ghost: skip per-pair checks

    // Against the real particles of a forward vertex-connected neighbour, one by one.
    auto pairWith = [&](std::size_t w) {
      const Vertex& nb = level.vertices[w];
      if (v.active == 0 && nb.active == 0) return;
      if constexpr (kCrowded) {
        if (v.sortedByX() || nb.sortedByX()) {
          candidatePairs += sweepCrowdedPair(level, v, nb, halo, pruneScale, onPair);
          return;
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
    };
    // Whether vertices [t0, t1) are all plain (their particles are then one run of positions).
    auto plain = [&](std::size_t t0, std::size_t t1) {
      if constexpr (kCrowded) {
        for (std::size_t t = t0; t < t1; ++t)
          if (level.vertices[t].sortedByX()) return false;
      }
      return true;
    };

    if (v.active > 0 && plain(p, p + 1)) {
      // A plain vertex with an active particle: its particles after a, with those of a plain
      // (i, j, k + 1), are one run of positions (sorted by key); so are those of each forward
      // row's k - 1 .. k + 1 when all are plain. Each a goes against a whole run.
      const std::int32_t n = v.end - v.begin;
      const bool next = p + 1 < nv && keys[p + 1] == key + 1;
      const bool nextPlain = next && plain(p + 1, p + 2);
      const std::int32_t end = nextPlain ? level.vertices[p + 1].end : v.end;
      CandidateRun runs[kByVertex ? 5 : 1];  // kByVertex: the vertex's runs, passed together
      int nRuns = 0;
      if constexpr (kByVertex)
        runs[nRuns++] = {v.begin, end};
      else
        onPair.runs(v.begin, v.end, 0, end, true);
      candidatePairs += std::uint64_t(n) * (n - 1) / 2 + std::uint64_t(n) * std::uint64_t(end - v.end);
      if (next && !nextPlain) pairWith(p + 1);
      for (int c = 0; c < 4; ++c) {
        const std::uint64_t first = key + kRowOffsets[c];
        std::size_t t = cursor[c];
        while (t < nv && keys[t] < first) ++t;
        cursor[c] = t;
        const std::size_t t0 = t;
        while (t < nv && keys[t] <= first + 2) ++t;
        if (t == t0) continue;
        if (!plain(t0, t)) {
          for (std::size_t w = t0; w < t; ++w) pairWith(w);
          continue;
        }
        const std::int32_t b0 = level.vertices[t0].begin, b1 = level.vertices[t - 1].end;
        if constexpr (kByVertex)
          runs[nRuns++] = {b0, b1};
        else
          onPair.runs(v.begin, v.end, b0, b1, false);
        candidatePairs += std::uint64_t(n) * std::uint64_t(b1 - b0);
      }
      if constexpr (kByVertex) onPair.vertexRuns(v.begin, v.end, runs, nRuns);
      continue;
    }

    // 1. Real particles of this vertex among themselves.
    if (kCrowded && v.sortedByX()) {
      const double reach = (2.0 * level.crowds[std::size_t(v.box)].maxSmallRadius + halo) * pruneScale;
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
    if (p + 1 < nv && keys[p + 1] == key + 1) pairWith(p + 1);
    for (int c = 0; c < 4; ++c) {
      const std::uint64_t first = key + kRowOffsets[c];
      std::size_t t = cursor[c];
      while (t < nv && keys[t] < first) ++t;
      cursor[c] = t;
      for (; t < nv && keys[t] <= first + 2; ++t) pairWith(t);
    }
  }
  comparisons += candidatePairs;
}

template <class SliceRange, class OnRow>
void Spacetree::forEachRowIn(const Level& level, const std::int64_t lo[2], const std::int64_t hi[2],
                             SliceRange&& sliceRange, OnRow&& onRow) const {
  if (level.rows.empty()) return;
  const Slice* lastSlice = level.slices.data() + level.slices.size() - 1;  // past the end
  const Slice* slice = branchlessPartitionPoint(level.slices.data(), lastSlice,
                                                [&](const Slice& t) { return t.i < lo[0]; });
  const Row* rows = level.rows.data();
  for (; slice != lastSlice && slice->i <= hi[0]; ++slice) {
    std::int64_t j0 = lo[1], j1 = hi[1];
    if (!sliceRange(std::int64_t(slice->i), j0, j1)) continue;
    const Row* row = rows + slice->firstRow;
    const Row* rowEnd = rows + slice[1].firstRow;
    if (rowEnd - row > 8)
      row = branchlessPartitionPoint(row, rowEnd, [&](const Row& r) { return r.j < j0; });
    else
      while (row != rowEnd && row->j < j0) ++row;
    for (; row != rowEnd && row->j <= j1; ++row) onRow(std::int64_t(slice->i), *row);
  }
}

template <class F>
void Spacetree::forEachVertexInRow(const Level& level, const Row& row, std::int64_t k0, std::int64_t k1, F&& f) {
  if (k1 < 0) return;  // vertex indices are >= 0
  // The keys of one row differ only in k: compare them directly.
  const std::uint64_t* keys = level.keys.data();
  const std::uint64_t base = keys[row.begin] & ~kVertexKeyMask;
  const std::uint64_t first = base + std::uint64_t(std::max<std::int64_t>(k0, 0) + kVertexKeyBias);
  const std::uint64_t last = base + std::uint64_t(k1 + kVertexKeyBias);
  std::int32_t w = row.begin;
  if (row.end - w > 8)
    w = std::int32_t(branchlessPartitionPoint(keys + w, keys + row.end, [&](std::uint64_t key) { return key < first; }) -
                     keys);
  else
    while (w < row.end && keys[w] < first) ++w;
  for (; w < row.end && keys[w] <= last; ++w) f(w);
}

template <class F>
void Spacetree::forEachVertexIn(const Level& level, const std::int64_t lo[3], const std::int64_t hi[3], F&& f) const {
  forEachRowIn(
      level, lo, hi, [](std::int64_t, std::int64_t&, std::int64_t&) { return true; },
      [&](std::int64_t, const Row& row) { forEachVertexInRow(level, row, lo[2], hi[2], f); });
}

template <bool kCrowded, class PairFunction>
std::uint64_t Spacetree::linkLevels(int m, int l, PairFunction& onPair, double pruneScale,
                                    std::uint64_t& comparisons, std::uint64_t& tests) {
  std::uint64_t candidatePairs = 0, virtualLinks = 0, linkTests = 0;
  const double halo = 2.0 * options_.epsilon;
  const Level& coarse = levels_[m];
  const Level& fine = levels_[l];
  const double h = fine.meshSize;
  // Virtual-link radius beyond the coarse particle's own radius, before the relative margin
  // (linkRadius).
  const double linkReach = 2.0 * options_.epsilon + kLinkMeshFactor * h;
  // A fine vertex takes links only from the 3x3x3 coarse vertices around its nearest coarse
  // vertex: fine index n has the nearest coarse index (n + half) / s.
  const std::int64_t s = kPowersOfThree[l - m], half = (s - 1) / 2;
  const double inverse = 1.0 / h;

  // A link to coarse particle q pairs it with the vertex's particles; on a crowded vertex only
  // with those whose x lies within reach of q's.
  auto linked = [&](const Vertex& v, std::int32_t q) {
    ++virtualLinks;
    const bool qActive = isActive(q);
    if (!qActive && v.active == 0) return;
    const bool allActive = v.active == v.end - v.begin;
    std::int32_t smallBegin = v.begin, smallEnd = v.bigBegin;  // the whole vertex if plain
    if (kCrowded && v.sortedByX()) {
      const double pairReach = (sr_[q] + fine.crowds[std::size_t(v.box)].maxSmallRadius + halo) * pruneScale;
      smallBegin = firstWithinX(v.begin, v.bigBegin, sx_[q], pairReach);
      smallEnd = endWithinX(smallBegin, v.bigBegin, sx_[q], pairReach);
    }
    for (std::int32_t a = smallBegin; a < smallEnd; ++a)
      if (qActive || allActive || isActive(a)) onPair(a, q);
    for (std::int32_t a = v.bigBegin; a < v.end; ++a)
      if (qActive || allActive || isActive(a)) onPair(a, q);
    candidatePairs += std::uint64_t(smallEnd - smallBegin) + std::uint64_t(v.end - v.bigBegin);
  };
  // The fine vertices within r_q + linkReach of q's centre: rows whose (i, j) lie beyond it
  // are skipped with the partial sums linksTo computes (so no vertex it would accept); a long
  // row narrows its k range from the remaining reach (padded by a vertex) and tests vertex by
  // vertex; a short one (a dilute level: a ball crosses many rows of a few vertices, most of
  // them outside its k range) tests all its vertices in one branch-free pass. The distance is
  // that of linksTo, on the vertex coordinates the row and the key give (the vertex itself is
  // read when linked).
  const std::uint64_t* fineKeys = fine.keys.data();
  auto linkBall = [&](std::int32_t q, const std::int64_t near[2][3]) {
    const double reach = linkRadius(sr_[q], h), reach2 = reach * reach;
    const double c[3] = {sx_[q], sy_[q], sz_[q]};
    std::int64_t lo[3], hi[3];
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::max(near[0][d], indexBelow((c[d] - reach - origin_[d]) * inverse));
      hi[d] = std::min(near[1][d], indexAbove((c[d] + reach - origin_[d]) * inverse));
    }
    double dx2 = 0.0;  // of the current slice
    auto testVertex = [&](double dxy2, std::int32_t w) {
      ++linkTests;
      const double k = double(std::int64_t(fineKeys[w] & kVertexKeyMask) - kVertexKeyBias);
      const double dz = c[2] - (origin_[2] + k * h);
      if (dxy2 + dz * dz < reach2) linked(fine.vertices[std::size_t(w)], q);
    };
    forEachRowIn(
        fine, lo, hi,
        [&](std::int64_t i, std::int64_t& j0, std::int64_t& j1) {
          const double dx = c[0] - (origin_[0] + double(i) * h);
          dx2 = dx * dx;
          const double rest = reach2 - dx2;
          if (!(rest > 0.0)) return false;
          const double w = std::sqrt(rest);
          j0 = std::max(j0, indexBelow((c[1] - w - origin_[1]) * inverse));
          j1 = std::min(j1, indexAbove((c[1] + w - origin_[1]) * inverse));
          return j0 <= j1;
        },
        [&](std::int64_t, const Row& row) {
          const double dy = c[1] - (origin_[1] + double(row.j) * h);
          const double dxy2 = dx2 + dy * dy;
          const double rest = reach2 - dxy2;
          if (!(rest > 0.0)) return;
          if (row.end - row.begin > kShortRow) {
            const double w = std::sqrt(rest);
            const std::int64_t k0 = std::max(lo[2], indexBelow((c[2] - w - origin_[2]) * inverse));
            const std::int64_t k1 = std::min(hi[2], indexAbove((c[2] + w - origin_[2]) * inverse));
            if (k0 <= k1) forEachVertexInRow(fine, row, k0, k1, [&](std::int32_t w) { testVertex(dxy2, w); });
            return;
          }
          // Same vertices, tests and links as the k-range scan of a long row: those with k in
          // [lo, hi] are tested, those within reach linked, in k order.
          std::int32_t hits[kShortRow], count = 0, inRange = 0;
          for (std::int32_t w = row.begin; w < row.end; ++w) {
            const std::int64_t k = std::int64_t(fineKeys[w] & kVertexKeyMask) - kVertexKeyBias;
            const double dz = c[2] - (origin_[2] + double(k) * h);
            const bool within = (k >= lo[2]) & (k <= hi[2]);
            inRange += within ? 1 : 0;
            hits[count] = w;
            count += (within & (dxy2 + dz * dz < reach2)) ? 1 : 0;
          }
          linkTests += std::uint64_t(inRange);
          for (std::int32_t t = 0; t < count; ++t) linked(fine.vertices[std::size_t(hits[t])], q);
        });
  };

  // The links of fine vertex v to crowded coarse vertex u: when v is within reach of u's box
  // on every axis, the particles in the x window of v.
  auto linkCrowded = [&](const Vertex& u, const Vertex& v, double vx, double vy, double vz) {
    const Crowd& crowd = coarse.crowds[std::size_t(u.box)];
    const Box& box = crowd.box;
    const double reach = (crowd.maxSmallRadius + linkReach) * (1.0 + kPruneMargin);
    if (box.lo[0] - vx <= reach && vx - box.hi[0] <= reach && box.lo[1] - vy <= reach && vy - box.hi[1] <= reach &&
        box.lo[2] - vz <= reach && vz - box.hi[2] <= reach) {
      const std::int32_t first = firstWithinX(u.begin, u.bigBegin, vx, reach);
      const std::int32_t last = endWithinX(first, u.bigBegin, vx, reach);
      linkTests += std::uint64_t(last - first);
      const std::int32_t count = collectLinks(first, last, vx, vy, vz, linkReach);
      for (std::int32_t t = 0; t < count; ++t) linked(v, linkHits_[std::size_t(t)]);
    }
  };

  // Each fine vertex looks for the coarse vertices around its nearest coarse vertex: with the
  // coarse level's bitmap nine 3-bit reads, else a search over its slices and rows. Out of
  // line: inlined, it tips the compiler into calling the same-level sweep out of line, which
  // costs a dense pack 5-10 % of its sweep.
  auto lookUpFromFineVertices = [&](const VertexBitmap* around) __attribute__((noinline)) {
    // Nearest coarse index (n + half) / s as a multiply-high: exact for n s < 2^64 (indices
    // below 2^21, s = 3^(l - m) <= 3^19).
    const std::uint64_t reciprocal = ~std::uint64_t(0) / std::uint64_t(s) + 1;
    auto nearestCoarse = [&](std::int32_t n) {
      return std::int64_t((static_cast<unsigned __int128>(std::uint64_t(n + half)) * reciprocal) >> 64);
    };
    for (std::size_t w = 0; w < fine.vertices.size(); ++w) {
      const VertexIndex vi = indexOf(fine, w);
      const std::int64_t cc[3] = {nearestCoarse(vi.i), nearestCoarse(vi.j), nearestCoarse(vi.k)};
      std::uint32_t occupied = 0;
      if (around) {
        if (!around->anyAround(cc[0], cc[1], cc[2])) continue;
        occupied = around->around(cc[0], cc[1], cc[2]);
      }
      const Vertex& v = fine.vertices[w];
      const double vx = origin_[0] + vi.i * h, vy = origin_[1] + vi.j * h, vz = origin_[2] + vi.k * h;
      auto linkCoarseVertex = [&](std::int32_t cu) {
        const Vertex& u = coarse.vertices[std::size_t(cu)];
        std::int32_t q = u.begin;
        if (kCrowded && u.sortedByX()) {
          linkCrowded(u, v, vx, vy, vz);
          q = u.bigBegin;
        }
        linkTests += std::uint64_t(u.end - q);
        for (; q < u.end; ++q)
          if (linksTo(q, vx, vy, vz, linkReach)) linked(v, q);
      };
      if (around) {
        while (occupied) {
          const unsigned t = unsigned(__builtin_ctz(occupied));
          occupied &= occupied - 1;
          linkCoarseVertex(around->slotAround(cc[0], cc[1], cc[2], t));
        }
      } else {
        const std::int64_t lo[3] = {cc[0] - 1, cc[1] - 1, cc[2] - 1}, hi[3] = {cc[0] + 1, cc[1] + 1, cc[2] + 1};
        forEachVertexIn(coarse, lo, hi, linkCoarseVertex);
      }
    }
  };

  const VertexBitmap* around = nullptr;
  if (linkFromFineVertices(m, l, around)) {
    stats_.levels[l].linkLookups += fine.vertices.size();
    lookUpFromFineVertices(around);
  } else {
    for (std::size_t cu = 0; cu < coarse.vertices.size(); ++cu) {
      const Vertex& u = coarse.vertices[cu];
      const VertexIndex ui = indexOf(coarse, cu);
      const std::int64_t uc[3] = {ui.i, ui.j, ui.k};
      std::int64_t near[2][3];
      for (int d = 0; d < 3; ++d) {
        near[0][d] = (uc[d] - 1) * s - half;
        near[1][d] = (uc[d] + 1) * s + half;
      }
      std::int32_t q = u.begin;
      if (kCrowded && u.sortedByX()) {
        // A crowded coarse vertex: the fine vertices near its box scan the x window of its
        // ordered particles; the big ones go one by one.
        const Crowd& crowd = coarse.crowds[std::size_t(u.box)];
        const Box& box = crowd.box;
        const double reach = (crowd.maxSmallRadius + linkReach) * (1.0 + kPruneMargin);
        std::int64_t lo[3], hi[3];
        for (int d = 0; d < 3; ++d) {
          lo[d] = std::max(near[0][d], indexBelow((box.lo[d] - reach - origin_[d]) * inverse));
          hi[d] = std::min(near[1][d], indexAbove((box.hi[d] + reach - origin_[d]) * inverse));
        }
        forEachVertexIn(fine, lo, hi, [&](std::int32_t w) {
          const VertexIndex vi = indexOf(fine, std::size_t(w));
          linkCrowded(u, fine.vertices[std::size_t(w)], origin_[0] + vi.i * h, origin_[1] + vi.j * h, origin_[2] + vi.k * h);
        });
        q = u.bigBegin;
      }
      for (; q < u.end; ++q) linkBall(q, near);
    }
  }
  comparisons += candidatePairs;
  tests += linkTests;
  return virtualLinks;
}

template <class PairFunction>
std::uint64_t Spacetree::sweepCrowdedPair(const Level& level, const Vertex& v, const Vertex& nb, double halo,
                                          double pruneScale, PairFunction& onPair) {
  const bool bothActive = v.active == v.end - v.begin && nb.active == nb.end - nb.begin;
  std::uint64_t comparisons = 0;
  // The ordinary particles: those of v near nb's box, and those of nb near theirs.
  const double reach = (maxSmallRadius(level, v) + maxSmallRadius(level, nb) + halo) * pruneScale;
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
