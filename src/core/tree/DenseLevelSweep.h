// The traversal of a built DenseLevel (its member templates, included by DenseLevel.h): each
// occupied cell against itself and its 13 forward neighbours, as runs of positions between two
// cell starts, and the two ways of visiting the candidates.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "tree/DenseLevel.h"

namespace spacetree {

template <class OnCell>
std::uint64_t DenseLevel::forEachCell(OnCell&& onCell) const {
  // Forward neighbours of cell (i, j, k): (i, j, k + 1), which follows the cell's own particles
  // in the order, and the rows (i, j + 1), (i + 1, j - 1), (i + 1, j), (i + 1, j + 1) at
  // k - 1 .. k + 1: the positions from the start of the row's cell k - 1 to the start of its
  // cell k + 2. The margin keeps every one of these cells inside the array.
  const std::int64_t slice = rowsPerSlice_ * cellsPerRow_;
  const std::int64_t rowOffsets[4] = {cellsPerRow_, slice - cellsPerRow_, slice, slice + cellsPerRow_};
  const std::int32_t* start = cellStart_.data();
  std::uint64_t candidates = 0;
  // From the first to the last cell that can be occupied; the margin's cells are empty.
  const std::int64_t last = slices_ * slice - slice;
  for (std::int64_t c = cellsPerRow_ + 1; c < last; ++c) {
    const std::int32_t s0 = start[c], s1 = start[c + 1];
    if (s0 == s1) continue;
    const std::uint64_t n = std::uint64_t(s1 - s0);
    const std::int32_t end = start[c + 2];
    std::int32_t b0[4], b1[4];
    std::uint64_t rows = 0;
    for (int r = 0; r < 4; ++r) {
      const std::int64_t row = c + rowOffsets[r];
      b0[r] = start[row - 1];
      b1[r] = start[row + 2];
      rows += std::uint64_t(b1[r] - b0[r]);
    }
    onCell(s0, s1, end, b0, b1);
    candidates += n * (n - 1) / 2 + n * (std::uint64_t(end - s1) + rows);
  }
  return candidates;
}

template <class Visit>
std::uint64_t DenseLevel::forEachCandidatePair(Visit& visit) const {
  const std::int32_t* order = order_.data();
  auto run = [&](std::int32_t a, std::int32_t first, std::int32_t last) {
    for (std::int32_t t = first; t < last; ++t)
      if (a < nActive_ || order[t] < nActive_) visit(a, order[t]);
  };
  return forEachCell([&](std::int32_t s0, std::int32_t s1, std::int32_t end, const std::int32_t* b0,
                         const std::int32_t* b1) {
    for (std::int32_t s = s0; s < s1; ++s) {
      run(order[s], s + 1, end);
      for (int r = 0; r < 4; ++r) run(order[s], b0[r], b1[r]);
    }
  });
}

template <class Visit>
std::uint64_t DenseLevel::forEachPairWithin(Visit& visit, double halo, double scale) const {
  // The candidates (as original indices) are queued and tested a block at a time, as the
  // general path's WithinVisitor does with its sorted copies: on a dense level most runs hold
  // one to three particles, and testing them as they come would pay a mispredicted branch per
  // run. Here the block pass reads the caller's arrays through the indices (a gather; the atoms
  // of a pack that was sorted or built in space order lie near each other).
  constexpr std::int32_t kBlock = 1024, kShortRun = kOrderSlack;
  // A cell queues at most this many slots (fewer than kMaxPerVertex particles, each against
  // the rest of its cell and the next one, and four rows of three cells, a short run taking
  // kShortRun slots whatever its length): the block is tested when a cell leaves it full.
  constexpr std::int32_t kCellSlots = (kMaxPerVertex - 1) * (2 * kMaxPerVertex + 12 * kMaxPerVertex + 5 * kShortRun);
  // not initialised: filled before read
  std::int32_t first[kBlock + kCellSlots], second[kBlock + kCellSlots], hit[kBlock + kCellSlots];
  std::int32_t queued = 0;
  const bool allActive = nActive_ >= n_;
  const double (*x)[3] = x_;
  const double* radius = radius_;
  const std::int32_t* order = order_.data();
  // Tests the first `queued` slots; takes the fill by value, so the walk keeps it in a register.
  // One size (every radius equal): the cut-off is one number, computed by the same expression.
  const double uniformCut = (radius_[0] + radius_[0] + halo) * scale, uniformCut2 = uniformCut * uniformCut;
  auto test = [&](std::int32_t queued) __attribute__((noinline)) {
    std::int32_t hits = 0;
    if (uniform_) {
      for (std::int32_t t = 0; t < queued; ++t) {
        const std::int32_t a = first[t], b = second[t];
        const double dx = x[a][0] - x[b][0], dy = x[a][1] - x[b][1], dz = x[a][2] - x[b][2];
        hit[hits] = t;
        hits += dx * dx + dy * dy + dz * dz <= uniformCut2 ? 1 : 0;
      }
    } else {
      for (std::int32_t t = 0; t < queued; ++t) {
        const std::int32_t a = first[t], b = second[t];
        const double dx = x[a][0] - x[b][0], dy = x[a][1] - x[b][1], dz = x[a][2] - x[b][2];
        const double c = (radius[a] + radius[b] + halo) * scale;
        hit[hits] = t;
        hits += dx * dx + dy * dy + dz * dz <= c * c ? 1 : 0;
      }
    }
    for (std::int32_t h = 0; h < hits; ++h) {
      const std::int32_t a = first[hit[h]], b = second[hit[h]];
      if (!allActive && a >= nActive_ && b >= nActive_) continue;
      const double dx = x[a][0] - x[b][0], dy = x[a][1] - x[b][1], dz = x[a][2] - x[b][2];
      const double d2 = dx * dx + dy * dy + dz * dz;
      if constexpr (std::is_invocable_v<Visit&, int, int, double, double>)
        visit(a, b, d2, radius[a] + radius[b]);
      else
        visit(a, b, d2);
    }
  };
  // A short run (an empty one too) is written as kShortRun slots whatever its length (the
  // order has that many positions of slack) and counted by its length: no branch on the length.
  auto queue = [&](std::int32_t a, std::int32_t from, std::int32_t to) {
    if (to - from <= kShortRun) {
      std::memcpy(second + queued, order + from, sizeof(std::int32_t) * kShortRun);  // one vector load
      for (std::int32_t t = 0; t < kShortRun; ++t) first[queued + t] = a;
      queued += to - from;
      return;
    }
    for (; from < to; ++from, ++queued) {
      first[queued] = a;
      second[queued] = order[from];
    }
  };
  const std::uint64_t candidates = forEachCell([&](std::int32_t s0, std::int32_t s1, std::int32_t end,
                                                   const std::int32_t* b0, const std::int32_t* b1) {
    if (s1 - s0 == 1) {  // the common case of a dense pack: one particle per cell
      const std::int32_t a = order[s0];
      queue(a, s1, end);
      for (int r = 0; r < 4; ++r) queue(a, b0[r], b1[r]);
    } else {
      for (std::int32_t s = s0; s < s1; ++s) {
        const std::int32_t a = order[s];
        queue(a, s + 1, end);
        for (int r = 0; r < 4; ++r) queue(a, b0[r], b1[r]);
      }
    }
    if (queued >= kBlock) {
      test(queued);
      queued = 0;
    }
  });
  test(queued);
  return candidates;
}

}  // namespace spacetree
