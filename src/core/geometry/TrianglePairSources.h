// The three ways the array forms of the distance methods receive their pairs, as one interface
// for the batching code: count(), random access first(k) / second(k), and loadBatch(), which
// fills a TrianglePairBatch with pairs begin, begin + 1, ... and returns how many lanes hold
// real pairs (unused lanes repeat the last real pair, so the kernel never sees garbage).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstring>

#include "geometry/TrianglePairBatch.h"

namespace spacetree::geometry {

// Pair k = (first[k], second[k]).
struct ElementwisePairs {
  const Triangle* firstTriangles;
  const Triangle* secondTriangles;
  std::size_t pairCount;

  std::size_t count() const { return pairCount; }
  const Triangle& first(std::size_t k) const { return firstTriangles[k]; }
  const Triangle& second(std::size_t k) const { return secondTriangles[k]; }
  int loadBatch(TrianglePairBatch& batch, std::size_t begin) const {
    const int lanes = int(std::min<std::size_t>(kTrianglePairBatchSize, pairCount - begin));
    for (int l = 0; l < kTrianglePairBatchSize; ++l) {
      const std::size_t k = begin + std::size_t(std::min(l, lanes - 1));
      batch.set(l, firstTriangles[k], secondTriangles[k]);
    }
    return lanes;
  }
};

// Pair k = (triangle, others[k]).
struct OneAgainstMany {
  const Triangle* triangle;
  const Triangle* others;
  std::size_t otherCount;

  std::size_t count() const { return otherCount; }
  const Triangle& first(std::size_t) const { return *triangle; }
  const Triangle& second(std::size_t k) const { return others[k]; }
  int loadBatch(TrianglePairBatch& batch, std::size_t begin) const {
    const int lanes = int(std::min<std::size_t>(kTrianglePairBatchSize, otherCount - begin));
    for (int l = 0; l < kTrianglePairBatchSize; ++l)
      batch.set(l, *triangle, others[begin + std::size_t(std::min(l, lanes - 1))]);
    return lanes;
  }
};

// Pair k = (first[k / secondCount], second[k % secondCount]): every pair of two meshes, row by
// row, batches running across rows (no half-empty batch per row for small meshes).
struct AllPairs {
  const Triangle* firstTriangles;
  std::size_t firstCount;
  const Triangle* secondTriangles;
  std::size_t secondCount;

  std::size_t count() const { return firstCount * secondCount; }
  const Triangle& first(std::size_t k) const { return firstTriangles[k / secondCount]; }
  const Triangle& second(std::size_t k) const { return secondTriangles[k % secondCount]; }
  int loadBatch(TrianglePairBatch& batch, std::size_t begin) const {
    const int lanes = int(std::min<std::size_t>(kTrianglePairBatchSize, count() - begin));
    std::size_t i = begin / secondCount, j = begin % secondCount;  // one division per batch
    for (int l = 0; l < kTrianglePairBatchSize; ++l) {
      batch.set(l, firstTriangles[i], secondTriangles[j]);
      if (l + 1 < lanes && ++j == secondCount) {
        j = 0;
        ++i;
      }
    }
    return lanes;
  }
};

// The same pairs as AllPairs, with the second mesh's coordinates copied once into a
// structure of arrays repeated periodically (coordinate[c][p] of second[p % secondCount]), so
// that a batch's second triangles, second[j], second[j + 1], ... across row ends, are 16
// consecutive values per coordinate: nine block copies per batch instead of a transposition
// per lane. The first triangles are constant along a row: one fill per coordinate and row run.
// The buffer is the caller's (kept between calls: no allocation once it is large enough).
struct PackedAllPairs {
  const Triangle* firstTriangles;
  std::size_t firstCount;
  const Triangle* secondTriangles;
  std::size_t secondCount;
  const double* packedSecond;  // 9 arrays of `stride` values
  std::size_t stride;

  static std::size_t strideFor(std::size_t secondCount) {
    return secondCount + kTrianglePairBatchSize - 1;
  }
  // Fills `buffer` (9 * strideFor(secondCount) values) for `second`.
  static void pack(const Triangle* second, std::size_t secondCount, double* buffer) {
    const std::size_t stride = strideFor(secondCount);
    for (std::size_t p = 0, j = 0; p < stride; ++p, j = (j + 1 == secondCount ? 0 : j + 1))
      for (int v = 0; v < 3; ++v)
        for (int c = 0; c < 3; ++c) buffer[std::size_t(3 * v + c) * stride + p] = second[j][v][c];
  }

  std::size_t count() const { return firstCount * secondCount; }
  const Triangle& first(std::size_t k) const { return firstTriangles[k / secondCount]; }
  const Triangle& second(std::size_t k) const { return secondTriangles[k % secondCount]; }
  int loadBatch(TrianglePairBatch& batch, std::size_t begin) const {
    const int lanes = int(std::min<std::size_t>(kTrianglePairBatchSize, count() - begin));
    const std::size_t i = begin / secondCount;
    const std::size_t j = begin % secondCount;
    for (int v = 0; v < 3; ++v)
      for (int c = 0; c < 3; ++c)
        std::memcpy(batch.coordinate[1][v][c],
                    packedSecond + std::size_t(3 * v + c) * stride + j, sizeof batch.coordinate[1][v][c]);
    // Lanes past the last pair keep the last row (real triangles, results unused).
    const auto row = [&](std::size_t r) -> const Triangle& {
      return firstTriangles[std::min(r, firstCount - 1)];
    };
    if (secondCount >= kTrianglePairBatchSize / 2) {
      // At most three rows in a batch: lanes [0, s1) row i, [s1, s2) row i + 1, then i + 2.
      const int s1 = int(secondCount - j), s2 = s1 + int(secondCount);
      const Triangle &t0 = row(i), &t1 = row(i + 1), &t2 = row(i + 2);
      for (int v = 0; v < 3; ++v)
        for (int c = 0; c < 3; ++c) {
          const double x0 = t0[v][c], x1 = t1[v][c], x2 = t2[v][c];
          double* to = batch.coordinate[0][v][c];
          for (int l = 0; l < kTrianglePairBatchSize; ++l) to[l] = l < s1 ? x0 : (l < s2 ? x1 : x2);
        }
      return lanes;
    }
    for (int l = 0; l < kTrianglePairBatchSize; ++l) {
      const Triangle& t = row(i + (j + std::size_t(l)) / secondCount);
      for (int v = 0; v < 3; ++v)
        for (int c = 0; c < 3; ++c) batch.coordinate[0][v][c][l] = t[v][c];
    }
    return lanes;
  }
};

}  // namespace spacetree::geometry
