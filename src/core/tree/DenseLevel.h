// A dense pack of one level, sorted and swept like LAMMPS' bins: when every particle of a build
// lives on the same level, the occupied vertices fill a good part of their bounding box and no
// vertex is crowded, the tree keeps no vertex records, keys, rows or sorted copies. One
// counting sort over the box's cells (a cell per vertex: the cell of mesh size h around it)
// gives the cell starts (4 bytes per cell) and the particle order (4 bytes per particle); the
// sweep pairs each cell with itself and its 13 forward neighbours at fixed offsets in the
// cell-start array, and tests the candidates on the caller's arrays (x[id], radius[id], as
// LAMMPS reads x[j]). The cells, their order and the forward neighbours are those of the
// general path's vertices, so the candidates and pairs are the same.
//
// The box has an empty margin of one cell before and after every row and slice, and one empty
// slice after the last: each forward neighbour row (i, j + 1), (i + 1, j - 1 .. j + 1) at
// k - 1 .. k + 1 is then the run of particles between the starts of two cells, with no bound
// check.
#pragma once

#include <cstdint>
#include <vector>

namespace spacetree {

class DenseLevel {
 public:
  // The box (with its margin) may hold at most this many cells per occupied vertex.
  static constexpr std::int64_t kCellsPerOccupiedVertex = 4;
  // A vertex holding this many particles or more is crowded (the general path sorts and
  // prunes it): no dense level then.
  static constexpr std::int32_t kMaxPerVertex = 8;

  // Sorts particles [0, n) into the cells of mesh size 1 / inverseMeshSize of the box from
  // `origin` (the smallest coordinates, so every index is >= 0) to `highest` (the largest).
  // Returns false, holding no storage, when the pack is not dense (more than
  // kCellsPerOccupiedVertex cells per occupied vertex) or a vertex holds kMaxPerVertex particles
  // or more. The arrays must stay unchanged until the last sweep of this build.
  // uniform: every radius is the same.
  bool build(const double (*x)[3], const double* radius, int n, int nActive, const double origin[3],
             double inverseMeshSize, const double highest[3], bool uniform);
  // Forgets the build, keeping the storage (the next build reuses it).
  void forget() { x_ = nullptr; }
  // Frees the storage (the tree's general path is in use).
  void release();
  bool built() const { return x_ != nullptr; }

  std::uint64_t occupiedVertices() const { return occupied_; }
  std::uint64_t memoryBytes() const { return (cellStart_.capacity() + order_.capacity()) * sizeof(std::int32_t); }

  // visit(i, j) (original indices) for every candidate pair with an active particle; returns
  // the candidates.
  template <class Visit>
  std::uint64_t forEachCandidatePair(Visit& visit) const;
  // visit(i, j, squaredDistance[, radiusSum]) for the candidates with
  // dx^2 + dy^2 + dz^2 <= ((r_i + r_j + halo) scale)^2 and an active particle, the distance
  // evaluated as the general path evaluates it; returns the candidates.
  template <class Visit>
  std::uint64_t forEachPairWithin(Visit& visit, double halo, double scale) const;

 private:
  // onCell(s0, s1, end, b0, b1) for each occupied cell: its particles at positions [s0, s1),
  // each against the positions after it up to `end` (the rest of the cell and the next one)
  // and the four rows [b0[r], b1[r]) (some may be empty); returns the candidates.
  template <class OnCell>
  std::uint64_t forEachCell(OnCell&& onCell) const;
  std::int64_t cellOf(const double p[3]) const {
    const std::int64_t i = std::int64_t((p[0] - origin_[0]) * inverse_ + 0.5);
    const std::int64_t j = std::int64_t((p[1] - origin_[1]) * inverse_ + 0.5);
    const std::int64_t k = std::int64_t((p[2] - origin_[2]) * inverse_ + 0.5);
    return (i * rowsPerSlice_ + j + 1) * cellsPerRow_ + k + 1;
  }
  // Positions past the last particle that a short run may read (its value is never used).
  static constexpr std::int32_t kOrderSlack = 4;

  const double (*x_)[3] = nullptr;
  const double* radius_ = nullptr;
  std::int32_t n_ = 0, nActive_ = 0;
  bool uniform_ = false;
  double origin_[3] = {0.0, 0.0, 0.0};
  double inverse_ = 0.0;
  std::int64_t slices_ = 0, rowsPerSlice_ = 0, cellsPerRow_ = 0;  // with the margin
  std::uint64_t occupied_ = 0;
  // cellStart_[c] = position of the first particle of cell c, cellStart_[c + 1] its end.
  std::vector<std::int32_t> cellStart_;
  std::vector<std::int32_t> order_;  // original index at each position, kOrderSlack more
};

}  // namespace spacetree

#include "tree/DenseLevelSweep.h"  // the traversal templates
