// Binary search whose steps are conditional moves, for the look-ups of the sweep on sorted
// vertex keys, rows and slices: which half a step keeps depends on the data, so a branch per
// step would be mispredicted about every other time (the link balls of a dilute level do
// such a search per slice and row they touch).
#pragma once

#include <cstddef>

namespace spacetree {

// std::partition_point's result: the first element of [first, last) for which pred is false,
// for a range in which every element that satisfies pred comes before every one that does not.
template <class T, class Pred>
const T* branchlessPartitionPoint(const T* first, const T* last, Pred&& pred) {
  std::size_t n = std::size_t(last - first);
  if (n == 0) return first;
  // The answer lies in [first, first + n]; each step halves n.
  while (n > 1) {
    const std::size_t half = n / 2;
    first = pred(first[half]) ? first + half : first;
    n -= half;
  }
  return first + (pred(*first) ? 1 : 0);
}

}  // namespace spacetree
