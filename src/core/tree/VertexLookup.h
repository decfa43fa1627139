// Finds the slot of a vertex of one grid level from its integer coordinates.
// Dense levels (vertices fill a good part of their bounding box) use a 3D array: neighbour
// look-ups then touch neighbouring memory. Sparse levels (a few big particles in a big
// domain, a cluster in a corner) use a hash map, so memory stays proportional to the
// particles, not to the domain volume.
#pragma once

#include <cstdint>
#include <vector>

#include "tree/VertexHashMap.h"
#include "tree/VertexKey.h"

namespace spacetree {

class VertexLookup {
 public:
  static constexpr std::int32_t kAbsent = VertexHashMap::kAbsent;

  // Index the given vertices (slot = position in the vector).
  template <class VertexRange>
  void build(const VertexRange& vertices) {
    if (vertices.empty()) {
      dense_ = false;
      hash_.reset(0);
      return;
    }
    std::int32_t lo[3] = {vertices[0].index.i, vertices[0].index.j, vertices[0].index.k};
    std::int32_t hi[3] = {lo[0], lo[1], lo[2]};
    for (const auto& v : vertices) {
      const std::int32_t c[3] = {v.index.i, v.index.j, v.index.k};
      for (int d = 0; d < 3; ++d) {
        lo[d] = c[d] < lo[d] ? c[d] : lo[d];
        hi[d] = c[d] > hi[d] ? c[d] : hi[d];
      }
    }
    // One layer of padding: the 26 neighbours of any stored vertex are inside the array.
    for (int d = 0; d < 3; ++d) {
      lo_[d] = std::int64_t(lo[d]) - 1;
      extent_[d] = std::int64_t(hi[d]) - lo[d] + 3;
    }
    const double cells = double(extent_[0]) * double(extent_[1]) * double(extent_[2]);
    dense_ = cells <= kDenseCellsPerVertex * double(vertices.size()) + kDenseMinimumCells;
    if (dense_) {
      slots_.assign(std::size_t(cells), kAbsent);
      for (std::size_t s = 0; s < vertices.size(); ++s) {
        const auto& v = vertices[s];
        slots_[std::size_t(linear(v.index.i, v.index.j, v.index.k))] = std::int32_t(s);
      }
    } else {
      slots_.clear();
      hash_.reset(vertices.size());
      for (std::size_t s = 0; s < vertices.size(); ++s) {
        const auto& v = vertices[s];
        hash_.insert(packVertexKey(v.index.i, v.index.j, v.index.k), std::int32_t(s));
      }
    }
  }

  std::int32_t find(std::int64_t i, std::int64_t j, std::int64_t k) const {
    if (!dense_) return hash_.find(packVertexKey(i, j, k));
    const std::uint64_t a = std::uint64_t(i - lo_[0]), b = std::uint64_t(j - lo_[1]),
                        c = std::uint64_t(k - lo_[2]);
    if (a >= std::uint64_t(extent_[0]) || b >= std::uint64_t(extent_[1]) || c >= std::uint64_t(extent_[2]))
      return kAbsent;
    return slots_[std::size_t((a * extent_[1] + b) * extent_[2] + c)];
  }

  bool dense() const { return dense_; }

  // Dense levels only: the array position of a stored vertex, and the position offset of a
  // neighbour (di, dj, dk in -1..1), so that neighbour look-ups need no bounds checks.
  std::int64_t densePosition(std::int64_t i, std::int64_t j, std::int64_t k) const {
    return linear(i, j, k);
  }
  std::int64_t denseOffset(int di, int dj, int dk) const {
    return (std::int64_t(di) * extent_[1] + dj) * extent_[2] + dk;
  }
  std::int32_t atDensePosition(std::int64_t position) const { return slots_[std::size_t(position)]; }
  std::size_t memoryBytes() const {
    return slots_.capacity() * sizeof(std::int32_t) + (dense_ ? 0 : hash_.memoryBytes());
  }

 private:
  // A 3D array is used while it has at most this many cells per vertex (plus a floor).
  static constexpr double kDenseCellsPerVertex = 8.0;
  static constexpr double kDenseMinimumCells = 4096.0;

  std::int64_t linear(std::int64_t i, std::int64_t j, std::int64_t k) const {
    return ((i - lo_[0]) * extent_[1] + (j - lo_[1])) * extent_[2] + (k - lo_[2]);
  }

  bool dense_ = false;
  std::int64_t lo_[3] = {0, 0, 0};
  std::int64_t extent_[3] = {0, 0, 0};
  std::vector<std::int32_t> slots_;
  VertexHashMap hash_;
};

}  // namespace spacetree
