// Counters a Spacetree keeps about its last build and sweep (cheap to maintain: per vertex,
// not per pair).
#pragma once

#include <cstdint>
#include <vector>

namespace spacetree {

struct LevelStatistics {
  double meshSize = 0.0;
  std::uint64_t realParticles = 0;  // particles hosted on this level
  std::uint64_t vertices = 0;       // vertices that host at least one real particle
  std::uint64_t virtualLinks = 0;   // (vertex, coarser particle) links made in the last sweep
  std::uint64_t linkTests = 0;      // (vertex, coarser particle) distances tested for them
  std::uint64_t linkLookups = 0;    // (vertex, coarser level) look-ups of the coarse vertices around a vertex
};

struct SpacetreeStatistics {
  std::vector<LevelStatistics> levels;  // index = level, 0 = root
  std::uint64_t candidatePairs = 0;     // pairs handed to the visitor's exact check
  int deepestPopulatedLevel = -1;
  std::uint64_t memoryBytes = 0;        // arrays held by the tree after build()
};

}  // namespace spacetree
