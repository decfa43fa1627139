// Integer vertex coordinates of one grid level, packed into one 64-bit key.
#pragma once

#include <cstdint>

namespace spacetree {

// 21 bits per axis. The bias keeps the small negative offsets that neighbour and ancestor
// look-ups produce (down to -kVertexKeyBias) representable.
constexpr int kVertexKeyBits = 21;
constexpr std::int64_t kVertexKeyBias = 4;

// Deepest level a tree may use: 3^13 + 2*bias vertices per axis still fit into 21 bits.
constexpr int kMaxSpacetreeLevel = 13;

struct VertexIndex {
  std::int32_t i, j, k;
};

inline std::uint64_t packVertexKey(std::int64_t i, std::int64_t j, std::int64_t k) {
  return (std::uint64_t(i + kVertexKeyBias) << (2 * kVertexKeyBits)) |
         (std::uint64_t(j + kVertexKeyBias) << kVertexKeyBits) | std::uint64_t(k + kVertexKeyBias);
}

}  // namespace spacetree
