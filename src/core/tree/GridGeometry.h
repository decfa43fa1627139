// The cube and level count of a spacetree, fixed from outside. A persistent (adaptive) grid
// must keep its cells in place from step to step, so it owns the geometry and hands it to
// Spacetree::build together with the level each particle is hosted on.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>

#include "tree/VertexKey.h"

namespace spacetree {

inline constexpr std::array<std::int64_t, kMaxSpacetreeLevel + 1> kPowersOfThree{
    1, 3, 9, 27, 81, 243, 729, 2187, 6561, 19683, 59049, 177147, 531441};

struct GridGeometry {
  std::array<double, 3> origin{0.0, 0.0, 0.0};  // lower corner of the root cube
  double rootSize = 0.0;                        // edge length of the root cube (level 0 cell)
  int depth = 0;                                // finest level; mesh size rootSize / 3^depth
};

// Mesh size of `level` in a root cube of edge rootSize: every level splits its cells in 3 per
// axis. The tree and the persistent grid compute it alike, so they agree on cells and vertices.
inline double meshSizeOfLevel(double rootSize, int level) { return rootSize / double(kPowersOfThree[level]); }

// Root cube for particles needing mesh sizes from finestNeed up and a cube of at least
// rootNeed: the finest mesh size the smallest particle needs, tripled until the cube covers
// the particles and the biggest particle. Choosing it from the smallest particle makes the
// finest level fit it tightly (no up-to-3x slack from the 3-way refinement there). Sets
// rootSize and depth (at most maxLevel; then the finest level is coarser than ideal).
inline void chooseRootCube(double finestNeed, double rootNeed, int maxLevel, GridGeometry& geometry) {
  if (!(finestNeed > 0.0)) finestNeed = rootNeed > 0.0 ? rootNeed : 1.0;
  int depth = 0;
  double root = finestNeed;
  while (root < rootNeed && depth < maxLevel) {
    root *= 3.0;
    ++depth;
  }
  if (root < rootNeed) root = rootNeed;
  // (finestNeed * 3^depth) / 3^depth rounds below finestNeed about once in four: the smallest
  // particles would then not fit the finest level and crowd the next coarser one (27 times
  // the particles per vertex). Round the cube up until the finest mesh holds them.
  while (meshSizeOfLevel(root, depth) < finestNeed) root = std::nextafter(root, 2.0 * root);
  geometry.rootSize = root;
  geometry.depth = depth;
}

// Index along one axis of the vertex nearest to coordinate x on a level (origin: the cube's
// lower corner there; inverseMeshSize = 1 / mesh size). Coordinates inside the cube are >= 0,
// so the truncation rounds to nearest. The tree keys particles and the grid derives hosts with
// this one rounding, so both put a particle on the same vertex.
inline std::int64_t nearestVertexCoordinate(double x, double origin, double inverseMeshSize) {
  return std::int64_t((x - origin) * inverseMeshSize + 0.5);
}

}  // namespace spacetree
