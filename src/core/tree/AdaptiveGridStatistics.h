// Counters an AdaptiveGrid keeps about its last update() (virtual links per level come from
// the Spacetree sweep, which owns them; vertices from AdaptiveGrid::verticesPerLevel()).
#pragma once

#include <cstdint>
#include <vector>

namespace spacetree {

struct AdaptiveLevelStatistics {
  double meshSize = 0.0;
  std::uint64_t cells = 0;          // cells of this level that exist (children of refined cells)
  std::uint64_t realParticles = 0;  // particles hosted on this level
};

struct AdaptiveGridStatistics {
  std::vector<AdaptiveLevelStatistics> levels;  // index = level, 0 = root
  std::uint64_t cells = 0;                      // sum over the levels
  // Counted over the last update() and the refineForPairs() after it (one list build).
  std::uint64_t refinements = 0;                // cells refined
  std::uint64_t coarsenings = 0;                // patches of 27 cells removed
  std::uint64_t spared = 0;                     // cool cells kept: the criterion would refine them again
  int deepestLevel = 0;                         // finest level hosting a particle
  int regularDepth = 0;                         // levels above it are refined everywhere
  std::uint64_t geometryResets = 0;             // cube re-chosen (particles left it), cumulative
  std::uint64_t rehosted = 0;                   // particles whose host was recomputed last update
  bool incremental = false;                     // last update touched only the moved particles
};

}  // namespace spacetree
