// Integer counter per packed vertex key (the reluctant grid's heat markers): open addressing
// (VertexHashMap) into parallel key/value arrays, so look-ups and iteration stream through
// flat memory instead of the nodes of a std::unordered_map.
#pragma once

#include <cstdint>
#include <vector>

#include "tree/VertexHashMap.h"

namespace spacetree {

class VertexCounters {
 public:
  std::vector<std::uint64_t> keys;   // in insertion order
  std::vector<std::int64_t> values;  // values[i] belongs to keys[i]

  // Empties the counters, sized for `expected` keys (memory is kept).
  void reset(std::size_t expected) {
    keys.clear();
    values.clear();
    capacity_ = expected < 16 ? 16 : expected;
    map_.reset(capacity_);
  }

  // The counter of `key`, created as 0 if absent. The reference is valid until the next insert.
  std::int64_t& operator[](std::uint64_t key) {
    if (capacity_ == 0) reset(16);
    const std::int32_t slot = map_.find(key);
    if (slot != VertexHashMap::kAbsent) return values[std::size_t(slot)];
    if (keys.size() >= capacity_) grow();
    map_.insert(key, std::int32_t(keys.size()));
    keys.push_back(key);
    values.push_back(0);
    return values.back();
  }

  // The counter of `key` without creating it (0 if absent).
  std::int64_t get(std::uint64_t key) const {
    if (capacity_ == 0) return 0;
    const std::int32_t slot = map_.find(key);
    return slot == VertexHashMap::kAbsent ? 0 : values[std::size_t(slot)];
  }

  std::size_t size() const { return keys.size(); }

 private:
  void grow() {
    capacity_ *= 2;
    map_.reset(capacity_);
    for (std::size_t i = 0; i < keys.size(); ++i) map_.insert(keys[i], std::int32_t(i));
  }

  VertexHashMap map_;
  std::size_t capacity_ = 0;
};

}  // namespace spacetree
