// For one coarse level: for every vertex within one index step of an occupied vertex, the
// real particles of its 3x3x3 vertex neighbourhood. A finer vertex finds its virtual-link
// candidates on this level with one look-up of its nearest coarse vertex (its ancestor),
// instead of 27 look-ups; vertices far from every coarse particle find nothing at once.
#pragma once

#include <cstdint>
#include <vector>

#include "tree/VertexHashMap.h"
#include "tree/VertexKey.h"

namespace spacetree {

class CoarseNeighbourhoods {
 public:
  struct Range {
    const std::int32_t* begin;
    const std::int32_t* end;
  };

  // `vertices` of one level, each with .index and the range [.begin, .end) of its particles.
  template <class VertexRange>
  void build(const VertexRange& vertices) {
    slotOf_.reset(27 * vertices.size());
    first_.clear();
    for (int pass = 0; pass < 2; ++pass) {
      for (const auto& u : vertices) {
        for (int di = -1; di <= 1; ++di)
          for (int dj = -1; dj <= 1; ++dj)
            for (int dk = -1; dk <= 1; ++dk) {
              const std::uint64_t key = packVertexKey(std::int64_t(u.index.i) + di,
                                                      std::int64_t(u.index.j) + dj,
                                                      std::int64_t(u.index.k) + dk);
              std::int32_t slot = slotOf_.find(key);
              if (pass == 0) {
                if (slot == VertexHashMap::kAbsent) {
                  slot = std::int32_t(first_.size());
                  slotOf_.insert(key, slot);
                  first_.push_back(0);
                }
                first_[slot] += u.end - u.begin;
              } else {
                for (std::int32_t q = u.begin; q < u.end; ++q) particles_[fill_[slot]++] = q;
              }
            }
      }
      if (pass == 0) {  // counts -> offsets
        std::int32_t sum = 0;
        for (std::int32_t& f : first_) {
          const std::int32_t count = f;
          f = sum;
          sum += count;
        }
        first_.push_back(sum);
        particles_.resize(std::size_t(sum));
        fill_.assign(first_.begin(), first_.end() - 1);
      }
    }
  }

  Range near(std::int64_t i, std::int64_t j, std::int64_t k) const {
    const std::int32_t slot = slotOf_.find(packVertexKey(i, j, k));
    if (slot == VertexHashMap::kAbsent) return Range{nullptr, nullptr};
    return Range{particles_.data() + first_[slot], particles_.data() + first_[slot + 1]};
  }

  std::size_t memoryBytes() const {
    return slotOf_.memoryBytes() + (first_.capacity() + fill_.capacity() + particles_.capacity()) * sizeof(std::int32_t);
  }

 private:
  VertexHashMap slotOf_;
  std::vector<std::int32_t> first_, fill_, particles_;
};

}  // namespace spacetree
