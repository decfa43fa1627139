// The reluctant grid's refinement criterion (paper §5.1), shared by the refinement and by the
// spare check of its coarsening: a pair of touching particles (bounding spheres + eps) makes
// the grid refine the cell of the finer one, p, if p would drop, the pair approaches and the
// other, q, is held by that cell: real on one of its 2^d vertices, or virtual there (coarser
// and within the link radius of a vertex).
#pragma once

#include <cmath>

#include "tree/RefinedCells.h"

namespace spacetree {

// Whether the particles a and b approach (v == nullptr: every pair counts as approaching).
inline bool approaching(const double (*x)[3], const double (*v)[3], int a, int b) {
  if (!v) return true;
  double approach = 0.0;
  for (int d = 0; d < 3; ++d) approach += (x[b][d] - x[a][d]) * (v[b][d] - v[a][d]);
  return approach < 0.0;
}

// Whether a coarser particle at q is virtual on a vertex of cell c of `level`: within its
// radius + 2 eps + h sqrt(3) of one of the cell's 2^d corners.
inline bool linksToCell(const RefinedCells& cells, double epsilon, int level, const Index3& c, const double q[3],
                        double radius) {
  const double h = cells.meshSize(level);
  const double reach = radius + 2.0 * epsilon + std::sqrt(3.0) * h;
  const GridGeometry& g = cells.geometry();
  for (int corner = 0; corner < 8; ++corner) {
    const double vx = g.origin[0] + double(c.i + (corner & 1)) * h;
    const double vy = g.origin[1] + double(c.j + ((corner >> 1) & 1)) * h;
    const double vz = g.origin[2] + double(c.k + ((corner >> 2) & 1)) * h;
    const double dx = q[0] - vx, dy = q[1] - vy, dz = q[2] - vz;
    if (dx * dx + dy * dy + dz * dz < reach * reach) return true;
  }
  return false;
}

// Whether particle q (at x, hosted on qLevel, of radius qRadius) is held by cell c of `level`:
// a particle hosted on `level` (or finer: it is taken on `level` too) must sit at one of the
// cell's vertices, a coarser one must link to them.
inline bool heldByCell(const RefinedCells& cells, double epsilon, int level, const Index3& c, const double q[3],
                       int qLevel, double qRadius) {
  if (qLevel >= level) {
    const Index3 w = cells.nearestVertex(level, q);
    return w.i >= c.i && w.i <= c.i + 1 && w.j >= c.j && w.j <= c.j + 1 && w.k >= c.k && w.k <= c.k + 1;
  }
  return linksToCell(cells, epsilon, level, c, q, qRadius);
}

}  // namespace spacetree
