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

}  // namespace spacetree
