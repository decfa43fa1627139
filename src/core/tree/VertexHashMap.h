// Open-addressing hash map from a packed vertex key to a slot, for the persistent grid's sparse
// sets of refined cells and counted vertices (VertexKeySet, VertexCounters), where a dense
// array would cost memory proportional to the domain volume; this costs memory per vertex.
#pragma once

#include <cstdint>
#include <vector>

namespace spacetree {

class VertexHashMap {
 public:
  static constexpr std::int32_t kAbsent = -1;

  // Forget all entries and size the table for `expected` keys (load factor <= 1/2).
  void reset(std::size_t expected) {
    std::size_t capacity = 16;
    while (capacity < 2 * expected) capacity *= 2;
    keys_.assign(capacity, kEmptyKey);
    values_.resize(capacity);
    mask_ = capacity - 1;
  }

  void insert(std::uint64_t key, std::int32_t value) {
    std::size_t slot = hash(key) & mask_;
    while (keys_[slot] != kEmptyKey && keys_[slot] != key) slot = (slot + 1) & mask_;
    keys_[slot] = key;
    values_[slot] = value;
  }

  std::int32_t find(std::uint64_t key) const {
    std::size_t slot = hash(key) & mask_;
    while (true) {
      const std::uint64_t k = keys_[slot];
      if (k == key) return values_[slot];
      if (k == kEmptyKey) return kAbsent;
      slot = (slot + 1) & mask_;
    }
  }

  // Removes `key` if present (backward-shift deletion: no tombstones on the look-up path).
  void erase(std::uint64_t key) {
    std::size_t i = hash(key) & mask_;
    while (keys_[i] != key) {
      if (keys_[i] == kEmptyKey) return;
      i = (i + 1) & mask_;
    }
    for (std::size_t j = i;;) {
      j = (j + 1) & mask_;
      if (keys_[j] == kEmptyKey) break;
      const std::size_t home = hash(keys_[j]) & mask_;
      // The entry at j may move back to the hole at i unless its home lies cyclically in (i, j].
      const bool stays = i <= j ? (i < home && home <= j) : (i < home || home <= j);
      if (stays) continue;
      keys_[i] = keys_[j];
      values_[i] = values_[j];
      i = j;
    }
    keys_[i] = kEmptyKey;
  }

  std::size_t memoryBytes() const {
    return keys_.capacity() * sizeof(std::uint64_t) + values_.capacity() * sizeof(std::int32_t);
  }

 private:
  // Packed keys use 63 bits, so all-ones never is a real key.
  static constexpr std::uint64_t kEmptyKey = ~std::uint64_t(0);

  static std::uint64_t hash(std::uint64_t k) {  // murmur3 finaliser
    k ^= k >> 33;
    k *= 0xff51afd7ed558ccdULL;
    k ^= k >> 33;
    k *= 0xc4ceb9fe1a85ec53ULL;
    k ^= k >> 33;
    return k;
  }

  std::vector<std::uint64_t> keys_;
  std::vector<std::int32_t> values_;
  std::size_t mask_ = 0;
};

}  // namespace spacetree
