// Stable LSD radix sort of (64-bit key, payload) records by key. Building the tree sorts
// every particle by (level, vertex) at every neighbour-list rebuild; this is linear and
// skips the digit positions in which all keys agree.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

namespace spacetree {

struct KeyedIndex {
  std::uint64_t key;
  std::int32_t index;
};
// Half the size, for keys that fit into 32 bits (a tree of few levels).
struct KeyedIndex32 {
  std::uint32_t key;
  std::int32_t index;
};

// Sorts `records` (KeyedIndex or KeyedIndex32) by key; equal keys keep their order. `scratch`
// is resized as needed. Only the bits in which the keys differ are sorted on, in as few passes
// of at most 12 bits as they need (keys varying in 21 bits: two passes), each pass skipped
// where all keys agree.
template <class Record>
void radixSortByKey(std::vector<Record>& records, std::vector<Record>& scratch) {
  constexpr int kMaxDigitBits = 12;
  const std::size_t n = records.size();
  if (n < 2) return;
  std::uint64_t varying = 0;
  for (const Record& r : records) varying |= std::uint64_t(r.key ^ records[0].key);
  if (varying == 0) return;
  int low = 0, high = 63;
  while (!((varying >> low) & 1)) ++low;
  while (!((varying >> high) & 1)) --high;
  const int bits = high - low + 1;
  const int passes = (bits + kMaxDigitBits - 1) / kMaxDigitBits;
  const int digitBits = (bits + passes - 1) / passes;
  const std::uint64_t mask = (std::uint64_t(1) << digitBits) - 1;
  scratch.resize(n);
  std::array<std::uint32_t, std::size_t(1) << kMaxDigitBits> offset;
  for (int shift = low; shift <= high; shift += digitBits) {
    if (((varying >> shift) & mask) == 0) continue;  // all keys share this digit
    std::fill(offset.begin(), offset.begin() + (mask + 1), 0u);
    for (const Record& r : records) ++offset[(std::uint64_t(r.key) >> shift) & mask];
    std::uint32_t sum = 0;
    for (std::size_t d = 0; d <= mask; ++d) {
      const std::uint32_t count = offset[d];
      offset[d] = sum;
      sum += count;
    }
    for (const Record& r : records) scratch[offset[(std::uint64_t(r.key) >> shift) & mask]++] = r;
    records.swap(scratch);
  }
}

}  // namespace spacetree
