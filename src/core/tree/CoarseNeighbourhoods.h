// For one coarse level: for every vertex within one index step of an occupied vertex, the
// real particles of its 3x3x3 vertex neighbourhood. A finer vertex finds its virtual-link
// candidates on this level with one look-up of its nearest coarse vertex (its ancestor),
// instead of 27 look-ups; vertices far from every coarse particle find nothing at once.
// Crowded vertices (many particles, ordered by x) are listed by their slot instead of copied
// particle by particle: the finer vertex prunes their particles by position (x window), and
// copying dozens of particles into 27 neighbourhoods would cost more than the whole look-up.
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
  struct Neighbourhood {
    Range particles;        // of the plain vertices
    Range crowdedVertices;  // slots of the crowded ones
  };

  // `vertices` of one level, each with .index and the range [.begin, .end) of its particles;
  // crowded(u) says whether vertex u is listed by its slot rather than by its particles.
  template <class VertexRange, class Crowded>
  void build(const VertexRange& vertices, Crowded&& crowded) {
    slotOf_.reset(27 * vertices.size());
    first_.clear();
    firstCrowded_.clear();
    anyCrowded_ = false;
    for (const auto& u : vertices) anyCrowded_ = anyCrowded_ || crowded(u);
    for (int pass = 0; pass < 2; ++pass) {
      for (std::size_t s = 0; s < vertices.size(); ++s) {
        const auto& u = vertices[s];
        const bool isCrowded = crowded(u);
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
                  if (anyCrowded_) firstCrowded_.push_back(0);
                }
                if (isCrowded)
                  ++firstCrowded_[slot];
                else
                  first_[slot] += u.end - u.begin;
              } else if (isCrowded) {
                crowded_[fillCrowded_[slot]++] = std::int32_t(s);
              } else {
                for (std::int32_t q = u.begin; q < u.end; ++q) particles_[fill_[slot]++] = q;
              }
            }
      }
      if (pass == 0) {  // counts -> offsets
        countsToOffsets(first_, fill_, particles_);
        if (anyCrowded_) countsToOffsets(firstCrowded_, fillCrowded_, crowded_);
      }
    }
  }
  template <class VertexRange>
  void build(const VertexRange& vertices) {
    build(vertices, [](const auto&) { return false; });
  }

  Neighbourhood near(std::int64_t i, std::int64_t j, std::int64_t k) const {
    const std::int32_t slot = slotOf_.find(packVertexKey(i, j, k));
    if (slot == VertexHashMap::kAbsent) return Neighbourhood{{nullptr, nullptr}, {nullptr, nullptr}};
    if (!anyCrowded_)  // the common case off the reluctant grid: no second look-up
      return Neighbourhood{{particles_.data() + first_[slot], particles_.data() + first_[slot + 1]}, {nullptr, nullptr}};
    return Neighbourhood{{particles_.data() + first_[slot], particles_.data() + first_[slot + 1]},
                         {crowded_.data() + firstCrowded_[slot], crowded_.data() + firstCrowded_[slot + 1]}};
  }

  std::size_t memoryBytes() const {
    return slotOf_.memoryBytes() + (first_.capacity() + fill_.capacity() + particles_.capacity() +
                                    firstCrowded_.capacity() + fillCrowded_.capacity() + crowded_.capacity()) *
                                       sizeof(std::int32_t);
  }

 private:
  static void countsToOffsets(std::vector<std::int32_t>& first, std::vector<std::int32_t>& fill,
                              std::vector<std::int32_t>& items) {
    std::int32_t sum = 0;
    for (std::int32_t& f : first) {
      const std::int32_t count = f;
      f = sum;
      sum += count;
    }
    first.push_back(sum);
    items.resize(std::size_t(sum));
    fill.assign(first.begin(), first.end() - 1);
  }

  bool anyCrowded_ = false;
  VertexHashMap slotOf_;
  std::vector<std::int32_t> first_, fill_, particles_;
  std::vector<std::int32_t> firstCrowded_, fillCrowded_, crowded_;
};

}  // namespace spacetree
