// The cells of a persistent adaptive grid (paper §5.1) and where a particle is hosted on them.
// Every grid type (regular, adaptive, reluctant) works on the same cells: a cube, a start-off
// depth above which every cell is refined (not stored), and below it the refined cells of each
// level, sparsely, in one hash set per level. This file answers what the grid types ask of the
// cells (does a cell exist, is it refined, is a vertex hanging, which cell or vertex holds a
// point) and derives a particle's host level from them; which cells get refined or removed is
// the grid types' business (AdaptiveGridPolicy, ReluctantGridPolicy, GridCoarsening).
//
// Host level: descend from the root while the cell containing the particle centre is refined
// and the next level still fits the particle; then lift while the nearest vertex on that level
// is hanging (not all 2^d adjacent cells exist).
//
// The small look-ups are defined here, in the header: the grid types call them per particle
// and per pair from their own files.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "tree/GridGeometry.h"
#include "tree/VertexKey.h"
#include "tree/VertexKeySet.h"

namespace spacetree {

// Integer coordinates of a cell or vertex on one level.
struct Index3 {
  std::int64_t i, j, k;
};

// A cell of the grid: (level, packed cell coordinates).
using LevelCell = std::pair<int, std::uint64_t>;

class RefinedCells {
 public:
  bool hasCube() const { return haveCube_; }
  const GridGeometry& geometry() const { return geometry_; }
  int depth() const { return geometry_.depth; }
  // Levels above it are refined everywhere and not stored.
  int regularDepth() const { return regularDepth_; }
  // Counts up with every change of the cells: a caller's derived state (hosts) is current
  // while the version is the one it was derived at.
  std::uint64_t version() const { return version_; }

  // A new cube: no cell below the start-off depth is refined.
  void resetCube(const GridGeometry& geometry);
  // Stored refinements inside the everywhere-refined levels become redundant and are dropped.
  void setRegularDepth(int regularDepth);
  // The state serialise() stored (AdaptiveGridSerialisation.cpp): cube, start-off depth and
  // the refined cells of every level (empty without a cube).
  void restore(bool haveCube, const GridGeometry& geometry, int regularDepth,
               std::vector<VertexKeySet> refined);

  double meshSize(int level) const { return meshSizeOfLevel(geometry_.rootSize, level); }
  // meshSize() and its inverse, cached per level of the cube (the hot paths read these).
  double cachedMeshSize(int level) const { return meshSize_[std::size_t(level)]; }
  double inverseMeshSize(int level) const { return inverseMeshSize_[std::size_t(level)]; }
  std::int64_t cellsPerAxis(int level) const { return kPowersOfThree[level]; }
  // Finest level whose mesh size is at least `required` (the finest level a particle fits).
  int finestFit(double required) const {
    int l = 0;
    while (l < geometry_.depth && meshSize_[std::size_t(l) + 1] >= required) ++l;
    return l;
  }

  // The cell of `level` containing p (clamped into the cube) and the vertex nearest to p.
  Index3 cellOf(int level, const double p[3]) const {
    const double inv = inverseMeshSize_[level];
    const std::int64_t last = cellsPerAxis(level) - 1;
    auto c = [&](int d) {
      return std::clamp(std::int64_t(std::floor((p[d] - geometry_.origin[d]) * inv)), std::int64_t(0), last);
    };
    return {c(0), c(1), c(2)};
  }
  Index3 nearestVertex(int level, const double p[3]) const {
    const double inv = inverseMeshSize_[level];
    auto v = [&](int d) { return nearestVertexCoordinate(p[d], geometry_.origin[d], inv); };
    return {v(0), v(1), v(2)};
  }

  bool isRefined(int level, std::int64_t i, std::int64_t j, std::int64_t k) const {
    if (level < regularDepth_) return true;
    if (level >= geometry_.depth) return false;
    return refined_[level].contains(packVertexKey(i, j, k));
  }
  bool cellExists(int level, std::int64_t i, std::int64_t j, std::int64_t k) const {
    const std::int64_t n = cellsPerAxis(level);
    if (i < 0 || j < 0 || k < 0 || i >= n || j >= n || k >= n) return false;
    return level == 0 || isRefined(level - 1, i / 3, j / 3, k / 3);
  }
  bool isHanging(int level, std::int64_t i, std::int64_t j, std::int64_t k) const {
    // Cells outside the cube do not count: the padding keeps particles off its boundary.
    // Levels down to the start-off one exist everywhere; below, a cell exists iff its parent is
    // refined, and the 2^d cells around a vertex share parents (one look-up per distinct
    // parent, about 2.4 instead of 8 on average).
    if (level <= regularDepth_) return false;
    const std::int64_t last = cellsPerAxis(level) - 1;
    auto lo = [](std::int64_t v) { return std::max<std::int64_t>(v - 1, 0) / 3; };
    auto hi = [last](std::int64_t v) { return std::min(v, last) / 3; };
    if (i - 1 > last || j - 1 > last || k - 1 > last || i < 0 || j < 0 || k < 0) return false;
    for (std::int64_t a = lo(i); a <= hi(i); ++a)
      for (std::int64_t b = lo(j); b <= hi(j); ++b)
        for (std::int64_t c = lo(k); c <= hi(k); ++c)
          if (!isRefined(level - 1, a, b, c)) return true;
    return false;
  }
  // Whether the cell of `level` containing point p exists and is refined.
  bool isRefinedAt(int level, const double p[3]) const;

  // Host level of a particle at p whose finest admissible level is `admissible`, and the level
  // where the descent stopped (before the lifts).
  int hostPath(const double p[3], int admissible, int& descent) const {
    // Levels above the start-off grid are refined everywhere: no look-up needed there.
    int l = std::max(0, std::min(regularDepth_, admissible));
    while (l < admissible) {
      const Index3 c = cellOf(l, p);
      if (!isRefined(l, c.i, c.j, c.k)) break;
      ++l;
    }
    descent = l;
    while (l > 0) {
      const Index3 v = nearestVertex(l, p);
      if (!isHanging(l, v.i, v.j, v.k)) break;
      --l;  // lift: the vertex does not exist as a full vertex on this level
    }
    return l;
  }
  int hostOf(const double p[3], int admissible) const {
    int descent;
    return hostPath(p, admissible, descent);
  }

  // Whether refine() would add the cell: it exists, is not refined and is above the finest level.
  bool canRefine(int level, std::int64_t i, std::int64_t j, std::int64_t k) const {
    return level < geometry_.depth && !isRefined(level, i, j, k) && cellExists(level, i, j, k);
  }
  void refine(int level, std::uint64_t cellKey) {
    refined_[level].insert(cellKey);
    ++version_;
  }
  // Removes the refined cells `cellKeys` of `level` (their 3^d children).
  void coarsen(int level, const std::vector<std::uint64_t>& cellKeys) {
    if (cellKeys.empty()) return;
    refined_[level].eraseAll(cellKeys);
    ++version_;
  }
  // The stored refined cells of `level` (levels below the start-off depth; index < levels()).
  const VertexKeySet& refinedOn(int level) const { return refined_[std::size_t(level)]; }
  std::size_t levels() const { return refined_.size(); }

  // Cells of `level` that exist (the children of refined cells below the start-off depth).
  std::uint64_t cellsOn(int level) const;
  // Leaf cells (cells that exist and are not refined): f(level, i, j, k) with the cell's
  // integer coordinates on its level.
  template <class F>
  void forEachLeafCell(F&& f) const;
  std::uint64_t leafCellCount() const;
  // Non-hanging vertices per level (index = level).
  std::vector<std::uint64_t> verticesPerLevel() const;

 private:
  bool haveCube_ = false;
  GridGeometry geometry_;
  int regularDepth_ = 0;
  std::vector<VertexKeySet> refined_;  // per level, cells (not above regularDepth_) that are refined
  std::vector<double> meshSize_, inverseMeshSize_;  // meshSize(level) and 1 / it, per level
  std::uint64_t version_ = 0;

  void cacheMeshSizes();
};

template <class F>
void RefinedCells::forEachLeafCell(F&& f) const {
  if (!haveCube_) return;
  const int depth = geometry_.depth;
  // The start-off level: every cell exists, the stored refined ones are not leaves.
  const std::int64_t n = cellsPerAxis(regularDepth_);
  for (std::int64_t i = 0; i < n; ++i)
    for (std::int64_t j = 0; j < n; ++j)
      for (std::int64_t k = 0; k < n; ++k)
        if (!isRefined(regularDepth_, i, j, k)) f(regularDepth_, i, j, k);
  // Below it: the children of refined cells that are not refined themselves.
  for (int l = regularDepth_ + 1; l <= depth; ++l)
    for (std::uint64_t parentKey : refined_[l - 1].keys) {
      const VertexIndex c = unpackVertexKey(parentKey);
      for (std::int64_t a = 3 * c.i; a < 3 * c.i + 3; ++a)
        for (std::int64_t b = 3 * c.j; b < 3 * c.j + 3; ++b)
          for (std::int64_t e = 3 * c.k; e < 3 * c.k + 3; ++e)
            if (!isRefined(l, a, b, e)) f(l, a, b, e);
    }
}

}  // namespace spacetree
