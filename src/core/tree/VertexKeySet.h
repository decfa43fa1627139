// Set of packed vertex keys with the list of its members: open addressing (VertexHashMap)
// for fast membership, the list for iteration. Members leave only in batches (eraseAll),
// which rebuilds the table: no tombstones on the look-up path.
#pragma once

#include <cstdint>
#include <vector>

#include "tree/VertexHashMap.h"

namespace spacetree {

class VertexKeySet {
 public:
  std::vector<std::uint64_t> keys;  // members (insertion order until an erase)

  // Empties the set, sized for `expected` members.
  void reset(std::size_t expected) {
    keys.clear();
    capacity_ = expected;
    map_.reset(expected);
  }

  // Makes room for `extra` further members without rehashing on every insert.
  void reserveMore(std::size_t extra) {
    if (keys.size() + extra <= capacity_) return;
    capacity_ = keys.size() + extra;
    map_.reset(capacity_);
    for (std::size_t i = 0; i < keys.size(); ++i) map_.insert(keys[i], std::int32_t(i));
  }

  void insert(std::uint64_t key) {
    if (capacity_ == 0) reserveMore(16);
    if (map_.find(key) != VertexHashMap::kAbsent) return;
    if (keys.size() >= capacity_) reserveMore(keys.size() + 16);  // keep load <= 1/2
    map_.insert(key, std::int32_t(keys.size()));
    keys.push_back(key);
  }

  bool contains(std::uint64_t key) const { return capacity_ > 0 && map_.find(key) != VertexHashMap::kAbsent; }
  std::size_t size() const { return keys.size(); }

  // Removes every member of `removals` (keys that are not members are ignored). A few
  // removals are erased one by one (the last member takes the place of a removed one, so the
  // member order changes); many rebuild the table.
  void eraseAll(const std::vector<std::uint64_t>& removals) {
    if (removals.empty() || keys.empty()) return;
    if (8 * removals.size() < keys.size()) {
      for (std::uint64_t k : removals) {
        const std::int32_t slot = map_.find(k);
        if (slot == VertexHashMap::kAbsent) continue;
        map_.erase(k);
        const std::uint64_t last = keys.back();
        keys.pop_back();
        if (std::size_t(slot) < keys.size()) {
          keys[std::size_t(slot)] = last;
          map_.insert(last, slot);
        }
      }
      return;
    }
    VertexKeySet gone;
    gone.reset(removals.size());
    for (std::uint64_t k : removals) gone.insert(k);
    std::size_t kept = 0;
    for (std::uint64_t k : keys)
      if (!gone.contains(k)) keys[kept++] = k;
    keys.resize(kept);
    map_.reset(capacity_);
    for (std::size_t i = 0; i < keys.size(); ++i) map_.insert(keys[i], std::int32_t(i));
  }

 private:
  VertexHashMap map_;
  std::size_t capacity_ = 0;
};

}  // namespace spacetree
