// Integer vertex coordinates of one grid level, packed into one 64-bit key.
#pragma once

#include <cstdint>

namespace spacetree {

// 20 bits per axis; the top 4 bits hold the level, so one integer sort orders particles by
// (level, vertex). The bias keeps the small negative offsets that neighbour and ancestor
// look-ups produce (down to -kVertexKeyBias) representable.
constexpr int kVertexKeyBits = 20;
constexpr std::int64_t kVertexKeyBias = 4;
constexpr std::uint64_t kVertexKeyMask = (std::uint64_t(1) << kVertexKeyBits) - 1;

// Deepest level a tree may use: 3^12 + 2*bias vertices per axis still fit into 20 bits.
constexpr int kMaxSpacetreeLevel = 12;

struct VertexIndex {
  std::int32_t i, j, k;
};

inline std::uint64_t packVertexKey(std::int64_t i, std::int64_t j, std::int64_t k) {
  return (std::uint64_t(i + kVertexKeyBias) << (2 * kVertexKeyBits)) |
         (std::uint64_t(j + kVertexKeyBias) << kVertexKeyBits) | std::uint64_t(k + kVertexKeyBias);
}

inline VertexIndex unpackVertexKey(std::uint64_t key) {
  return VertexIndex{std::int32_t(std::int64_t((key >> (2 * kVertexKeyBits)) & kVertexKeyMask) - kVertexKeyBias),
                     std::int32_t(std::int64_t((key >> kVertexKeyBits) & kVertexKeyMask) - kVertexKeyBias),
                     std::int32_t(std::int64_t(key & kVertexKeyMask) - kVertexKeyBias)};
}

// Level in the top bits: sorting (level, vertex) is sorting one integer.
constexpr int kLevelShift = 3 * kVertexKeyBits;
inline std::uint64_t levelVertexKey(int level, std::uint64_t vertexKey) {
  return (std::uint64_t(level) << kLevelShift) | vertexKey;
}

// The same order in fewer bits, for sorting: (level, i, j, k) packed with `fieldBits` bits per
// biased index, just enough for the indices of a tree of `depth` levels (up to 3^depth +
// bias), so the radix sort passes over fewer digits. fromSortKey gives the levelVertexKey.
struct SortKeyPacking {
  int fieldBits = kVertexKeyBits;
  int keyBits = 0;  // of a whole sort key: the level's bits and three fields
  explicit SortKeyPacking(int depth) {
    std::int64_t largest = 1;
    for (int l = 0; l < depth; ++l) largest *= 3;
    largest += 2 * kVertexKeyBias + 1;
    fieldBits = 1;
    while ((std::int64_t(1) << fieldBits) <= largest) ++fieldBits;
    int levelBits = 0;
    while ((1 << levelBits) <= depth) ++levelBits;
    keyBits = levelBits + 3 * fieldBits;
  }
  // Level of a sort key, and whether two sort keys name the same level.
  int levelOf(std::uint64_t key) const { return int(key >> (3 * fieldBits)); }
  std::uint64_t toSortKey(int level, std::int64_t i, std::int64_t j, std::int64_t k) const {
    return (((((std::uint64_t(level) << fieldBits) | std::uint64_t(i + kVertexKeyBias)) << fieldBits) |
             std::uint64_t(j + kVertexKeyBias))
            << fieldBits) |
           std::uint64_t(k + kVertexKeyBias);
  }
  std::uint64_t fromSortKey(std::uint64_t key) const {
    const std::uint64_t field = (std::uint64_t(1) << fieldBits) - 1;
    const std::uint64_t k = key & field, j = (key >> fieldBits) & field, i = (key >> (2 * fieldBits)) & field;
    const std::uint64_t level = key >> (3 * fieldBits);
    return (level << kLevelShift) | (i << (2 * kVertexKeyBits)) | (j << kVertexKeyBits) | k;
  }
};

}  // namespace spacetree
