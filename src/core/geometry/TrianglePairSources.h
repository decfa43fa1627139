// The three ways the array forms of the distance methods receive their pairs, as one interface
// for the batching code: count(), random access first(k) / second(k), and loadBatch(), which
// fills a TrianglePairBatch with pairs begin, begin + 1, ... and returns how many lanes hold
// real pairs (unused lanes repeat the last real pair, so the kernel never sees garbage).
#pragma once

#include <algorithm>
#include <cstddef>

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

}  // namespace spacetree::geometry
