#include "tree/RefinedCells.h"

namespace spacetree {

void RefinedCells::cacheMeshSizes() {
  const std::size_t levels = std::size_t(geometry_.depth) + 1;
  inverseMeshSize_.resize(levels);
  meshSize_.resize(levels);
  for (std::size_t l = 0; l < levels; ++l) {
    meshSize_[l] = meshSize(int(l));
    inverseMeshSize_[l] = 1.0 / meshSize(int(l));
  }
}

void RefinedCells::resetCube(const GridGeometry& geometry) {
  geometry_ = geometry;
  haveCube_ = true;
  cacheMeshSizes();
  ++version_;
  refined_.assign(std::size_t(geometry_.depth) + 1, VertexKeySet{});
  for (VertexKeySet& cells : refined_) cells.reset(0);
}

void RefinedCells::setRegularDepth(int regularDepth) {
  regularDepth_ = regularDepth;
  for (int l = 0; l < regularDepth_ && l < int(refined_.size()); ++l)
    if (refined_[l].size()) refined_[l].reset(0);
  ++version_;  // the start-off depth may have changed
}

void RefinedCells::restore(bool haveCube, const GridGeometry& geometry, int regularDepth,
                           std::vector<VertexKeySet> refined) {
  haveCube_ = haveCube;
  geometry_ = geometry;
  regularDepth_ = regularDepth;
  refined_ = std::move(refined);
  if (haveCube_) cacheMeshSizes();
  ++version_;
}

bool RefinedCells::isRefinedAt(int level, const double p[3]) const {
  if (!haveCube_ || level < 0 || level > geometry_.depth) return false;
  const Index3 c = cellOf(level, p);
  return cellExists(level, c.i, c.j, c.k) && isRefined(level, c.i, c.j, c.k);
}

std::uint64_t RefinedCells::cellsOn(int level) const {
  if (level <= regularDepth_) {
    const std::uint64_t c = std::uint64_t(cellsPerAxis(level));
    return c * c * c;
  }
  return 27 * refined_[level - 1].size();
}

std::uint64_t RefinedCells::leafCellCount() const {
  if (!haveCube_) return 0;
  // Every cell at or below the start-off level is a leaf unless it is refined.
  const std::uint64_t n = std::uint64_t(cellsPerAxis(regularDepth_));
  std::uint64_t leaves = n * n * n;
  for (int l = regularDepth_; l < geometry_.depth; ++l) {
    leaves -= refined_[l].size();
    leaves += 27 * refined_[l].size();
  }
  return leaves;
}

std::vector<std::uint64_t> RefinedCells::verticesPerLevel() const {
  // Non-hanging vertices (all 2^d adjacent cells exist). Costs up to 64 hanging tests per
  // refined cell, so it is counted on request (output), not in every update.
  std::vector<std::uint64_t> count(haveCube_ ? std::size_t(geometry_.depth) + 1 : 0, 0);
  for (int l = 0; l < int(count.size()); ++l) {
    if (l <= regularDepth_) {
      const std::uint64_t c = std::uint64_t(cellsPerAxis(l));
      count[l] = (c + 1) * (c + 1) * (c + 1);
      continue;
    }
    // A vertex shared by several refined parents is counted by the first of them (lowest
    // index per axis); the 8 interior ones of a patch are never hanging.
    for (std::uint64_t cellKey : refined_[l - 1].keys) {
      const VertexIndex c = unpackVertexKey(cellKey);
      for (std::int64_t a = 3 * c.i; a <= 3 * c.i + 3; ++a)
        for (std::int64_t b = 3 * c.j; b <= 3 * c.j + 3; ++b)
          for (std::int64_t e = 3 * c.k; e <= 3 * c.k + 3; ++e) {
            if (a % 3 != 0 && b % 3 != 0 && e % 3 != 0) {
              ++count[l];
              continue;
            }
            if (isHanging(l, a, b, e)) continue;
            // Non-hanging: every parent cell around it is refined; the owner has the lowest.
            const bool owner = (a != 3 * c.i || a == 0) && (b != 3 * c.j || b == 0) &&
                               (e != 3 * c.k || e == 0);
            if (owner) ++count[l];
          }
    }
  }
  return count;
}

}  // namespace spacetree
