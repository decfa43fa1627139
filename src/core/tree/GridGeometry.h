// The cube and level count of a spacetree, fixed from outside. A persistent (adaptive) grid
// must keep its cells in place from step to step, so it owns the geometry and hands it to
// Spacetree::build together with the level each particle is hosted on.
#pragma once

#include <array>

namespace spacetree {

struct GridGeometry {
  std::array<double, 3> origin{0.0, 0.0, 0.0};  // lower corner of the root cube
  double rootSize = 0.0;                        // edge length of the root cube (level 0 cell)
  int depth = 0;                                // finest level; mesh size rootSize / 3^depth
};

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
  geometry.rootSize = root;
  geometry.depth = depth;
}

}  // namespace spacetree
