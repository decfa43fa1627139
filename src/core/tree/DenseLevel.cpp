#include "tree/DenseLevel.h"

#include <algorithm>

namespace spacetree {

void DenseLevel::release() {
  forget();
  std::vector<std::int32_t>().swap(cellStart_);
  std::vector<std::int32_t>().swap(order_);
}

bool DenseLevel::build(const double (*x)[3], const double* radius, int n, int nActive, const double origin[3],
                       double inverseMeshSize, const double highest[3], bool uniform) {
  forget();
  occupied_ = 0;
  for (int d = 0; d < 3; ++d) origin_[d] = origin[d];
  inverse_ = inverseMeshSize;
  std::int64_t vertices[3];
  for (int d = 0; d < 3; ++d) vertices[d] = std::int64_t((highest[d] - origin[d]) * inverseMeshSize + 0.5) + 1;
  slices_ = vertices[0] + 1;
  rowsPerSlice_ = vertices[1] + 2;
  cellsPerRow_ = vertices[2] + 2;
  // At most n vertices are occupied: a box too big for that is not dense (no pass needed).
  const std::int64_t cells = slices_ * rowsPerSlice_ * cellsPerRow_;
  if (n <= 0 || cells > kCellsPerOccupiedVertex * std::int64_t(n)) {
    release();
    return false;
  }

  // Counting sort. Cell c's count goes to cellStart_[c + 2]; the prefix sum makes
  // cellStart_[c + 1] the start of cell c, the scatter moves it to the end of c, which is the
  // start of c + 1: cellStart_[c] is then the start of c.
  cellStart_.assign(std::size_t(cells) + 2, 0);
  std::int32_t* start = cellStart_.data();
  std::uint64_t occupied = 0;
  for (int i = 0; i < n; ++i) occupied += start[cellOf(x[i]) + 2]++ == 0 ? 1 : 0;
  std::int32_t sum = 0, largest = 0;
  for (std::int64_t c = 2; c < cells + 2; ++c) {
    largest = std::max(largest, start[c]);
    sum += start[c];
    start[c] = sum;
  }
  if (std::int64_t(occupied) * kCellsPerOccupiedVertex < cells || largest >= kMaxPerVertex) {
    release();
    return false;
  }
  order_.resize(std::size_t(n) + kOrderSlack);
  std::int32_t* order = order_.data();
  for (int i = 0; i < n; ++i) order[start[cellOf(x[i]) + 1]++] = i;
  std::fill(order + n, order + n + kOrderSlack, 0);

  x_ = x;
  radius_ = radius;
  n_ = n;
  nActive_ = nActive;
  uniform_ = uniform;
  occupied_ = occupied;
  return true;
}

}  // namespace spacetree
