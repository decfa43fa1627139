// Stable LSD radix sort of (64-bit key, payload) records by key. Building the tree sorts
// every particle by (level, vertex) at every neighbour-list rebuild; this is linear and
// skips the digit positions in which all keys agree.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace spacetree {

struct KeyedIndex {
  std::uint64_t key;
  std::int32_t index;
};

// Sorts `records` by key; equal keys keep their order. `scratch` is resized as needed.
inline void radixSortByKey(std::vector<KeyedIndex>& records, std::vector<KeyedIndex>& scratch) {
  constexpr int kDigitBits = 11;
  constexpr std::size_t kBuckets = std::size_t(1) << kDigitBits;
  const std::size_t n = records.size();
  if (n < 2) return;
  std::uint64_t varying = 0;
  for (const KeyedIndex& r : records) varying |= r.key ^ records[0].key;
  scratch.resize(n);
  std::array<std::size_t, kBuckets> offset;
  for (int shift = 0; shift < 64 && (varying >> shift) != 0; shift += kDigitBits) {
    if (((varying >> shift) & (kBuckets - 1)) == 0) continue;  // all keys share this digit
    offset.fill(0);
    for (const KeyedIndex& r : records) ++offset[(r.key >> shift) & (kBuckets - 1)];
    std::size_t sum = 0;
    for (std::size_t& o : offset) {
      const std::size_t count = o;
      o = sum;
      sum += count;
    }
    for (const KeyedIndex& r : records) scratch[offset[(r.key >> shift) & (kBuckets - 1)]++] = r;
    records.swap(scratch);
  }
}

}  // namespace spacetree
