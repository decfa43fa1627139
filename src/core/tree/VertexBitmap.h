// Which vertices of one spacetree level are occupied, as one bit per vertex of the level's
// whole index cube, with the number of occupied vertices before each 64-bit word (a rank): the
// slot of an occupied vertex in the level's key-sorted vertex list in O(1), no search. A finer
// vertex looks up the 3x3x3 coarse vertices around its nearest coarse vertex (virtual links on
// a dilute finer level) with nine 3-bit reads instead of binary searches over slices and rows.
// A second bit set, dilated by one index per axis, tells in one read whether a finer vertex
// has any coarse vertex around it at all. 3.5 bits per vertex of the cube (with the dilation's
// scratch): for coarse levels only (the tree builds one when the cube is small against the
// particle count).
#pragma once

#include <cstdint>
#include <vector>

#include "tree/VertexKey.h"

namespace spacetree {

class VertexBitmap {
 public:
  // Bits needed for vertex indices 0 .. last per axis, with one index of padding on either side
  // (so that the 3x3x3 around any vertex needs no bounds test).
  static std::uint64_t bitsFor(std::int64_t last) {
    const std::uint64_t side = std::uint64_t(last) + 3;
    return side * side * side;
  }

  // The vertices of packed keys[0, count) (as VertexKey packs them, sorted ascending, every
  // index in [0, last]).
  void build(const std::uint64_t* keys, std::size_t count, std::int64_t last) {
    side_ = last + 3;
    for (int r = 0; r < 9; ++r) runOffset_[r] = (std::uint64_t(r / 3) * std::uint64_t(side_) + std::uint64_t(r % 3)) * std::uint64_t(side_);
    const std::uint64_t bits = bitsFor(last);
    words_.assign(std::size_t(bits / 64 + 2), 0);  // one word of slack for the 3-bit reads
    // Keys ascending: bits ascending, so the rank of each word is the slot of its first bit.
    rank_.resize(words_.size());
    std::size_t filled = 0;  // words whose rank is set
    for (std::size_t s = 0; s < count; ++s) {
      const VertexIndex v = unpackVertexKey(keys[s]);
      const std::uint64_t b = cell(v.i, v.j, v.k);
      const std::size_t w = std::size_t(b >> 6);
      words_[w] |= std::uint64_t(1) << (b & 63);
      for (; filled <= w; ++filled) rank_[filled] = std::int32_t(s);
    }
    for (; filled < rank_.size(); ++filled) rank_[filled] = std::int32_t(count);
    // The occupied bits dilated by one index along k, then j, then i (a vertex's indices lie
    // in [0, last], so the dilation stays within the padding of its row, slice and cube).
    near_ = words_;
    scratch_.resize(near_.size());
    for (const std::uint64_t offset : {std::uint64_t(1), std::uint64_t(side_), std::uint64_t(side_) * std::uint64_t(side_)}) {
      scratch_ = near_;
      orShifted(scratch_, near_, offset);
      near_.swap(scratch_);
    }
  }

  // Whether any of the 27 vertices with indices in [c - 1, c + 1] per axis is occupied (one
  // bit read); c in [0, last] per axis.
  bool anyAround(std::int64_t i, std::int64_t j, std::int64_t k) const {
    const std::uint64_t b = cell(i, j, k);
    return (near_[std::size_t(b >> 6)] >> (b & 63)) & 1u;
  }

  // Which of the 27 vertices with indices in [c - 1, c + 1] per axis are occupied: bit
  // 3 (3 di + dj) + dk for offsets di, dj, dk in {0, 1, 2} (c - 1 + offset), so bit order is
  // key order; c in [0, last] per axis. Branch-free: around most vertices of a dilute finer
  // level there is no coarse vertex at all.
  std::uint32_t around(std::int64_t i, std::int64_t j, std::int64_t k) const {
    const std::uint64_t base = cell(i - 1, j - 1, k - 1);
    std::uint32_t runs = 0;
    for (int r = 0; r < 9; ++r) {
      const std::uint64_t b = base + runOffset_[r];
      const std::size_t w = std::size_t(b >> 6);
      // bits b .. b + 2, which may straddle two words
      const unsigned __int128 pair = (static_cast<unsigned __int128>(words_[w + 1]) << 64) | words_[w];
      runs |= (std::uint32_t(pair >> (b & 63)) & 7u) << (3 * r);
    }
    return runs;
  }
  // Slot (in the level's key-sorted vertex list) of the vertex of bit t of around(i, j, k).
  std::int32_t slotAround(std::int64_t i, std::int64_t j, std::int64_t k, unsigned t) const {
    const std::uint64_t b = cell(i - 1, j - 1, k - 1) + runOffset_[t / 3] + t % 3;
    const std::size_t w = std::size_t(b >> 6);
    const std::uint64_t below = words_[w] & ((std::uint64_t(1) << (b & 63)) - 1);
    return rank_[w] + std::int32_t(__builtin_popcountll(below));
  }

  std::size_t bytes() const {
    return (words_.capacity() + near_.capacity() + scratch_.capacity()) * sizeof(std::uint64_t) +
           rank_.capacity() * sizeof(std::int32_t);
  }

 private:
  // Bit of vertex (i, j, k): lexicographic like the keys, so bit order is slot order.
  std::uint64_t cell(std::int64_t i, std::int64_t j, std::int64_t k) const {
    return (std::uint64_t(i + 1) * std::uint64_t(side_) + std::uint64_t(j + 1)) * std::uint64_t(side_) + std::uint64_t(k + 1);
  }

  // to |= from shifted by +offset and by -offset bits (offset < 64 * size).
  static void orShifted(std::vector<std::uint64_t>& to, const std::vector<std::uint64_t>& from, std::uint64_t offset) {
    const std::size_t n = from.size(), words = std::size_t(offset >> 6);
    const unsigned bits = unsigned(offset & 63);
    for (std::size_t w = 0; w < n; ++w) {
      // up: bit b of from -> bit b + offset; down: bit b -> b - offset
      std::uint64_t up = 0, down = 0;
      if (w >= words) {
        up = from[w - words] << bits;
        if (bits && w >= words + 1) up |= from[w - words - 1] >> (64 - bits);
      }
      if (w + words < n) {
        down = from[w + words] >> bits;
        if (bits && w + words + 1 < n) down |= from[w + words + 1] << (64 - bits);
      }
      to[w] |= up | down;
    }
  }

  std::int64_t side_ = 0;
  std::uint64_t runOffset_[9] = {};  // bit of (c - 1 + (r / 3, r % 3, 0)) from that of c - 1
  std::vector<std::uint64_t> words_;
  std::vector<std::int32_t> rank_;
  std::vector<std::uint64_t> near_;     // occupied bits dilated by one index per axis
  std::vector<std::uint64_t> scratch_;  // of the dilation, kept from build to build
};

}  // namespace spacetree
